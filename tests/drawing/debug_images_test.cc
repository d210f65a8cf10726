#include <random>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "contour_reg/drawing/debug_images.h"
#include "scenes.h"

namespace contour_reg::drawing {
namespace {

bool hasColour(const cv::Mat &image, cv::Point at, int radius, const cv::Scalar &colour) {
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const cv::Point p = at + cv::Point(dx, dy);
      if (p.x < 0 || p.y < 0 || p.x >= image.cols || p.y >= image.rows) continue;
      const cv::Vec3b v = image.at<cv::Vec3b>(p);
      if (v[0] == colour[0] && v[1] == colour[1] && v[2] == colour[2]) return true;
    }
  return false;
}

int countColour(const cv::Mat &image, const cv::Scalar &colour) {
  int n = 0;
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) n += hasColour(image, {x, y}, 0, colour);
  return n;
}

TEST(DebugImages, ScanImageMarksEveryKnownCornerVertexInTheSpecialPointColour) {
  const test::RoomWithBoxes room;
  const auto pose = test::pose2d(0.0, 0.0, 0.0);
  const LaserScan scan = test::scanFrom(room.world, pose);
  const ContourParams params;
  const ContourFeatures features = extractContourFeatures(scan, params);
  const cv::Mat image = drawScan(scan, features, params, "room", 1200);
  EXPECT_EQ(image.cols, 1200);
  EXPECT_EQ(image.rows, 900 + 240);
  // Same view as drawScan: fitted to the scan's points in the top panel.
  std::vector<Eigen::Vector2d> points;
  for (const Complex &c : polarCode(scan))
    if (isFinite(c)) points.push_back(toEigen(c));
  const View view = View::fit(points, 1200, 900);
  const auto corners = room.visibleCorners(pose);
  ASSERT_GE(corners.size(), 4u);
  for (const Eigen::Vector2d &corner : corners)
    EXPECT_TRUE(hasColour(image, view.pixel(corner), 2, Palette::specialPoint())) << corner.transpose();
  EXPECT_FALSE(hasColour(image, view.pixel({0.0, 0.0}), 3, Palette::specialPoint()));  // the sensor is no corner
}

TEST(DebugImages, AScanWithoutSpecialPointsSaysSo) {
  simulation::World circle;
  circle.addCircle({0.0, 0.0}, 4.0);
  const LaserScan scan = test::scanFrom(circle, test::pose2d(0.5, 0.0, 0.0));
  const ContourParams params;
  const ContourFeatures features = extractContourFeatures(scan, params);
  ASSERT_TRUE(features.special_points.empty());
  const cv::Mat image = drawScan(scan, features, params, "circle");
  EXPECT_GT(countColour(image(cv::Rect(0, 60, 1200, 40)), Palette::warning()), 100);  // the red notice line
  EXPECT_GT(countColour(image, {150, 150, 150}), 50);                                 // the raw points are drawn
}

// The raw scan (grey) shows beside the deskewed one only when the motion moved its beams.
TEST(DebugImages, DeskewImageShowsTheRawScanWhereTheMotionMovedIt) {
  const test::RoomWithBoxes room;
  LaserScan scan = test::scanFrom(room.world, test::pose2d(0.0, 0.0, 0.0));
  scan.time_increment = 1e-4;
  const cv::Rect points_only(0, 100, 1200, 900 - 100 - 80);  // below the text, above the legend
  const cv::Scalar grey(150, 150, 150);
  const cv::Mat still = drawDeskew(scan, Twist2D{}, "still");
  EXPECT_EQ(still.rows, 900);
  EXPECT_GT(countColour(still(points_only), Palette::source()), 500);
  EXPECT_EQ(countColour(still(points_only), grey), 0);  // the deskewed points cover the raw ones
  const cv::Mat moving = drawDeskew(scan, Twist2D{1.0, 0.0, 1.0}, "moving");
  EXPECT_GT(countColour(moving(points_only), grey), 300);
}

