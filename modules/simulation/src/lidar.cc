#include "contour_reg/simulation/lidar.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace contour_reg::simulation {

LidarModel LidarModel::hokuyoUtm30lx() {
  LidarModel model;
  model.name = "hokuyo-utm30lx";
  return model;
}

LidarModel LidarModel::ydlidarX4() {
  LidarModel model;
  model.name = "ydlidar-x4";
  model.beams = 720;
  model.field_of_view = 2.0 * M_PI * (719.0 / 720.0);  // 0.5 deg steps all round
  model.range_min = 0.12;
  model.range_max = 10.0;
  model.range_noise = 0.02;
  model.dropout = 0.01;
  return model;
}

LidarModel LidarModel::sickLms200() {
  LidarModel model;
  model.name = "sick-lms200";
  model.beams = 181;
  model.field_of_view = M_PI;  // 1 deg steps
  model.range_min = 0.0;
  model.range_max = 80.0;
  model.range_noise = 0.01;
  model.range_resolution = 0.01;
  return model;
}

const std::vector<std::string> &lidarModelNames() {
  static const std::vector<std::string> names{"hokuyo", "ydlidar", "sick"};
  return names;
}

std::optional<LidarModel> lidarModelNamed(const std::string &name) {
  if (name == "hokuyo") return LidarModel::hokuyoUtm30lx();
  if (name == "ydlidar") return LidarModel::ydlidarX4();
  if (name == "sick") return LidarModel::sickLms200();
  return std::nullopt;
}

LaserScan simulateScan(const World &world, const Eigen::Isometry2d &pose, const LidarModel &model, std::mt19937 &rng) {
  return simulateScan(
      world, [&pose](std::size_t) { return pose; }, model, rng);
}

LaserScan simulateScan(const World &world, const std::function<Eigen::Isometry2d(std::size_t)> &pose_of_beam,
                       const LidarModel &model, std::mt19937 &rng) {
  LaserScan scan;
  scan.angle_min = -0.5 * model.field_of_view;
  scan.angle_increment = model.angleIncrement();
  scan.range_min = model.range_min;
  scan.range_max = model.range_max;
  scan.ranges.resize(static_cast<std::size_t>(std::max(model.beams, 0)));
  std::normal_distribution<double> noise(0.0, model.range_noise > 0.0 ? model.range_noise : 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (std::size_t n = 0; n < scan.ranges.size(); ++n) {
    const Eigen::Isometry2d pose = pose_of_beam(n);
    const double heading = std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
    const double angle = heading + scan.bearing(n);
    double range = world.castRay(pose.translation(), {std::cos(angle), std::sin(angle)});
    if (model.range_noise > 0.0 && std::isfinite(range)) range += noise(rng);
    if (model.dropout > 0.0 && uniform(rng) < model.dropout) range = std::numeric_limits<double>::infinity();
    if (model.range_resolution > 0.0 && std::isfinite(range))
      range = model.range_resolution * std::round(range / model.range_resolution);
    const bool valid = std::isfinite(range) && range >= model.range_min && range < model.range_max;
    scan.ranges[n] = valid ? static_cast<float>(range) : std::numeric_limits<float>::quiet_NaN();
  }
  return scan;
}

}  // namespace contour_reg::simulation
