// Uses the installed package the way a PCL pipeline would: builds a scan of an L-shaped
// corner and asks the Feature class for its special points.
#include <cmath>
#include <cstdio>

#include <contour_reg/contour_corner_estimation.h>

int main() {
  auto scan = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (int n = 0; n <= 180; ++n) {  // walls x = 3 and y = 2 seen from the origin
    const double a = (n - 90) * M_PI / 180.0 * 0.75;
    const double c = std::cos(a), s = std::sin(a);
    double r = 1e9;
    if (c > 1e-9) r = std::min(r, 3.0 / c);
    if (s > 1e-9) r = std::min(r, 2.0 / s);
    scan->push_back(pcl::PointXYZ(float(r * c), float(r * s), 0.0f));
  }
  contour_reg::ContourCornerEstimation<pcl::PointXYZ> estimation;
  estimation.setInputCloud(scan);
  pcl::PointCloud<contour_reg::ContourCorner> corners;
  estimation.compute(corners);
  for (const auto &c : corners) std::printf("corner %.3f %.3f\n", c.x, c.y);
  const bool ok = corners.size() == 1 && std::abs(corners[0].x - 3.0f) < 0.02f && std::abs(corners[0].y - 2.0f) < 0.02f;
  std::printf("%s\n", ok ? "consumer: ok" : "consumer: wrong corners");
  return ok ? 0 : 1;
}
