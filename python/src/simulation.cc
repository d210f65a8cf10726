// simulate(): a LIDAR log with wheel odometry and ground truth along a path through a map.
#include <memory>

#include "bindings.h"
#include "contour_reg/simulation/occupancy_grid.h"
#include "contour_reg/simulation/office.h"
#include "contour_reg/simulation/paths.h"
#include "contour_reg/simulation/simulated_run.h"

namespace contour_reg::python {

namespace {

simulation::SimulatedRun simulate(const std::string &path, double rate, const std::string &map, double resolution,
                                  const std::string &lidar, const std::string &motion, double speed,
                                  double odometry_noise, unsigned seed, const py::object &waypoints,
                                  const py::object &laser_pose, int people) {
  if (!(rate > 0.0) || !(speed > 0.0) || !(odometry_noise >= 0.0) || !(resolution > 0.0) || people < 0)
    throw py::value_error("rate (Hz), speed (m/s) and resolution (m) must be > 0, odometry_noise and people >= 0");
  simulation::RunSettings settings;
  const std::optional<simulation::LidarModel> model = simulation::lidarModelNamed(lidar);
  if (!model) throw py::value_error("unknown lidar '" + lidar + "' (" + listed(simulation::lidarModelNames()) + ")");
  const std::optional<simulation::Motion> named_motion = simulation::motionNamed(motion);
  if (!named_motion)
    throw py::value_error("unknown motion '" + motion + "' (" + listed(simulation::motionNames()) + ")");
  settings.lidar = *model;
  settings.motion = *named_motion;
  settings.rate = rate;
  settings.speed = speed;
  settings.odometry_noise = odometry_noise;
  settings.seed = seed;
  settings.people = people;
  settings.laser_pose = mountingFrom(laser_pose, "laser_pose").value_or(io::Pose2D{});

  simulation::World world;
  std::vector<Eigen::Vector2d> route;
  if (!waypoints.is_none()) {
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(waypoints);
    if (!a || a.ndim() != 2 || a.shape(1) != 2 || a.shape(0) < 2)
      throw py::value_error("waypoints must be an N x 2 array of two points or more (m)");
    for (py::ssize_t n = 0; n < a.shape(0); ++n) route.emplace_back(a.at(n, 0), a.at(n, 1));
  }
  if (simulation::isBuiltInWorld(map)) {
    world = simulation::makeBuiltInWorld(map);
    if (route.empty()) route = simulation::builtInPath(map, path);
    if (route.empty()) throw py::value_error("unknown path '" + path + "' in " + simulation::builtInPathChoices(map));
  } else {
    simulation::MapReadOptions read;
    read.resolution = resolution;
    world.setGrid(std::make_shared<simulation::OccupancyGrid>(simulation::readOccupancyGrid(map, read)));
    if (route.empty()) {
      const auto shape = simulation::pathShape(path);
      if (shape.empty()) throw py::value_error("unknown path '" + path + "' (S, L, Y, O)");
      route = simulation::placePath(world, shape);
      if (route.empty()) throw py::value_error(map + ": path " + path + " fits nowhere in the map; give waypoints");
    }
  }
  py::gil_scoped_release release;
  return simulation::simulateRun(world, route, settings);
}

}  // namespace

void bindSimulation(py::module_ &m) {
  py::class_<simulation::SimulatedRun>(m, "SimulatedRun", "A simulated log and the truth about it.")
      .def_readonly("log", &simulation::SimulatedRun::log, "the scans, stamped k / rate s, with wheel odometry")
      .def_property_readonly(
          "ground_truth", [](const simulation::SimulatedRun &r) { return trajectoryArray(r.ground_truth); },
          "N x 4 (stamp, x, y, yaw): the robot's true pose at each scan")
      .def_readonly("path_length", &simulation::SimulatedRun::path_length, "m");

  m.def("simulate", &simulate, py::arg("path") = "L", py::arg("rate") = 2.0, py::arg("map") = "office",
        py::arg("resolution") = 0.1, py::arg("lidar") = "hokuyo", py::arg("motion") = "stop-and-go",
        py::arg("speed") = 0.5, py::arg("odometry_noise") = 0.02, py::arg("seed") = 1,
        py::arg("waypoints") = py::none(), py::arg("laser_pose") = py::none(), py::arg("people") = 0,
        "Drives a robot with a LIDAR (hokuyo, ydlidar or sick) at `rate` Hz and `speed` m/s along a path (S, L, Y, O, "
        "line in the built-in office; line in the built-in door row, map 'doors'; S, L, Y, O placed automatically in a "
        "map file, map_server YAML or a PGM/PNG "
        "of `resolution` m per pixel; or `waypoints`, N x 2 in map metres). motion: stop-and-go (the paper's) or "
        "continuous (every beam from where the robot is when it fires). laser_pose: (x m, y m, yaw rad) of the LIDAR "
        "on the robot (None: at its centre). people: how many walk about the path (circles of 0.2-0.25 m at 0.5-1.5 "
        "m/s, placed with the seed). Returns a SimulatedRun.");
}

}  // namespace contour_reg::python
