#pragma once
/// @file contour_corner_estimation.h
/// The contour corner Feature: special points of a 2-D scan by contour analysis.

#include <pcl/features/feature.h>
#include <pcl/point_types.h>

#include "contour_reg/cloud_conversions.h"
#include "contour_reg/core/contour_features.h"
#include "contour_reg/point_types.h"

namespace contour_reg {

/// Finds corner special points of a 2-D LIDAR scan by contour analysis: polar and
/// differential code (paper eqs. 1-2), equalization (eqs. 3-11), the matched filter for
/// the corner form (eqs. 12-13), and non-maximum suppression. Each output point carries
/// its vertex, corner angle, orientation, filter response and the local fragment that
/// correspondence (eq. 14) compares.
///
/// Input: one scan as a cloud in beam order; z is ignored; NaN points mark invalid beams
/// (is_dense = false). A cloud without NaN that is not in bearing order is sorted by
/// bearing first (see cloud_conversions.h). If indices are set, only those points are
/// used, in the order of the indices.
///
/// Output: pcl::Feature's contract, one output point per input point (per index when
/// indices are set, in their order). The point nearest a corner's vertex carries that corner
/// (its vertex, angle, orientation, response, turn and fragment; the stronger one where two
/// corners share a point); every other output point is NaN in every field, as PCL marks
/// points a feature cannot be computed for, and is_dense is false unless every point carries
/// a corner. A corner is a property of its neighbourhood on the contour, as a boundary is in
/// pcl::BoundaryEstimation, so a per-point answer lets a user keep the output beside the
/// scan (pcl::concatenateFields) or pick the corners by index. getCornerIndices() lists
/// the cloud indices that carry a corner, as pcl::Keypoint::getKeypointsIndices() would, and
/// getContourFeatures() every stage's result. PointOutT is ContourCorner or any PCL point
/// type: the fields it shares with ContourCorner by name are copied (x, y, z into
/// pcl::PointXYZ, say). An empty scan gives an empty output, one without valid beams or
/// without corners an output of NaN points, without error. The class derives from
/// pcl::Feature so that it plugs into PCL's feature interfaces; a contour needs no
/// neighbour search, so initCompute() skips the search set-up that pcl::Feature demands.
///
/// \code
/// contour_reg::ContourCornerEstimation<pcl::PointXYZ> corners;
/// corners.setInputCloud(scan);
/// pcl::PointCloud<contour_reg::ContourCorner> out;
/// corners.compute(out);                        // out.size() == scan->size()
/// for (int index : corners.getCornerIndices())  // the corners only
///   use(out[index]);
/// \endcode
template <typename PointInT, typename PointOutT = ContourCorner>
class ContourCornerEstimation : public pcl::Feature<PointInT, PointOutT> {
 public:
  using Ptr = std::shared_ptr<ContourCornerEstimation<PointInT, PointOutT>>;
  using ConstPtr = std::shared_ptr<const ContourCornerEstimation<PointInT, PointOutT>>;
  using PointCloudOut = typename pcl::Feature<PointInT, PointOutT>::PointCloudOut;
  using pcl::Feature<PointInT, PointOutT>::feature_name_;
  using pcl::Feature<PointInT, PointOutT>::getClassName;
  using pcl::Feature<PointInT, PointOutT>::input_;
  using pcl::Feature<PointInT, PointOutT>::indices_;

  ContourCornerEstimation() { feature_name_ = "ContourCornerEstimation"; }

  /// All settings at once; see docs/parameters.md for units and defaults.
  void setParams(const ContourParams &params) { params_ = params; }
  const ContourParams &getParams() const { return params_; }

  /// Arc length of one equalized element in metres (fixed-step equalization).
  void setContourStep(double step) {
    params_.equalization.mode = EqualizationMode::kFixedStep;
    params_.equalization.step = step;
  }
  /// The paper's equalization: p elements over the scan's contour.
  void setContourElementCount(int count) {
    params_.equalization.mode = EqualizationMode::kFixedCount;
    params_.equalization.count = count;
  }
  /// s: elements per arm of the reference corner.
  void setArmElements(int s) { params_.corner_filter.arm_elements = s; }
  /// The bank of reference corner angles, degrees.
  void setCornerAngles(const std::vector<double> &degrees) { params_.corner_filter.corner_angles_deg = degrees; }
  /// Minimum matched-filter response c(n) of a special point.
  void setResponseThreshold(double threshold) { params_.special_points.threshold = threshold; }
  /// L: elements on each side of the vertex in the fragment (at most kFragmentElements / 2).
  void setFragmentHalfLength(int half_length) { params_.special_points.fragment_half_length = half_length; }

  /// Every stage's result for the last computed scan (segments, contours, responses).
  const ContourFeatures &getContourFeatures() const { return features_; }
  /// The indices into the input cloud of the points that carry a corner, one per special
  /// point of getContourFeatures() in its order (-1 for a special point without a raw point).
  const pcl::Indices &getCornerIndices() const { return corner_indices_; }

 protected:
  bool initCompute() override;
  void computeFeature(PointCloudOut &output) override;

 private:
  ContourParams params_;
  ContourFeatures features_;
  std::vector<int> order_;  // the position in the indices of each polar code point
  pcl::Indices corner_indices_;
};

}  // namespace contour_reg

#include "contour_reg/impl/contour_corner_estimation.hpp"

namespace contour_reg {
extern template class ContourCornerEstimation<pcl::PointXYZ, ContourCorner>;
extern template class ContourCornerEstimation<pcl::PointXYZI, ContourCorner>;
extern template class ContourCornerEstimation<pcl::PointXYZ, pcl::PointXYZ>;
}  // namespace contour_reg
