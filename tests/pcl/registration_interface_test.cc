// pcl::Registration's contract, checked the way a PCL pipeline uses a registration: only
// through pcl::Registration<PointXYZ, PointXYZ>::Ptr, for both contour_reg classes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

#include <gtest/gtest.h>
#include <pcl/console/print.h>
#include <pcl/registration/incremental_registration.h>
#include <pcl/registration/meta_registration.h>

#include "contour_reg/coarse_to_fine_registration.h"
#include "contour_reg/contour_registration.h"
#include "scenes.h"

namespace contour_reg {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using Registration = pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>;

// A scan of the furnished room from `pose`, as a cloud in beam order with NaN beams.
template <typename PointT = pcl::PointXYZ>
void fillScan(pcl::PointCloud<PointT> &cloud, const Eigen::Isometry2d &pose, unsigned seed) {
  static const simulation::World world = simulation::makeFurnishedRoom();
  cloud.clear();
  for (const Complex &c : polarCode(test::scanFrom(world, pose, 0.01, seed))) {
    PointT p;
    p.x = float(c.real());
    p.y = float(c.imag());
    p.z = 0.0f;
    cloud.push_back(p);
  }
  cloud.is_dense = false;
}

template <typename PointT = pcl::PointXYZ>
typename pcl::PointCloud<PointT>::Ptr scan(const Eigen::Isometry2d &pose, unsigned seed) {
  auto cloud = pcl::make_shared<pcl::PointCloud<PointT>>();
  fillScan(*cloud, pose, seed);
  return cloud;
}

// Poses along a straight run through the room, 0.25 m apart, turning 2 degrees a step.
Eigen::Isometry2d runPose(int k) { return test::pose2d(-1.0 + 0.25 * k, -0.3 + 0.02 * k, 10 + 2 * k); }

Eigen::Isometry2d toIsometry(const Eigen::Matrix4f &t) {
  return test::pose2d(t(0, 3), t(1, 3), std::atan2(t(1, 0), t(0, 0)) * 180 / M_PI);
}

// Translation (m) and rotation (deg) between two motions.
std::pair<double, double> difference(const Eigen::Isometry2d &a, const Eigen::Isometry2d &b) {
  const Eigen::Isometry2d d = a.inverse() * b;
  return {d.translation().norm(), std::abs(std::atan2(d.linear()(1, 0), d.linear()(0, 0))) * 180 / M_PI};
}

#define EXPECT_MOTION_NEAR(a, b, metres, degrees)        \
  do {                                                   \
    const auto [moved_, turned_] = difference((a), (b)); \
    EXPECT_LT(moved_, metres);                           \
    EXPECT_LT(turned_, degrees);                         \
  } while (0)

struct ContourFactory {
  using Concrete = ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>;
  static constexpr double kChainedMetres = 0.01, kChainedDegrees = 0.1;
  static Registration::Ptr make() { return pcl::make_shared<Concrete>(); }
};
struct CoarseToFineFactory {
  using Concrete = CoarseToFineRegistration<pcl::PointXYZ, pcl::PointXYZ>;
  // ICP's point-to-point answer, the fine stage's, is a few millimetres off at each step on
  // these scans of 1 cm noise (docs/benchmarks.md), and the steps add up.
  static constexpr double kChainedMetres = 0.07, kChainedDegrees = 0.3;
  static Registration::Ptr make() { return pcl::make_shared<Concrete>(); }
};

template <typename Factory>
class RegistrationInterface : public ::testing::Test {};
using Factories = ::testing::Types<ContourFactory, CoarseToFineFactory>;
TYPED_TEST_SUITE(RegistrationInterface, Factories);

// The pattern of a ROS callback that keeps two cloud objects: the last scan is copied into
// the target, the new scan is written over the source, and both are set again.
TYPED_TEST(RegistrationInterface, CloudsRefilledInPlaceAndSetAgainGiveTheirNewMotion) {
  const Registration::Ptr registration = TypeParam::make();
  auto source = pcl::make_shared<Cloud>(), target = pcl::make_shared<Cloud>();
  fillScan(*source, runPose(0), 1);
  for (int k = 1; k <= 6; ++k) {
    SCOPED_TRACE(k);
    *target = *source;
    fillScan(*source, runPose(k), 1 + k);
    registration->setInputTarget(target);
    registration->setInputSource(source);
    Cloud aligned;
    registration->align(aligned);
    ASSERT_TRUE(registration->hasConverged());
    EXPECT_MOTION_NEAR(toIsometry(registration->getFinalTransformation()), runPose(k - 1).inverse() * runPose(k), 0.02,
                       0.5);
  }
}

TYPED_TEST(RegistrationInterface, SourceChangedInPlaceIsReadAgainByAlign) {
  const Registration::Ptr registration = TypeParam::make();
  auto source = scan(runPose(1), 2);
  registration->setInputTarget(scan(runPose(0), 1));
  registration->setInputSource(source);
  Cloud aligned;
  registration->align(aligned);
  ASSERT_TRUE(registration->hasConverged());
  fillScan(*source, runPose(3), 4);  // not set again: align() reads the cloud it holds, as ICP does
  registration->align(aligned);
  ASSERT_TRUE(registration->hasConverged());
  EXPECT_MOTION_NEAR(toIsometry(registration->getFinalTransformation()), runPose(0).inverse() * runPose(3), 0.02, 0.5);
}

TYPED_TEST(RegistrationInterface, TargetChangedInPlaceAndSetAgainIsNewData) {
  const Registration::Ptr registration = TypeParam::make();
  auto target = scan(runPose(0), 1);
  registration->setInputTarget(target);
  registration->setInputSource(scan(runPose(2), 3));
  Cloud aligned;
  registration->align(aligned);
  ASSERT_TRUE(registration->hasConverged());
  fillScan(*target, runPose(4), 5);
  registration->setInputTarget(target);
  registration->align(aligned);
  ASSERT_TRUE(registration->hasConverged());
  EXPECT_MOTION_NEAR(toIsometry(registration->getFinalTransformation()), runPose(4).inverse() * runPose(2), 0.02, 0.5);
}

TYPED_TEST(RegistrationInterface, SwappingSourceAndTargetGivesTheInverse) {
  const Registration::Ptr registration = TypeParam::make();
  const auto a = scan(runPose(0), 1), b = scan(runPose(2), 3);
  Cloud aligned;
  registration->setInputTarget(a);
  registration->setInputSource(b);
  registration->align(aligned);
  ASSERT_TRUE(registration->hasConverged());
  const Eigen::Isometry2d forward = toIsometry(registration->getFinalTransformation());
  registration->setInputTarget(b);
  registration->setInputSource(a);
  registration->align(aligned);
  ASSERT_TRUE(registration->hasConverged());
  const Eigen::Isometry2d backward = toIsometry(registration->getFinalTransformation());
  EXPECT_MOTION_NEAR(forward * backward, Eigen::Isometry2d::Identity(), 0.01, 0.2);
}

TYPED_TEST(RegistrationInterface, TheSameCloudsSetTwiceGiveTheSameAnswer) {
  const Registration::Ptr registration = TypeParam::make();
  const auto a = scan(runPose(0), 1), b = scan(runPose(2), 3);
  Cloud aligned;
  Eigen::Matrix4f answers[2];
  for (Eigen::Matrix4f &answer : answers) {
    registration->setInputTarget(a);
    registration->setInputSource(b);
    registration->align(aligned);
    ASSERT_TRUE(registration->hasConverged());
    answer = registration->getFinalTransformation();
  }
  EXPECT_TRUE(answers[0].isApprox(answers[1], 1e-6f));
  EXPECT_EQ(aligned.size(), b->size());
}

TYPED_TEST(RegistrationInterface, PointXYZIGivesTheSameAnswerAsPointXYZ) {
  const Registration::Ptr registration = TypeParam::make();
  Cloud aligned;
  registration->setInputTarget(scan(runPose(0), 1));
  registration->setInputSource(scan(runPose(2), 3));
  registration->align(aligned);
  ASSERT_TRUE(registration->hasConverged());

  using CloudI = pcl::PointCloud<pcl::PointXYZI>;
  std::shared_ptr<pcl::Registration<pcl::PointXYZI, pcl::PointXYZI>> with_intensity;
  if (std::is_same_v<TypeParam, ContourFactory>)
    with_intensity = pcl::make_shared<ContourRegistration<pcl::PointXYZI, pcl::PointXYZI>>();
  else
    with_intensity = pcl::make_shared<CoarseToFineRegistration<pcl::PointXYZI, pcl::PointXYZI>>();
  with_intensity->setInputTarget(scan<pcl::PointXYZI>(runPose(0), 1));
  with_intensity->setInputSource(scan<pcl::PointXYZI>(runPose(2), 3));
  CloudI aligned_i;
  with_intensity->align(aligned_i);
  ASSERT_TRUE(with_intensity->hasConverged());
  EXPECT_TRUE(with_intensity->getFinalTransformation().isApprox(registration->getFinalTransformation(), 1e-5f));
}

TYPED_TEST(RegistrationInterface, NoInputFailsWithoutCrashing) {
  const auto verbosity = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const Registration::Ptr registration = TypeParam::make();
  Cloud aligned;
  registration->align(aligned);  // neither cloud set: PCL's initCompute refuses
  EXPECT_FALSE(registration->hasConverged());
  registration->setInputSource(scan(runPose(1), 2));
  registration->align(aligned);  // no target yet
  EXPECT_FALSE(registration->hasConverged());
  registration->setInputTarget(scan(runPose(0), 1));
  registration->align(aligned);
  EXPECT_TRUE(registration->hasConverged());
  pcl::console::setVerbosityLevel(verbosity);
}

// pcl::Registration::setIndices() names the source points to register, as for PCL's ICP: a
// cloud of two scans one after the other, taken 0.5 m apart, registers as the scan its indices
// name. (Indices outside the cloud are the caller's error: PCL's align() copies the points they
// name into the output before any registration runs.)
TYPED_TEST(RegistrationInterface, SourceIndicesNameThePointsRegistered) {
  const Registration::Ptr registration = TypeParam::make();
  const auto first = scan(runPose(2), 3), second = scan(runPose(4), 4);
  auto both = pcl::make_shared<Cloud>(*first);
  *both += *second;
  auto first_half = pcl::make_shared<pcl::Indices>(first->size()),
       second_half = pcl::make_shared<pcl::Indices>(second->size());
  std::iota(first_half->begin(), first_half->end(), 0);
  std::iota(second_half->begin(), second_half->end(), static_cast<int>(first->size()));
  registration->setInputTarget(scan(runPose(0), 1));
  registration->setInputSource(both);
  Cloud aligned;
  for (const auto &[indices, pose] : {std::pair{first_half, runPose(2)}, std::pair{second_half, runPose(4)}}) {
    registration->setIndices(indices);
    registration->align(aligned);
    ASSERT_TRUE(registration->hasConverged());
    EXPECT_MOTION_NEAR(toIsometry(registration->getFinalTransformation()), runPose(0).inverse() * pose, 0.02, 0.5);
  }
}

// A beam without a return is a NaN point, as the classes take their scans; PCL's
// getFitnessScore() searches the target for every source point, those too. The score is the
// mean squared distance of the finite source points, moved by the answer, to their nearest
// target point.
TYPED_TEST(RegistrationInterface, FitnessScoreSkipsBeamsWithoutReturn) {
  const Registration::Ptr registration = TypeParam::make();
  const auto source = scan(runPose(1), 2), target = scan(runPose(0), 1);
  for (std::size_t k = 100; k < 110; ++k) (*source)[k].x = (*source)[k].y = (*source)[k].z = NAN;
  (*target)[50].x = (*target)[50].y = (*target)[50].z = NAN;
  registration->setInputSource(source);
  registration->setInputTarget(target);
  Cloud aligned;
  registration->align(aligned);
  ASSERT_TRUE(registration->hasConverged());
  const Eigen::Matrix4f motion = registration->getFinalTransformation();
  double squares = 0.0;
  int counted = 0;
  for (const pcl::PointXYZ &p : *source) {
    if (!std::isfinite(p.x)) continue;
    const Eigen::Vector4f moved = motion * Eigen::Vector4f(p.x, p.y, p.z, 1.0f);
    float nearest = INFINITY;
    for (const pcl::PointXYZ &q : *target)
      if (std::isfinite(q.x)) nearest = std::min(nearest, (moved.head<3>() - q.getVector3fMap()).squaredNorm());
    squares += nearest;
    ++counted;
  }
  EXPECT_NEAR(registration->getFitnessScore(), squares / counted, 1e-6);
}

// The odometry path: swapSourceAndTarget() makes the last source the target (with what was
// extracted from it); the answer is the same as setting both clouds anew.
TYPED_TEST(RegistrationInterface, SwapSourceAndTargetMatchesSettingThemAnew) {
  using Concrete = typename TypeParam::Concrete;
  const auto swapped = pcl::make_shared<Concrete>(), fresh = pcl::make_shared<Concrete>();
  const auto a = scan(runPose(0), 1), b = scan(runPose(2), 3), c = scan(runPose(4), 5);
  Cloud aligned;
  swapped->setInputTarget(a);
  swapped->setInputSource(b);
  swapped->align(aligned);
  ASSERT_TRUE(swapped->hasConverged());
  swapped->swapSourceAndTarget();  // target b; the source is a: aligning now gives a onto b
  swapped->align(aligned);
  ASSERT_TRUE(swapped->hasConverged());
  EXPECT_MOTION_NEAR(toIsometry(swapped->getFinalTransformation()), runPose(2).inverse() * runPose(0), 0.02, 0.5);
  swapped->swapSourceAndTarget();  // back: target a, source b
  swapped->swapSourceAndTarget();  // target b, source a
  swapped->setInputSource(c);
  swapped->align(aligned);
  fresh->setInputTarget(b);
  fresh->setInputSource(c);
  fresh->align(aligned);
  ASSERT_TRUE(swapped->hasConverged());
  ASSERT_TRUE(fresh->hasConverged());
  EXPECT_TRUE(swapped->getFinalTransformation().isApprox(fresh->getFinalTransformation(), 1e-6f));
}

TYPED_TEST(RegistrationInterface, ClearingAndSettingAgainWorks) {
  const auto verbosity = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const auto registration = pcl::make_shared<typename TypeParam::Concrete>();
  const auto a = scan(runPose(0), 1), b = scan(runPose(2), 3);
  Cloud aligned;
  registration->setInputTarget(a);
  registration->setInputSource(b);
  registration->align(aligned);
  ASSERT_TRUE(registration->hasConverged());
  registration->clearTarget();
  registration->align(aligned);
  EXPECT_FALSE(registration->hasConverged());  // no target: PCL refuses, and nothing of the last answer stays
  registration->setInputTarget(a);
  registration->clearSource();
  registration->align(aligned);
  EXPECT_FALSE(registration->hasConverged());
  registration->setInputSource(b);
  registration->align(aligned);
  ASSERT_TRUE(registration->hasConverged());
  EXPECT_MOTION_NEAR(toIsometry(registration->getFinalTransformation()), runPose(0).inverse() * runPose(2), 0.02, 0.5);
  pcl::console::setVerbosityLevel(verbosity);
}

// PCL's own users of a registration (pcl/registration/incremental_registration.h and
// meta_registration.h) take it as pcl::Registration::Ptr. Poses chained over 2 m of the run
// stay within the factory's chained tolerance.

// IncrementalRegistration chains scan-to-scan motions into poses through one registration
// object: each scan is set as the source, the one before as the target.
TYPED_TEST(RegistrationInterface, IncrementalRegistrationChainsScansIntoPoses) {
  pcl::registration::IncrementalRegistration<pcl::PointXYZ> incremental;
  incremental.setRegistration(TypeParam::make());
  for (int k = 0; k <= 8; ++k) {
    ASSERT_TRUE(incremental.registerCloud(scan(runPose(k), 10 + k))) << "scan " << k;
    EXPECT_MOTION_NEAR(toIsometry(incremental.getAbsoluteTransform()), runPose(0).inverse() * runPose(k),
                       TypeParam::kChainedMetres, TypeParam::kChainedDegrees);
  }
}

// MetaRegistration registers each scan against the map of all before it: their clouds moved
// into the first scan's frame and appended one after another, so scans with no-return beams
// give a target whose contours overlap in bearing.
TYPED_TEST(RegistrationInterface, MetaRegistrationRegistersAgainstTheMergedMap) {
  for (const bool no_return_beams : {false, true}) {
    pcl::registration::MetaRegistration<pcl::PointXYZ> meta;
    meta.setRegistration(TypeParam::make());
    for (int k = 0; k <= 8; ++k) {
      const Cloud::Ptr cloud = scan(runPose(k), 10 + k);
      if (no_return_beams)
        for (std::size_t n = 0; n < cloud->size(); n += 40)
          (*cloud)[n].x = (*cloud)[n].y = std::numeric_limits<float>::quiet_NaN();
      ASSERT_TRUE(meta.registerCloud(cloud)) << "scan " << k << (no_return_beams ? ", no-return beams" : "");
      EXPECT_MOTION_NEAR(toIsometry(meta.getAbsoluteTransform()), runPose(0).inverse() * runPose(k),
                         TypeParam::kChainedMetres, TypeParam::kChainedDegrees);
    }
  }
}

}  // namespace
}  // namespace contour_reg
