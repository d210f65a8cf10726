#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <pcl/common/copy_point.h>

#include <pcl/console/print.h>

#include "contour_reg/contour_corner_estimation.h"

namespace contour_reg {

template <typename PointInT, typename PointOutT>
bool ContourCornerEstimation<PointInT, PointOutT>::initCompute() {
  if (!pcl::PCLBase<PointInT>::initCompute()) {
    PCL_ERROR("[contour_reg::%s::compute] Init failed: no input cloud.\n", getClassName().c_str());
    return false;
  }
  // PCL's initCompute checks how many indices there are, not what they name.
  if (!indicesWithin(*input_, *indices_)) {
    PCL_ERROR("[contour_reg::%s::compute] An index names no point of the %zu-point cloud.\n", getClassName().c_str(),
              input_->size());
    return false;
  }
  std::string why;
  if (!params_.validate(&why)) {
    PCL_ERROR("[contour_reg::%s::compute] Invalid parameters: %s.\n", getClassName().c_str(), why.c_str());
    return false;
  }
  if (params_.special_points.fragment_half_length > ContourCorner::kFragmentElements / 2) {
    PCL_ERROR("[contour_reg::%s::compute] fragment_half_length %d exceeds %d.\n", getClassName().c_str(),
              params_.special_points.fragment_half_length, ContourCorner::kFragmentElements / 2);
    return false;
  }
  return true;
}

template <typename PointInT, typename PointOutT>
void ContourCornerEstimation<PointInT, PointOutT>::computeFeature(PointCloudOut &output) {
  extractContourFeatures(*input_, params_, features_, this->fake_indices_ ? nullptr : indices_.get(), &order_);

  // One output point per index: NaN, but where the nearest raw point of a corner's vertex is.
  PointOutT none;
  pcl::copyPoint(noContourCorner(), none);
  output.resize(indices_->size());
  std::fill(output.begin(), output.end(), none);
  corner_indices_.assign(features_.special_points.size(), -1);
  std::vector<double> response(indices_->size(), -1.0);
  std::size_t carried = 0;
  for (std::size_t k = 0; k < features_.special_points.size(); ++k) {
    const SpecialPoint &point = features_.special_points[k];
    const int beam = nearestBeam(features_, point);
    if (beam < 0) continue;
    const auto position = static_cast<std::size_t>(order_[static_cast<std::size_t>(beam)]);
    corner_indices_[k] = (*indices_)[position];
    if (point.response <= response[position]) continue;
    carried += response[position] < 0.0;
    response[position] = point.response;
    pcl::copyPoint(toContourCorner(point), output[position]);
  }
  output.width = static_cast<std::uint32_t>(output.size());
  output.height = 1;
  output.is_dense = carried == output.size();
}

}  // namespace contour_reg
