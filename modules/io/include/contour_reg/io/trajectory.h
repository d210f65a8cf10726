#pragma once
/// @file trajectory.h
/// Trajectories in TUM format (`stamp x y z qx qy qz qw`) and relation files of
/// Kümmerle et al. 2009 (`t1 t2 x y z roll pitch yaw`).

#include <string>
#include <vector>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io {

using Trajectory = std::vector<StampedPose>;

/// The pose at t2 in the frame of the pose at t1.
struct Relation {
  double t1 = 0.0, t2 = 0.0;
  Pose2D motion;
};

/// Writes a TUM file; a non-empty `comment` becomes a `#` line at its head (readTum skips it).
void writeTum(const std::string &path, const Trajectory &trajectory, const std::string &comment = {});
/// Reads a TUM file, in stamp order whatever the file's order; the yaw is taken from the
/// quaternion. Throws ReadError naming file and line.
Trajectory readTum(const std::string &path);
/// Reads a relations file. Throws ReadError naming file and line.
std::vector<Relation> readRelations(const std::string &path);

}  // namespace contour_reg::io
