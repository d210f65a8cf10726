#pragma once
// Scans as PCL users hold them, for the tests of the PCL classes.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "contour_reg/core/contour.h"

namespace contour_reg::test {

/// One point per beam in beam order, NaN where the beam has no return (not dense).
inline pcl::PointCloud<pcl::PointXYZ>::Ptr beamCloud(const LaserScan &scan) {
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (const Complex &c : polarCode(scan)) cloud->push_back(pcl::PointXYZ(float(c.real()), float(c.imag()), 0.0f));
  cloud->is_dense = false;
  return cloud;
}

}  // namespace contour_reg::test
