// Uses the installed package the way a PCL pipeline would: the Feature class on a scan of
// a room, ContourRegistration through pcl::Registration's interface, and the pattern of a
// ROS callback that refills its clouds in place, checked against the core API.
#include <cmath>
#include <cstdio>
#include <random>

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

// The core API on the same scans: what the PCL class must reproduce.
Eigen::Matrix3d coreMotion(const Cloud &target, const Cloud &source) {
  const contour_reg::ContourFeatures t =
      contour_reg::extractContourFeatures(contour_reg::polarCodeFromCloud(target), {});
  const contour_reg::ContourFeatures s =
      contour_reg::extractContourFeatures(contour_reg::polarCodeFromCloud(source), {});
  std::mt19937 rng(42);
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const contour_reg::RegistrationResult result = contour_reg::registerContours(s, t, {}, rng, &identity);
  return result.converged ? result.transform : Eigen::Matrix3d::Constant(std::nan(""));
}

Eigen::Matrix3d planar(const Eigen::Matrix4f &t) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  m.topLeftCorner<2, 2>() = t.topLeftCorner<2, 2>().cast<double>();
  m.topRightCorner<2, 1>() = t.block<2, 1>(0, 3).cast<double>();
  return m;
}

}  // namespace

int main() {
  bool ok = true;
  const Cloud::Ptr target = roomScan(0, 0, 0), source = roomScan(0.3, -0.2, 0.2);

  // The Feature: one output point per scan point, the corners at getCornerIndices().
  contour_reg::ContourCornerEstimation<pcl::PointXYZ> estimation;
  estimation.setInputCloud(target);
  pcl::PointCloud<contour_reg::ContourCorner> corners;
  estimation.compute(corners);
  std::printf("special points in the target scan: %zu\n", estimation.getCornerIndices().size());
  ok = ok && corners.size() == target->size() && estimation.getCornerIndices().size() >= 4;

  pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>::Ptr registration(
      new contour_reg::ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>());
  registration->setInputSource(source);
  registration->setInputTarget(target);
  Cloud aligned;
  registration->align(aligned);
  const Eigen::Matrix4f t = registration->getFinalTransformation();
  const double yaw = std::atan2(t(1, 0), t(0, 0));
  std::printf("converged %d: x %.4f y %.4f yaw %.4f\n", registration->hasConverged(), t(0, 3), t(1, 3), yaw);
  ok = ok && registration->hasConverged() && std::abs(t(0, 3) - 0.3) < 0.02 && std::abs(t(1, 3) + 0.2) < 0.02 &&
       std::abs(yaw - 0.2) < 0.01;

  // A ROS callback's pattern: two cloud objects refilled in place for every scan and set
  // again. Every step must match the core API on the same scans.
  auto previous = pcl::make_shared<Cloud>(), current = pcl::make_shared<Cloud>();
  *current = *roomScan(-0.5, 0.0, 0.0);
  Eigen::Matrix3d pose = Eigen::Matrix3d::Identity(), core_pose = Eigen::Matrix3d::Identity();
  for (int k = 1; k <= 8; ++k) {
    *previous = *current;
    *current = *roomScan(-0.5 + 0.15 * k, 0.03 * k, 0.03 * k);
    registration->setInputTarget(previous);
    registration->setInputSource(current);
    registration->align(aligned);
    ok = ok && registration->hasConverged();
    pose = pose * planar(registration->getFinalTransformation());
    core_pose = core_pose * coreMotion(*previous, *current);
  }
  const double end_yaw = std::atan2(pose(1, 0), pose(0, 0));
  std::printf("refilled in place, 8 steps: x %.4f y %.4f yaw %.4f (true 1.2000 0.2400 0.2400)\n", pose(0, 2),
              pose(1, 2), end_yaw);
  ok = ok && (pose - core_pose).cwiseAbs().maxCoeff() < 1e-4 && std::abs(pose(0, 2) - 1.2) < 0.03 &&
       std::abs(pose(1, 2) - 0.24) < 0.03 && std::abs(end_yaw - 0.24) < 0.01;

  std::printf("%s\n", ok ? "consumer: ok" : "consumer: wrong answer");
  return ok ? 0 : 1;
}
