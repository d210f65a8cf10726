#pragma once
/// @file carmen.h
/// CARMEN logs: FLASER / RLASER, RAWLASER1-4, ROBOTLASER1 and ODOM lines, plain or gzip.
///
/// FLASER lines carry no beam angles; beam i is taken at -90 deg + i * step with
/// step = 180 deg / (n - n mod 2) (1 deg for 180/181 beams, 0.5 deg for 360/361), the
/// GMapping convention. Readings at or above `max_range` are no-return. Laser lines
/// without a pose (RAWLASER) get their odometry interpolated from ODOM lines. The laser's
/// pose against the robot's in the first ROBOTLASER1 line is the log's mounting
/// (ScanLog::laser_pose); FLASER lines give none. Scans are
/// returned in stamp order. A bad or truncated line is skipped and reported with its file
/// and line number; a file with no usable scan is a ReadError.

#include <string>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io {

struct CarmenOptions {
  double max_range = 40.0;         ///< m, readings at or above are no-return (SICK logs use 81.83)
  std::size_t max_beams = 100000;  ///< lines announcing more beams are rejected
};

/// Reads a CARMEN log (gzip-compressed or plain; zlib tells them apart).
ScanLog readCarmen(const std::string &path, const CarmenOptions &options = {});

/// Writes scans as ROBOTLASER1 lines (beam geometry included) and, when present,
/// odometry as ODOM lines. Throws ReadError when the file cannot be written.
void writeCarmen(const std::string &path, const ScanLog &log);

}  // namespace contour_reg::io
