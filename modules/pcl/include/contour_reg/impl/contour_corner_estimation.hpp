#pragma once

#include <string>

#include <pcl/console/print.h>

#include "contour_reg/contour_corner_estimation.h"

namespace contour_reg {

template <typename PointInT, typename PointOutT>
bool ContourCornerEstimation<PointInT, PointOutT>::initCompute() {
  if (!pcl::PCLBase<PointInT>::initCompute()) {
    PCL_ERROR("[contour_reg::%s::compute] Init failed: no input cloud.\n", getClassName().c_str());
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
  const bool all_points = indices_->size() == input_->size();
  extractContourFeatures(*input_, params_, features_, all_points ? nullptr : indices_.get());
  output.resize(features_.special_points.size());
  for (std::size_t k = 0; k < features_.special_points.size(); ++k)
    output[k] = toContourCorner(features_.special_points[k]);
  output.width = static_cast<std::uint32_t>(output.size());
  output.height = 1;
  output.is_dense = true;
}

}  // namespace contour_reg
