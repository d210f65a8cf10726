#include "contour_reg/evaluation/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "contour_reg/io/pose2d.h"

namespace contour_reg::evaluation {

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * double(values.size() - 1) + 0.5)];
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double normalisedErrorSquared(const io::Pose2D &estimate, const io::Pose2D &reference,
                              const Eigen::Matrix3d &covariance, double floor_m, double floor_rad) {
  const Eigen::Vector3d error(estimate.x - reference.x, estimate.y - reference.y,
                              std::remainder(estimate.yaw - reference.yaw, 2.0 * M_PI));
  const Eigen::Matrix3d spread =
      covariance +
      Eigen::Vector3d(floor_m * floor_m, floor_m * floor_m, floor_rad * floor_rad).asDiagonal().toDenseMatrix();
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(spread);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0.0))
    return std::numeric_limits<double>::infinity();
  return error.dot(ldlt.solve(error));
}

namespace {

using io::between;

double norm(const io::Pose2D &p) { return std::hypot(p.x, p.y); }

struct MeanStd {
  std::vector<double> values;
  void add(double v) { values.push_back(v); }
  double mean() const {
    double sum = 0.0;
    for (double v : values) sum += v;
    return values.empty() ? 0.0 : sum / double(values.size());
  }
  double std() const {  // sample standard deviation, two passes
    if (values.size() < 2) return 0.0;
    const double m = mean();
    double sum_sq = 0.0;
    for (double v : values) sum_sq += (v - m) * (v - m);
    return std::sqrt(sum_sq / double(values.size() - 1));
  }
};

}  // namespace

std::optional<io::Pose2D> poseAt(const io::Trajectory &trajectory, double stamp, double max_gap) {
  if (trajectory.empty() || stamp < trajectory.front().stamp || stamp > trajectory.back().stamp) return std::nullopt;
  auto after = std::lower_bound(trajectory.begin(), trajectory.end(), stamp,
                                [](const io::StampedPose &p, double t) { return p.stamp < t; });
  if (after->stamp == stamp || after == trajectory.begin()) return after->pose;
  const io::StampedPose &b = *after, &a = *(after - 1);
  if (b.stamp - a.stamp > max_gap) return std::nullopt;
  const double w = (stamp - a.stamp) / (b.stamp - a.stamp);
  const io::Pose2D d = between(a.pose, b.pose);
  return io::compose(a.pose, io::scaled(d, w));
}

double pathLength(const io::Trajectory &trajectory) {
  double length = 0.0;
  for (std::size_t k = 1; k < trajectory.size(); ++k)
    length +=
        std::hypot(trajectory[k].pose.x - trajectory[k - 1].pose.x, trajectory[k].pose.y - trajectory[k - 1].pose.y);
  return length;
}

Association associate(const io::Trajectory &estimate, const io::Trajectory &reference, double max_gap) {
  Association association;
  for (const io::StampedPose &e : estimate)
    if (auto r = poseAt(reference, e.stamp, max_gap)) {
      association.estimate.push_back(e.pose);
      association.reference.push_back(*r);
      association.stamps.push_back(e.stamp);
    }
  return association;
}

EndPointError endPointError(const Association &a) {
  EndPointError result;
  if (a.estimate.size() < 2) return result;
  const io::Pose2D e = between(a.estimate.front(), a.estimate.back());
  const io::Pose2D r = between(a.reference.front(), a.reference.back());
  result.error = std::hypot(e.x - r.x, e.y - r.y);
  for (std::size_t k = 1; k < a.reference.size(); ++k)
    result.path_length += std::hypot(a.reference[k].x - a.reference[k - 1].x, a.reference[k].y - a.reference[k - 1].y);
  result.percent = result.path_length > 0.0 ? 100.0 * result.error / result.path_length : 0.0;
  return result;
}

Drift drift(const Association &a, double window) {
  Drift result;
  const std::size_t n = a.reference.size();
  std::vector<double> travelled(n, 0.0);
  for (std::size_t k = 1; k < n; ++k)
    travelled[k] =
        travelled[k - 1] + std::hypot(a.reference[k].x - a.reference[k - 1].x, a.reference[k].y - a.reference[k - 1].y);
  double sum = 0.0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; ++i) {
    j = std::max(j, i);
    while (j < n && travelled[j] - travelled[i] < window) ++j;
    if (j == n) break;
    const io::Pose2D error = between(between(a.reference[i], a.reference[j]), between(a.estimate[i], a.estimate[j]));
    sum += 100.0 * norm(error) / (travelled[j] - travelled[i]);
    ++result.windows;
  }
  result.mean_percent = result.windows ? sum / double(result.windows) : 0.0;
  return result;
}

