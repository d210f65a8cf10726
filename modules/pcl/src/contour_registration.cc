#include "contour_reg/contour_registration.h"

namespace contour_reg {
template class ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>;
template class ContourRegistration<pcl::PointXYZI, pcl::PointXYZI>;
}  // namespace contour_reg
