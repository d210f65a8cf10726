#include "contour_reg/odometry/scan_matcher.h"

#include <chrono>
#include <cmath>

#include <pcl/registration/gicp.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt.h>
#include <pcl/registration/ndt_2d.h>
#include <pcl/registration/transformation_estimation_2D.h>

#include "contour_reg/coarse_to_fine_registration.h"
#include "contour_reg/contour_registration.h"
#include "contour_reg/core/contour.h"
#include "contour_reg/point_to_line_icp.h"

namespace contour_reg::odometry {

namespace {

// Each ICP's correspondence distance at its best on the relation logs (docs/baselines.md: the
// sweep), used unless the settings give one.
constexpr double kIcpMaxDistance = 0.5, kIcpPlMaxDistance = 0.25, kGicpMaxDistance = 0.5;

using Contour = ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>;
using CoarseToFine = CoarseToFineRegistration<pcl::PointXYZ, pcl::PointXYZ>;

Contour::Ptr makeContour(const MatcherSettings &settings) {
  auto contour = pcl::make_shared<Contour>();
  contour->setContourParams(settings.contour);
  contour->setRegistrationParams(settings.registration);
  return contour;
}

Registration::Ptr makeIcp(const MatcherSettings &settings) {
  auto icp = pcl::make_shared<pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>>();
  icp->setTransformationEstimation(
      pcl::make_shared<pcl::registration::TransformationEstimation2D<pcl::PointXYZ, pcl::PointXYZ>>());
  icp->setMaxCorrespondenceDistance(settings.icp_max_correspondence.value_or(kIcpMaxDistance));
  icp->setMaximumIterations(settings.icp_iterations);
  icp->setTransformationEpsilon(1e-8);
  icp->setEuclideanFitnessEpsilon(1e-8);
  return icp;
}

Registration::Ptr makeIcpPointToLine(const MatcherSettings &settings) {
  auto icp = pcl::make_shared<PointToLineIcp<pcl::PointXYZ, pcl::PointXYZ>>();
  icp->setMaxCorrespondenceDistance(settings.icp_max_correspondence.value_or(kIcpPlMaxDistance));
  icp->setMaximumIterations(settings.icp_iterations);
  return icp;
}

Registration::Ptr makeNdt2d(const MatcherSettings &settings) {
  auto ndt = pcl::make_shared<pcl::NormalDistributionsTransform2D<pcl::PointXYZ, pcl::PointXYZ>>();
  ndt->setGridCentre(Eigen::Vector2f(0, 0));
  ndt->setGridExtent(Eigen::Vector2f(float(settings.ndt_extent), float(settings.ndt_extent)));
  ndt->setGridStep(Eigen::Vector2f(float(settings.ndt_resolution), float(settings.ndt_resolution)));
  ndt->setMaximumIterations(settings.icp_iterations);
  ndt->setTransformationEpsilon(1e-6);
  ndt->setOptimizationStepSize(Eigen::Vector3d(0.4, 0.4, 0.1));
  return ndt;
}

Registration::Ptr makeNdt(const MatcherSettings &settings) {
  auto ndt = pcl::make_shared<pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ>>();
  ndt->setResolution(float(settings.ndt_resolution));
  ndt->setStepSize(0.1);
  ndt->setMaximumIterations(settings.icp_iterations);
  ndt->setTransformationEpsilon(1e-4);
  return ndt;
}

Registration::Ptr makeGicp(const MatcherSettings &settings) {
  auto gicp = pcl::make_shared<pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>>();
  gicp->setMaxCorrespondenceDistance(settings.icp_max_correspondence.value_or(kGicpMaxDistance));
  gicp->setMaximumIterations(settings.icp_iterations);
  gicp->setTransformationEpsilon(1e-8);
  return gicp;
}

Eigen::Matrix4f toMatrix4(const Eigen::Matrix3d &planar) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.topLeftCorner<2, 2>() = planar.topLeftCorner<2, 2>().cast<float>();
  m.block<2, 1>(0, 3) = planar.topRightCorner<2, 1>().cast<float>();
  return m;
}

// The planar part of a 4x4 transform, re-orthonormalized by its yaw.
Eigen::Matrix3d toPlanar(const Eigen::Matrix4f &m) {
  const double yaw = std::atan2(double(m(1, 0)), double(m(0, 0)));
  Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
  t(0, 0) = t(1, 1) = std::cos(yaw);
  t(1, 0) = std::sin(yaw);
  t(0, 1) = -t(1, 0);
  t(0, 2) = m(0, 3);
  t(1, 2) = m(1, 3);
  return t;
}

}  // namespace

const std::vector<std::string> &methodNames() {
  static const std::vector<std::string> names{"contour", "icp", "icp-pl", "ndt2d", "ndt", "gicp", "contour+icp"};
  return names;
}

Cloud::Ptr beamCloud(const LaserScan &scan, const SweepMotion &motion) {
  auto cloud = pcl::make_shared<Cloud>();
  cloud->reserve(scan.ranges.size());
  for (const Complex &c : deskewedPolarCode(scan, motion))
    cloud->push_back(pcl::PointXYZ(float(c.real()), float(c.imag()), 0.f));
  cloud->is_dense = false;
  return cloud;
}

ScanMatcher::ScanMatcher(std::string name, Registration::Ptr registration, bool wants_beam_order,
                         std::function<void()> swap_source_and_target, const Contour *contour)
    : name_(std::move(name)),
      registration_(std::move(registration)),
      wants_beam_order_(wants_beam_order),
      swap_source_and_target_(std::move(swap_source_and_target)),
      contour_(contour) {}

