#pragma once
// Writes the debug images of a scan pair: both scans, the contour registration of the
// pair, and optionally other methods' alignments. Used by `debug` and `odometry --debug-dir`.

#include <string>
#include <vector>

#include "contour_reg/io/scan_log.h"
#include "contour_reg/odometry/scan_matcher.h"

namespace contour_reg::cli {

class DebugDumper {
 public:
  DebugDumper(std::string folder, odometry::MatcherSettings settings)
      : folder_(std::move(folder)), settings_(std::move(settings)) {}

  /// Writes scan_<source>.png, pair_<target>_<source>.png, for a source with beam timing
  /// deskew_<source>.png (raw and deskewed), and, with methods, methods_<target>_<source>.png;
  /// returns the files written.
  std::vector<std::string> dumpPair(const io::ScanLog &log, std::size_t target, std::size_t source,
                                    const std::vector<std::string> &methods = {}) const;

  /// The same for `source` registered against the local map drawn at keyframe `keyframe`:
  /// pair_map<keyframe>_<source>.png shows `map` as the target.
  std::vector<std::string> dumpMapPair(const io::ScanLog &log, const LaserScan &map, std::size_t keyframe,
                                       std::size_t source) const;

 private:
  // `a` is the target, named `target_name`, `stem` names the pair's files.
  std::vector<std::string> dump(const io::ScanLog &log, const LaserScan &a, const std::string &target_name,
                                const std::string &stem, std::size_t source,
                                const std::vector<std::string> &methods) const;

  std::string folder_;
  odometry::MatcherSettings settings_;
};

}  // namespace contour_reg::cli
