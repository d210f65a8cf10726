#pragma once
// Writes the debug images of a scan pair: both scans, the contour registration of the
// pair, and optionally other methods' alignments. Used by `debug` and `odometry --debug-dir`.

#include <optional>
#include <string>
#include <vector>

#include "contour_reg/io/scan_log.h"
#include "contour_reg/odometry/scan_matcher.h"

namespace contour_reg::cli {

/// What is known of a pair besides its scans: motions source to target, in the laser's frame.
struct PairMotions {
  std::optional<io::Pose2D> guess;      ///< where every method drawn starts (none: no motion)
  std::optional<io::Pose2D> reference;  ///< the true motion (a ground truth's), drawn beside the methods'
};

class DebugDumper {
 public:
  DebugDumper(std::string folder, odometry::MatcherSettings settings)
      : folder_(std::move(folder)), settings_(std::move(settings)) {}

  /// Writes scan_<source>.png, pair_<target>_<source>.png, for a source with beam timing
  /// deskew_<source>.png (raw and deskewed), and, with methods or a reference motion,
  /// methods_<target>_<source>.png (with a reference and no methods: the contour method's);
  /// returns the files written. Every registration drawn starts from `motions.guess`.
  std::vector<std::string> dumpPair(const io::ScanLog &log, std::size_t target, std::size_t source,
                                    const std::vector<std::string> &methods = {},
                                    const PairMotions &motions = {}) const;

  /// The same for `source` registered against the local map drawn at keyframe `keyframe`:
  /// pair_map<keyframe>_<source>.png shows `map` as the target.
  std::vector<std::string> dumpMapPair(const io::ScanLog &log, const LaserScan &map, std::size_t keyframe,
                                       std::size_t source, const PairMotions &motions = {}) const;

 private:
  // `a` is the target, named `target_name`, `stem` names the pair's files.
  std::vector<std::string> dump(const io::ScanLog &log, const LaserScan &a, const std::string &target_name,
                                const std::string &stem, std::size_t source, const std::vector<std::string> &methods,
                                const PairMotions &motions) const;

  std::string folder_;
  odometry::MatcherSettings settings_;
};

}  // namespace contour_reg::cli
