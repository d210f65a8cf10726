#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>
#include <pcl/console/print.h>
#include <Eigen/Cholesky>

#include "contour_reg/evaluation/metrics.h"
#include "contour_reg/io/pose2d.h"
#include "contour_reg/odometry/odometry.h"
#include "contour_reg/simulation/office.h"
#include "contour_reg/simulation/paths.h"
#include "contour_reg/simulation/simulated_run.h"
#include "scenes.h"

namespace contour_reg::odometry {
namespace {

// Scans along a curve through the furnished room, 0.2 m and a few degrees apart.
struct Sequence {
  io::ScanLog log;
  io::Trajectory truth;
};

Sequence roomSequence(int scans = 20, double noise = 0.01) {
  const simulation::World world = simulation::makeFurnishedRoom();
  Sequence s;
  for (int k = 0; k < scans; ++k) {
    const double x = -3.0 + 0.2 * k, y = -1.0 + 0.4 * std::sin(0.15 * k), yaw_deg = 10.0 * std::sin(0.1 * k);
    io::LogEntry entry;
    entry.scan = test::scanFrom(world, test::pose2d(x, y, yaw_deg), noise, 100 + k);
    entry.scan.stamp = 0.2 * k;
    s.log.entries.push_back(entry);
    s.truth.push_back({entry.scan.stamp, {x, y, yaw_deg * M_PI / 180.0}});
  }
  return s;
}

// The robot turns `yaw` rad on the spot just before scan `from`: the truth and the scans from
// there on turn with it.
void turnOnTheSpot(Sequence &s, std::size_t from, double yaw) {
  for (std::size_t k = from; k < s.log.entries.size(); ++k) {
    io::Pose2D &pose = s.truth[k].pose;
    pose.yaw += yaw;
    const double stamp = s.log.entries[k].scan.stamp;
    s.log.entries[k].scan =
        test::scanFrom(simulation::makeFurnishedRoom(), test::pose2d(pose.x, pose.y, pose.yaw * 180.0 / M_PI), 0.0,
                       100 + static_cast<int>(k));
    s.log.entries[k].scan.stamp = stamp;
  }
}

// Wheel odometry at every scan: the truth, its yaw off by `yaw_error` times 0, 2, 4, 1, 3, 0, ...
// so that each increment errs by 2 or 3 times `yaw_error`.
void addWheels(Sequence &s, double yaw_error) {
  for (std::size_t k = 0; k < s.log.entries.size(); ++k) {
    io::Pose2D wheels = s.truth[k].pose;
    wheels.yaw += yaw_error * static_cast<double>(k * 7 % 5);
    s.log.entries[k].odometry = wheels;
  }
}

// The error of the run's motion from scan 0 to scan k against the truth.
io::Pose2D errorTo(const Sequence &s, const OdometryRun &run, std::size_t k) {
  return io::between(io::between(s.truth[0].pose, s.truth[k].pose),
                     io::between(run.trajectory[0].pose, run.trajectory[k].pose));
}

TEST(Odometry, ContourOdometryFollowsTheTrueTrajectory) {
  const Sequence s = roomSequence();
  auto matcher = makeScanMatcher("contour");
  ASSERT_TRUE(matcher);
  const OdometryRun run = runOdometry(s.log, *matcher);
  ASSERT_EQ(run.trajectory.size(), s.truth.size());
  EXPECT_EQ(run.stats.failures, 0u);
  const auto a = evaluation::associate(run.trajectory, s.truth);
  EXPECT_LT(evaluation::endPointError(a).error, 0.05);
  EXPECT_LT(evaluation::absoluteTrajectoryError(a), 0.03);
}

// Each step's motion and covariance, as a pose graph takes them: the motions chain to the
// trajectory, and the true motion lies within the covariance's 99.9 % ellipsoid (with 1 cm /
// 0.2 deg added for the scans' noise).
TEST(Odometry, StepsCarryTheChainedMotionAndAnHonestCovariance) {
  const Sequence s = roomSequence();
  auto matcher = makeScanMatcher("contour");
  const OdometryRun run = runOdometry(s.log, *matcher);
  ASSERT_EQ(run.steps.size(), s.truth.size() - 1);
  for (const OdometryStep &step : run.steps) {
    ASSERT_TRUE(step.converged) << step.status;
    EXPECT_EQ(step.scan, step.reference + 1);
    const io::Pose2D chained = io::between(run.trajectory[step.reference].pose, run.trajectory[step.scan].pose);
    EXPECT_NEAR(chained.x, step.motion.x, 1e-9);
    EXPECT_EQ(step.covariance.llt().info(), Eigen::Success) << "step " << step.scan << ": no covariance";
    const io::Pose2D truth = io::between(s.truth[step.reference].pose, s.truth[step.scan].pose);
    EXPECT_LT(evaluation::normalisedErrorSquared(step.motion, truth, step.covariance, 0.01, 0.2 * M_PI / 180), 16.27)
        << "step " << step.scan;
  }
}

// The office's S path driven without stopping: the scans are bent by the motion. The end-point
// error in % of the path, raw and deskewed, of a run at `rate` Hz with the wheel odometry the
// simulator logs (50 Hz), with the wheel odometry at the scans' stamps only, or without any.
enum class Wheels { kLogged, kAtScansOnly, kNone };
struct DeskewedRun {
  double raw = 0.0, deskewed = 0.0;
};
DeskewedRun endPointErrors(double rate, Wheels wheels) {
  simulation::RunSettings settings;
  settings.rate = rate;
  settings.motion = simulation::Motion::kContinuous;
  simulation::SimulatedRun run =
      simulation::simulateRun(simulation::makeOfficeWorld(), simulation::officePath("S"), settings);
  if (wheels != Wheels::kLogged) run.log.wheel_odometry.clear();
  if (wheels == Wheels::kNone)
    for (io::LogEntry &entry : run.log.entries) entry.odometry.reset();
  auto endPoint = [&](bool deskew) {
    auto matcher = makeScanMatcher("contour");
    OdometryOptions options;
    options.deskew = deskew;
    const OdometryRun odometry = runOdometry(run.log, *matcher, options);
    return evaluation::endPointError(evaluation::associate(odometry.trajectory, run.ground_truth)).percent;
  };
  return {endPoint(false), endPoint(true)};
}

// Without wheel odometry each scan is deskewed by the previous motion, then by the one found.
TEST(Odometry, DeskewingScansTakenWhileMovingCutsTheEndPointError) {
  const DeskewedRun errors = endPointErrors(5.0, Wheels::kNone);
  EXPECT_GT(errors.raw, 2.0);  // % of the path
  EXPECT_LT(errors.deskewed, 0.5 * errors.raw);
}

// Without wheel odometry a scan is first deskewed by the last motion. Where a turn ends within
// the interval, that bends a scan taken straight; the registration is tried again with the scan
// as taken. The office's L path at 5 Hz: every registration converges, each within 10 cm / 2 deg.
TEST(Odometry, WithoutWheelsAScanBentByAnEndedTurnIsRegisteredAsTaken) {
  simulation::RunSettings settings;
  settings.rate = 5.0;
  settings.motion = simulation::Motion::kContinuous;
  simulation::SimulatedRun run =
      simulation::simulateRun(simulation::makeOfficeWorld(), simulation::officePath("L"), settings);
  run.log.wheel_odometry.clear();
  for (io::LogEntry &entry : run.log.entries) entry.odometry.reset();
  auto matcher = makeScanMatcher("contour");
  const OdometryRun odometry = runOdometry(run.log, *matcher);
  EXPECT_EQ(odometry.stats.failures, 0u);
  EXPECT_GE(odometry.stats.recovered_by_retry, 1u);  // where the turn ends
  for (const OdometryStep &step : odometry.steps) {
    if (!step.converged) continue;
    const io::Pose2D truth = io::between(run.ground_truth[step.reference].pose, run.ground_truth[step.scan].pose);
    EXPECT_LT(std::hypot(step.motion.x - truth.x, step.motion.y - truth.y), 0.1) << "step " << step.scan;
    EXPECT_LT(std::abs(step.motion.yaw - truth.yaw), 2.0 * M_PI / 180) << "step " << step.scan;
  }
}

// With wheel odometry each scan is deskewed by the odometry over its own sweep, which holds in
// the S path's turns at 2 Hz, where the previous motion is a poor guess of the next.
TEST(Odometry, DeskewingByWheelOdometryHoldsThroughTurns) {
  const DeskewedRun errors = endPointErrors(2.0, Wheels::kAtScansOnly);
  EXPECT_GT(errors.raw, 10.0);
  EXPECT_LT(errors.deskewed, 2.0);
}

// At 1 Hz the robot begins and ends its turns within a sweep: the odometry logged between the
// scans gives the motion piece by piece, where one twist per scan interval misplaces the beams.
TEST(Odometry, DeskewingFollowsTheLoggedWheelOdometryWithinASweep) {
  const DeskewedRun logged = endPointErrors(1.0, Wheels::kLogged);
  const DeskewedRun at_scans = endPointErrors(1.0, Wheels::kAtScansOnly);
  EXPECT_LT(logged.deskewed, 1.0);
  EXPECT_GT(at_scans.deskewed, 5.0 * logged.deskewed);  // 2.7 % against 0.25 %
}

// A log with odometry at its scans only whose logger stamped scans in bursts, as intel's did:
// the robot turns 0.05 rad per scan at 10 Hz (0.5 rad/s), but scans 5 and 6 are stamped 1 ms
// apart. The twist over scan 5's sweep is the turn over the usual scan interval, not the turn
// divided into 1 ms (50 rad/s, which would turn the scan by 0.67 rad within its 13 ms sweep).
TEST(Odometry, ScansStampedInABurstDoNotGiveTheirSweepAFasterTwist) {
  io::ScanLog log;
  for (int k = 0; k < 12; ++k) {
    io::LogEntry entry;
    entry.scan.stamp = k < 6 ? 0.1 * k : 0.1 * (k - 1) + 0.001;  // scan 6 stamped 1 ms after scan 5
    entry.scan.angle_increment = M_PI / 180.0;
    entry.scan.time_increment = 0.0133 / 180.0;
    entry.scan.ranges.assign(181, 5.0f);
    entry.odometry = io::Pose2D{0.0, 0.0, 0.05 * k};
    log.entries.push_back(entry);
  }
  for (const std::size_t k : {std::size_t{3}, std::size_t{5}}) {
    const std::optional<SweepMotion> sweep = wheelMotionOverSweep(log, k);
    ASSERT_TRUE(sweep.has_value()) << "scan " << k;
    EXPECT_TRUE(sweep->changes.empty()) << "scan " << k;
    EXPECT_NEAR(sweep->twist.wz, 0.5, 0.05) << "scan " << k;  // rad/s
  }
}

// The first scan is deskewed too: it is the first registration's target. With exact wheel
// odometry the first step comes out as it would from scans taken at rest.
TEST(Odometry, TheFirstScanIsDeskewedByTheWheelOdometry) {
  simulation::RunSettings settings;
  settings.rate = 1.0;
  settings.motion = simulation::Motion::kContinuous;
  settings.odometry_noise = 0.0;
  const simulation::SimulatedRun run =
      simulation::simulateRun(simulation::makeOfficeWorld(), simulation::officePath("L"), settings);
  auto matcher = makeScanMatcher("contour");
  const OdometryRun odometry = runOdometry(run.log, *matcher);
  ASSERT_TRUE(odometry.steps.at(0).converged) << odometry.steps[0].status;
  const io::Pose2D truth = io::between(run.ground_truth[0].pose, run.ground_truth[1].pose);
  const io::Pose2D &step = odometry.steps[0].motion;
  EXPECT_LT(std::hypot(step.x - truth.x, step.y - truth.y), 0.005);
  EXPECT_LT(std::abs(step.yaw - truth.yaw), 0.1 * M_PI / 180);
}

// The command line and Python take guess sources and frames by these names.
TEST(Odometry, GuessSourcesAndFramesAreKnownByName) {
  EXPECT_EQ(guessSourceNamed("zero"), GuessSource::kZero);
  EXPECT_EQ(guessSourceNamed("odom"), GuessSource::kOdometry);
  EXPECT_EQ(guessSourceNamed("velocity"), GuessSource::kConstantVelocity);
  EXPECT_EQ(frameNamed("robot"), Frame::kRobot);
  EXPECT_EQ(frameNamed("laser"), Frame::kLaser);
  EXPECT_FALSE(guessSourceNamed("Odom").has_value());
  EXPECT_FALSE(frameNamed("").has_value());
  EXPECT_EQ(guessSourceNames().size(), 3u);
  EXPECT_EQ(frameNames().size(), 2u);
}

// Deskewing is on by default, and scans without beam timing are left as they are.
TEST(Odometry, DeskewingIsOnByDefaultAndLeavesStoppedScansAlone) {
  EXPECT_TRUE(OdometryOptions{}.deskew);
  const Sequence s = roomSequence();
  auto matcher = makeScanMatcher("contour");
  OdometryOptions raw;
  raw.deskew = false;
  const OdometryRun a = runOdometry(s.log, *matcher, raw), b = runOdometry(s.log, *matcher);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t k = 0; k < a.trajectory.size(); ++k) {
    EXPECT_EQ(a.trajectory[k].pose.x, b.trajectory[k].pose.x);
    EXPECT_EQ(a.trajectory[k].pose.yaw, b.trajectory[k].pose.yaw);
  }
}

// Each registration is reported with the guess it started from (debug pictures redraw the
// pair from it): the wheels' motion over the step when they are the guess, no motion for the
// zero guess.
TEST(Odometry, EachRegistrationIsReportedWithTheGuessItStartedFrom) {
  Sequence s = roomSequence(8);
  addWheels(s, 0.0);
  auto matcher = makeScanMatcher("contour");
  for (const GuessSource source : {GuessSource::kOdometry, GuessSource::kZero}) {
    OdometryOptions options;
    options.guess = source;
    std::vector<std::size_t> reported;
    options.on_match = [&](std::size_t reference, std::size_t k, const LaserScan &, const MatchResult &,
                           const Eigen::Matrix3d &guess) {
      reported.push_back(k);
      const io::Pose2D expected =
          source == GuessSource::kOdometry ? io::between(s.truth[reference].pose, s.truth[k].pose) : io::Pose2D{};
      const io::Pose2D started = io::toPose(guess);
      EXPECT_NEAR(started.x, expected.x, 1e-9) << "scan " << k;
      EXPECT_NEAR(started.y, expected.y, 1e-9) << "scan " << k;
      EXPECT_NEAR(started.yaw, expected.yaw, 1e-9) << "scan " << k;
    };
    runOdometry(s.log, *matcher, options);
    EXPECT_EQ(reported.size(), s.log.entries.size() - 1);
  }
}

// The office's L path, stop and go, with the LIDAR mounted at `laser_pose` on the robot; wheel
// odometry (2 % noise) as the guess. The run in `frame`, and its truth (the robot's poses).
struct MountedRun {
  simulation::SimulatedRun simulated;
  OdometryRun run;
};
MountedRun mountedRun(const io::Pose2D &laser_pose, Frame frame, bool tell_mounting = true) {
  simulation::RunSettings settings;
  settings.laser_pose = laser_pose;
  MountedRun m{simulation::simulateRun(simulation::makeOfficeWorld(), simulation::officePath("L"), settings), {}};
  if (!tell_mounting) m.simulated.log.laser_pose.reset();
  auto matcher = makeScanMatcher("contour");
  OdometryOptions options;
  options.guess = GuessSource::kOdometry;
  options.frame = frame;
  m.run = runOdometry(m.simulated.log, *matcher, options);
  return m;
}
double absoluteError(const MountedRun &m) {
  return evaluation::absoluteTrajectoryError(evaluation::associate(m.run.trajectory, m.simulated.ground_truth));
}

// A laser mounted 0.3 m ahead of the robot's centre, 0.1 m to the left and turned 30 deg gives
// the robot's trajectory as well as a laser at the centre does; the laser's own trajectory, or
// the robot's computed as if the laser sat at the centre, is off by the mounting's lever in
// every turn.
TEST(Odometry, AMountedLaserGivesTheRobotsTrajectory) {
  const io::Pose2D mounting{0.3, 0.1, 30.0 * M_PI / 180.0};
  const MountedRun centre = mountedRun({}, Frame::kRobot);
  const MountedRun robot = mountedRun(mounting, Frame::kRobot);
  const MountedRun laser = mountedRun(mounting, Frame::kLaser);
  const MountedRun unaware = mountedRun(mounting, Frame::kRobot, false);
  EXPECT_EQ(robot.run.frame, Frame::kRobot);
  EXPECT_EQ(laser.run.frame, Frame::kLaser);
  EXPECT_EQ(unaware.run.frame, Frame::kLaser);
  EXPECT_EQ(robot.run.stats.failures, 0u);
  EXPECT_LT(absoluteError(centre), 0.03);  // m
  EXPECT_LT(absoluteError(robot), 0.03);
  EXPECT_LT(absoluteError(robot), 1.5 * absoluteError(centre) + 0.005);
  EXPECT_GT(absoluteError(laser), 0.1);
  EXPECT_GT(absoluteError(unaware), 0.1);
  // The steps are the robot's too: they chain to its trajectory.
  for (const OdometryStep &step : robot.run.steps) {
    const io::Pose2D chained =
        io::between(robot.run.trajectory[step.reference].pose, robot.run.trajectory[step.scan].pose);
    EXPECT_NEAR(chained.x, step.motion.x, 1e-9);
    EXPECT_NEAR(chained.y, step.motion.y, 1e-9);
  }
}

TEST(Odometry, KeyframesGiveATrajectoryAsGood) {
  const Sequence s = roomSequence();
  auto matcher = makeScanMatcher("contour");
  OdometryOptions options;
  options.keyframes = true;
  const OdometryRun run = runOdometry(s.log, *matcher, options);
  EXPECT_EQ(run.stats.failures, 0u);
  EXPECT_LT(evaluation::endPointError(evaluation::associate(run.trajectory, s.truth)).error, 0.05);
}

// Against a local map of the last three keyframes, over the L path of the office (each
// keyframe reached after 0.3 m or 11.5 deg): no failure, the end point as close.
TEST(Odometry, ALocalMapGivesATrajectoryAsGood) {
  const simulation::SimulatedRun run =
      simulation::simulateRun(simulation::makeOfficeWorld(), simulation::officePath("L"), {});
  auto matcher = makeScanMatcher("contour");
  OdometryOptions options;
  const OdometryRun scan_to_scan = runOdometry(run.log, *matcher, options);
  options.local_map_keyframes = 3;
  const OdometryRun mapped = runOdometry(run.log, *matcher, options);
  EXPECT_EQ(mapped.stats.failures, 0u);
  std::size_t against_older = 0;  // registrations against a keyframe before the previous scan
  for (const OdometryStep &step : mapped.steps) against_older += step.reference + 1 < step.scan;
  EXPECT_GT(against_older, mapped.steps.size() / 4);
  const double mapped_error =
      evaluation::endPointError(evaluation::associate(mapped.trajectory, run.ground_truth)).percent;
  const double chained_error =
      evaluation::endPointError(evaluation::associate(scan_to_scan.trajectory, run.ground_truth)).percent;
  EXPECT_LT(mapped_error, 0.5);  // % of the path
  EXPECT_LT(mapped_error, 2.0 * chained_error + 0.1);
}

TEST(Odometry, AFailedScanIsCountedAndBridgedByTheLastMotionNotChained) {
  Sequence s = roomSequence(12, 0.0);
  for (float &r : s.log.entries[6].scan.ranges) r = std::nanf("");
  auto matcher = makeScanMatcher("contour");
  const OdometryRun run = runOdometry(s.log, *matcher);
  EXPECT_EQ(run.stats.failures, 2u);  // 5 -> 6 and 6 -> 7
  ASSERT_EQ(run.stats.failed_scans.size(), 2u);
  EXPECT_EQ(run.stats.failed_scans[0], 6u);
  EXPECT_EQ(run.stats.failure_reasons.at("too_few_special_points"), 2u);
  // Scan 6's pose is the constant-velocity prediction: close to the truth, not a wild jump.
  const io::Pose2D error = io::between(io::between(s.truth[0].pose, s.truth[6].pose),
                                       io::between(run.trajectory[0].pose, run.trajectory[6].pose));
  EXPECT_LT(std::hypot(error.x, error.y), 0.1);
}

TEST(Odometry, WheelOdometryBridgesFailuresWhenItIsTheGuess) {
  Sequence s = roomSequence(8, 0.0);
  for (std::size_t k = 0; k < s.log.entries.size(); ++k) s.log.entries[k].odometry = s.truth[k].pose;
  for (float &r : s.log.entries[4].scan.ranges) r = std::nanf("");
  auto matcher = makeScanMatcher("icp");
  OdometryOptions options;
  options.guess = GuessSource::kOdometry;
  const OdometryRun run = runOdometry(s.log, *matcher, options);
  EXPECT_GE(run.stats.failures, 1u);
  const io::Pose2D error = io::between(io::between(s.truth[0].pose, s.truth[4].pose),
                                       io::between(run.trajectory[0].pose, run.trajectory[4].pose));
  EXPECT_LT(std::hypot(error.x, error.y), 0.02);
}

// A wheel odometry sample corrupt in a log (1e300 m) gives two increments nothing can be
// fused with: the scans' own motions stand, and no pose is NaN.
TEST(Odometry, AnAbsurdWheelSampleIsNotFused) {
  Sequence s = roomSequence(8, 0.0);
  addWheels(s, 0.0);
  s.log.entries[4].odometry->x = 1e300;
  auto matcher = makeScanMatcher("contour");
  OdometryOptions options;
  options.guess = GuessSource::kOdometry;
  const OdometryRun run = runOdometry(s.log, *matcher, options);
  ASSERT_EQ(run.trajectory.size(), s.truth.size());
  for (const io::StampedPose &p : run.trajectory)
    ASSERT_TRUE(std::isfinite(p.pose.x) && std::isfinite(p.pose.y) && std::isfinite(p.pose.yaw)) << p.stamp;
  const io::Pose2D error = io::between(io::between(s.truth[0].pose, s.truth.back().pose),
                                       io::between(run.trajectory[0].pose, run.trajectory.back().pose));
  EXPECT_LT(std::hypot(error.x, error.y), 0.05);
}

// The same sample where the scan is lost too: the interval is bridged by a motion the robot
// could have made, not by the wheels' 1e300 m.
TEST(Odometry, AnAbsurdWheelSampleDoesNotBridgeALostScan) {
  Sequence s = roomSequence(10, 0.0);
  addWheels(s, 0.0);
  s.log.entries[6].odometry->x = 1e300;
  for (float &r : s.log.entries[6].scan.ranges) r = std::nanf("");
  auto matcher = makeScanMatcher("contour");
  const OdometryRun run = runOdometry(s.log, *matcher);
  EXPECT_EQ(run.stats.failures, 2u);  // 5 -> 6 and 6 -> 7
  for (const io::StampedPose &p : run.trajectory)
    ASSERT_TRUE(std::isfinite(p.pose.x) && std::isfinite(p.pose.y) && std::isfinite(p.pose.yaw)) << p.stamp;
  EXPECT_LT(std::hypot(errorTo(s, run, 9).x, errorTo(s, run, 9).y), 0.1);
}

// The wheels measured the interval a failed registration leaves open; the previous motion only
// extrapolates it. A scan lost just as the robot turns sharply, registered from a zero guess:
// bridged by the wheels, it keeps the heading; by constant velocity, it would not turn at all.
TEST(Odometry, WheelOdometryBridgesFailuresWhateverTheGuess) {
  Sequence s = roomSequence(8, 0.0);
  turnOnTheSpot(s, 4, 0.5);  // 29 deg between scans 3 and 4
  addWheels(s, 0.0);
  for (float &r : s.log.entries[4].scan.ranges) r = std::nanf("");
  auto matcher = makeScanMatcher("contour");
  const OdometryRun run = runOdometry(s.log, *matcher);  // zero guess
  EXPECT_EQ(run.stats.failures, 2u);                     // 3 -> 4 and 4 -> 5
  const io::Pose2D error = errorTo(s, run, 7);
  EXPECT_LT(std::hypot(error.x, error.y), 0.05);
  EXPECT_LT(std::abs(error.yaw), 0.02);
}

// Wheels that err by 0.2-0.3 rad a step on a smooth drive: the previous motion has predicted
// the registrations better, and the failed scan is bridged by it, not by the wheels.
TEST(Odometry, AFailedScanIsBridgedByThePredictionThatHasDoneBetter) {
  Sequence s = roomSequence(10, 0.0);
  addWheels(s, 0.1);
  for (float &r : s.log.entries[6].scan.ranges) r = std::nanf("");
  auto matcher = makeScanMatcher("contour");
  const OdometryRun run = runOdometry(s.log, *matcher);
  EXPECT_EQ(run.stats.failures, 2u);  // 5 -> 6 and 6 -> 7
  const io::Pose2D error = errorTo(s, run, 9);
  EXPECT_LT(std::abs(error.yaw), 0.03);
  EXPECT_LT(std::hypot(error.x, error.y), 0.05);
}

// The same smooth drive, wheels erring by 0.03-0.045 rad a step, and a 29 deg turn on the spot
// where the scan is lost: the previous motion has predicted better so far, but the wheels'
// increment and it disagree far beyond their records, a change of motion only the wheels saw.
TEST(Odometry, AFailedScanInATurnIsBridgedByTheWheels) {
  Sequence s = roomSequence(10, 0.0);
  turnOnTheSpot(s, 6, 0.5);
  addWheels(s, 0.015);
  for (float &r : s.log.entries[6].scan.ranges) r = std::nanf("");
  auto matcher = makeScanMatcher("contour");
  const OdometryRun run = runOdometry(s.log, *matcher);
  EXPECT_EQ(run.stats.failures, 2u);  // 5 -> 6 and 6 -> 7
  EXPECT_LT(std::abs(errorTo(s, run, 9).yaw), 0.1);
}

// Along the simulator's row of doors (a recess every 3 m) at 1 m a step, a YDLidar (10 m)
// rarely sees the corridor's ends: most registrations are ambiguous, a motion a period along
// fitting as well as the truth. The motion the odometry expects over the interval (the wheels
// and the last motion, weighed by their record) is a few centimetres off at most and allows
// one of them alone: those steps converge, each on the true motion, none a period off.
TEST(Odometry, ThePredictedMotionDecidesBetweenMotionsAPeriodApart) {
  simulation::RunSettings settings;
  settings.lidar = simulation::LidarModel::ydlidarX4();
  settings.rate = 1.0;
  settings.speed = 1.0;
  const simulation::SimulatedRun sim =
      simulation::simulateRun(simulation::makeBuiltInWorld("doors"), simulation::doorRowPath("line"), settings);
  auto matcher = makeScanMatcher("contour");
  const OdometryRun run = runOdometry(sim.log, *matcher);  // zero guess
  const std::size_t steps = run.stats.registrations;
  EXPECT_GE(run.stats.decided_by_prediction, steps / 2);
  EXPECT_EQ(run.stats.failure_reasons.count("ambiguous"), 0u);
  EXPECT_LE(run.stats.failures, steps / 4);
  for (const OdometryStep &step : run.steps) {
    if (!step.converged) continue;
    const io::Pose2D truth = io::between(sim.ground_truth[step.reference].pose, sim.ground_truth[step.scan].pose);
    EXPECT_NEAR(step.motion.x, truth.x, 0.05) << "scan " << step.scan;
    EXPECT_NEAR(step.motion.y, truth.y, 0.05) << "scan " << step.scan;
  }
}

// A bare corridor (walls beyond the LIDAR's reach at both ends) driven with a lane change and
// noisy wheels: the scans pin the cross-axis position and the heading but not the position
// along the axis. Fused, the trajectory keeps the wheels' motion along the axis and the scans'
// across it and in heading; without fusion every step fails and the wheels' drift is all there is.
simulation::SimulatedRun corridorDrive() {
  const simulation::World corridor = test::bareCorridor(100.0);
  simulation::RunSettings settings;
  settings.odometry_noise = 0.15;
  settings.seed = 7;
  return simulation::simulateRun(corridor, {{0.0, 0.0}, {3.0, 0.0}, {5.0, 0.5}, {9.0, 0.5}}, settings);
}
struct CorridorRun {
  simulation::SimulatedRun run;
  OdometryRun fused, unfused;
};
CorridorRun corridorRun() {
  CorridorRun c{corridorDrive(), {}, {}};
  auto matcher = makeScanMatcher("contour");
  OdometryOptions options;
  options.guess = GuessSource::kOdometry;
  c.fused = runOdometry(c.run.log, *matcher, options);
  options.fuse_wheel_odometry = false;
  c.unfused = runOdometry(c.run.log, *matcher, options);
  return c;
}

TEST(Odometry, InACorridorTheWheelsGiveTheAxisAndTheScansTheRest) {
  const CorridorRun c = corridorRun();
  const io::Trajectory wheels = wheelOdometry(c.run.log);
  const std::size_t steps = c.fused.stats.registrations;
  ASSERT_EQ(c.fused.trajectory.size(), c.run.ground_truth.size());
  EXPECT_EQ(c.fused.stats.failures, 0u);
  EXPECT_GE(c.fused.stats.pinned_by_wheels, steps * 9 / 10);
  EXPECT_GE(c.unfused.stats.failures, steps * 9 / 10);  // without the wheels the scans cannot decide
  EXPECT_EQ(c.unfused.stats.failure_reasons.count("unconstrained"), 1u);
  double worst_wheel_heading = 0.0, worst_wheel_across = 0.0;
  for (std::size_t k = 0; k < c.fused.trajectory.size(); ++k) {
    // Poses from the first scan's, the corridor's axis along x.
    const io::Pose2D truth = io::between(c.run.ground_truth[0].pose, c.run.ground_truth[k].pose);
    const io::Pose2D &fused = c.fused.trajectory[k].pose, &wheel = wheels[k].pose;
    const double fused_heading = std::abs(std::remainder(fused.yaw - truth.yaw, 2 * M_PI));
    EXPECT_LT(fused_heading, 0.3 * M_PI / 180.0) << "scan " << k;
    EXPECT_LT(std::abs(fused.y - truth.y), 0.02) << "scan " << k;
    // Along the axis each step is the wheels' step, turned by the scans' heading; within a
    // centimetre and a half, as the wheels' errors along their drive are correlated with those
    // across it, which the scans see, once the drive turns off the axis (the lane change).
    if (k > 0) {
      const io::Pose2D &before = c.fused.trajectory[k - 1].pose;
      const io::Pose2D wheel_step = io::between(wheels[k - 1].pose, wheel);
      const double wheel_along = std::cos(before.yaw) * wheel_step.x - std::sin(before.yaw) * wheel_step.y;
      EXPECT_NEAR(fused.x - before.x, wheel_along, 0.015) << "scan " << k;
    }
    worst_wheel_heading = std::max(worst_wheel_heading, std::abs(std::remainder(wheel.yaw - truth.yaw, 2 * M_PI)));
    worst_wheel_across = std::max(worst_wheel_across, std::abs(wheel.y - truth.y));
  }
  // The wheels alone drift in heading and across: what the scans corrected.
  EXPECT_GT(worst_wheel_heading, 1.0 * M_PI / 180.0);
  EXPECT_GT(worst_wheel_across, 0.05);
  // The unfused run is the wheels' wherever its steps failed: no better across the axis.
  const io::Pose2D last_truth = io::between(c.run.ground_truth[0].pose, c.run.ground_truth.back().pose);
  EXPECT_GT(std::abs(c.unfused.trajectory.back().pose.y - last_truth.y),
            2.0 * std::abs(c.fused.trajectory.back().pose.y - last_truth.y));
}

// From a zero guess too, a step the scans leave free along the corridor's axis is fused with
// the wheels' increment by what the scans pin, rather than bridged whole by the wheels: the
// heading and the cross-axis position stay the scans'.
TEST(Odometry, FromAZeroGuessTheWheelsGiveOnlyTheAxisOfStepsTheScansLeaveFree) {
  const simulation::SimulatedRun sim = corridorDrive();
  auto matcher = makeScanMatcher("contour");
  const OdometryRun run = runOdometry(sim.log, *matcher);  // zero guess, fusion on (the defaults)
  const std::size_t steps = run.stats.registrations;
  EXPECT_GE(run.stats.pinned_by_wheels, steps * 9 / 10);
  EXPECT_LE(run.stats.failures, steps / 10);
  ASSERT_EQ(run.trajectory.size(), sim.ground_truth.size());
  for (std::size_t k = 0; k < run.trajectory.size(); ++k) {
    const io::Pose2D truth = io::between(sim.ground_truth[0].pose, sim.ground_truth[k].pose);
    const io::Pose2D &pose = run.trajectory[k].pose;
    EXPECT_LT(std::abs(std::remainder(pose.yaw - truth.yaw, 2 * M_PI)), 0.3 * M_PI / 180.0) << "scan " << k;
    EXPECT_LT(std::abs(pose.y - truth.y), 0.02) << "scan " << k;
  }
}

// The fused steps' covariance describes their errors on a simulated run whose wheels follow the
// model: the office's S path, the wheel noise as the simulator makes it (2 % of each increment,
// 0.4 % of a radian per metre in heading); mean normalised error squared near 3 (x, y, yaw).
TEST(Odometry, FusedStepsCarryAConsistentCovariance) {
  double nees_sum = 0.0;
  std::size_t count = 0;
  for (const unsigned seed : {1u, 2u, 3u}) {
    simulation::RunSettings settings;
    settings.seed = seed;
    const simulation::SimulatedRun run =
        simulation::simulateRun(simulation::makeOfficeWorld(), simulation::officePath("S"), settings);
    auto matcher = makeScanMatcher("contour");
    OdometryOptions options;
    options.guess = GuessSource::kOdometry;
    options.wheel_noise.rotation_per_rotation = 0.02 * 0.02 / 2;
    options.wheel_noise.rotation_per_translation = 0.004 * 0.004 / 2;
    options.wheel_noise.translation_per_translation = 0.02 * 0.02;
    options.wheel_noise.translation_per_rotation = 0.0;
    options.wheel_noise.translation_floor = 0.001;
    options.wheel_noise.rotation_floor = 0.001;
    const OdometryRun fused = runOdometry(run.log, *matcher, options);
    EXPECT_EQ(fused.stats.fused, fused.stats.registrations);
    for (const OdometryStep &step : fused.steps) {
      const io::Pose2D truth = io::between(run.ground_truth[step.reference].pose, run.ground_truth[step.scan].pose);
      nees_sum += evaluation::normalisedErrorSquared(step.motion, truth, step.covariance, 0.0, 0.0);
      ++count;
    }
  }
  const double mean = nees_sum / static_cast<double>(count);
  std::printf("mean NEES of %zu fused steps: %.2f\n", count, mean);
  EXPECT_GT(mean, 2.0);
  EXPECT_LT(mean, 4.0);
}

// How many extractions of stages A-C have run in this process so far (each takes the next number).
std::uint64_t extractionsSoFar() { return extractContourFeatures(ComplexSequence{}, ContourParams{}).extraction - 1; }

// Odometry reads each scan once: the last source serves as the next target with its features.
TEST(Odometry, ExtractsEachScansFeaturesOnce) {
  const Sequence s = roomSequence(12);
  for (const std::string method : {"contour", "contour+icp"}) {
    SCOPED_TRACE(method);
    auto matcher = makeScanMatcher(method);
    const std::uint64_t before = extractionsSoFar();
    const OdometryRun run = runOdometry(s.log, *matcher);               // every scan against the one before
    const std::uint64_t extractions = extractionsSoFar() - before - 1;  // less the count's own
    EXPECT_EQ(run.stats.failures, 0u);
    EXPECT_EQ(extractions, s.log.entries.size());
  }
}

TEST(ScanMatcher, EveryMethodRegistersAPairOfTheRoom) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const simulation::World world = simulation::makeFurnishedRoom();
  const LaserScan target = test::scanFrom(world, test::pose2d(0.0, 0.0, 0.0), 0.0);
  const LaserScan source = test::scanFrom(world, test::pose2d(0.1, 0.05, 2.0), 0.0);
  for (const std::string &name : methodNames()) {
    auto matcher = makeScanMatcher(name);
    ASSERT_TRUE(matcher) << name;
    const MatchResult result = matcher->match(target, source);
    EXPECT_GT(result.milliseconds, 0.0) << name;
    if (name == "ndt2d") continue;  // PCL's NDT2D is not reliable on this pair (see docs/results.md)
    EXPECT_TRUE(result.converged) << name;
    EXPECT_NEAR(result.transform(0, 2), 0.1, 0.05) << name;
    EXPECT_NEAR(result.transform(1, 2), 0.05, 0.05) << name;
  }
  EXPECT_EQ(makeScanMatcher("no-such-method"), nullptr);
}