TEST(DebugImages, PairAndAlignmentImagesAreDrawn) {
  const simulation::World world = simulation::makeFurnishedRoom();
  const LaserScan a = test::scanFrom(world, test::pose2d(0, 0, 0)),
                  b = test::scanFrom(world, test::pose2d(0.2, 0.1, 5));
  const ContourParams params;
  const ContourFeatures fa = extractContourFeatures(a, params), fb = extractContourFeatures(b, params);
  std::mt19937 rng(1);
  const RegistrationResult result = registerContours(fb, fa, RegistrationParams{}, rng);
  ASSERT_TRUE(result.converged);
  const cv::Mat pair = drawPair(a, b, fa, fb, result, "pair", 1600);
  EXPECT_EQ(pair.cols, 1600);
  EXPECT_GT(countColour(pair, Palette::inlier()), 20);
  EXPECT_GT(countColour(pair, Palette::source()), 500);
  const cv::Mat sides = drawAlignments(
      a, b, {{"contour", result.transform, true, ""}, {"none", Eigen::Matrix3d::Identity(), false, "too few inliers"}},
      500);
  EXPECT_EQ(sides.cols, 1000);
  const int band = sides.rows - 500;  // the words above the panels
  ASSERT_GT(band, 0);
  // The failure and its reason are written in the band, not over the scans.
  EXPECT_GT(countColour(sides(cv::Rect(500, 0, 500, band)), Palette::warning()), 100);
  EXPECT_EQ(countColour(sides(cv::Rect(0, band, 1000, 500)), Palette::warning()), 0);

  // With the pair's true motion, a panel of the source moved by it comes first, on the same
  // view: where the result is the true motion, the two panels' scans are drawn alike.
  const std::vector<Alignment> contour{{"contour", result.transform, true, ""}};
  const cv::Mat truth = drawAlignments(a, b, contour, 500, result.transform);
  ASSERT_EQ(truth.cols, 1000);
  const auto scans = [&](const cv::Mat &image, int panel) {
    return image(cv::Rect(panel * 500 + 1, band, 499, 440));  // above the legend
  };
  EXPECT_EQ(cv::norm(scans(truth, 0), scans(truth, 1), cv::NORM_L1), 0.0);
  Eigen::Matrix3d elsewhere = result.transform;
  elsewhere(0, 2) += 1.0;
  const cv::Mat other = drawAlignments(a, b, contour, 500, elsewhere);
  EXPECT_GT(cv::norm(scans(other, 0), scans(other, 1), cv::NORM_L1), 0.0);
  EXPECT_GT(countColour(scans(other, 0), Palette::source()), 100);
}

// Two scans of a corridor with a door recess every 3 m, closed 9 m ahead: the target at the
// origin, the source at `source_pose`; their features.
struct CorridorPair {
  explicit CorridorPair(const Eigen::Isometry2d &source_pose)
      : target(test::scanFrom(test::corridorOfDoors(), test::pose2d(0, 0, 0), 0.01, 1)),
        source(test::scanFrom(test::corridorOfDoors(), source_pose, 0.01, 2)),
        ft(extractContourFeatures(target, ContourParams{})),
        fs(extractContourFeatures(source, ContourParams{})) {}
  LaserScan target, source;
  ContourFeatures ft, fs;
};

// One door back, the walls still fit, but the end wall lands where the other scan looked through.
TEST(DebugImages, PairImageShowsTheContourAMotionPutsInFreeSpace) {
  const CorridorPair pair(test::pose2d(0.5, 0.0, 0));
  const auto &[target, source, ft, fs] = pair;
  RegistrationResult right, alias;
  right.converged = alias.converged = true;
  right.transform(0, 2) = 0.5;
  alias.transform(0, 2) = 0.5 - 3.0;
  EXPECT_EQ(countColour(drawPair(target, source, ft, fs, right, "right", 1200), Palette::freeSpace()), 0);
  EXPECT_GT(countColour(drawPair(target, source, ft, fs, alias, "one door back", 1200), Palette::freeSpace()), 50);
}

// Registered, a pair 3 m apart converges on the truth; the third panel shows the rival the
// judge weighed, one door back, with its end wall in the free space.
TEST(DebugImages, PairImageShowsTheBestRejectedMotion) {
  const CorridorPair pair(test::pose2d(3.0, 0.05, 1));
  const auto &[target, source, ft, fs] = pair;
  std::mt19937 rng(3);
  RegistrationResult result = registerContours(fs, ft, RegistrationParams{}, rng);
  ASSERT_TRUE(result.converged) << result.reason;
  ASSERT_TRUE(result.rejected.has_value());
  const cv::Mat image = drawPair(target, source, ft, fs, result, "pair", 1200);
  ASSERT_EQ(image.cols, 1800);
  const int band = image.rows - 600;  // the words above the panels
  ASSERT_GT(band, 0);
  const cv::Mat middle = image(cv::Rect(600, band, 600, 600)), third = image(cv::Rect(1200, band, 600, 600));
  EXPECT_EQ(countColour(middle, Palette::freeSpace()), 0);
  EXPECT_GT(countColour(third, Palette::freeSpace()), 50);
  EXPECT_GT(countColour(third, Palette::source()), 300);
  result.rejected.reset();
  EXPECT_EQ(drawPair(target, source, ft, fs, result, "pair", 1200).cols, 1200);
}

TEST(DebugImages, TrajectoriesAreDrawnOverGroundTruth) {
  io::Trajectory truth, estimate;
  for (int k = 0; k < 50; ++k) {
    truth.push_back({double(k), {0.2 * k, 0.0, 0.0}});
    estimate.push_back({double(k), {0.2 * k, 0.01 * k, 0.0}});
  }
  const cv::Mat image = drawTrajectories({{"contour", estimate}}, truth, 900);
  EXPECT_EQ(image.cols, 900);
  EXPECT_GT(countColour(image, {0, 0, 0}), 300);
  // A method keeps its colour whatever else is drawn beside it.
  const cv::Mat both = drawTrajectories({{"contour", estimate}, {"icp", truth}}, truth, 900, "title");
  EXPECT_GT(countColour(both, Palette::method("contour")), 300);
  EXPECT_GT(countColour(both, Palette::method("icp")), 300);
  EXPECT_NE(Palette::method("contour"), Palette::method("icp"));
}

}  // namespace
}  // namespace contour_reg::drawing