double absoluteTrajectoryError(const Association &a) {
  const std::size_t n = a.estimate.size();
  if (n == 0) return 0.0;
  Eigen::Vector2d mean_e = Eigen::Vector2d::Zero(), mean_r = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    mean_e += Eigen::Vector2d(a.estimate[k].x, a.estimate[k].y);
    mean_r += Eigen::Vector2d(a.reference[k].x, a.reference[k].y);
  }
  mean_e /= double(n);
  mean_r /= double(n);
  Eigen::Matrix2d cross = Eigen::Matrix2d::Zero();
  for (std::size_t k = 0; k < n; ++k)
    cross += (Eigen::Vector2d(a.reference[k].x, a.reference[k].y) - mean_r) *
             (Eigen::Vector2d(a.estimate[k].x, a.estimate[k].y) - mean_e).transpose();
  // The rotation maximising trace(R^T cross): angle atan2(c10 - c01, c00 + c11).
  const double angle = std::atan2(cross(1, 0) - cross(0, 1), cross(0, 0) + cross(1, 1));
  const Eigen::Rotation2Dd rotation(angle);
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d e = rotation * (Eigen::Vector2d(a.estimate[k].x, a.estimate[k].y) - mean_e) + mean_r;
    sum_sq += (e - Eigen::Vector2d(a.reference[k].x, a.reference[k].y)).squaredNorm();
  }
  return std::sqrt(sum_sq / double(n));
}

RelationErrors relationErrors(const io::Trajectory &estimate, const std::vector<io::Relation> &relations,
                              double max_dt) {
  RelationErrors result;
  MeanStd translation, rotation;
  for (const io::Relation &relation : relations) {
    if (std::abs(relation.t2 - relation.t1) > max_dt) continue;
    const auto p1 = poseAt(estimate, relation.t1), p2 = poseAt(estimate, relation.t2);
    if (!p1 || !p2) {
      ++result.missing;
      continue;
    }
    const io::Pose2D error = between(relation.motion, between(*p1, *p2));
    translation.add(norm(error));
    rotation.add(std::abs(error.yaw) * 180.0 / M_PI);
  }
  result.count = translation.values.size();
  result.translation_mean = translation.mean();
  result.translation_std = translation.std();
  result.rotation_mean = rotation.mean();
  result.rotation_std = rotation.std();
  return result;
}

std::size_t nonIncreasingStamps(const io::Trajectory &trajectory) {
  std::size_t count = 0;
  for (std::size_t k = 1; k < trajectory.size(); ++k) count += !(trajectory[k].stamp > trajectory[k - 1].stamp);
  return count;
}

Evaluation evaluate(const io::Trajectory &estimate, const io::Trajectory *ground_truth,
                    const std::vector<io::Relation> *relations, double local_dt) {
  Evaluation result;
  result.estimate_poses = estimate.size();
  result.estimate_stamps_not_increasing = nonIncreasingStamps(estimate);
  if (ground_truth) result.ground_truth_stamps_not_increasing = nonIncreasingStamps(*ground_truth);
  if (result.estimate_stamps_not_increasing > 0) return result;
  if (ground_truth && result.ground_truth_stamps_not_increasing == 0) {
    const Association association = associate(estimate, *ground_truth);
    result.matched_poses = association.stamps.size();
    if (result.matched_poses >= 2) {
      if (const EndPointError e = endPointError(association); e.path_length > 0.0) result.end_point = e;
      if (const Drift d = drift(association); d.windows > 0) result.drift = d;
      result.ate = absoluteTrajectoryError(association);
    }
  }
  if (relations) {
    result.relations_all = relationErrors(estimate, *relations);  // with none covered: how many were not
    if (result.relations_all->count > 0) result.relations_local = relationErrors(estimate, *relations, local_dt);
  }
  return result;
}

}  // namespace contour_reg::evaluation