// PCL's methods register in single precision: a guess that puts the source beyond 10 km (where a
// float resolves no millimetre, and 1e38 m overflows in ICP's search) is refused with a status
// of its own, before PCL's nearest-neighbour search would end the process with an assertion.
// The contour methods work in double precision and find the pair without the guess.
TEST(ScanMatcher, AGuessFarBeyondTheScansIsRefusedByPclsMethods) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const simulation::World world = simulation::makeFurnishedRoom();
  const LaserScan target = test::scanFrom(world, test::pose2d(0.0, 0.0, 0.0), 0.0);
  const LaserScan source = test::scanFrom(world, test::pose2d(0.1, 0.05, 2.0), 0.0);
  for (const double far : {1e300, 1e38, 2e4}) {
    Eigen::Matrix3d guess = Eigen::Matrix3d::Identity();
    guess(0, 2) = far;
    for (const std::string &name : methodNames()) {
      const MatchResult result = makeScanMatcher(name)->match(target, source, guess);
      if (name == "contour" || name == "contour+icp") {
        EXPECT_TRUE(result.converged) << name << " " << far;
        EXPECT_NEAR(result.transform(0, 2), 0.1, 0.05) << name << " " << far;
        continue;
      }
      EXPECT_FALSE(result.converged) << name << " " << far;
      EXPECT_EQ(result.status, "guess_out_of_range") << name << " " << far;
    }
  }
}

