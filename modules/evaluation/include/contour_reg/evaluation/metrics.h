#pragma once
/// @file metrics.h
/// Accuracy of an estimated trajectory: the paper's end-point error over path length,
/// drift over fixed distance windows, absolute trajectory error after SE(2) alignment,
/// and the relation errors of Kümmerle et al. 2009.

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/io/trajectory.h"

namespace contour_reg::evaluation {

/// Percentile q in [0, 1] of `values`, the nearest sample (0 when empty).
double percentile(std::vector<double> values, double q);
/// Median of `values`, the mean of the two middle ones for an even count (0 when empty).
double median(std::vector<double> values);

/// The pose of `trajectory` (stamp order) at `stamp`, interpolated between the samples
/// around it; nothing outside its span or when those samples are more than `max_gap` s apart.
std::optional<io::Pose2D> poseAt(const io::Trajectory &trajectory, double stamp, double max_gap = 1.0);

/// Sum of the distances between consecutive positions, m.
double pathLength(const io::Trajectory &trajectory);

/// Poses of the estimate and of the reference at the estimate's stamps where both exist.
struct Association {
  std::vector<io::Pose2D> estimate, reference;
  std::vector<double> stamps;
};
Association associate(const io::Trajectory &estimate, const io::Trajectory &reference, double max_gap = 1.0);

/// The paper's metric: both trajectories start together (re-anchored at the first
/// associated pose); the distance between their last positions over the reference path length.
struct EndPointError {
  double error = 0.0;        ///< m
  double path_length = 0.0;  ///< m, of the reference over the associated span
  double percent = 0.0;      ///< 100 * error / path_length
};
EndPointError endPointError(const Association &association);

/// Translation drift over windows of `window` m of reference path: for every associated
/// pose, the relative-pose translation error to the first pose `window` m further, in %.
struct Drift {
  double mean_percent = 0.0;
  std::size_t windows = 0;
};
Drift drift(const Association &association, double window = 10.0);

/// Absolute trajectory error: RMSE of positions after the rigid SE(2) alignment of the
/// estimate onto the reference that minimises it (Umeyama without scale), m.
double absoluteTrajectoryError(const Association &association);

/// Relation errors (Kümmerle et al. 2009): for every relation (t1, t2) whose two stamps
/// the estimate covers, the error motion (reference^-1 estimate) of the relative pose.
struct RelationErrors {
  std::size_t count = 0;                                 ///< relations evaluated
  std::size_t missing = 0;                               ///< relations the estimate does not cover
  double translation_mean = 0.0, translation_std = 0.0;  ///< m
  double rotation_mean = 0.0, rotation_std = 0.0;        ///< deg
};
RelationErrors relationErrors(const io::Trajectory &estimate, const std::vector<io::Relation> &relations,
                              double max_dt = std::numeric_limits<double>::infinity());

/// How well reported covariances describe the errors they belong to: the normalised
/// estimation error squared (NEES) e^T (C + F)^-1 e, with e the estimate less the reference
/// (x, y and the yaw wrapped to [-pi, pi], both relative motions in one frame), C the
/// estimate's covariance and F = diag(floor_m^2, floor_m^2, floor_rad^2) the reference's own
/// error. An honest covariance of a motion in (x, y, yaw) gives a mean of 3, and 1 % of
/// errors above kNees99 (chi-square, 3 degrees of freedom). Infinite where C + F is singular
/// (a zero covariance without a floor).
constexpr double kNees99 = 11.34;
double normalisedErrorSquared(const io::Pose2D &estimate, const io::Pose2D &reference,
                              const Eigen::Matrix3d &covariance, double floor_m, double floor_rad);

/// The poses of `trajectory` whose stamp is no later than the one before: stamps that do not
/// tell poses apart (a log that kept its stamps to six digits, or none).
std::size_t nonIncreasingStamps(const io::Trajectory &trajectory);

/// Every metric the references allow: against ground truth (end point, drift, ATE) and
/// against relations (all of them, and the local ones with |t2 - t1| <= local_dt). A
/// reference that covers too little gives no metric rather than a zero: the ground-truth
/// metrics need two estimated poses with a ground-truth pose (the end point a reference path
/// of some length, the drift one window of it), the relation means one relation whose stamps
/// the estimate covers (relations_all then says only how many it missed).
/// Every metric finds poses by their stamps: an estimate whose stamps do not increase gets
/// none, and a ground truth whose stamps do not increase gives none.
struct Evaluation {
  std::size_t estimate_poses = 0;  ///< poses in the estimate
  /// nonIncreasingStamps of the estimate and of the ground truth (0 without one)
  std::size_t estimate_stamps_not_increasing = 0, ground_truth_stamps_not_increasing = 0;
  std::size_t matched_poses = 0;  ///< of them, with a ground-truth pose (0 without ground truth)
  std::optional<EndPointError> end_point;
  std::optional<Drift> drift;
  std::optional<double> ate;
  std::optional<RelationErrors> relations_all, relations_local;
};
Evaluation evaluate(const io::Trajectory &estimate, const io::Trajectory *ground_truth,
                    const std::vector<io::Relation> *relations, double local_dt = 5.0);

}  // namespace contour_reg::evaluation
