#include "contour_reg/drawing/debug_images.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "contour_reg/core/contour.h"
#include "contour_reg/core/free_space.h"
#include "contour_reg/core/transform_estimation.h"
#include "contour_reg/io/pose2d.h"

namespace contour_reg::drawing {

namespace {

const cv::Scalar kWhite(255, 255, 255), kBlack(0, 0, 0), kRawPoint(150, 150, 150);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

// Distinct colours for contour segments (no red: red marks special points).
cv::Scalar segmentColour(std::size_t k) {
  static const cv::Scalar colours[] = {{180, 119, 31},  {44, 160, 44},  {189, 103, 148}, {75, 86, 140},
                                       {194, 119, 227}, {34, 189, 188}, {207, 190, 23},  {14, 127, 255}};
  return colours[k % 8];
}

std::vector<Eigen::Vector2d> finitePoints(const LaserScan &scan, const Eigen::Matrix3d &transform) {
  std::vector<Eigen::Vector2d> points;
  for (const Complex &c : polarCode(scan))
    if (isFinite(c)) points.push_back(transformPoint(transform, toEigen(c)));
  return points;
}

// Warnings are drawn bold and without anti-aliasing, in exactly Palette::warning().
void text(cv::Mat &image, const std::string &s, cv::Point at, double size = 0.6, cv::Scalar colour = kBlack) {
  const bool warning = colour == Palette::warning();
  cv::putText(image, s, at, kFont, size, colour, warning ? 2 : 1, warning ? cv::LINE_8 : cv::LINE_AA);
}

// A scale bar of a round length in the lower-right corner, and (with `sensor`) the sensor at the origin.
void decorate(cv::Mat &image, const View &view, bool sensor = true) {
  const double metres_wanted = 150.0 / view.scale;
  double bar = 1.0;
  for (double candidate : {0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0})
    if (candidate <= metres_wanted) bar = candidate;
  const int length = static_cast<int>(bar * view.scale);
  const cv::Point end(view.width - 30, view.height - 25);
  cv::line(image, end - cv::Point(length, 0), end, kBlack, 3);
  char label[32];
  std::snprintf(label, sizeof label, "%g m", bar);
  text(image, label, end - cv::Point(length, 10));
  if (sensor) cv::drawMarker(image, view.pixel({0, 0}), kBlack, cv::MARKER_TRIANGLE_UP, 14, 2);
}

void drawPoints(cv::Mat &image, const View &view, const std::vector<Eigen::Vector2d> &points, cv::Scalar colour,
                int radius = 1) {
  for (const Eigen::Vector2d &p : points) cv::circle(image, view.pixel(p), radius, colour, cv::FILLED, cv::LINE_AA);
}

// A special point: a filled disc at the vertex and the two arms of its corner.
void drawSpecialPoint(cv::Mat &image, const View &view, const SpecialPoint &point, const Eigen::Matrix3d &transform,
                      cv::Scalar colour) {
  const Eigen::Vector2d at = transformPoint(transform, point.position);
  const double turn = yawOf(transform);
  const double arm = 0.35;
  for (double side : {-0.5, 0.5}) {
    const double a = point.orientation + turn + side * point.corner_angle;
    cv::line(image, view.pixel(at), view.pixel(at + arm * Eigen::Vector2d(std::cos(a), std::sin(a))), colour, 2,
             cv::LINE_AA);
  }
  cv::circle(image, view.pixel(at), 6, colour, cv::FILLED, cv::LINE_AA);
}

void legend(cv::Mat &image, const std::vector<std::pair<std::string, cv::Scalar>> &entries, cv::Point at) {
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const cv::Point row = at + cv::Point(0, static_cast<int>(22 * k));
    cv::circle(image, row + cv::Point(6, -5), 6, entries[k].second, cv::FILLED, cv::LINE_AA);
    text(image, entries[k].first, row + cv::Point(18, 0), 0.55);
  }
}

}  // namespace

