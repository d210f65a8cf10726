#include "contour_reg/core/registration.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "contour_reg/core/transform_estimation.h"
#include "scenes.h"

namespace contour_reg {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(Correspondence, FragmentDistanceIsEquation14) {
  const ComplexSequence g = {{1, 0}, {1, 0.1}, {0, 1}, {0.1, 1}};
  ComplexSequence n;
  const Complex turn = std::polar(1.0, 0.4);
  for (const Complex &v : g) n.push_back(v * turn);
  double rotation = 0.0;
  // |(G, N)| form: invariant to the rotation, and arg (N, G) is the rotation.
  EXPECT_NEAR(fragmentDistanceSquared(g, n, FragmentDistance::kModulus, &rotation), 0.0, 1e-12);
  EXPECT_NEAR(rotation, 0.4, 1e-12);
  // Re form: |G|^2 + |N|^2 - 2 Re (G, N) = |G - N|^2 for equal lengths.
  double expected = 0.0;
  for (std::size_t m = 0; m < g.size(); ++m) expected += std::norm(g[m] - n[m]);
  EXPECT_NEAR(fragmentDistanceSquared(g, n, FragmentDistance::kReal), expected, 1e-12);
}

// The kd-tree search (both scans with at least kKdTreeMinPoints special points) ranks the same
// candidates as the search over all pairs when it is asked for more neighbours than there are
// targets: the furnished room's corners, seen from two poses.
TEST(Correspondence, TheKdTreeFindsThePairsTheSearchOverAllPairsFinds) {
  const simulation::World room = simulation::makeFurnishedRoom();
  const ContourFeatures a = extractContourFeatures(test::scanFrom(room, test::pose2d(0, 0, 10), 0.005, 1), {});
  const ContourFeatures b = extractContourFeatures(test::scanFrom(room, test::pose2d(0.3, 0.1, 14), 0.005, 2), {});
  ASSERT_GE(a.special_points.size(), 6u);
  ASSERT_LE(b.special_points.size(), 16u);  // under the 4 x 3 + 4 neighbours the tree returns
  for (int candidates : {1, 3}) {
    CorrespondenceParams params;
    params.candidates_per_point = candidates;
    const auto key = [](const Correspondence &c) { return std::make_pair(c.source, c.target); };
    std::vector<std::pair<int, int>> expected, found;
    for (const Correspondence &c :
         findCorrespondences(a.special_points, b.special_points, params, CandidateSearch::kAllPairs))
      expected.push_back(key(c));
    for (const Correspondence &c :
         findCorrespondences(a.special_points, b.special_points, params, CandidateSearch::kKdTree))
      found.push_back(key(c));
    std::sort(expected.begin(), expected.end());
    std::sort(found.begin(), found.end());
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(found, expected) << candidates << " candidates";
  }
}

// Special points whose fragments differ in length (extracted with different fragment lengths,
// or built by hand) are compared over the shorter one, by either search: the tree must not
// lay the longer ones into rows sized for the others.
TEST(Correspondence, FragmentsOfDifferentLengthsArePairedAsOverAllPairs) {
  const simulation::World room = simulation::makeFurnishedRoom();
  ContourParams longer;
  longer.special_points.fragment_half_length = 12;
  const ContourFeatures a = extractContourFeatures(test::scanFrom(room, test::pose2d(0, 0, 10), 0.005, 1), longer);
  const ContourFeatures b = extractContourFeatures(test::scanFrom(room, test::pose2d(0.3, 0.1, 14), 0.005, 2), {});
  ASSERT_FALSE(a.special_points.empty());
  ASSERT_GT(a.special_points.front().fragment.size(), b.special_points.front().fragment.size());
  const std::vector<Correspondence> expected =
      findCorrespondences(a.special_points, b.special_points, {}, CandidateSearch::kAllPairs);
  const std::vector<Correspondence> found =
      findCorrespondences(a.special_points, b.special_points, {}, CandidateSearch::kKdTree);
  ASSERT_EQ(found.size(), expected.size());
  for (std::size_t k = 0; k < found.size(); ++k) {
    EXPECT_EQ(found[k].source, expected[k].source);
    EXPECT_EQ(found[k].target, expected[k].target);
  }
}

using Variant = std::tuple<TransformModel, FragmentDistance>;

class RegistrationTest : public ::testing::TestWithParam<Variant> {
 protected:
  RegistrationParams params() const {
    RegistrationParams p;
    p.ransac.model = std::get<0>(GetParam());
    p.correspondence.distance = std::get<1>(GetParam());
    return p;
  }

