// LaserScan as a Python class, and features(): the special points and equalized contours of a scan.
#include <cmath>
#include <sstream>

#include "bindings.h"
#include "contour_reg/core/contour.h"
#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/laser_scan.h"

namespace contour_reg::python {

namespace {

py::array_t<float> rangesArray(const LaserScan &scan) {
  return py::array_t<float>(static_cast<py::ssize_t>(scan.ranges.size()), scan.ranges.data());
}

void setRanges(LaserScan &scan, const py::handle &ranges) {
  const auto r = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(ranges);
  if (!r || r.ndim() != 1) throw py::value_error("ranges must be a 1-D array (m; NaN, inf or 0: no return)");
  scan.ranges.assign(r.data(), r.data() + r.size());
}

// The beam geometry, checked the same way by the constructor and by the attributes' setters.
void setAngleMin(LaserScan &scan, double angle_min) {
  if (!std::isfinite(angle_min)) throw py::value_error("angle_min must be finite (rad)");
  scan.angle_min = angle_min;
}

void setAngleIncrement(LaserScan &scan, double angle_increment) {
  if (!std::isfinite(angle_increment) || angle_increment == 0.0)
    throw py::value_error("angle_increment must be finite and not 0 (rad)");
  scan.angle_increment = angle_increment;
}

void setTimeIncrement(LaserScan &scan, double time_increment) {
  if (!(std::isfinite(time_increment) && time_increment >= 0.0))
    throw py::value_error("time_increment must be finite and >= 0 s");
  scan.time_increment = time_increment;
}

LaserScan makeScan(const py::handle &ranges, double angle_min, double angle_increment, double stamp, double range_min,
                   double range_max, double time_increment) {
  LaserScan scan;
  setAngleMin(scan, angle_min);
  setAngleIncrement(scan, angle_increment);
  setTimeIncrement(scan, time_increment);
  setRanges(scan, ranges);
  scan.stamp = stamp;
  scan.range_min = range_min;
  scan.range_max = range_max;
  return scan;
}

// A scan from ranges and the bearing of each beam, which must be evenly spaced.
LaserScan scanFromAngles(const py::handle &ranges, const py::handle &angles, double stamp, double range_min,
                         double range_max, double time_increment) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(angles);
  if (!a || a.ndim() != 1 || a.size() < 2) throw py::value_error("angles must be a 1-D array of two bearings or more");
  const auto v = a.unchecked<1>();
  const double increment = (v(a.size() - 1) - v(0)) / double(a.size() - 1);
  for (py::ssize_t n = 0; n < a.size(); ++n)
    if (!(std::abs(v(n) - (v(0) + double(n) * increment)) <= 0.01 * std::abs(increment)))  // 1 % of a step
      throw py::value_error("angles must be evenly spaced (beam " + std::to_string(n) +
                            " is off); give such scans as N x 2 points instead");
  LaserScan scan = makeScan(ranges, v(0), increment, stamp, range_min, range_max, time_increment);
  if (scan.ranges.size() != static_cast<std::size_t>(a.size()))
    throw py::value_error("ranges and angles must have the same length");
  return scan;
}

py::array_t<double> scanPoints(const LaserScan &scan) {
  std::vector<Eigen::Vector2d> points;
  for (const Complex &c : polarCode(scan)) points.push_back(toEigen(c));  // NaN stays NaN
  return pointsArray(points);
}

// What stages A-C found, as arrays.
struct Features {
  py::array_t<double> points, corner_angles, orientations, responses;
  py::array_t<int> turns;
  py::list contours;
};

Features features(const py::handle &scan, const py::kwargs &settings) {
  const ContourParams params = matcherSettings(settings).contour;
  ContourFeatures f;
  if (py::isinstance<LaserScan>(scan)) {
    const LaserScan &s = scan.cast<const LaserScan &>();
    py::gil_scoped_release release;
    f = extractContourFeatures(s, params);
  } else {
    const odometry::Cloud::Ptr beams = beamsOf(scan);
    ComplexSequence code;
    code.reserve(beams->size());
    for (const auto &p : *beams) code.emplace_back(p.x, p.y);
    py::gil_scoped_release release;
    f = extractContourFeatures(code, params);
  }
  Features out;
  const auto n = static_cast<py::ssize_t>(f.special_points.size());
  std::vector<Eigen::Vector2d> positions;
  out.corner_angles = py::array_t<double>(n);
  out.orientations = py::array_t<double>(n);
  out.responses = py::array_t<double>(n);
  out.turns = py::array_t<int>(n);
  for (py::ssize_t k = 0; k < n; ++k) {
    const SpecialPoint &p = f.special_points[k];
    positions.push_back(p.position);
    out.corner_angles.mutable_at(k) = p.corner_angle;
    out.orientations.mutable_at(k) = p.orientation;
    out.responses.mutable_at(k) = p.response;
    out.turns.mutable_at(k) = p.turn;
  }
  out.points = pointsArray(positions);
  for (const EqualizedContour &c : f.contours) {
    std::vector<Eigen::Vector2d> vertices;
    for (const Complex &q : c.vertices) vertices.push_back(toEigen(q));
    out.contours.append(pointsArray(vertices));
  }
  return out;
}

}  // namespace

