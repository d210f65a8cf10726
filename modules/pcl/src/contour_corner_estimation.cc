#include "contour_reg/contour_corner_estimation.h"

namespace contour_reg {
template class ContourCornerEstimation<pcl::PointXYZ, ContourCorner>;
template class ContourCornerEstimation<pcl::PointXYZI, ContourCorner>;
template class ContourCornerEstimation<pcl::PointXYZ, pcl::PointXYZ>;
}  // namespace contour_reg
