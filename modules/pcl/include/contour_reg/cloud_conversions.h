#pragma once
/// @file cloud_conversions.h
/// Between PCL clouds and the core's types.
///
/// A 2-D scan arrives as a pcl::PointCloud in beam order with NaN points for invalid
/// beams (is_dense = false), as a sensor_msgs/LaserScan converts; z is ignored. A cloud
/// without NaN points whose bearings (atan2(y, x)) do not increase along the cloud, with
/// at most one wrap-around, is sorted by bearing first.

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <pcl/point_cloud.h>
#include <pcl/types.h>

#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/deskew.h"
#include "contour_reg/core/special_points.h"
#include "contour_reg/core/types.h"
#include "contour_reg/point_types.h"

namespace contour_reg {

/// True when the bearings of `points` increase along the sequence, allowing one wrap-around.
bool isInBearingOrder(const ComplexSequence &points);

/// Sorts finite points by bearing, from -pi. With `order` (holding each point's position
/// before the sort), the positions are moved along with their points.
void sortByBearing(ComplexSequence &points, std::vector<int> *order = nullptr);

/// True when every index names a point of `cloud` (none negative or past its end).
template <typename PointT>
bool indicesWithin(const pcl::PointCloud<PointT> &cloud, const pcl::Indices &indices) {
  return std::all_of(indices.begin(), indices.end(),
                     [&](pcl::index_t index) { return index >= 0 && static_cast<std::size_t>(index) < cloud.size(); });
}

/// The polar code of a cloud (or of the points named by `indices`, in that order; they must
/// lie within it), into `code`, reusing its buffer. With `order`, order[n] is the position in
/// the cloud (or in `indices`) of code point n. With a moving `sweep`, the points, each at the
/// time of its position in the cloud, are deskewed (deskew.h) before any sort by bearing.
template <typename PointT>
void polarCodeFromCloud(const pcl::PointCloud<PointT> &cloud, ComplexSequence &code,
                        const pcl::Indices *indices = nullptr, std::vector<int> *order = nullptr,
                        const Sweep &sweep = {}) {
  const std::size_t count = indices ? indices->size() : cloud.size();
  code.clear();
  code.reserve(count);
  if (indices && sweep.moving()) {
    // The whole sweep deskewed, then the points the indices name.
    ComplexSequence all;
    polarCodeFromCloud(cloud, all, nullptr, nullptr, sweep);
    for (const pcl::index_t index : *indices) code.push_back(all[static_cast<std::size_t>(index)]);
  } else {
    for (std::size_t k = 0; k < count; ++k) {
      const PointT &p = cloud[indices ? static_cast<std::size_t>((*indices)[k]) : k];
      code.emplace_back(p.x, p.y);
    }
    deskewPolarCode(code, sweep);
  }
  const bool has_invalid = std::any_of(code.begin(), code.end(), [](const Complex &c) { return !isFinite(c); });
  if (order) {
    order->resize(count);
    std::iota(order->begin(), order->end(), 0);
  }
  if (!has_invalid && !isInBearingOrder(code)) sortByBearing(code, order);
}

/// The polar code of a cloud (or of the points named by `indices`, in that order).
template <typename PointT>
ComplexSequence polarCodeFromCloud(const pcl::PointCloud<PointT> &cloud, const pcl::Indices *indices = nullptr) {
  ComplexSequence code;
  polarCodeFromCloud(cloud, code, indices);
  return code;
}

/// Stages A-C on a cloud (or on the points named by `indices`) into `features`; the polar
/// code goes into the features' own buffer, so a warm `features` allocates nothing.
/// With `order`, as polarCodeFromCloud() gives it: the cloud position of each beam index of
/// the features' segments.
template <typename PointT>
void extractContourFeatures(const pcl::PointCloud<PointT> &cloud, const ContourParams &params,
                            ContourFeatures &features, const pcl::Indices *indices = nullptr,
                            std::vector<int> *order = nullptr, const Sweep &sweep = {}) {
  ComplexSequence &code = features.buffers.polar_code;  // the extraction reads it, never writes it
  polarCodeFromCloud(cloud, code, indices, order, sweep);
  extractContourFeatures(code, params, features);
}

/// Fills a PCL special point from a core special point.
ContourCorner toContourCorner(const SpecialPoint &point);

/// A ContourCorner whose every field is NaN: no corner at this point.
ContourCorner noContourCorner();

/// The raw point nearest a special point's vertex, as an index into the polar code the
/// features were extracted from (a beam index of its segment).
int nearestBeam(const ContourFeatures &features, const SpecialPoint &point);

}  // namespace contour_reg