cv::Point View::pixel(const Eigen::Vector2d &p) const {
  return {static_cast<int>(std::lround((p.x() - origin.x()) * scale)),
          static_cast<int>(std::lround(height - (p.y() - origin.y()) * scale))};
}

View View::fit(const std::vector<Eigen::Vector2d> &points, int width, int height) {
  View view;
  view.width = width;
  view.height = height;
  Eigen::Vector2d lo(-1, -1), hi(1, 1);
  for (const Eigen::Vector2d &p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double margin = 0.08;
  const Eigen::Vector2d size = (hi - lo) * (1.0 + 2 * margin);
  view.scale = std::min(width / size.x(), height / size.y());
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  view.origin = centre - 0.5 * Eigen::Vector2d(width, height) / view.scale;
  return view;
}

cv::Mat drawDeskew(const LaserScan &scan, const SweepMotion &motion, const std::string &title, int width) {
  const int height = width * 3 / 4;
  cv::Mat image(height, width, CV_8UC3, kWhite);
  const ComplexSequence raw = polarCode(scan);
  ComplexSequence deskewed = raw;
  deskewPolarCode(deskewed, Sweep{scan.time_increment, motion});
  std::vector<Eigen::Vector2d> raw_points, deskewed_points;
  double largest_shift = 0.0;
  for (std::size_t n = 0; n < raw.size() && n < deskewed.size(); ++n) {
    if (!isFinite(raw[n]) || !isFinite(deskewed[n])) continue;
    raw_points.push_back(toEigen(raw[n]));
    deskewed_points.push_back(toEigen(deskewed[n]));
    largest_shift = std::max(largest_shift, magnitude(deskewed[n] - raw[n]));
  }
  std::vector<Eigen::Vector2d> all = raw_points;
  all.insert(all.end(), deskewed_points.begin(), deskewed_points.end());
  const View view = View::fit(all, width, height);
  drawPoints(image, view, raw_points, kRawPoint, 2);
  drawPoints(image, view, deskewed_points, Palette::source(), 2);
  decorate(image, view);
  text(image, title, {15, 30}, 0.8);
  char summary[240];
  const double sweep = scan.time_increment * static_cast<double>(scan.ranges.empty() ? 0 : scan.ranges.size() - 1);
  const Twist2D &twist = motion.twist;
  char changes[64] = "";
  if (!motion.changes.empty())
    std::snprintf(changes, sizeof changes, " at the first beam, %zu changes", motion.changes.size());
  std::snprintf(summary, sizeof summary,
                "motion over the sweep: %.2f m/s forward, %.2f m/s left, %.1f deg/s%s; sweep %.3f s; largest beam "
                "shift %.3f m",
                twist.vx, twist.vy, twist.wz * 180.0 / M_PI, changes, sweep, largest_shift);
  text(image, summary, {15, 58});
  if (scan.time_increment == 0.0)
    text(image, "NO BEAM TIMING: the scan is taken as if all at once", {15, 88}, 0.7, Palette::warning());
  legend(image,
         {{"raw (each beam where the sensor was then)", kRawPoint}, {"deskewed (all at the stamp)", Palette::source()}},
         {15, height - 60});
  return image;
}

cv::Mat drawScan(const LaserScan &scan, const ContourFeatures &features, const ContourParams &params,
                 const std::string &title, int width) {
  const int panel_height = width * 3 / 4, strip_height = width / 5;
  cv::Mat image(panel_height + strip_height, width, CV_8UC3, kWhite);
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const std::vector<Eigen::Vector2d> points = finitePoints(scan, identity);
  const View view = View::fit(points, width, panel_height);
  cv::Mat panel = image(cv::Rect(0, 0, width, panel_height));

  drawPoints(panel, view, points, kRawPoint, 2);
  for (std::size_t k = 0; k < features.contours.size(); ++k) {
    const ComplexSequence &v = features.contours[k].vertices;
    for (std::size_t r = 0; r + 1 < v.size(); ++r)
      cv::line(panel, view.pixel(toEigen(v[r])), view.pixel(toEigen(v[r + 1])), segmentColour(k), 2, cv::LINE_AA);
    if (features.contours[k].step * view.scale >= 6.0)  // vertices only where they stand apart
      for (const Complex &c : v) cv::circle(panel, view.pixel(toEigen(c)), 2, kBlack, cv::FILLED);
  }
  for (const SpecialPoint &p : features.special_points)
    drawSpecialPoint(panel, view, p, identity, Palette::specialPoint());
  decorate(panel, view);
  text(panel, title, {15, 30}, 0.8);
  char summary[160];
  std::snprintf(summary, sizeof summary, "%zu beams, %zu contour segments, %zu special points (threshold %.2f)",
                scan.ranges.size(), features.segments.size(), features.special_points.size(),
                params.special_points.threshold);
  text(panel, summary, {15, 58});
  if (features.special_points.empty())
    text(panel, "NO SPECIAL POINTS: this scan cannot be matched by its corners", {15, 88}, 0.7, Palette::warning());
  legend(panel,
         {{"raw points", kRawPoint},
          {"contour segment (one colour each)", segmentColour(0)},
          {"equalized vertex", kBlack},
          {"special point (corner arms)", Palette::specialPoint()}},
         {15, panel_height - 122});
  text(panel, "triangle: the sensor", {15, panel_height - 122 + 4 * 22}, 0.55);

  // The strip: response c(n) of every contour, one after another, separated by ticks.
  cv::Mat strip = image(cv::Rect(0, panel_height, width, strip_height));
  cv::line(strip, {0, 0}, {width, 0}, kBlack, 1);
  std::size_t total = 0;
  for (const CornerResponse &r : features.responses) total += r.response.size();
  const int left = 50, right = width - 20, top = 25, bottom = strip_height - 25;
  auto y_of = [&](double c) { return static_cast<int>(bottom - std::clamp(c, 0.0, 1.0) * (bottom - top)); };
  text(strip, "matched-filter response c(n) along the contours", {left, 18}, 0.55);
  text(strip, "1", {left - 20, top + 5}, 0.45);
  text(strip, "0", {left - 20, bottom + 5}, 0.45);
  const int threshold_y = y_of(params.special_points.threshold);
  cv::line(strip, {left, threshold_y}, {right, threshold_y}, Palette::specialPoint(), 1, cv::LINE_AA);
  text(strip, "threshold", {right - 80, threshold_y - 4}, 0.45, Palette::specialPoint());
  if (total > 1) {
    const double dx = double(right - left) / double(total - 1);
    std::size_t offset = 0;
    for (std::size_t k = 0; k < features.responses.size(); ++k) {
      const auto &c = features.responses[k].response;
      for (std::size_t n = 0; n + 1 < c.size(); ++n)
        cv::line(strip, {left + int((offset + n) * dx), y_of(c[n])},
                 {left + int((offset + n + 1) * dx), y_of(c[n + 1])}, segmentColour(k), 1, cv::LINE_AA);
      for (const SpecialPoint &p : features.special_points)
        if (p.contour == int(k) && p.vertex >= 0)
          cv::circle(strip, {left + int((offset + std::size_t(p.vertex)) * dx), y_of(p.response)}, 5,
                     Palette::specialPoint(), cv::FILLED, cv::LINE_AA);
      offset += c.size();
      cv::line(strip, {left + int(offset * dx), bottom}, {left + int(offset * dx), bottom + 6}, kBlack, 1);
    }
  } else {
    text(strip, "no contour long enough for the filter", {left, (top + bottom) / 2}, 0.6, Palette::warning());
  }
  return image;
}

// Writes `reason` wrapped at about `columns` characters, at most `rows` lines, from `at` down.
void wrapped(cv::Mat &image, std::string reason, cv::Point at, std::size_t columns, int rows, cv::Scalar colour) {
  for (int row = 0; !reason.empty() && row < rows; ++row) {
    std::size_t cut = reason.size();
    if (reason.size() > columns) {
      cut = reason.rfind(' ', columns);
      if (cut == std::string::npos || cut == 0) cut = columns;
    }
    text(image, reason.substr(0, cut), at + cv::Point(0, 22 * row), 0.5, colour);
    reason = cut < reason.size() ? reason.substr(cut + 1) : std::string();
  }
}

// A motion's overlap and score as the judge weighed it, written at the same height in the
// result's band and the rejected motion's, so that the two read side by side.
void writeScore(cv::Mat &band, double overlap, double score) {
  char line[120];
  std::snprintf(line, sizeof line, "overlap %.0f %%, score %.2f (overlap less the share in free space)",
                100.0 * overlap, score);
  text(band, line, {15, 80}, 0.5);
}

// `panel`: the target and the source moved onto it by `motion`, and in magenta the contour
// that motion puts in the other scan's free space (free_space.h): source contour where the
// target looked through, target contour where the source did, both in the target frame. The
// amount is written in `band`.
void drawMotion(cv::Mat panel, cv::Mat band, const View &view, const std::vector<Eigen::Vector2d> &target_points,
                const LaserScan &source, const ContourFeatures &target_features, const ContourFeatures &source_features,
                const Eigen::Matrix3d &motion, const std::string &moved) {
  drawPoints(panel, view, target_points, Palette::target(), 2);
  drawPoints(panel, view, finitePoints(source, motion), Palette::source(), 1);
  std::vector<Eigen::Vector2d> contradicted;
  const FreeSpaceEvidence evidence_against =
      mutualFreeSpaceEvidence(source_features, RangeView(source_features), target_features, RangeView(target_features),
                              motion, FreeSpaceParams{}, &contradicted);
  drawPoints(panel, view, contradicted, Palette::freeSpace(), 3);
  decorate(panel, view);
  char evidence[160];
  std::snprintf(evidence, sizeof evidence, "magenta: %.1f m of contour (%.0f %%) in the other scan's free space",
                evidence_against.contradicted_length, 100.0 * evidence_against.fraction());
  text(band, evidence, {15, 122}, 0.5, contradicted.empty() ? kBlack : Palette::freeSpace());
  legend(panel, {{"target scan", Palette::target()}, {moved, Palette::source()}}, {15, panel.rows - 50});
}

cv::Mat drawPair(const LaserScan &target, const LaserScan &source, const ContourFeatures &target_features,
                 const ContourFeatures &source_features, const RegistrationResult &result, const std::string &title,
                 int width) {
  // A band on top for the words, two panels below for the data, a third for the best
  // motion the judge rejected when it weighed one.
  const int panel = width / 2, height = panel, band = 150;
  const int panels = result.rejected ? 3 : 2;
  cv::Mat image(band + height, panel * panels, CV_8UC3, kWhite);
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const auto target_points = finitePoints(target, identity), source_points = finitePoints(source, identity);
  std::vector<Eigen::Vector2d> all = target_points;
  all.insert(all.end(), source_points.begin(), source_points.end());
  const View view = View::fit(all, panel, height);
  cv::Mat top_left = image(cv::Rect(0, 0, panel, band)), top_right = image(cv::Rect(panel, 0, panel, band));
  cv::line(image, {0, band}, {image.cols, band}, kBlack, 1);

  // Left: both scans in their own sensor frames, pairs between their special points.
  cv::Mat left = image(cv::Rect(0, band, panel, height));
  drawPoints(left, view, target_points, Palette::target());
  drawPoints(left, view, source_points, Palette::source());
  for (const SpecialPoint &p : target_features.special_points)
    drawSpecialPoint(left, view, p, identity, Palette::target());
  for (const SpecialPoint &p : source_features.special_points)
    drawSpecialPoint(left, view, p, identity, Palette::source());
  std::vector<bool> is_inlier(result.candidates.size(), false);
  for (int i : result.inliers) is_inlier[std::size_t(i)] = true;
  for (int inliers_last = 0; inliers_last < 2; ++inliers_last)  // inlier pairs on top of the others
    for (std::size_t k = 0; k < result.candidates.size(); ++k) {
      const Correspondence &c = result.candidates[k];
      const auto from = static_cast<std::size_t>(c.source), to = static_cast<std::size_t>(c.target);
      if (is_inlier[k] != (inliers_last == 1) || c.source < 0 || c.target < 0 ||
          from >= source_features.special_points.size() || to >= target_features.special_points.size())
        continue;
      const cv::Scalar colour =
          is_inlier[k] ? Palette::inlier() : (result.inliers.empty() ? Palette::candidate() : Palette::outlier());
      cv::line(left, view.pixel(source_features.special_points[from].position),
               view.pixel(target_features.special_points[to].position), colour, is_inlier[k] ? 3 : 1, cv::LINE_AA);
    }
  decorate(left, view);
  text(top_left, title, {15, 28}, 0.7);
  char counts[200];
  std::snprintf(counts, sizeof counts, "special points: %zu target, %zu source; %zu candidate pairs, %zu inliers",
                result.target_points, result.source_points, result.candidates.size(), result.inliers.size());
  text(top_left, counts, {15, 54}, 0.5);
  legend(top_left,
         {{"target scan (sensor frame)", Palette::target()},
          {"source scan (sensor frame)", Palette::source()},
          {"RANSAC inlier pair", Palette::inlier()},
          {"outlier pair", Palette::outlier()}},
         {15, 80});
  text(top_left, "(grey lines: candidate pairs, no motion found)", {300, 102}, 0.45);
  text(top_left, "triangle: the sensor; bar: scale", {300, 124}, 0.45);

  // Middle: the source moved by the result.
  const View overlay = View::fit(target_points, panel, height);
  cv::line(image, {panel, 0}, {panel, band + height}, kBlack, 1);
  drawMotion(image(cv::Rect(panel, band, panel, height)), top_right, overlay, target_points, source, target_features,
             source_features, result.transform, "source moved by the result");
  const io::Pose2D pose = io::toPose(result.transform);
  char line[200];
  if (result.converged) {
    std::snprintf(line, sizeof line, "converged: x %.3f m, y %.3f m, yaw %.2f deg; contour rmse %.3f m%s", pose.x,
                  pose.y, pose.yaw * 180 / M_PI, result.contour_rmse, result.degenerate ? ", DEGENERATE" : "");
    text(top_right, line, {15, 28}, 0.55);
    writeScore(top_right, result.overlap, result.score);
  } else {
    text(top_right, std::string("NOT CONVERGED (") + toString(result.status) + "):", {15, 28}, 0.6, Palette::warning());
    wrapped(top_right, result.reason, {15, 52}, 75, 3, Palette::warning());
  }

  // Right: the best motion the judge weighed and did not return, on the same scale.
  if (result.rejected) {
    const RejectedMotion &rejected = *result.rejected;
    cv::Mat top = image(cv::Rect(2 * panel, 0, panel, band));
    cv::line(image, {2 * panel, 0}, {2 * panel, band + height}, kBlack, 1);
    drawMotion(image(cv::Rect(2 * panel, band, panel, height)), top, overlay, target_points, source, target_features,
               source_features, rejected.transform, "source moved by the rejected motion");
    const io::Pose2D other = io::toPose(rejected.transform);
    text(top, result.converged ? "best distinct rival the judge weighed:" : "best motion the judge declined:", {15, 28},
         0.6);
    std::snprintf(line, sizeof line, "x %.3f m, y %.3f m, yaw %.2f deg", other.x, other.y, other.yaw * 180 / M_PI);
    text(top, line, {15, 54}, 0.55);
    writeScore(top, rejected.overlap, rejected.score);
  }
  return image;
}

cv::Mat drawAlignments(const LaserScan &target, const LaserScan &source, const std::vector<Alignment> &given,
                       int panel_width, const std::optional<Eigen::Matrix3d> &reference) {
  std::vector<Alignment> alignments;
  if (reference) alignments.push_back({"reference", *reference, true, ""});
  alignments.insert(alignments.end(), given.begin(), given.end());
  const int n = std::max<int>(1, static_cast<int>(alignments.size())), band = 110;
  cv::Mat image(band + panel_width, panel_width * n, CV_8UC3, kWhite);
  const auto target_points = finitePoints(target, Eigen::Matrix3d::Identity());
  // The view shows the target and every converged alignment of the source in full.
  std::vector<Eigen::Vector2d> shown = target_points;
  for (const Alignment &a : alignments)
    if (a.converged) {
      const auto moved = finitePoints(source, a.transform);
      shown.insert(shown.end(), moved.begin(), moved.end());
    }
  const View view = View::fit(shown, panel_width, panel_width);
  cv::line(image, {0, band}, {panel_width * n, band}, kBlack, 1);
  for (int k = 0; k < static_cast<int>(alignments.size()); ++k) {
    cv::Mat top = image(cv::Rect(k * panel_width, 0, panel_width, band));
    cv::Mat panel = image(cv::Rect(k * panel_width, band, panel_width, panel_width));
    const Alignment &a = alignments[std::size_t(k)];
    drawPoints(panel, view, target_points, Palette::target(), 2);
    drawPoints(panel, view, finitePoints(source, a.transform), Palette::source(), 1);
    decorate(panel, view);
    const io::Pose2D pose = io::toPose(a.transform);
    char line[160];
    std::snprintf(line, sizeof line, "%s: %s", a.method.c_str(),
                  reference && k == 0 ? "the pair's true motion"
                  : a.converged       ? "converged"
                                      : "NOT CONVERGED");
    text(top, line, {12, 26}, 0.65, a.converged ? kBlack : Palette::warning());
    std::snprintf(line, sizeof line, "x %.3f m, y %.3f m, yaw %.2f deg", pose.x, pose.y, pose.yaw * 180 / M_PI);
    text(top, line, {12, 50}, 0.5);
    if (!a.converged) wrapped(top, a.reason, {12, 72}, 60, 2, Palette::warning());
    if (reference && k > 0 && a.converged) {
      const io::Pose2D truth = io::toPose(*reference);
      std::snprintf(line, sizeof line, "%.3f m, %.2f deg from the reference",
                    std::hypot(pose.x - truth.x, pose.y - truth.y),
                    std::abs(std::remainder(pose.yaw - truth.yaw, 2.0 * M_PI)) * 180 / M_PI);
      text(top, line, {12, 72}, 0.5);
    }
    if (k > 0) cv::line(image, {k * panel_width, 0}, {k * panel_width, band + panel_width}, kBlack, 1);
    legend(panel, {{"target scan", Palette::target()}, {"source moved by " + a.method, Palette::source()}},
           {12, panel_width - 50});
  }
  return image;
}

cv::Scalar Palette::method(const std::string &name) {
  if (name == "contour") return {200, 120, 20};     // blue
  if (name == "contour+icp") return {0, 140, 255};  // orange
  if (name == "icp") return {40, 170, 40};          // green
  if (name == "icp-pl") return {150, 160, 0};       // teal
  if (name == "ndt2d") return {180, 80, 150};       // purple
  if (name == "ndt") return {40, 80, 140};          // brown
  if (name == "gicp") return {190, 120, 240};       // pink
  if (name == "wheel-odometry") return {150, 150, 150};
  return {40, 140, 140};  // olive
}

cv::Mat drawTrajectories(const std::map<std::string, io::Trajectory> &estimates, const io::Trajectory &ground_truth,
                         int width, const std::string &title) {
  const int title_height = title.empty() ? 0 : 40;
  const int map_height = width * 2 / 3, plot_height = width / 4;
  cv::Mat image(title_height + map_height + plot_height, width, CV_8UC3, kWhite);
  if (!title.empty()) text(image, title, {15, 28}, 0.75);
  // Everything re-anchored at the ground truth's first pose.
  const io::Pose2D anchor = ground_truth.empty() ? io::Pose2D{} : ground_truth.front().pose;
  std::map<std::string, std::vector<Eigen::Vector2d>> paths;
  std::vector<Eigen::Vector2d> all;
  for (const auto &[name, trajectory] : estimates) {
    if (trajectory.empty()) continue;
    for (const io::StampedPose &p : trajectory) {
      const io::Pose2D q = io::compose(anchor, io::between(trajectory.front().pose, p.pose));
      paths[name].push_back({q.x, q.y});
    }
    all.insert(all.end(), paths[name].begin(), paths[name].end());
  }
  std::vector<Eigen::Vector2d> truth;
  for (const io::StampedPose &p : ground_truth) truth.push_back({p.pose.x, p.pose.y});
  all.insert(all.end(), truth.begin(), truth.end());
  const View view = View::fit(all, width, map_height);
  cv::Mat map = image(cv::Rect(0, title_height, width, map_height));
  auto polyline = [&](const std::vector<Eigen::Vector2d> &path, cv::Scalar colour, int thickness) {
    for (std::size_t k = 1; k < path.size(); ++k)
      cv::line(map, view.pixel(path[k - 1]), view.pixel(path[k]), colour, thickness, cv::LINE_AA);
  };
  std::vector<std::pair<std::string, cv::Scalar>> entries;
  int thickness = 2 + 2 * static_cast<int>(paths.size());
  for (const auto &[name, path] : paths) {
    thickness -= 2;
    polyline(path, Palette::method(name), thickness + 1);
    entries.push_back({name, Palette::method(name)});
  }
  polyline(truth, kBlack, 1);
  entries.push_back({"ground truth", kBlack});
  if (!truth.empty()) cv::drawMarker(map, view.pixel(truth.front()), kBlack, cv::MARKER_TRIANGLE_UP, 16, 2);
  decorate(map, view, false);
  legend(map, entries, {15, 30});
  text(map, "triangle: start, where every trajectory is anchored", {15, 30 + 22 * static_cast<int>(entries.size())},
       0.5);

  // Position error along the distance travelled (ground truth's), per method, log scale.
  cv::Mat plot = image(cv::Rect(0, title_height + map_height, width, plot_height));
  cv::line(plot, {0, 0}, {width, 0}, kBlack, 1);
  text(plot, "position error (m, log scale) along the distance travelled (m)", {70, 18}, 0.55);
  std::map<std::string, std::vector<std::pair<double, double>>> errors;
  double max_error = 0.01, max_distance = 1.0;
  for (const auto &[name, trajectory] : estimates) {
    if (trajectory.empty() || ground_truth.empty()) continue;
    double travelled = 0.0;
    std::size_t g = 0;
    for (std::size_t k = 0; k < trajectory.size(); ++k) {
      while (g + 1 < ground_truth.size() && ground_truth[g + 1].stamp <= trajectory[k].stamp) {
        travelled += std::hypot(ground_truth[g + 1].pose.x - ground_truth[g].pose.x,
                                ground_truth[g + 1].pose.y - ground_truth[g].pose.y);
        ++g;
      }
      const Eigen::Vector2d &p = paths[name][k];
      const double e = std::hypot(p.x() - ground_truth[g].pose.x, p.y() - ground_truth[g].pose.y);
      errors[name].push_back({travelled, e});
      max_error = std::max(max_error, e);
      max_distance = std::max(max_distance, travelled);
    }
  }
  const int left = 70, right = width - 20, top = 28, bottom = plot_height - 26;
  const double low = 1e-3, high = std::pow(10.0, std::ceil(std::log10(max_error)));  // m
  auto y_of = [&](double e) {
    const double f = (std::log10(std::max(e, low)) - std::log10(low)) / (std::log10(high) - std::log10(low));
    return bottom - static_cast<int>(f * (bottom - top));
  };
  char label[32];
  for (double tick = low; tick <= high * 1.01; tick *= 10.0) {
    const int y = y_of(tick);
    cv::line(plot, {left, y}, {right, y}, {225, 225, 225}, 1);
    std::snprintf(label, sizeof label, "%g", tick);
    text(plot, label, {4, y + 5}, 0.45);
  }
  cv::line(plot, {left, top}, {left, bottom}, kBlack, 1);
  cv::line(plot, {left, bottom}, {right, bottom}, kBlack, 1);
  text(plot, "0", {left - 4, plot_height - 6}, 0.45);
  std::snprintf(label, sizeof label, "%.0f m", max_distance);
  text(plot, label, {right - 50, plot_height - 6}, 0.45);
  for (const auto &[name, series] : errors) {
    const cv::Scalar colour = Palette::method(name);
    for (std::size_t k = 1; k < series.size(); ++k) {
      auto at = [&](const std::pair<double, double> &s) {
        return cv::Point(left + int(s.first / max_distance * (right - left)), y_of(s.second));
      };
      cv::line(plot, at(series[k - 1]), at(series[k]), colour, 2, cv::LINE_AA);
    }
  }
  return image;
}

cv::Mat drawWorld(const simulation::World &world, const std::map<std::string, std::vector<Eigen::Vector2d>> &paths,
                  int width) {
  std::vector<Eigen::Vector2d> extent;
  const simulation::OccupancyGrid *grid = world.grid();
  if (grid) {
    extent.push_back(grid->origin());
    extent.push_back(grid->origin() + grid->resolution() * Eigen::Vector2d(grid->width(), grid->height()));
  }
  for (const simulation::Segment &s : world.segments()) extent.insert(extent.end(), {s.a, s.b});
  for (const auto &[name, path] : paths) extent.insert(extent.end(), path.begin(), path.end());
  const int height = width * 3 / 4;
  const View view = View::fit(extent, width, height);
  cv::Mat image(height, width, CV_8UC3, kWhite);
  if (grid) {  // every pixel looks up its cell
    for (int row = 0; row < height; ++row) {
      for (int col = 0; col < width; ++col) {
        const Eigen::Vector2d p = view.origin + Eigen::Vector2d(col + 0.5, height - row - 0.5) / view.scale;
        const Eigen::Vector2i c = grid->cellOf(p);
        if (!grid->contains(c.x(), c.y())) continue;
        const auto cell = grid->cell(c.x(), c.y());
        if (cell == simulation::OccupancyGrid::Cell::kOccupied)
          image.at<cv::Vec3b>(row, col) = {0, 0, 0};
        else if (cell == simulation::OccupancyGrid::Cell::kUnknown)
          image.at<cv::Vec3b>(row, col) = {215, 215, 215};
      }
    }
  }
  for (const simulation::Segment &s : world.segments())
    cv::line(image, view.pixel(s.a), view.pixel(s.b), kBlack, 2, cv::LINE_AA);
  for (const simulation::Circle &c : world.circles())
    cv::circle(image, view.pixel(c.centre), std::max(1, static_cast<int>(c.radius * view.scale)), kBlack, 2,
               cv::LINE_AA);
  std::vector<std::pair<std::string, cv::Scalar>> entries;
  std::size_t index = 0;
  for (const auto &[name, path] : paths) {
    const cv::Scalar colour = segmentColour(index++);
    for (std::size_t k = 1; k < path.size(); ++k) {
      const bool last = k + 1 == path.size();
      if (last)
        cv::arrowedLine(image, view.pixel(path[k - 1]), view.pixel(path[k]), colour, 3, cv::LINE_AA, 0,
                        std::min(0.5, 15.0 / std::max(1.0, (path[k] - path[k - 1]).norm() * view.scale)));
      else
        cv::line(image, view.pixel(path[k - 1]), view.pixel(path[k]), colour, 3, cv::LINE_AA);
    }
    if (!path.empty()) {
      cv::circle(image, view.pixel(path.front()), 7, colour, -1, cv::LINE_AA);
      text(image, name, view.pixel(path.front()) + cv::Point(9, -9), 0.7, colour);
    }
    entries.push_back({"path " + name, colour});
  }
  decorate(image, view, false);
  legend(image, entries, {15, 30});
  return image;
}

void writeImage(const std::string &path, const cv::Mat &image) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception &error) {
    throw std::runtime_error(path + ": cannot write image: " + error.what());
  }
  if (!ok) throw std::runtime_error(path + ": cannot write image");
}

}  // namespace contour_reg::drawing
