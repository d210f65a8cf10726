#pragma once
/// @file debug_images.h
/// Pictures of what the contour method saw, drawn with OpenCV: one scan (points,
/// contour segments, equalized vertices, special points, matched-filter response), one
/// pair (special points, candidate pairs, RANSAC inliers and outliers, overlays after
/// alignment by one or more methods), and trajectories against ground truth.

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/deskew.h"
#include "contour_reg/core/laser_scan.h"
#include "contour_reg/core/registration.h"
#include "contour_reg/io/trajectory.h"
#include "contour_reg/simulation/world.h"

namespace contour_reg::drawing {

/// Colours (BGR) the pictures use, so tests and readers can rely on them.
struct Palette {
  static cv::Scalar specialPoint() { return {0, 0, 230}; }   ///< red
  static cv::Scalar target() { return {200, 120, 20}; }      ///< blue
  static cv::Scalar source() { return {0, 140, 255}; }       ///< orange
  static cv::Scalar inlier() { return {40, 170, 40}; }       ///< green
  static cv::Scalar outlier() { return {60, 60, 220}; }      ///< light red
  static cv::Scalar candidate() { return {170, 170, 170}; }  ///< grey
  static cv::Scalar warning() { return {0, 0, 255}; }        ///< pure red text
  static cv::Scalar freeSpace() { return {200, 0, 200}; }    ///< magenta: contour in the other scan's free space
  /// One colour per method, the same in every picture: contour blue, contour+icp orange, icp
  /// green, ndt2d purple, ndt brown, gicp pink, wheel-odometry grey (others olive).
  static cv::Scalar method(const std::string &name);
};

/// A metric-to-pixel map for a square-ish panel: y up, 1 m = `scale` px.
struct View {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< world point at the panel's lower-left
  double scale = 50.0;                               ///< px per m
  int width = 1200, height = 900;
  cv::Point pixel(const Eigen::Vector2d &p) const;
  /// A view that shows every finite point of `points` with a margin.
  static View fit(const std::vector<Eigen::Vector2d> &points, int width, int height);
};

/// One scan: the panel (points, segments, equalized vertices, special points with a glyph
/// showing corner angle and orientation, legend, scale bar) above a strip plot of the
/// matched-filter response along the contours with the threshold and the maxima.
cv::Mat drawScan(const LaserScan &scan, const ContourFeatures &features, const ContourParams &params,
                 const std::string &title, int width = 1200);

/// A scan taken while moving (LaserScan::time_increment), raw (grey) and deskewed by `motion`
/// (deskew.h; orange) over each other in the frame of the sensor at the stamp, with the
/// velocity at the first beam and how often it changes, the sweep's duration and the largest
/// shift of a beam.
cv::Mat drawDeskew(const LaserScan &scan, const SweepMotion &motion, const std::string &title, int width = 1200);

/// One pair: left, both scans in their own frames with special points, candidate pairs
/// (grey), RANSAC inliers (green) and outliers (red); middle, the source moved onto the
/// target by the result (or the failure reason when it did not converge), and in magenta the
/// contour that motion puts in the other scan's free space (free_space.h). When the result
/// has a rejected motion (RegistrationResult::rejected: the best distinct rival of a converged
/// result, the declined motion of another), a third panel shows it the same way, with its
/// overlap and score. `width` is that of the first two panels; the third adds half of it.
cv::Mat drawPair(const LaserScan &target, const LaserScan &source, const ContourFeatures &target_features,
                 const ContourFeatures &source_features, const RegistrationResult &result, const std::string &title,
                 int width = 1600);

/// Overlays of the source moved onto the target by several methods, side by side.
/// Each entry: method name, source-to-target transform, converged. With `reference` (the
/// pair's true motion, source to target, when known: a ground truth's), the first panel shows
/// the source moved by it, and each converged method's band says how far its motion lies
/// from it (m between the translations, deg between the headings).
struct Alignment {
  std::string method;
  Eigen::Matrix3d transform = Eigen::Matrix3d::Identity();
  bool converged = false;
  std::string reason;  ///< why not, when not converged
};
cv::Mat drawAlignments(const LaserScan &target, const LaserScan &source, const std::vector<Alignment> &alignments,
                       int panel_width = 600, const std::optional<Eigen::Matrix3d> &reference = std::nullopt);

/// Trajectories (method name -> trajectory, each in Palette::method's colour) under the
/// ground truth (black, drawn last so that it stays visible), each re-anchored at the ground
/// truth's first pose, which a triangle marks; methods drawn earlier are drawn wider, so one
/// that follows another stays visible beside it. `title` (input, path, rate) heads the
/// picture. Below, each method's position error along the distance travelled, on a
/// logarithmic axis from 1 mm, so that methods a thousand times apart are all readable.
cv::Mat drawTrajectories(const std::map<std::string, io::Trajectory> &estimates, const io::Trajectory &ground_truth,
                         int width = 1200, const std::string &title = "");

/// A map (segments, circles, occupancy grid: obstacles black, unknown grey) with named
/// paths drawn over it, each from a circle at its start to an arrow at its end.
cv::Mat drawWorld(const simulation::World &world, const std::map<std::string, std::vector<Eigen::Vector2d>> &paths,
                  int width = 1200);

/// Writes `image` to `path` (format by extension). Throws std::runtime_error naming the file.
void writeImage(const std::string &path, const cv::Mat &image);

}  // namespace contour_reg::drawing
