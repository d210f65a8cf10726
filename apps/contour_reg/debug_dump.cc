#include "debug_dump.h"

#include <cmath>
#include <filesystem>
#include <random>

#include "contour_reg/core/registration.h"
#include "contour_reg/drawing/debug_images.h"
#include "contour_reg/io/pose2d.h"
#include "contour_reg/odometry/odometry.h"

namespace contour_reg::cli {

std::vector<std::string> DebugDumper::dumpPair(const io::ScanLog &log, std::size_t target, std::size_t source,
                                               const std::vector<std::string> &methods,
                                               const PairMotions &motions) const {
  return dump(log, log.entries[target].scan, "scan " + std::to_string(target),
              std::to_string(target) + "_" + std::to_string(source), source, methods, motions);
}

std::vector<std::string> DebugDumper::dumpMapPair(const io::ScanLog &log, const LaserScan &map, std::size_t keyframe,
                                                  std::size_t source, const PairMotions &motions) const {
  return dump(log, map, "the local map at scan " + std::to_string(keyframe),
              "map" + std::to_string(keyframe) + "_" + std::to_string(source), source, {}, motions);
}

std::vector<std::string> DebugDumper::dump(const io::ScanLog &log, const LaserScan &a, const std::string &target_name,
                                           const std::string &stem, std::size_t source,
                                           const std::vector<std::string> &methods, const PairMotions &motions) const {
  namespace fs = std::filesystem;
  const LaserScan &b = log.entries[source].scan;
  const ContourFeatures fa = extractContourFeatures(a, settings_.contour),
                        fb = extractContourFeatures(b, settings_.contour);
  std::mt19937 rng(42);  // ContourRegistration's default seed
  const Eigen::Matrix3d guess = io::toMatrix(motions.guess.value_or(io::Pose2D{}));
  const RegistrationResult result =
      registerContours(fb, fa, settings_.registration, rng, motions.guess ? &guess : nullptr);
  std::vector<std::string> written{(fs::path(folder_) / ("scan_" + std::to_string(source) + ".png")).string(),
                                   (fs::path(folder_) / ("pair_" + stem + ".png")).string()};
  char title[160];
  std::snprintf(title, sizeof title, "scan %zu (stamp %.3f s)", source, b.stamp);
  drawing::writeImage(written[0], drawing::drawScan(b, fb, settings_.contour, title));
  std::snprintf(title, sizeof title, "scan %zu (source) onto %s (target)", source, target_name.c_str());
  drawing::writeImage(written[1], drawing::drawPair(a, b, fa, fb, result, title));
  if (b.time_increment > 0.0) {
    // The motion over the source's sweep, as the odometry deskews it: the wheel odometry's when
    // the log has it, else the motion this pair's registration found.
    SweepMotion motion;
    const double dt = b.stamp - a.stamp;
    if (const auto wheel = odometry::wheelMotionOverSweep(log, source))
      motion = *wheel;
    else if (result.converged && std::abs(dt) > 1e-3)
      motion = odometry::twistOver(io::toPose(result.transform), dt);
    written.push_back((fs::path(folder_) / ("deskew_" + std::to_string(source) + ".png")).string());
    std::snprintf(title, sizeof title, "scan %zu raw and deskewed", source);
    drawing::writeImage(written.back(), drawing::drawDeskew(b, motion, title));
  }
  const std::vector<std::string> drawn =
      methods.empty() && motions.reference ? std::vector<std::string>{"contour"} : methods;
  if (!drawn.empty()) {
    std::vector<drawing::Alignment> alignments;
    for (const std::string &method : drawn) {
      auto matcher = odometry::makeScanMatcher(method, settings_);
      const odometry::MatchResult match = matcher->match(a, b, guess);
      alignments.push_back({method, match.transform, match.converged, match.reason});
    }
    std::optional<Eigen::Matrix3d> reference;
    if (motions.reference) reference = io::toMatrix(*motions.reference);
    written.push_back((fs::path(folder_) / ("methods_" + stem + ".png")).string());
    drawing::writeImage(written.back(), drawing::drawAlignments(a, b, alignments, 600, reference));
  }
  return written;
}

}  // namespace contour_reg::cli
