// odometry(): a whole log chained into a trajectory by one method, with every step's result.
#include <sstream>

#include "bindings.h"
#include "contour_reg/odometry/odometry.h"

namespace contour_reg::python {

namespace {

odometry::OdometryRun runOdometry(const io::ScanLog &log, const std::string &method, const std::string &guess,
                                  bool keyframes, std::size_t local_map, bool deskew, const std::string &frame,
                                  bool wheel_fusion, const py::kwargs &settings) {
  const std::optional<odometry::Frame> frame_named = odometry::frameNamed(frame);
  if (!frame_named) throw py::value_error("unknown frame '" + frame + "' (" + listed(odometry::frameNames()) + ")");
  const std::optional<odometry::GuessSource> guess_named = odometry::guessSourceNamed(guess);
  if (!guess_named)
    throw py::value_error("unknown guess '" + guess + "' (" + listed(odometry::guessSourceNames()) + ")");
  odometry::OdometryOptions options;
  options.frame = *frame_named;
  options.guess = *guess_named;
  options.keyframes = keyframes;
  options.local_map_keyframes = local_map;
  options.deskew = deskew;
  options.fuse_wheel_odometry = wheel_fusion;
  std::unique_ptr<odometry::ScanMatcher> matcher = odometry::makeScanMatcher(method, matcherSettings(settings));
  if (!matcher) throw py::value_error("unknown method '" + method + "'; methods() lists them");
  py::gil_scoped_release release;
  return odometry::runOdometry(log, *matcher, options);
}

}  // namespace

void bindOdometry(py::module_ &m) {
  py::class_<odometry::OdometryStep>(m, "OdometryStep", "One registration of an odometry run.")
      .def_readonly("reference", &odometry::OdometryStep::reference, "index of the scan registered against")
      .def_readonly("scan", &odometry::OdometryStep::scan, "index of the scan registered")
      .def_readonly("converged", &odometry::OdometryStep::converged)
      .def_property_readonly(
          "status", [](const odometry::OdometryStep &s) { return s.converged ? std::string("converged") : s.status; })
      .def_property_readonly(
          "motion",
          [](const odometry::OdometryStep &s) { return py::make_tuple(s.motion.x, s.motion.y, s.motion.yaw); },
          "(x m, y m, yaw rad) from the reference scan to the scan, as chained (bridged when not converged)")
      .def_property_readonly(
          "covariance", [](const odometry::OdometryStep &s) { return matrixArray(s.covariance); },
          "3 x 3 covariance of the motion; zero when the method gives none or the step failed");

  py::class_<odometry::OdometryRun>(m, "OdometryRun", "A trajectory and the registrations it was chained from.")
      .def_property_readonly(
          "trajectory", [](const odometry::OdometryRun &r) { return trajectoryArray(r.trajectory); },
          "N x 4 (stamp, x, y, yaw): one pose per scan, the first at the origin")
      .def_readonly("steps", &odometry::OdometryRun::steps)
      .def_property_readonly(
          "frame",
          [](const odometry::OdometryRun &r) { return r.frame == odometry::Frame::kRobot ? "robot" : "laser"; },
          "'robot' or 'laser': the frame of trajectory and steps")
      .def_property_readonly("registrations", [](const odometry::OdometryRun &r) { return r.stats.registrations; })
      .def_property_readonly(
          "failures", [](const odometry::OdometryRun &r) { return r.stats.failures; },
          "registrations that did not converge (bridged by the wheel odometry and the previous motion, weighted by "
          "their record)")
      .def_property_readonly(
          "fused", [](const odometry::OdometryRun &r) { return r.stats.fused; },
          "registrations fused with the wheel odometry (wheel_fusion: all with guess 'odom', those that leave a "
          "direction free with another guess)")
      .def_property_readonly(
          "pinned_by_wheels", [](const odometry::OdometryRun &r) { return r.stats.pinned_by_wheels; },
          "of those, the ones whose scans left a direction free (a corridor's axis)")
      .def_property_readonly(
          "recovered_by_retry", [](const odometry::OdometryRun &r) { return r.stats.recovered_by_retry; },
          "registrations declined from the guess that converged on a retry: from the constant-velocity "
          "prediction, or, without wheel odometry, with the scan as taken")
      .def_property_readonly(
          "decided_by_prediction", [](const odometry::OdometryRun &r) { return r.stats.decided_by_prediction; },
          "ambiguous registrations (distinct motions fit the scans as well) where the motion predicted over the "
          "interval allows one of them alone: taken as converged")
      .def_property_readonly(
          "failure_reasons", [](const odometry::OdometryRun &r) { return r.stats.failure_reasons; }, "status -> count")
      .def_property_readonly(
          "milliseconds",
          [](const odometry::OdometryRun &r) {
            return py::array_t<double>(static_cast<py::ssize_t>(r.stats.milliseconds.size()),
                                       r.stats.milliseconds.data());
          },
          "wall time of each registration")
      .def("__repr__", [](const odometry::OdometryRun &r) {
        std::ostringstream out;
        out << "OdometryRun(" << r.trajectory.size() << " poses, " << r.stats.failures << " of "
            << r.stats.registrations << " registrations failed)";
        return out.str();
      });

  m.def("odometry", &runOdometry, py::arg("log"), py::arg("method") = "contour", py::arg("guess") = "zero",
        py::arg("keyframes") = false, py::arg("local_map") = 0, py::arg("deskew") = true, py::arg("frame") = "robot",
        py::arg("wheel_fusion") = true,
        "Laser odometry over a Log with `method` (see methods()): each scan registered against the previous one "
        "(or the last keyframe, or a local map of the last `local_map` keyframes), from a guess of 'zero', 'odom' (the "
        "log's wheel odometry) or 'velocity'. A failed "
        "registration is retried from the constant-velocity prediction, then bridged. deskew: scans with beam "
        "timing are deskewed by the motion over each (the wheel odometry when the log has it). frame: 'robot' gives "
        "the robot's trajectory when the log knows the laser's mounting (Log.laser_pose), 'laser' the laser's. "
        "wheel_fusion: with guess 'odom', each contour registration is fused with the wheels' increment by "
        "covariance, the wheels deciding the directions the scans leave free; with another guess, only those that "
        "leave a direction free (fused steps count as converged). "
        "Keyword settings as register(). Releases the GIL.");
}

}  // namespace contour_reg::python