Cloud::Ptr ScanMatcher::inputFrom(const Cloud::Ptr &beams) const {
  if (wants_beam_order_) return beams;
  auto finite = pcl::make_shared<Cloud>();  // ICP and NDT take the valid beams only
  finite->reserve(beams->size());
  for (const pcl::PointXYZ &p : *beams)
    if (std::isfinite(p.x) && std::isfinite(p.y)) finite->push_back(p);
  return finite;
}

Cloud::Ptr ScanMatcher::cloudFor(const LaserScan &scan, const SweepMotion &motion) {
  return inputFrom(beamCloud(scan, motion));
}

MatchResult ScanMatcher::match(const LaserScan &target, const LaserScan &source, const Eigen::Matrix3d &guess,
                               const SweepMotion &target_motion, const SweepMotion &source_motion) {
  // The clouds first (scan conversion is not the registration's time), then what changed.
  ScanKey target_key = keyOf(target, target_motion), source_key = keyOf(source, source_motion);
  const bool new_target = !(target_key == target_key_);
  const bool was_source = new_target && target_key == source_key_;
  const bool swap = was_source && swap_source_and_target_ && source_cloud_;
  const bool new_source = !(source_key == (swap ? target_key_ : source_key_));
  Cloud::Ptr next_target =
      new_target && !swap ? (was_source ? source_cloud_ : cloudFor(target, target_motion)) : nullptr;
  Cloud::Ptr next_source = new_source ? cloudFor(source, source_motion) : nullptr;

  const auto start = std::chrono::steady_clock::now();
  if (swap) {
    swap_source_and_target_();  // the last source, with its features, becomes the target
    std::swap(source_cloud_, target_cloud_);
    std::swap(source_key_, target_key_);
  } else if (new_target) {
    target_cloud_ = std::move(next_target);
    target_key_ = std::move(target_key);
    registration_->setInputTarget(target_cloud_);
  }
  if (new_source) {
    source_cloud_ = std::move(next_source);
    source_key_ = std::move(source_key);
    registration_->setInputSource(source_cloud_);
  }
  return align(guess, start);
}

MatchResult ScanMatcher::match(const Cloud::Ptr &target, const Cloud::Ptr &source, const Eigen::Matrix3d &guess) {
  Cloud::Ptr next_target = inputFrom(target), next_source = inputFrom(source);
  const auto start = std::chrono::steady_clock::now();
  source_key_ = target_key_ = ScanKey{};  // a later scan call sets both inputs anew
  target_cloud_ = std::move(next_target);
  source_cloud_ = std::move(next_source);
  registration_->setInputTarget(target_cloud_);
  registration_->setInputSource(source_cloud_);
  return align(guess, start);
}

MatchResult ScanMatcher::align(const Eigen::Matrix3d &guess, std::chrono::steady_clock::time_point start) {
  MatchResult result;
  Cloud aligned;
  if (target_cloud_->empty() || source_cloud_->empty()) {
    result.transform = guess;
    result.reason = target_cloud_->empty() ? "target scan has no valid beam" : "source scan has no valid beam";
    result.status = "empty_scan";
    return result;
  }
  if (!contour_ && !isLocalGuess(guess)) {
    result.transform = guess;
    result.reason =
        "the guess moves the source more than 10 km, beyond what " + name_ + " resolves in single precision";
    result.status = "guess_out_of_range";
    return result;
  }
  registration_->align(aligned, toMatrix4(guess));
  result.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  result.converged = registration_->hasConverged();
  result.transform = result.converged ? toPlanar(registration_->getFinalTransformation()) : guess;
  if (contour_) {
    result.degenerate = contour_->isDegenerate();
    result.inliers = contour_->getResult().inliers.size();
    // The covariance and the pinned part describe the contour stage's estimate: a later stage
    // (contour+icp's ICP) that moves it gives none.
    if (static_cast<const Registration *>(contour_) == registration_.get()) {
      result.covariance = contour_->getCovariance();
      result.pinned = contour_->getResult().pinned;
      if (result.converged) {
        result.overlap = contour_->getResult().overlap;
        result.score = contour_->getResult().score;
      }
    }
    if (contour_->getResult().rejected && contour_->hasConverged() == result.converged)
      result.rejected = contour_->getResult().rejected->transform;
    if (!contour_->hasConverged()) {
      result.reason = contour_->getFailureReason();
      result.status = toString(contour_->getResult().status);
      result.alternatives = contour_->getResult().alternatives;
    }
  }
  if (!result.converged && result.reason.empty()) result.reason = name_ + " did not converge";
  if (!result.converged && result.status.empty()) result.status = "not_converged";
  return result;
}

std::unique_ptr<ScanMatcher> makeScanMatcher(const std::string &method, const MatcherSettings &settings) {
  if (method == "contour") {
    const Contour::Ptr contour = makeContour(settings);
    return std::make_unique<ScanMatcher>(
        method, contour, true, [stage = contour.get()] { stage->swapSourceAndTarget(); }, contour.get());
  }
  if (method == "contour+icp") {
    auto composed = pcl::make_shared<CoarseToFine>();
    composed->setCoarseStage(makeContour(settings));
    return std::make_unique<ScanMatcher>(
        method, composed, true, [stage = composed.get()] { stage->swapSourceAndTarget(); },
        composed->getCoarseStage().get());
  }
  if (method == "icp") return std::make_unique<ScanMatcher>(method, makeIcp(settings), false);
  if (method == "icp-pl") return std::make_unique<ScanMatcher>(method, makeIcpPointToLine(settings), false);
  if (method == "ndt2d") return std::make_unique<ScanMatcher>(method, makeNdt2d(settings), false);
  if (method == "ndt") return std::make_unique<ScanMatcher>(method, makeNdt(settings), false);
  if (method == "gicp") return std::make_unique<ScanMatcher>(method, makeGicp(settings), false);
  return nullptr;
}

}  // namespace contour_reg::odometry
