// Logs: read_log() for every reader, the Log class, and TUM, relation and CARMEN files.
#include <cmath>
#include <limits>
#include <sstream>

#include "bindings.h"
#include "contour_reg/io/carmen.h"
#include "contour_reg/io/read_log.h"

namespace contour_reg::python {

namespace {

io::ScanLog makeLog(const std::vector<LaserScan> &scans, const py::object &odometry) {
  io::ScanLog log;
  log.source = "python";
  for (const LaserScan &scan : scans) log.entries.push_back({scan, std::nullopt});
  if (!odometry.is_none()) {
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(odometry);
    if (!a || a.ndim() != 2 || a.shape(1) != 3 || static_cast<std::size_t>(a.shape(0)) != scans.size())
      throw py::value_error("odometry must be an N x 3 array (x m, y m, yaw rad), one row per scan, NaN: none");
    const auto v = a.unchecked<2>();
    for (std::size_t n = 0; n < scans.size(); ++n)
      if (std::isfinite(v(n, 0)) && std::isfinite(v(n, 1)) && std::isfinite(v(n, 2)))
        log.entries[n].odometry = io::Pose2D{v(n, 0), v(n, 1), v(n, 2)};
  }
  for (std::size_t n = 1; n < log.entries.size(); ++n)
    if (log.entries[n].scan.stamp < log.entries[n - 1].scan.stamp)
      throw py::value_error("scans must be in stamp order (scan " + std::to_string(n) +
                            " is earlier than the one before)");
  return log;
}

py::array_t<double> odometryArray(const io::ScanLog &log) {
  py::array_t<double> out({static_cast<py::ssize_t>(log.entries.size()), py::ssize_t(3)});
  auto o = out.mutable_unchecked<2>();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t n = 0; n < log.entries.size(); ++n) {
    const auto &pose = log.entries[n].odometry;
    o(n, 0) = pose ? pose->x : nan;
    o(n, 1) = pose ? pose->y : nan;
    o(n, 2) = pose ? pose->yaw : nan;
  }
  return out;
}

const LaserScan &scanAt(const io::ScanLog &log, py::ssize_t index) {
  const auto size = static_cast<py::ssize_t>(log.entries.size());
  if (index < 0) index += size;
  if (index < 0 || index >= size) throw py::index_error("scan index out of range");
  return log.entries[static_cast<std::size_t>(index)].scan;
}

py::array_t<double> relationsArray(const std::vector<io::Relation> &relations) {
  py::array_t<double> out({static_cast<py::ssize_t>(relations.size()), py::ssize_t(5)});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t n = 0; n < relations.size(); ++n) {
    const io::Relation &r = relations[n];
    o(n, 0) = r.t1;
    o(n, 1) = r.t2;
    o(n, 2) = r.motion.x;
    o(n, 3) = r.motion.y;
    o(n, 4) = r.motion.yaw;
  }
  return out;
}

}  // namespace

py::object poseOrNone(const std::optional<io::Pose2D> &pose) {
  return pose ? py::object(py::make_tuple(pose->x, pose->y, pose->yaw)) : py::object(py::none());
}

std::optional<io::Pose2D> mountingFrom(const py::object &value, const char *what) {
  if (value.is_none()) return std::nullopt;
  std::vector<double> v;
  try {
    v = value.cast<std::vector<double>>();
  } catch (const py::cast_error &) {
  }
  if (v.size() != 3 || !io::isMounting({v[0], v[1], v[2]}))
    throw py::value_error(std::string(what) +
                          " must be None or (x m, y m, yaw rad), finite, within 100 m of the robot and 2 pi rad");
  return io::Pose2D{v[0], v[1], v[2]};
}

