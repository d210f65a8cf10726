#pragma once
/// @file scan_matcher.h
/// Registration methods by name, behind one interface that takes LaserScans: the
/// contour method, PCL's ICP, NDT2D, NDT and GICP, and contour followed by ICP. Every
/// method sees the same scans and the same guess; each gets the cloud form it needs
/// (beam order with NaN beams for the contour method, finite points for the others).

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/registration.h>
#include <Eigen/Core>

#include "contour_reg/contour_registration.h"
#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/deskew.h"
#include "contour_reg/core/laser_scan.h"
#include "contour_reg/core/registration.h"

namespace contour_reg::odometry {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using Registration = pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>;

/// The outcome of one registration. `transform` maps the source scan into the target
/// scan's frame (the source sensor pose seen from the target sensor).
struct MatchResult {
  Eigen::Matrix3d transform = Eigen::Matrix3d::Identity();
  bool converged = false;
  bool degenerate = false;
  /// short failure class ("too_few_special_points", "not_converged", "guess_out_of_range"); "" when converged
  std::string status;
  std::string reason;         ///< why not converged, in words ("" when converged)
  double milliseconds = 0.0;  ///< registration only (features of new scans included)
  /// x, y, yaw; zero when the method gives none (ICP, NDT, GICP, and contour+icp, whose ICP
  /// moves the contour stage's estimate away from what its covariance describes).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  std::size_t inliers = 0;  ///< contour methods: the special-point pairs the motion rests on (0 otherwise)
  /// The contour method, converged: the share of the source contour the refinement paired
  /// (RegistrationResult::overlap) and the judge's score of the answer, that overlap less the
  /// share of both contours in the other scan's free space (RegistrationResult::score). None
  /// otherwise (not converged, other methods, contour+icp, whose ICP moves the estimate).
  std::optional<double> overlap, score;
  /// The contour method: what the scans pin when they leave one direction free (RegistrationResult::pinned).
  std::optional<PinnedMotion> pinned;
  /// Contour methods: the best motion the judge weighed and did not take
  /// (RegistrationResult::rejected). Not converged: the motion it declined; converged: the
  /// best distinct rival of the answer. None when it weighed none (too few special points, a
  /// converged motion without a distinct rival), or when a later stage (contour+icp's ICP)
  /// decided otherwise than the judge.
  std::optional<Eigen::Matrix3d> rejected;
  /// Contour methods, ambiguous: the distinct motions that fit the scans about as well, with
  /// their covariances (RegistrationResult::alternatives).
  std::vector<RejectedMotion> alternatives;
};

/// Settings of the methods that are worth changing from the command line.
struct MatcherSettings {
  ContourParams contour;
  RegistrationParams registration;
  /// m, the correspondence distance of ICP, point-to-line ICP and GICP; unset: each method's
  /// best on the relation logs (docs/baselines.md): icp 0.5, icp-pl 0.25, gicp 0.5.
  std::optional<double> icp_max_correspondence;
  int icp_iterations = 50;
  double ndt_resolution = 1.0;  ///< m, NDT's cell size and NDT2D's grid step (docs/baselines.md)
  double ndt_extent = 80.0;     ///< m, NDT2D grid extent around the target origin
};

/// The method names makeScanMatcher knows: contour, icp, icp-pl (point-to-line ICP), ndt2d, ndt, gicp, contour+icp.
const std::vector<std::string> &methodNames();

/// The beam-order cloud of a scan, NaN points for invalid beams (is_dense = false); with a
/// motion over its sweep, deskewed by it (deskew.h).
Cloud::Ptr beamCloud(const LaserScan &scan, const SweepMotion &motion = {});

/// Registers scans with one method. The scans must not change while a matcher is used on
/// them: a scan is known by its address, its range buffer, its stamp and its sweep's motion. A call whose target
/// is the last call's target sets no new target (the registration keeps what it extracted
/// from it); a call whose target is the last call's source hands that source over with
/// `swap_source_and_target` when the method has one (ContourRegistration and
/// CoarseToFineRegistration), so each scan's features are extracted once.
class ScanMatcher {
 public:
  /// `swap_source_and_target` (may be empty): the registration's swapSourceAndTarget().
  /// `contour` (may be null): the contour stage whose status, reason and degeneracy each
  /// MatchResult reports, and its covariance and pinned part when it is `registration` itself.
  ScanMatcher(std::string name, Registration::Ptr registration, bool wants_beam_order,
              std::function<void()> swap_source_and_target = {},
              const ContourRegistration<pcl::PointXYZ, pcl::PointXYZ> *contour = nullptr);

  const std::string &name() const { return name_; }
  Registration &registration() { return *registration_; }

  /// Registers `source` onto `target` from `guess` (source to target). A scan that carries
  /// beam timing is deskewed with its motion (deskew.h) when its cloud is built; a scan's
  /// cloud is built once, when it first appears, so its motion then is the one used.
  MatchResult match(const LaserScan &target, const LaserScan &source,
                    const Eigen::Matrix3d &guess = Eigen::Matrix3d::Identity(), const SweepMotion &target_motion = {},
                    const SweepMotion &source_motion = {});

  /// Registers beam-order clouds (x, y in the sensor frame, a NaN point for an invalid beam,
  /// as beamCloud makes them); methods that take finite points get the finite ones. Nothing
  /// is kept between such calls.
  MatchResult match(const Cloud::Ptr &target, const Cloud::Ptr &source,
                    const Eigen::Matrix3d &guess = Eigen::Matrix3d::Identity());

 private:
  // A scan is known by its address, its range buffer, its stamp and the motion it is deskewed with.
  struct ScanKey {
    const LaserScan *scan = nullptr;
    const float *ranges = nullptr;
    double stamp = 0.0;
    SweepMotion motion;
    bool operator==(const ScanKey &o) const {
      return scan == o.scan && ranges == o.ranges && stamp == o.stamp && motion == o.motion;
    }
  };
  static ScanKey keyOf(const LaserScan &scan, const SweepMotion &motion) {
    return {&scan, scan.ranges.data(), scan.stamp, motion};
  }
  Cloud::Ptr cloudFor(const LaserScan &scan, const SweepMotion &motion);
  // The cloud the registration takes from a beam-order cloud: itself, or its finite points.
  Cloud::Ptr inputFrom(const Cloud::Ptr &beams) const;
  // Aligns the inputs set from `guess`; `start` is when the registration's time began.
  MatchResult align(const Eigen::Matrix3d &guess, std::chrono::steady_clock::time_point start);

  std::string name_;
  Registration::Ptr registration_;
  bool wants_beam_order_;
  std::function<void()> swap_source_and_target_;
  const ContourRegistration<pcl::PointXYZ, pcl::PointXYZ> *contour_;
  ScanKey source_key_, target_key_;
  Cloud::Ptr source_cloud_, target_cloud_;
};

/// A matcher for `method` (see methodNames()); nullptr for an unknown name.
std::unique_ptr<ScanMatcher> makeScanMatcher(const std::string &method, const MatcherSettings &settings = {});

}  // namespace contour_reg::odometry
