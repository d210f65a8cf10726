#pragma once
// The Python module's parts and the conversions between NumPy arrays and the library's types
// that they share. Scans cross as LaserScan objects or as N x 2 arrays of points in beam order
// (a NaN row for an invalid beam); trajectories as N x 4 arrays (stamp, x, y, yaw); poses as
// (x, y, yaw); transforms and covariances as 3 x 3 arrays.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // in every part alike: the conversions of std types must agree

#include <Eigen/Core>

#include "contour_reg/io/trajectory.h"
#include "contour_reg/odometry/scan_matcher.h"

namespace contour_reg::python {

namespace py = pybind11;

void bindScans(py::module_ &m);         // LaserScan, features()
void bindRegistration(py::module_ &m);  // register(), RegistrationResult
void bindLogs(py::module_ &m);          // Log, read_log(), TUM and relation files
void bindOdometry(py::module_ &m);      // odometry()
void bindEvaluation(py::module_ &m);    // evaluate(), relation_errors(), pose helpers
void bindSimulation(py::module_ &m);    // simulate()

/// "a, b, c": the names a setting takes, for an error message.
std::string listed(const std::vector<std::string> &names);

/// A beam-order cloud from a LaserScan (deskewed by `twist` when it has beam timing) or an N x 2
/// array of points (NaN rows: invalid beams; a twist is a py::value_error).
/// Throws py::type_error for anything else, py::value_error for a wrong shape.
odometry::Cloud::Ptr beamsOf(const py::handle &scan, const Twist2D &twist = {});

/// The matcher settings given as keyword arguments (contour_step, threshold, candidates, arm,
/// local_fallback, probe_distance, free_space, icp_max_distance, ndt_resolution, iterations). An unknown
/// name raises TypeError, a value the library rejects ValueError.
odometry::MatcherSettings matcherSettings(const py::kwargs &settings);

/// An N x 2 float64 array from points.
py::array_t<double> pointsArray(const std::vector<Eigen::Vector2d> &points);
/// A 3 x 3 float64 array.
py::array_t<double> matrixArray(const Eigen::Matrix3d &m);
/// A 3 x 3 matrix from a finite array-like of that shape (py::value_error naming `what` otherwise).
Eigen::Matrix3d matrixOf(const py::handle &array, const char *what);
/// The same, which must be a rigid motion (rotation block, last row 0 0 1), or ValueError.
Eigen::Matrix3d rigidMatrixOf(const py::handle &array, const char *what);

/// N x 4 (stamp, x, y, yaw) and back; a wrong shape raises ValueError naming `what`.
py::array_t<double> trajectoryArray(const io::Trajectory &trajectory);
io::Trajectory trajectoryOf(const py::handle &array, const char *what);

/// None or (x m, y m, yaw rad) and back.
py::object poseOrNone(const std::optional<io::Pose2D> &pose);
/// A laser's mounting on the robot from None or (x m, y m, yaw rad): anything else, or a
/// mounting more than io::kFarthestMounting from the robot or turned more than 2 pi, raises
/// ValueError naming `what`.
std::optional<io::Pose2D> mountingFrom(const py::object &value, const char *what);

}  // namespace contour_reg::python
