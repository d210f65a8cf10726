#include "contour_reg/coarse_to_fine_registration.h"

namespace contour_reg {
template class CoarseToFineRegistration<pcl::PointXYZ, pcl::PointXYZ>;
template class CoarseToFineRegistration<pcl::PointXYZI, pcl::PointXYZI>;
}  // namespace contour_reg
