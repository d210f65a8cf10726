// Uses the installed package the way a PCL pipeline would: the Feature class on a scan of
// a room corner, and ContourRegistration through pcl::Registration's interface.
#include <cmath>
#include <cstdio>

#include <contour_reg/contour_corner_estimation.h>
#include <contour_reg/contour_registration.h>

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

// A 360-degree scan of a 6 m x 4 m room with a 1 m box, from pose (x, y, yaw).
Cloud::Ptr roomScan(double x, double y, double yaw) {
  const double walls[][4] = {{-2, -1.5, 4, -1.5}, {4, -1.5, 4, 2.5}, {4, 2.5, -2, 2.5}, {-2, 2.5, -2, -1.5},
                             {1, 0.5, 2, 0.5},    {2, 0.5, 2, 1.5},  {2, 1.5, 1, 1.5},  {1, 1.5, 1, 0.5}};
  auto scan = pcl::make_shared<Cloud>();
  for (int n = 0; n < 720; ++n) {
    const double a = yaw + n * M_PI / 360.0, dx = std::cos(a), dy = std::sin(a);
    double best = 1e9;
    for (const auto &w : walls) {  // ray against segment
      const double ex = w[2] - w[0], ey = w[3] - w[1], den = dx * ey - dy * ex;
      if (std::abs(den) < 1e-12) continue;
      const double t = ((w[0] - x) * ey - (w[1] - y) * ex) / den, u = ((w[0] - x) * dy - (w[1] - y) * dx) / den;
      if (t > 0 && u >= 0 && u <= 1) best = std::min(best, t);
    }
    const double b = n * M_PI / 360.0;
    scan->push_back(pcl::PointXYZ(float(best * std::cos(b)), float(best * std::sin(b)), 0.f));
  }
  return scan;
}

}  // namespace

int main() {
  const Cloud::Ptr target = roomScan(0, 0, 0), source = roomScan(0.3, -0.2, 0.2);

  contour_reg::ContourCornerEstimation<pcl::PointXYZ> estimation;
  estimation.setInputCloud(target);
  pcl::PointCloud<contour_reg::ContourCorner> corners;
  estimation.compute(corners);
  std::printf("special points in the target scan: %zu\n", corners.size());

  pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>::Ptr registration(
      new contour_reg::ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>());
  registration->setInputSource(source);
  registration->setInputTarget(target);
  Cloud aligned;
  registration->align(aligned);
  const Eigen::Matrix4f t = registration->getFinalTransformation();
  const double yaw = std::atan2(t(1, 0), t(0, 0));
  std::printf("converged %d: x %.4f y %.4f yaw %.4f\n", registration->hasConverged(), t(0, 3), t(1, 3), yaw);
  const bool ok = corners.size() >= 4 && registration->hasConverged() && std::abs(t(0, 3) - 0.3) < 0.02 &&
                  std::abs(t(1, 3) + 0.2) < 0.02 && std::abs(yaw - 0.2) < 0.01;
  std::printf("%s\n", ok ? "consumer: ok" : "consumer: wrong answer");
  return ok ? 0 : 1;
}