void bindScans(py::module_ &m) {
  py::class_<LaserScan>(m, "LaserScan",
                        "One 2-D LIDAR scan in the shape of sensor_msgs/LaserScan: beam n at bearing angle_min + n * "
                        "angle_increment (rad), ranges in m; NaN, inf, 0 and readings outside [range_min, range_max) "
                        "are invalid beams.")
      .def(py::init(&makeScan), py::arg("ranges"), py::arg("angle_min"), py::arg("angle_increment"),
           py::arg("stamp") = 0.0, py::arg("range_min") = 0.0, py::arg("range_max") = 0.0,
           py::arg("time_increment") = 0.0,
           "A scan from its ranges (m) and beam geometry (rad); range_max 0: no limit; time_increment: s between "
           "beams of a moving sensor (0: all at the stamp).")
      .def_static("from_angles", &scanFromAngles, py::arg("ranges"), py::arg("angles"), py::arg("stamp") = 0.0,
                  py::arg("range_min") = 0.0, py::arg("range_max") = 0.0, py::arg("time_increment") = 0.0,
                  "A scan from ranges (m) and the bearing of each beam (rad, evenly spaced; ValueError otherwise).")
      .def_readwrite("stamp", &LaserScan::stamp, "s, when beam 0 was taken")
      .def_property(
          "angle_min", [](const LaserScan &s) { return s.angle_min; }, &setAngleMin, "rad, bearing of beam 0")
      .def_property(
          "angle_increment", [](const LaserScan &s) { return s.angle_increment; }, &setAngleIncrement,
          "rad between consecutive beams (finite, not 0)")
      .def_readwrite("range_min", &LaserScan::range_min, "m, readings below are invalid")
      .def_readwrite("range_max", &LaserScan::range_max, "m, readings at or above are invalid (0: no limit)")
      .def_property(
          "time_increment", [](const LaserScan &s) { return s.time_increment; }, &setTimeIncrement,
          "s between consecutive beams (0: none)")
      .def_property("ranges", &rangesArray, &setRanges, "m, one per beam (a copy; assign an array to change them)")
      .def(
          "angles",
          [](const LaserScan &s) {
            py::array_t<double> a(static_cast<py::ssize_t>(s.ranges.size()));
            for (std::size_t n = 0; n < s.ranges.size(); ++n) a.mutable_at(n) = s.bearing(n);
            return a;
          },
          "The bearing of every beam, rad.")
      .def("points", &scanPoints, "N x 2 points in the sensor frame (m), beam order, NaN rows for invalid beams.")
      .def("__len__", [](const LaserScan &s) { return s.ranges.size(); })
      .def("__repr__", [](const LaserScan &s) {
        std::ostringstream out;
        out << "LaserScan(" << s.ranges.size() << " beams, stamp " << s.stamp << " s)";
        return out.str();
      });

  py::class_<Features>(m, "Features", "What stages A-C of the contour method found in one scan.")
      .def_readonly("points", &Features::points, "N x 2 corner vertices (special points) in the sensor frame, m")
      .def_readonly("corner_angles", &Features::corner_angles, "rad, angle between each corner's arms (pi: straight)")
      .def_readonly("orientations", &Features::orientations, "rad, direction of each corner's bisector")
      .def_readonly("responses", &Features::responses, "the matched filter's response c(n) at each corner, 0-1")
      .def_readonly("turns", &Features::turns, "+1 left, -1 right turn along the contour (beam order)")
      .def_readonly("contours", &Features::contours, "the equalized contours, one M x 2 array of vertices each")
      .def("__len__", [](const Features &f) { return f.points.shape(0); });

  m.def("features", &features, py::arg("scan"),
        "The special points (corners) and equalized contours of a scan (a LaserScan or N x 2 points). Keyword "
        "settings: contour_step (m), threshold, arm.");
}

}  // namespace contour_reg::python
