#include <cmath>
#include <functional>
#include <map>
#include <string>

#include "bindings.h"
#include "contour_reg/core/laser_scan.h"

namespace contour_reg::python {

std::string listed(const std::vector<std::string> &names) {
  std::string text;
  for (const std::string &name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

odometry::Cloud::Ptr beamsOf(const py::handle &scan, const Twist2D &twist) {
  if (py::isinstance<LaserScan>(scan)) return odometry::beamCloud(scan.cast<const LaserScan &>(), twist);
  if (!twist.isZero()) throw py::value_error("a twist deskews a LaserScan with time_increment, not points");
  if (py::isinstance<py::str>(scan) || (!py::isinstance<py::array>(scan) && !py::isinstance<py::sequence>(scan)))
    throw py::type_error("a scan is a LaserScan or an N x 2 array of points");
  const auto points = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(scan);
  if (!points || points.ndim() != 2 || points.shape(1) != 2)
    throw py::value_error("a scan given as points must be an N x 2 array (x, y in metres; NaN rows: invalid beams)");
  auto cloud = pcl::make_shared<odometry::Cloud>();
  const auto p = points.unchecked<2>();
  cloud->reserve(static_cast<std::size_t>(p.shape(0)));
  for (py::ssize_t n = 0; n < p.shape(0); ++n) {
    const bool valid = std::isfinite(p(n, 0)) && std::isfinite(p(n, 1));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    cloud->push_back(valid ? pcl::PointXYZ(float(p(n, 0)), float(p(n, 1)), 0.f) : pcl::PointXYZ(nan, nan, nan));
  }
  cloud->is_dense = false;
  return cloud;
}

odometry::MatcherSettings matcherSettings(const py::kwargs &settings) {
  using Settings = odometry::MatcherSettings;
  // name -> how it sets the value, as the command line's options of the same names.
  static const std::map<std::string, std::function<void(Settings &, const py::handle &)>> setters{
      {"contour_step", [](Settings &s, const py::handle &v) { s.contour.equalization.step = v.cast<double>(); }},
      {"threshold", [](Settings &s, const py::handle &v) { s.contour.special_points.threshold = v.cast<double>(); }},
      {"arm", [](Settings &s, const py::handle &v) { s.contour.corner_filter.arm_elements = v.cast<int>(); }},
      {"candidates",
       [](Settings &s, const py::handle &v) { s.registration.correspondence.candidates_per_point = v.cast<int>(); }},
      {"local_fallback",
       [](Settings &s, const py::handle &v) { s.registration.local_fallback_min_overlap = v.cast<double>(); }},
      {"probe_distance", [](Settings &s, const py::handle &v) { s.registration.probe_distance = v.cast<double>(); }},
      {"free_space", [](Settings &s, const py::handle &v) { s.registration.free_space.enabled = v.cast<bool>(); }},
      {"icp_max_distance", [](Settings &s, const py::handle &v) { s.icp_max_correspondence = v.cast<double>(); }},
      {"ndt_resolution", [](Settings &s, const py::handle &v) { s.ndt_resolution = v.cast<double>(); }},
      {"iterations", [](Settings &s, const py::handle &v) { s.icp_iterations = v.cast<int>(); }},
  };
  Settings s;
  for (const auto &[key, value] : settings) {
    const std::string name = key.cast<std::string>();
    const auto setter = setters.find(name);
    if (setter == setters.end()) {
      std::string known;
      for (const auto &[n, unused] : setters) known += (known.empty() ? "" : ", ") + n;
      throw py::type_error("unknown setting '" + name + "' (settings: " + known + ")");
    }
    setter->second(s, value);
  }
  std::string why;
  if (!s.contour.validate(&why) || !s.registration.validate(&why)) throw py::value_error("invalid setting: " + why);
  if (s.icp_max_correspondence && !(*s.icp_max_correspondence > 0.0))
    throw py::value_error("invalid setting: icp_max_distance must be > 0 m");
  if (!(s.ndt_resolution >= 0.05)) throw py::value_error("invalid setting: ndt_resolution must be >= 0.05 m");
  if (s.icp_iterations < 1) throw py::value_error("invalid setting: iterations must be >= 1");
  return s;
}

py::array_t<double> pointsArray(const std::vector<Eigen::Vector2d> &points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t(2)});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t n = 0; n < points.size(); ++n) {
    o(n, 0) = points[n].x();
    o(n, 1) = points[n].y();
  }
  return out;
}

py::array_t<double> matrixArray(const Eigen::Matrix3d &m) {
  py::array_t<double> out({py::ssize_t(3), py::ssize_t(3)});
  auto o = out.mutable_unchecked<2>();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) o(r, c) = m(r, c);
  return out;
}

Eigen::Matrix3d matrixOf(const py::handle &array, const char *what) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 2 || a.shape(0) != 3 || a.shape(1) != 3)
    throw py::value_error(std::string(what) + " must be a 3 x 3 array");
  const auto v = a.unchecked<2>();
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = v(r, c);
  if (!m.allFinite()) throw py::value_error(std::string(what) + " must be finite");
  return m;
}

Eigen::Matrix3d rigidMatrixOf(const py::handle &array, const char *what) {
  const Eigen::Matrix3d m = matrixOf(array, what);
  const Eigen::Matrix2d rotation = m.topLeftCorner<2, 2>();
  // Tolerances that take a transform computed in single precision (PCL's), not a scaled one.
  constexpr double kTolerance = 1e-5;
  const bool rigid =
      m.row(2).isApprox(Eigen::RowVector3d(0.0, 0.0, 1.0), kTolerance) &&
      (rotation.transpose() * rotation - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff() <= kTolerance &&
      rotation.determinant() > 0.0;
  if (!rigid)
    throw py::value_error(
        std::string(what) +
        " must be a rigid motion: a 3 x 3 homogeneous transform with a rotation block and last row 0 0 1");
  return m;
}

py::array_t<double> trajectoryArray(const io::Trajectory &trajectory) {
  py::array_t<double> out({static_cast<py::ssize_t>(trajectory.size()), py::ssize_t(4)});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t n = 0; n < trajectory.size(); ++n) {
    o(n, 0) = trajectory[n].stamp;
    o(n, 1) = trajectory[n].pose.x;
    o(n, 2) = trajectory[n].pose.y;
    o(n, 3) = trajectory[n].pose.yaw;
  }
  return out;
}

io::Trajectory trajectoryOf(const py::handle &array, const char *what) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 2 || a.shape(1) != 4)
    throw py::value_error(std::string(what) + " must be an N x 4 array (stamp s, x m, y m, yaw rad)");
  const auto v = a.unchecked<2>();
  io::Trajectory trajectory(static_cast<std::size_t>(v.shape(0)));
  for (py::ssize_t n = 0; n < v.shape(0); ++n) {
    if (!std::isfinite(v(n, 0) + v(n, 1) + v(n, 2) + v(n, 3)))
      throw py::value_error(std::string(what) + " must be finite: row " + std::to_string(n) + " is not");
    trajectory[n] = {v(n, 0), {v(n, 1), v(n, 2), v(n, 3)}};
  }
  return trajectory;
}

}  // namespace contour_reg::python