void bindLogs(py::module_ &m) {
  py::class_<io::ScanLog>(m, "Log",
                          "A log of scans in stamp order, with the wheel odometry (or the log's own pose) at each.")
      .def(py::init(&makeLog), py::arg("scans"), py::arg("odometry") = py::none(),
           "A log from LaserScans in stamp order and, optionally, an N x 3 array of poses (NaN rows: none).")
      .def_readonly("source", &io::ScanLog::source, "the file it was read from")
      .def("__len__", [](const io::ScanLog &log) { return log.entries.size(); })
      .def("__getitem__", &scanAt, py::return_value_policy::copy, py::arg("index"))
      .def_property_readonly(
          "stamps",
          [](const io::ScanLog &log) {
            py::array_t<double> a(static_cast<py::ssize_t>(log.entries.size()));
            for (std::size_t n = 0; n < log.entries.size(); ++n) a.mutable_at(n) = log.entries[n].scan.stamp;
            return a;
          },
          "s, every scan's stamp")
      .def_property_readonly("odometry", &odometryArray,
                             "N x 3 (x m, y m, yaw rad) wheel odometry at every scan, or the pose the log carries; "
                             "NaN rows where there is none")
      .def_property_readonly(
          "wheel_odometry", [](const io::ScanLog &log) { return trajectoryArray(log.wheel_odometry); },
          "N x 4 (stamp s, x m, y m, yaw rad): every wheel odometry sample of the log (ODOM lines, "
          "nav_msgs/Odometry messages, the simulator's 50 Hz odometry), between the scans too; deskewing "
          "follows them within each sweep")
      .def_property(
          "laser_pose", [](const io::ScanLog &log) { return poseOrNone(log.laser_pose); },
          [](io::ScanLog &log, const py::object &value) { log.laser_pose = mountingFrom(value, "laser_pose"); },
          "(x m, y m, yaw rad): the laser's pose on the robot (base_link -> laser), when the log says (ROBOTLASER1 "
          "lines, a bag's tf) or it is set; None: unknown, odometry then takes the laser to be at the centre")
      .def_property_readonly(
          "skipped", [](const io::ScanLog &log) { return log.report.skipped; }, "bad or truncated lines skipped")
      .def_property_readonly(
          "problems", [](const io::ScanLog &log) { return log.report.problems; },
          "'file:line: what' for the first skipped lines")
      .def("__repr__", [](const io::ScanLog &log) {
        std::ostringstream out;
        out << "Log(" << log.entries.size() << " scans from " << log.source << ")";
        return out.str();
      });

  m.def(
      "read_log",
      [](const std::string &path, double max_range, const std::string &scan_topic, const std::string &odom_topic,
         double scan_period, const py::object &laser_pose, bool wheel_odometry, long beam_step) {
        if (beam_step < 1) throw py::value_error("beam_step must be >= 1");  // the rest: readLog
        io::LogReadOptions options;
        options.beam_step = static_cast<std::size_t>(beam_step);
        options.laser_pose = mountingFrom(laser_pose, "laser_pose");
        options.scan_period = scan_period;
        options.max_range = max_range;
        options.scan_topic = scan_topic;
        options.odometry_topic = odom_topic;
        options.wheel_odometry = wheel_odometry;
        py::gil_scoped_release release;
        return io::readLog(path, options);
      },
      py::arg("path"), py::arg("max_range") = io::LogReadOptions{}.max_range, py::arg("scan_topic") = "",
      py::arg("odom_topic") = "", py::arg("scan_period") = 0.0, py::arg("laser_pose") = py::none(),
      py::arg("wheel_odometry") = true, py::arg("beam_step") = 1,
      "Reads a CARMEN log (plain or gzip), a ROS 1 bag, a ROS 2 bag (its folder, a .db3 or a .mcap file, compressed by "
      "rosbag2 or not) or a folder of PCD scans. Readings at or above max_range (m) "
      "are no-return; bags: the LaserScan and Odometry topics ('' : the first); scan_period: s per LIDAR turn for "
      "scans without beam timing (beams in index order from the stamp; 0: none); laser_pose: (x m, y m, yaw rad) "
      "of the laser on the robot, over what the log says; wheel_odometry=False: the scans alone, without the log's "
      "wheel odometry and poses (as from a LIDAR without wheels); beam_step: keep every beam_step-th beam from the "
      "first (a LIDAR with that many times the angular step). Raises ReadError naming the file "
      "(and line) when it cannot be used; bad lines it can skip are counted in Log.skipped.");
  m.def(
      "write_carmen", [](const std::string &path, const io::ScanLog &log) { io::writeCarmen(path, log); },
      py::arg("path"), py::arg("log"), "Writes a log as a CARMEN log (FLASER and ODOM lines).");
  m.def(
      "write_log",
      [](const std::string &path, const io::ScanLog &log) {
        py::gil_scoped_release release;
        io::writeLog(path, log);
      },
      py::arg("path"), py::arg("log"),
      "Writes a log in the format its name asks for: a ROS 1 bag (.bag), a ROS 2 bag's storage file (.db3: sqlite3, "
      ".mcap: MCAP, which a viewer such as Foxglove opens) or a CARMEN log (any other name); scans with their beam "
      "timing, the wheel odometry and the laser's mounting. Raises ReadError naming the file when it cannot be "
      "written.");
  m.def(
      "read_tum", [](const std::string &path) { return trajectoryArray(io::readTum(path)); }, py::arg("path"),
      "Reads a TUM trajectory as N x 4 (stamp, x, y, yaw). Raises ReadError naming file and line.");
  m.def(
      "write_tum",
      [](const std::string &path, const py::handle &trajectory) {
        io::writeTum(path, trajectoryOf(trajectory, "trajectory"));
      },
      py::arg("path"), py::arg("trajectory"), "Writes an N x 4 (stamp, x, y, yaw) trajectory in TUM format.");
  m.def(
      "read_relations", [](const std::string &path) { return relationsArray(io::readRelations(path)); },
      py::arg("path"),
      "Reads a relations file (Kümmerle et al. 2009) as N x 5 (t1, t2, x, y, yaw): the pose at t2 in the frame of "
      "the pose at t1. Raises ReadError naming file and line.");
}

}  // namespace contour_reg::python
