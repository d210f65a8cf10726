// The simulator: exact ray casting, the noise model, paths and their placement, runs that a
// seed fixes and that round-trip through the CARMEN reader, occupancy maps.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "contour_reg/io/carmen.h"
#include "contour_reg/io/pose2d.h"
#include "contour_reg/simulation/lidar.h"
#include "contour_reg/simulation/occupancy_grid.h"
#include "contour_reg/simulation/office.h"
#include "contour_reg/simulation/paths.h"
#include "contour_reg/simulation/simulated_run.h"
#include "temp_dir.h"

namespace contour_reg::simulation {
namespace {

using V = Eigen::Vector2d;

TEST(RayCasting, ABoxGivesExactRanges) {
  World box;
  box.addBox({-2.0, -1.0}, {3.0, 4.0});
  EXPECT_DOUBLE_EQ(box.castRay({0, 0}, {1, 0}), 3.0);
  EXPECT_DOUBLE_EQ(box.castRay({0, 0}, {-1, 0}), 2.0);
  EXPECT_DOUBLE_EQ(box.castRay({0, 0}, {0, 1}), 4.0);
  EXPECT_NEAR(box.castRay({0, 0}, V(1, 1).normalized()), 3.0 * std::sqrt(2.0), 1e-12);
  World circle;
  circle.addCircle({5.0, 0.0}, 1.0);
  EXPECT_NEAR(circle.castRay({0, 0}, {1, 0}), 4.0, 1e-12);
  EXPECT_TRUE(std::isinf(circle.castRay({0, 0}, {-1, 0})));
}

TEST(RayCasting, ScanOfABoxMatchesGeometry) {
  World box;
  box.addBox({-2.0, -2.0}, {2.0, 2.0});
  LidarModel model = LidarModel::hokuyoUtm30lx();
  model.range_noise = 0.0;
  std::mt19937 rng(1);
  const LaserScan scan = simulateScan(box, Eigen::Isometry2d::Identity(), model, rng);
  ASSERT_EQ(scan.ranges.size(), 1081u);
  for (std::size_t n = 0; n < scan.ranges.size(); ++n) {
    const double a = scan.bearing(n);
    const double expected = 2.0 / std::max(std::abs(std::cos(a)), std::abs(std::sin(a)));
    ASSERT_NEAR(scan.ranges[n], expected, 1e-5) << "beam " << n;
  }
}

TEST(OccupancyGrid, RaysStopAtTheFirstOccupiedCellBoundary) {
  // 20 x 10 cells of 0.1 m, origin (-1, -0.5); a wall of occupied cells in column 15.
  std::vector<OccupancyGrid::Cell> cells(200, OccupancyGrid::Cell::kFree);
  for (int row = 0; row < 10; ++row) cells[static_cast<std::size_t>(row * 20 + 15)] = OccupancyGrid::Cell::kOccupied;
  const OccupancyGrid grid(20, 10, 0.1, {-1.0, -0.5}, cells);
  // The wall's near face is at x = -1 + 1.5 = 0.5.
  EXPECT_NEAR(grid.castRay({0.0, 0.0}, {1, 0}), 0.5, 1e-9);
  EXPECT_NEAR(grid.castRay({0.0, 0.0}, V(1, 0.2).normalized()), 0.5 * V(1, 0.2).norm(), 1e-9);
  EXPECT_TRUE(std::isinf(grid.castRay({0.0, 0.0}, {-1, 0})));  // leaves the grid
  EXPECT_NEAR(grid.clearance({0.0, 0.0}), 0.5, 0.15);
  EXPECT_TRUE(grid.isFree({0.0, 0.0}));
  EXPECT_FALSE(grid.isFree({0.55, 0.0}));
}

TEST(OccupancyGrid, MapServerYamlAndPgmAreRead) {
  test::TempDir dir;
  {  // 4 x 3 PGM: top row black (occupied), the rest white; one grey (unknown) pixel
    std::ofstream pgm(dir.file("map.pgm"), std::ios::binary);
    pgm << "P5\n4 3\n255\n";
    const unsigned char pixels[12] = {0, 0, 0, 0, 255, 205, 255, 255, 255, 255, 255, 255};
    pgm.write(reinterpret_cast<const char *>(pixels), 12);
  }
  dir.write("map.yaml",
            "image: map.pgm\nresolution: 0.5\norigin: [-1.0, 2.0, 0.0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const OccupancyGrid grid = readOccupancyGrid(dir.file("map.yaml"));
  EXPECT_EQ(grid.width(), 4);
  EXPECT_EQ(grid.height(), 3);
  EXPECT_DOUBLE_EQ(grid.resolution(), 0.5);
  EXPECT_EQ(grid.cell(0, 2), OccupancyGrid::Cell::kOccupied);  // the image's top row is the grid's last
  EXPECT_EQ(grid.cell(1, 1), OccupancyGrid::Cell::kUnknown);
  EXPECT_EQ(grid.cell(0, 0), OccupancyGrid::Cell::kFree);
  EXPECT_NEAR(grid.castRay({-0.75, 2.25}, {0, 1}), 0.75, 1e-9);  // from y 2.25 to the top row, which starts at 3.0
  const OccupancyGrid same = readOccupancyGrid(dir.file("map.pgm"), {0.5, V(-1.0, 2.0)});
  EXPECT_EQ(same.cell(0, 2), OccupancyGrid::Cell::kOccupied);

  dir.write("bad.yaml", "image: map.pgm\nresolution: [oops\n");
  try {
    readOccupancyGrid(dir.file("bad.yaml"));
    FAIL() << "a broken YAML file must be refused";
  } catch (const io::ReadError &error) {
    EXPECT_NE(std::string(error.what()).find("bad.yaml:"), std::string::npos) << error.what();
  }
  dir.write("noimage.yaml", "resolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_THROW(readOccupancyGrid(dir.file("noimage.yaml")), io::ReadError);
  EXPECT_THROW(readOccupancyGrid(dir.file("missing.pgm")), io::ReadError);
}

// Refused with the file (and line) named, none thrown past the reader or run for ever.
void expectRefused(const std::string &path, const std::string &named) {
  try {
    readOccupancyGrid(path);
    FAIL() << path << " must be refused";
  } catch (const io::ReadError &error) {
    EXPECT_NE(std::string(error.what()).find(named), std::string::npos) << error.what();
  }
}

TEST(OccupancyGrid, MapsNoGridCanHoldAreRefused) {
  test::TempDir dir;
  {
    std::ofstream pgm(dir.file("map.pgm"), std::ios::binary);
    pgm << "P5\n2 2\n255\n";
    pgm.write("\xff\xff\xff\x00", 4);
  }
  const std::string map = "image: map.pgm\nresolution: 0.05\n";
  dir.write("nan.yaml", map + "origin: [.nan, 0, 0]\n");
  expectRefused(dir.file("nan.yaml"), "nan.yaml:3");
  // Cells 5 cm wide 1e300 m from zero: doubles there are 1e284 m apart.
  dir.write("far.yaml", map + "origin: [1e300, 0, 0]\n");
  expectRefused(dir.file("far.yaml"), "far.yaml:3");
  dir.write("inf.yaml", "image: map.pgm\nresolution: 1e308\norigin: [0, 0, 0]\n");
  expectRefused(dir.file("inf.yaml"), "inf.yaml:2");
  {  // a header of 10^10 pixels: more than OpenCV reads
    std::ofstream pgm(dir.file("huge.pgm"), std::ios::binary);
    pgm << "P5\n100000 100000\n255\n";
  }
  expectRefused(dir.file("huge.pgm"), "huge.pgm");
  // An image name longer than the file system takes: no such image, as a missing one.
  dir.write("long.yaml", "image: " + std::string(300, 'l') + ".pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  expectRefused(dir.file("long.yaml"), "no such map image");
}

TEST(Lidar, NoiseAndDropoutFollowTheModel) {
  World wall;
  wall.addSegment({5.0, -100.0}, {5.0, 100.0});
  LidarModel model;
  model.beams = 20001;
  model.field_of_view = 0.02;  // all beams almost straight at the wall, 5 m away
  model.range_noise = 0.02;
  model.dropout = 0.1;
  std::mt19937 rng(7);
  const LaserScan scan = simulateScan(wall, Eigen::Isometry2d::Identity(), model, rng);
  std::vector<double> errors;
  for (std::size_t n = 0; n < scan.ranges.size(); ++n)
    if (std::isfinite(scan.ranges[n])) errors.push_back(scan.ranges[n] - 5.0 / std::cos(scan.bearing(n)));
  const double dropped = 1.0 - static_cast<double>(errors.size()) / static_cast<double>(scan.ranges.size());
  EXPECT_NEAR(dropped, 0.1, 0.01);
  const double mean = std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
  double variance = 0.0;
  for (double e : errors) variance += (e - mean) * (e - mean);
  variance /= static_cast<double>(errors.size() - 1);
  EXPECT_NEAR(mean, 0.0, 0.001);
  EXPECT_NEAR(std::sqrt(variance), 0.02, 0.001);
}

// A SICK LMS200 reports whole centimetres, one beam per degree over 180 deg: so does its model.
TEST(Lidar, SickRangesAreWholeCentimetresOneDegreeApart) {
  World wall;
  wall.addSegment({5.0, -100.0}, {5.0, 100.0});
  const LidarModel model = LidarModel::sickLms200();
  std::mt19937 rng(7);
  const LaserScan scan = simulateScan(wall, Eigen::Isometry2d::Identity(), model, rng);
  ASSERT_EQ(scan.ranges.size(), 181u);
  EXPECT_NEAR(scan.angle_increment, M_PI / 180.0, 1e-12);
  EXPECT_NEAR(scan.angle_min, -M_PI / 2.0, 1e-12);
  int finite = 0, off_true_range = 0;
  for (std::size_t n = 0; n < scan.ranges.size(); ++n) {
    if (!std::isfinite(scan.ranges[n])) continue;
    ++finite;
    EXPECT_NEAR(100.0 * scan.ranges[n], std::round(100.0 * scan.ranges[n]), 1e-3) << n;
    off_true_range += std::abs(scan.ranges[n] - 5.0 / std::cos(scan.bearing(n))) > 0.005;
  }
  // The beams that meet the wall within 80 m: within about 86.4 deg of straight ahead.
  EXPECT_EQ(finite, 2 * 86 + 1);
  EXPECT_GT(off_true_range, finite / 2);  // noise of 1 cm, not just the rounding
}

TEST(Paths, ShapesHaveTheirTurnsAndLengths) {
  EXPECT_NEAR(pathLength(officePath("L")), 24.4, 1e-9);
  EXPECT_EQ(officePath("L").size(), 3u);  // one turn
  EXPECT_EQ(officePath("S").size(), 6u);  // four turns, alternating
  const auto o = officePath("O");
  EXPECT_NEAR((o.front() - o.back()).norm(), 0.0, 1e-9);  // a closed loop
  EXPECT_TRUE(officePath("Q").empty());
  const auto poses = samplePath(officePath("L"), 0.5);
  EXPECT_EQ(poses.size(), 50u);  // 24.4 m every 0.5 m, and the end
  EXPECT_NEAR(poses.back().translation().x(), 22.5, 1e-9);
  EXPECT_NEAR(poses.back().translation().y(), 11.4, 1e-9);
  EXPECT_NEAR(std::atan2(poses.front().linear()(1, 0), poses.front().linear()(0, 0)), 0.0, 1e-9);
  EXPECT_NEAR(std::atan2(poses.back().linear()(1, 0), poses.back().linear()(0, 0)), M_PI / 2, 1e-9);
}

TEST(Paths, OfficePathsKeepClearOfObstacles) {
  const World office = makeOfficeWorld();
  for (const std::string &name : {"S", "L", "Y", "O", "line"}) {
    const auto waypoints = officePath(name);
    for (const auto &pose : samplePath(waypoints, 0.05))
      ASSERT_GE(office.clearance(pose.translation()), 0.45) << name << " at " << pose.translation().transpose();
  }
}

TEST(DoorRow, ScansAWholeNumberOfPeriodsApartSeeTheSame) {
  const World doors = makeDoorRowWorld();
  LidarModel model = LidarModel::ydlidarX4();  // 10 m: neither end in sight from the middle
  model.range_noise = 0.0;
  model.dropout = 0.0;
  std::mt19937 rng(1);
  const auto scanAt = [&](double x) {
    return simulateScan(doors, Eigen::Isometry2d(Eigen::Translation2d(x, 1.2)), model, rng);
  };
  const LaserScan here = scanAt(25.0), period_on = scanAt(25.0 + kDoorRowPeriod),
                  two_on = scanAt(25.0 + 2.0 * kDoorRowPeriod), half_on = scanAt(25.0 + 0.5 * kDoorRowPeriod);
  ASSERT_EQ(here.ranges.size(), period_on.ranges.size());
  const auto apart = [](double a, double b) { return std::abs(a - b); };
  double period_gap = 0.0, half_gap = 0.0;
  int returns = 0;
  for (std::size_t n = 0; n < here.ranges.size(); ++n) {
    if (!std::isfinite(here.ranges[n])) continue;
    ++returns;
    period_gap =
        std::max({period_gap, apart(period_on.ranges[n], here.ranges[n]), apart(two_on.ranges[n], here.ranges[n])});
    half_gap = std::max(half_gap, apart(half_on.ranges[n], here.ranges[n]));
  }
  EXPECT_GT(returns, 300);
  EXPECT_LT(period_gap, 1e-9);  // the same scan, beam for beam
  EXPECT_GT(half_gap, 0.1);     // half a period on, the recesses are elsewhere
  // The ends are in sight near them: a scan one period from the west end differs from the middle's.
  const LaserScan near_end = scanAt(1.0 + kDoorRowPeriod), next = scanAt(1.0 + 2.0 * kDoorRowPeriod);
  double end_gap = 0.0;
  for (std::size_t n = 0; n < near_end.ranges.size(); ++n)
    if (std::isfinite(near_end.ranges[n]) && std::isfinite(next.ranges[n]))
      end_gap = std::max(end_gap, apart(near_end.ranges[n], next.ranges[n]));
  EXPECT_GT(end_gap, 1.0);
  // Its path keeps clear of the walls.
  const auto line = doorRowPath("line");
  ASSERT_EQ(line.size(), 2u);
  for (const auto &pose : samplePath(line, 0.05)) ASSERT_GE(doors.clearance(pose.translation()), 1.0);
  EXPECT_TRUE(doorRowPath("L").empty());
}

TEST(Paths, PlacementFindsRoomInAMapAndKeepsClearance) {
  // A 30 m x 20 m hall as an occupancy grid (walls one cell thick).
  const int width = 300, height = 200;
  std::vector<OccupancyGrid::Cell> cells(static_cast<std::size_t>(width * height), OccupancyGrid::Cell::kFree);
  for (int col = 0; col < width; ++col)
    for (int row : {0, height - 1}) cells[static_cast<std::size_t>(row * width + col)] = OccupancyGrid::Cell::kOccupied;
  for (int row = 0; row < height; ++row)
    for (int col : {0, width - 1}) cells[static_cast<std::size_t>(row * width + col)] = OccupancyGrid::Cell::kOccupied;
  World hall;
  hall.setGrid(std::make_shared<OccupancyGrid>(width, height, 0.1, V(0, 0), cells));
  for (const std::string &shape : pathShapes()) {
    const auto placed = placePath(hall, pathShape(shape));
    ASSERT_FALSE(placed.empty()) << shape;
    EXPECT_NEAR(pathLength(placed), pathLength(pathShape(shape)), 1e-9) << shape;  // full size fits
    for (const auto &pose : samplePath(placed, 0.1)) EXPECT_GE(hall.clearance(pose.translation()), 0.6 - 0.15);
  }
  World closet;
  closet.addBox({0, 0}, {2, 2});
  EXPECT_TRUE(placePath(closet, pathShape("L")).empty());
}

TEST(Paths, PlacementInAVastMapTriesABoundedNumberOfPlaces) {
  // 40 x 40 cells of 1 km inside a ring of walls: the search does not try every half metre of
  // 40 km by 40 km, and the shape fits in the free cells.
  const int size = 40;
  std::vector<OccupancyGrid::Cell> cells(static_cast<std::size_t>(size * size), OccupancyGrid::Cell::kFree);
  for (int k = 0; k < size; ++k)
    for (int edge : {0, size - 1}) {
      cells[static_cast<std::size_t>(edge * size + k)] = OccupancyGrid::Cell::kOccupied;
      cells[static_cast<std::size_t>(k * size + edge)] = OccupancyGrid::Cell::kOccupied;
    }
  World vast;
  vast.setGrid(std::make_shared<OccupancyGrid>(size, size, 1000.0, V(0, 0), cells));
  PlacementOptions options;
  options.sight_range = 1e6;  // its walls are tens of kilometres away
  const auto placed = placePath(vast, pathShape("L"), options);
  ASSERT_FALSE(placed.empty());
  for (const auto &pose : samplePath(placed, 1.0)) EXPECT_GE(vast.clearance(pose.translation()), options.clearance);
}

TEST(SimulatedRun, ASeedFixesTheRunAndItRoundTripsThroughCarmen) {
  const World office = makeOfficeWorld();
  RunSettings settings;
  settings.rate = 2.0;
  settings.seed = 5;
  const auto path = officePath("L");
  const SimulatedRun a = simulateRun(office, path, settings);
  const SimulatedRun b = simulateRun(office, path, settings);
  ASSERT_EQ(a.log.entries.size(), 99u);  // 24.4 m at 0.25 m spacing, and the end
  ASSERT_EQ(a.ground_truth.size(), a.log.entries.size());
  for (std::size_t k = 0; k < a.log.entries.size(); ++k) {
    ASSERT_EQ(a.log.entries[k].scan.ranges.size(), b.log.entries[k].scan.ranges.size());
    for (std::size_t n = 0; n < a.log.entries[k].scan.ranges.size(); ++n) {
      const float x = a.log.entries[k].scan.ranges[n], y = b.log.entries[k].scan.ranges[n];
      ASSERT_TRUE((std::isnan(x) && std::isnan(y)) || x == y);
    }
  }
  settings.seed = 6;
  const SimulatedRun c = simulateRun(office, path, settings);
  EXPECT_NE(a.log.entries[3].scan.ranges[500], c.log.entries[3].scan.ranges[500]);

  test::TempDir dir;
  io::writeCarmen(dir.file("run.clf"), a.log);
  const io::ScanLog read = io::readCarmen(dir.file("run.clf"));
  ASSERT_EQ(read.entries.size(), a.log.entries.size());
  const LaserScan &original = a.log.entries[10].scan, &back = read.entries[10].scan;
  EXPECT_NEAR(back.angle_min, original.angle_min, 1e-6);
  EXPECT_NEAR(back.angle_increment, original.angle_increment, 1e-6);
  EXPECT_NEAR(back.stamp, original.stamp, 1e-6);
  for (std::size_t n = 0; n < original.ranges.size(); n += 37)
    if (std::isfinite(original.ranges[n])) EXPECT_NEAR(back.ranges[n], original.ranges[n], 1e-3);
  ASSERT_TRUE(read.entries[10].odometry.has_value());
  EXPECT_NEAR(read.entries[10].odometry->x, a.log.entries[10].odometry->x, 1e-4);
}

TEST(SimulatedRun, ContinuousMotionDistortsTheScan) {
  World box;
  box.addBox({-10.0, -10.0}, {10.0, 10.0});
  RunSettings settings;
  settings.rate = 1.0;
  settings.speed = 1.0;
  settings.lidar.range_noise = 0.0;
  const std::vector<V> line = {V(-5, 0), V(5, 0)};
  settings.motion = Motion::kStopAndGo;
  const SimulatedRun still = simulateRun(box, line, settings);
  settings.motion = Motion::kContinuous;
  const SimulatedRun moving = simulateRun(box, line, settings);
  ASSERT_EQ(still.log.entries.size(), moving.log.entries.size());
  const auto &a = still.log.entries[2].scan.ranges, &b = moving.log.entries[2].scan.ranges;
  // The first beam fires where the robot stands; the last about 0.75 m (a 270 deg sweep in 1 s) further on.
  EXPECT_NEAR(a.front(), b.front(), 1e-4);
  EXPECT_GT(std::abs(a.back() - b.back()), 0.3);
}

// The command line and Python take LIDAR models and motions by these names.
TEST(SimulatedRun, LidarModelsAndMotionsAreKnownByName) {
  EXPECT_EQ(lidarModelNamed("hokuyo")->beams, LidarModel::hokuyoUtm30lx().beams);
  EXPECT_EQ(lidarModelNamed("ydlidar")->beams, LidarModel::ydlidarX4().beams);
  EXPECT_EQ(lidarModelNamed("sick")->beams, LidarModel::sickLms200().beams);
  EXPECT_FALSE(lidarModelNamed("velodyne").has_value());
  EXPECT_EQ(motionNamed("stop-and-go"), Motion::kStopAndGo);
  EXPECT_EQ(motionNamed("continuous"), Motion::kContinuous);
  EXPECT_FALSE(motionNamed("moving").has_value());
  EXPECT_EQ(lidarModelNames().size(), 3u);
  EXPECT_EQ(motionNames().size(), 2u);
}

// A run longer than any simulation is refused before it starts, not cut short or left to run
// out of memory; its size is in the message.
TEST(SimulatedRun, ARunOfMoreThanAMillionScansIsRefused) {
  World box;
  box.addBox({-10.0, -10.0}, {10.0, 10.0});
  const std::vector<V> path = {V(-5, 0), V(5, 0)};
  const auto expectRefused = [&](const std::vector<V> &waypoints, const RunSettings &settings, const char *named) {
    try {
      simulateRun(box, waypoints, settings);
      FAIL() << "refused: " << named;
    } catch (const std::invalid_argument &error) {
      EXPECT_NE(std::string(error.what()).find(named), std::string::npos) << error.what();
    }
  };
  RunSettings crawl;
  crawl.speed = 1e-300;  // 10 m in 1e301 s
  expectRefused(path, crawl, "scans");
  RunSettings slow;
  slow.speed = 1e-5;  // 2 million scans
  expectRefused(path, slow, "scans");
  expectRefused({V(0, 0), V(1e300, 0)}, RunSettings(), "scans");
  expectRefused({V(0, 0), V(1e200, 1e200), V(-1e200, -1e200), V(1e300, 0)}, RunSettings(), "scans");
  RunSettings chatty;
  chatty.odometry_rate = 1e12;  // 10^12 odometry samples a second over 20 s
  expectRefused(path, chatty, "odometry samples");
  RunSettings ok;
  ok.speed = 1e-4;  // 200 001 scans: a long run, but one
  ok.lidar.beams = 2;
  ok.odometry_rate = 0.0;
  EXPECT_EQ(simulateRun(box, path, ok).log.entries.size(), 200001u);
}

// The wheel odometry is logged as a robot's /odom is, between the scans as well as at them:
// exact without noise, and at each scan's stamp the scan's own odometry.
TEST(SimulatedRun, WheelOdometryIsLoggedBetweenTheScans) {
  World box;
  box.addBox({-10.0, -10.0}, {10.0, 10.0});
  RunSettings settings;
  settings.rate = 2.0;
  settings.odometry_rate = 20.0;
  settings.odometry_noise = 0.0;
  settings.motion = Motion::kContinuous;
  const std::vector<V> path = {V(-5, 0), V(0, 0), V(0, 5)};
  const SimulatedRun run = simulateRun(box, path, settings);
  const double duration = run.log.entries.back().scan.stamp;
  ASSERT_EQ(run.log.wheel_odometry.size(), static_cast<std::size_t>(std::lround(duration * 20.0)) + 1);
  for (std::size_t i = 0; i < run.log.wheel_odometry.size(); ++i) {
    const io::StampedPose &sample = run.log.wheel_odometry[i];
    EXPECT_NEAR(sample.stamp, 0.05 * static_cast<double>(i), 1e-9);
    const io::Pose2D truth =
        io::toPose(poseAlongPath(path, std::min(0.5 * sample.stamp, run.path_length), settings.turn_radius).matrix());
    EXPECT_NEAR(sample.pose.x, truth.x, 1e-9) << sample.stamp;
    EXPECT_NEAR(sample.pose.y, truth.y, 1e-9) << sample.stamp;
    EXPECT_NEAR(std::remainder(sample.pose.yaw - truth.yaw, 2 * M_PI), 0.0, 1e-9) << sample.stamp;
  }
  settings.odometry_noise = 0.05;
  const SimulatedRun noisy = simulateRun(box, path, settings);
  for (const io::LogEntry &entry : noisy.log.entries) {
    const auto at = std::find_if(noisy.log.wheel_odometry.begin(), noisy.log.wheel_odometry.end(),
                                 [&](const io::StampedPose &p) { return p.stamp == entry.scan.stamp; });
    ASSERT_NE(at, noisy.log.wheel_odometry.end()) << entry.scan.stamp;
    EXPECT_EQ(at->pose.x, entry.odometry->x);
    EXPECT_EQ(at->pose.yaw, entry.odometry->yaw);
  }
  settings.odometry_rate = 0.0;
  EXPECT_TRUE(simulateRun(box, path, settings).log.wheel_odometry.empty());
}

}  // namespace
}  // namespace contour_reg::simulation
