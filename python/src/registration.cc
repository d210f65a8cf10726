// register(): one scan pair with any of the methods, and the result as Python sees it.
#include <cmath>
#include <sstream>

#include <pcl/console/print.h>

#include "bindings.h"
#include "contour_reg/core/laser_scan.h"

namespace contour_reg::python {

namespace {

std::string methodList() {
  std::string names;
  for (const std::string &n : odometry::methodNames()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

// The motion the judge did not take as a 3 x 3 array when the registration `converged` as
// asked (the declined one: not converged; the rival: converged), else None.
py::object rejectedOrNone(const odometry::MatchResult &r, bool converged) {
  return r.rejected && r.converged == converged ? py::object(matrixArray(*r.rejected)) : py::object(py::none());
}

// (vx m/s, vy m/s, wz rad/s), or none.
Twist2D twistOf(const py::object &twist, const char *name) {
  if (twist.is_none()) return {};
  const auto v = twist.cast<std::vector<double>>();
  if (v.size() != 3 || !std::isfinite(v[0] + v[1] + v[2]))
    throw py::value_error(std::string(name) + " must be 3 finite numbers: vx (m/s), vy (m/s), wz (rad/s)");
  return {v[0], v[1], v[2]};
}

odometry::MatchResult registerPair(const py::handle &source, const py::handle &target, const std::string &method,
                                   const py::object &guess, const py::object &source_twist,
                                   const py::object &target_twist, const py::kwargs &settings) {
  const odometry::MatcherSettings s = matcherSettings(settings);
  const Eigen::Matrix3d start = guess.is_none() ? Eigen::Matrix3d::Identity() : rigidMatrixOf(guess, "guess");
  std::unique_ptr<odometry::ScanMatcher> matcher = odometry::makeScanMatcher(method, s);
  if (!matcher) throw py::value_error("unknown method '" + method + "' (methods: " + methodList() + ")");
  const odometry::Cloud::Ptr source_beams = beamsOf(source, twistOf(source_twist, "source_twist")),
                             target_beams = beamsOf(target, twistOf(target_twist, "target_twist"));
  py::gil_scoped_release release;  // every call has its own matcher: threads run side by side
  return matcher->match(target_beams, source_beams, start);
}

}  // namespace

void bindRegistration(py::module_ &m) {
  // PCL's classes print a line for each pair they fail on; results say it instead.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  py::class_<odometry::MatchResult>(m, "RegistrationResult", "The outcome of one registration.")
      .def_property_readonly(
          "transform", [](const odometry::MatchResult &r) { return matrixArray(r.transform); },
          "3 x 3 homogeneous transform mapping source points into the target frame (the guess when not converged)")
      .def_property_readonly(
          "pose",
          [](const odometry::MatchResult &r) {
            return py::make_tuple(r.transform(0, 2), r.transform(1, 2),
                                  std::atan2(r.transform(1, 0), r.transform(0, 0)));
          },
          "(x m, y m, yaw rad): the source sensor's pose in the target frame")
      .def_readonly("converged", &odometry::MatchResult::converged, "True when the method vouches for the transform")
      .def_property_readonly(
          "status", [](const odometry::MatchResult &r) { return r.converged ? std::string("converged") : r.status; },
          "'converged', or the verdict: too_few_special_points, low_overlap, unconstrained, ambiguous, contradicted, "
          "...")
      .def_readonly("reason", &odometry::MatchResult::reason, "why not converged, in words ('' when converged)")
      .def_readonly("degenerate", &odometry::MatchResult::degenerate, "a direction of the motion is unconstrained")
      .def_property_readonly(
          "covariance", [](const odometry::MatchResult &r) { return matrixArray(r.covariance); },
          "3 x 3 covariance of (x, y, yaw), m^2 and rad^2; zero when the method gives none")
      .def_property_readonly(
          "declined", [](const odometry::MatchResult &r) { return rejectedOrNone(r, false); },
          "contour methods, not converged: the 3 x 3 transform of the best motion weighed and declined; "
          "None when none was weighed")
      .def_property_readonly(
          "rival", [](const odometry::MatchResult &r) { return rejectedOrNone(r, true); },
          "contour methods, converged: the 3 x 3 transform of the best-scoring distinct motion the judge weighed "
          "and did not take; None when it met none")
      .def_property_readonly(
          "alternatives",
          [](const odometry::MatchResult &r) {
            py::list motions;
            for (const RejectedMotion &motion : r.alternatives)
              motions.append(py::make_tuple(matrixArray(motion.transform), matrixArray(motion.covariance)));
            return motions;
          },
          "contour methods, ambiguous: the distinct motions that fit the scans about as well, each a "
          "(3 x 3 transform, 3 x 3 covariance of x, y, yaw) pair; empty for every other status")
      .def_readonly("overlap", &odometry::MatchResult::overlap,
                    "the contour method, converged: the share of the source contour on the target contour; "
                    "None otherwise")
      .def_readonly("score", &odometry::MatchResult::score,
                    "the contour method, converged: the judge's score of the answer, its overlap less the share of "
                    "both contours in the other scan's free space; None otherwise")
      .def_readonly("inliers", &odometry::MatchResult::inliers,
                    "contour methods: the special-point pairs the motion rests on")
      .def_readonly("milliseconds", &odometry::MatchResult::milliseconds, "wall time of the registration")
      .def("__repr__", [](const odometry::MatchResult &r) {
        std::ostringstream out;
        out << "RegistrationResult(" << (r.converged ? "converged" : r.status) << ", x " << r.transform(0, 2)
            << " m, y " << r.transform(1, 2) << " m, yaw " << std::atan2(r.transform(1, 0), r.transform(0, 0))
            << " rad)";
        return out.str();
      });

  m.def("methods", &odometry::methodNames, "The method names register() and odometry() take.");
  m.def("register", &registerPair, py::arg("source"), py::arg("target"), py::arg("method") = "contour",
        py::arg("guess") = py::none(), py::arg("source_twist") = py::none(), py::arg("target_twist") = py::none(),
        "Registers `source` onto `target` (each a LaserScan or N x 2 points in beam order, NaN rows for invalid "
        "beams) with `method` (see methods()), from `guess` (3 x 3, source to target; None: identity). "
        "source_twist / target_twist: (vx m/s, vy m/s, wz rad/s), the sensor's velocity over a LaserScan's sweep: "
        "a scan with time_increment is deskewed by it first. Keyword "
        "settings: contour_step (m), threshold, arm, candidates, local_fallback, probe_distance (m), free_space, "
        "icp_max_distance (m), ndt_resolution (m), iterations. Releases the GIL while it registers.");
}

}  // namespace contour_reg::python