  // Registers the scan from target_pose * motion onto the scan from target_pose, in both
  // directions. Returns how many converged; every converged one must be within tolerance.
  int checkMotions(double noise, double tolerance, double tolerance_deg, int trials) {
    const simulation::World world = simulation::makeFurnishedRoom();
    std::mt19937 prng(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int converged = 0;
    for (int trial = 0; trial < trials; ++trial) {
      const Eigen::Isometry2d target_pose = test::pose2d(1.5 * u(prng), 1.0 * u(prng), 180 * u(prng));
      const double yaw = 45 * u(prng);
      Eigen::Vector2d shift(u(prng), u(prng));
      if (shift.norm() > 1.0) shift.normalize();
      const Eigen::Isometry2d motion = test::pose2d(shift.x(), shift.y(), yaw);
      const ContourFeatures a =
          extractContourFeatures(test::scanFrom(world, target_pose, noise, trial), ContourParams{});
      const ContourFeatures b =
          extractContourFeatures(test::scanFrom(world, target_pose * motion, noise, 100 + trial), ContourParams{});
      for (bool inverse : {false, true}) {
        SCOPED_TRACE(testing::Message() << "trial " << trial << (inverse ? " inverse" : " forward"));
        const Eigen::Isometry2d expected = inverse ? motion.inverse() : motion;
        std::mt19937 rng(1);
        const RegistrationResult r =
            inverse ? registerContours(a, b, params(), rng) : registerContours(b, a, params(), rng);
        if (!r.converged) {
          EXPECT_FALSE(r.reason.empty());
          continue;
        }
        ++converged;
        const Eigen::Matrix3d rigid = rigidPart(r.transform);
        EXPECT_LT((rigid.topRightCorner<2, 1>() - expected.translation()).norm(), tolerance);
        const double expected_yaw = std::atan2(expected.linear()(1, 0), expected.linear()(0, 0));
        EXPECT_NEAR(std::remainder(yawOf(rigid) - expected_yaw, 2 * M_PI), 0.0, tolerance_deg * kDeg);
      }
    }
    return converged;
  }
};

// The share of the 2 x 10 registrations that must converge. The affine model needs four
// supporting corners (three fit any affine map), so it converges less often; whatever
// converges, in every variant, must be right.
int minimumConverged(TransformModel model) { return model == TransformModel::kRigid ? 16 : 10; }

TEST_P(RegistrationTest, RecoversKnownMotionsWithoutNoise) {
  EXPECT_GE(checkMotions(0.0, 0.02, 0.5, 10), minimumConverged(std::get<0>(GetParam())));
}

TEST_P(RegistrationTest, RecoversKnownMotionsWithOneCentimetreNoise) {
  EXPECT_GE(checkMotions(0.01, 0.05, 1.0, 10), minimumConverged(std::get<0>(GetParam())));
}

INSTANTIATE_TEST_SUITE_P(Variants, RegistrationTest,
                         ::testing::Combine(::testing::Values(TransformModel::kRigid, TransformModel::kAffine),
                                            ::testing::Values(FragmentDistance::kModulus, FragmentDistance::kReal)),
                         [](const ::testing::TestParamInfo<Variant> &variant) {
                           return std::string(std::get<0>(variant.param) == TransformModel::kRigid ? "Rigid"
                                                                                                   : "Affine") +
                                  (std::get<1>(variant.param) == FragmentDistance::kModulus ? "Modulus" : "Real");
                         });

TEST(Registration, SameSeedGivesTheSameAnswer) {
  const simulation::World world = simulation::makeFurnishedRoom();
  const ContourFeatures a =
      extractContourFeatures(test::scanFrom(world, test::pose2d(0, 0, 10), 0.01, 1), ContourParams{});
  const ContourFeatures b =
      extractContourFeatures(test::scanFrom(world, test::pose2d(0.5, 0.2, 30), 0.01, 2), ContourParams{});
  std::mt19937 rng1(5), rng2(5);
  const RegistrationResult r1 = registerContours(b, a, RegistrationParams{}, rng1);
  const RegistrationResult r2 = registerContours(b, a, RegistrationParams{}, rng2);
  ASSERT_TRUE(r1.converged);
  EXPECT_EQ(r1.transform, r2.transform);
  EXPECT_EQ(r1.inliers, r2.inliers);
}

void expectNotConverged(const simulation::World &world, const Eigen::Isometry2d &motion) {
  const ContourFeatures a =
      extractContourFeatures(test::scanFrom(world, test::pose2d(0, 0, 0), 0.01, 1), ContourParams{});
  const ContourFeatures b = extractContourFeatures(test::scanFrom(world, motion, 0.01, 2), ContourParams{});
  std::mt19937 rng(1);
  const RegistrationResult r = registerContours(b, a, RegistrationParams{}, rng);
  EXPECT_FALSE(r.converged) << r.transform;
  // No corner, and on the contours a direction stays free: the verdict is the contours'.
  EXPECT_EQ(r.status, RegistrationStatus::kUnconstrained) << r.reason;
  EXPECT_NE(r.reason.find("too few special points"), std::string::npos) << r.reason;
  EXPECT_TRUE(r.transform.isIdentity());
}

TEST(Registration, CorridorOfTwoParallelWallsDoesNotConverge) {
  simulation::World corridor;
  corridor.addSegment({-30, -1.2}, {30, -1.2});
  corridor.addSegment({-30, 1.3}, {30, 1.3});
  expectNotConverged(corridor, test::pose2d(0.5, 0.1, 3));
}

TEST(Registration, FeaturelessCircleDoesNotConverge) {
  simulation::World circle;
  const int sides = 720;  // a circle of radius 4 m as a fine polygon, seen from inside
  std::vector<Eigen::Vector2d> ring;
  for (int k = 0; k < sides; ++k)
    ring.emplace_back(4.0 * std::cos(2 * M_PI * k / sides), 4.0 * std::sin(2 * M_PI * k / sides));
  circle.addPolygon(ring);
  expectNotConverged(circle, test::pose2d(0.3, -0.2, 10));
}

TEST(Registration, EmptyScansDoNotConverge) {
  std::mt19937 rng(1);
  const RegistrationResult r = registerContours(ContourFeatures{}, ContourFeatures{}, RegistrationParams{}, rng);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, RegistrationStatus::kTooFewSpecialPoints);
}

TEST(Registration, InvalidParametersAreReported) {
  RegistrationParams params;
  params.ransac.inlier_threshold = -1.0;
  std::mt19937 rng(1);
  const RegistrationResult r = registerContours(ContourFeatures{}, ContourFeatures{}, params, rng);
  EXPECT_EQ(r.status, RegistrationStatus::kInvalidParameters);
  EXPECT_NE(r.reason.find("inlier_threshold"), std::string::npos);
}

// Odometry's reuse: features extracted into two alternating objects, one RegistrationBuffers
// and one result for every step, through corner registrations, a step the corners cannot
// decide (a corridor) and back. Each step must equal a registration from scratch: the
// target's index is rebuilt whenever the target is a new extraction, even into the same object.
TEST(Registration, ReusedBuffersGiveTheSameAnswersAsNewOnes) {
  const simulation::World room = simulation::makeFurnishedRoom();
  simulation::World corridor;
  corridor.addSegment({-20.0, -1.0}, {20.0, -1.0});
  corridor.addSegment({-20.0, 1.0}, {20.0, 1.0});
  std::vector<LaserScan> scans;
  for (int k = 0; k < 4; ++k) scans.push_back(test::scanFrom(room, test::pose2d(0.2 * k, 0.1 * k, 4.0 * k), 0.01, k));
  scans.push_back(test::scanFrom(corridor, test::pose2d(0.0, 0.0, 0.0), 0.01, 10));
  scans.push_back(test::scanFrom(corridor, test::pose2d(0.3, 0.0, 0.0), 0.01, 11));
  for (int k = 0; k < 3; ++k)
    scans.push_back(test::scanFrom(room, test::pose2d(0.3 * k, -0.2 * k, -5.0 * k), 0.01, 20 + k));

  const ContourParams contour_params;
  const RegistrationParams params;
  ContourFeatures features[2];
  RegistrationBuffers buffers;
  RegistrationResult result;
  std::mt19937 rng, fresh_rng;
  extractContourFeatures(scans[0], contour_params, features[0]);
  int converged = 0;
  for (std::size_t k = 1; k < scans.size(); ++k) {
    SCOPED_TRACE(testing::Message() << "step " << k);
    const ContourFeatures &target = features[(k - 1) % 2];
    ContourFeatures &source = features[k % 2];
    extractContourFeatures(scans[k], contour_params, source);
    rng.seed(7);
    registerContours(source, target, params, rng, nullptr, buffers, result);
    fresh_rng.seed(7);
    const RegistrationResult fresh =
        registerContours(extractContourFeatures(scans[k], contour_params),
                         extractContourFeatures(scans[k - 1], contour_params), params, fresh_rng);
    EXPECT_EQ(result.converged, fresh.converged);
    EXPECT_EQ(result.status, fresh.status);
    EXPECT_EQ(result.reason, fresh.reason);
    EXPECT_EQ(result.candidates.size(), fresh.candidates.size());
    EXPECT_EQ(result.inliers, fresh.inliers);
    EXPECT_TRUE(result.transform.isApprox(fresh.transform, 1e-12)) << result.transform << "\n" << fresh.transform;
    EXPECT_DOUBLE_EQ(result.overlap, fresh.overlap);
    converged += result.converged;
  }
  EXPECT_GE(converged, 5);  // the room steps; the corridor step may not
}

}  // namespace
}  // namespace contour_reg
