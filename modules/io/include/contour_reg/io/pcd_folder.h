#pragma once
/// @file pcd_folder.h
/// A folder of PCD files, one 2-D scan each, in the sensor frame (z ignored).
///
/// Scans are ordered by stamp: the file name when it is a number (`1234.56.pcd`), else the
/// PCD header stamp (microseconds, as pcl_conversions writes it), else the name's order at
/// one scan per second. Points are turned back into beams: bearings on a uniform grid
/// (clouds projected from a LaserScan, with or without their invalid beams) are kept
/// exactly; otherwise each point goes to the nearest beam of a grid of the median bearing
/// gap, which the report says. Unreadable files are reported and skipped.

#include <string>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io {

/// Reads every `*.pcd` file of `folder`. Throws ReadError when none gives a scan.
ScanLog readPcdFolder(const std::string &folder, double max_range = 40.0);

}  // namespace contour_reg::io