// A covariance, and the judge's overlap and score, come only with the estimate they describe:
// the contour method's converged one; contour+icp's ICP moves the contour stage's estimate, and
// ICP gives none. A pair of the room 0.1 m apart shares nearly all of its contour and puts none
// of it in the other scan's free space.
TEST(ScanMatcher, ACovarianceAndAScoreComeOnlyWithTheEstimateTheyDescribe) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const simulation::World world = simulation::makeFurnishedRoom();
  const LaserScan target = test::scanFrom(world, test::pose2d(0.0, 0.0, 0.0), 0.01);
  const LaserScan source = test::scanFrom(world, test::pose2d(0.1, 0.05, 2.0), 0.01);
  const MatchResult contour = makeScanMatcher("contour")->match(target, source);
  ASSERT_TRUE(contour.converged);
  EXPECT_EQ(contour.covariance.llt().info(), Eigen::Success);
  ASSERT_TRUE(contour.overlap.has_value() && contour.score.has_value());
  EXPECT_GT(*contour.overlap, 0.8);
  EXPECT_LE(*contour.overlap, 1.0);
  EXPECT_NEAR(*contour.score, *contour.overlap, 0.01);  // nothing in the other scan's free space
  for (const std::string name : {"contour+icp", "icp"}) {
    const MatchResult result = makeScanMatcher(name)->match(target, source);
    ASSERT_TRUE(result.converged) << name;
    EXPECT_TRUE(result.covariance.isZero()) << name;
    EXPECT_FALSE(result.pinned.has_value()) << name;
    EXPECT_FALSE(result.overlap.has_value() || result.score.has_value()) << name;
  }
  LaserScan empty = source;
  for (float &r : empty.ranges) r = std::nanf("");
  const MatchResult declined = makeScanMatcher("contour")->match(target, empty);
  ASSERT_FALSE(declined.converged);
  EXPECT_FALSE(declined.overlap.has_value() || declined.score.has_value());
}

}  // namespace
}  // namespace contour_reg::odometry
