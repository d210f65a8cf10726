#include "contour_reg/core/free_space.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "contour_reg/core/transform_estimation.h"
#include "validation.h"

namespace contour_reg {

namespace {

// Bracketing returns may be this many typical beam spacings apart (one missing beam is bridged).
constexpr double kGapSpacings = 2.5;

// m, the spacing along the equalized contour at which points are checked.
constexpr double kSampleStep = 0.1;

// m, a contour's direction at a point is taken over this far along it each way: over 0.5 m,
// 1 cm of range noise turns it by about 1.5 deg, over 0.2 m by 4 deg, enough to make a wall
// in line with the other scan's beam look as if the beam crossed it.
constexpr double kTangentHalfSpan = 0.25;

}  // namespace

bool FreeSpaceParams::validate(std::string *why) const {
  if (!(margin > 0.0)) return invalid(why, "free_space.margin must be > 0");
  if (!(min_object_length >= 0.0)) return invalid(why, "free_space.min_object_length must be >= 0");
  return true;
}

FreeSpaceEvidence &FreeSpaceEvidence::operator+=(const FreeSpaceEvidence &other) {
  tested_length += other.tested_length;
  contradicted_length += other.contradicted_length;
  contradicted_runs += other.contradicted_runs;
  return *this;
}

void RangeView::add(const Complex &point) {
  bearings_.push_back(approximateAtan2(point.imag(), point.real()));
  ranges_.push_back(magnitude(point));
  points_.push_back(toEigen(point));
}

void RangeView::assign(const ContourFeatures &scan) {
  bearings_.clear();
  ranges_.clear();
  points_.clear();
  std::size_t points = 0;
  for (const ContourSegment &segment : scan.segments) points += segment.points.size();
  bearings_.reserve(points);
  ranges_.reserve(points);
  points_.reserve(points);
  for (const ContourSegment &segment : scan.segments)
    for (const Complex &p : segment.points) add(p);
  index();
}

void RangeView::assign(const ComplexSequence &points) {
  bearings_.clear();
  ranges_.clear();
  points_.clear();
  for (const Complex &p : points)
    if (isFinite(p)) add(p);
  index();
}

void RangeView::index() {
  if (!std::is_sorted(bearings_.begin(), bearings_.end())) {
    std::vector<std::size_t> order(bearings_.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return bearings_[a] < bearings_[b]; });
    std::vector<double> bearings(order.size()), ranges(order.size());
    std::vector<Eigen::Vector2d> points(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      bearings[k] = bearings_[order[k]];
      ranges[k] = ranges_[order[k]];
      points[k] = points_[order[k]];
    }
    bearings_.swap(bearings);
    ranges_.swap(ranges);
    points_.swap(points);
  }
  buckets_.build(bearings_, 2);
  farthest_ = ranges_.empty() ? 0.0 : *std::max_element(ranges_.begin(), ranges_.end());
  max_gap_ = 0.0;
  if (bearings_.size() < 2) return;
  spacing_.resize(bearings_.size() - 1);
  for (std::size_t k = 1; k < bearings_.size(); ++k) spacing_[k - 1] = bearings_[k] - bearings_[k - 1];
  std::nth_element(spacing_.begin(), spacing_.begin() + spacing_.size() / 2, spacing_.end());
  max_gap_ = kGapSpacings * spacing_[spacing_.size() / 2];
}

bool RangeView::bracket(double bearing, std::size_t &lo, std::size_t &hi) const {
  if (bearings_.size() < 2) return false;
  const auto above = bearings_.begin() + buckets_.firstAtOrAbove(bearings_, bearing);
  double gap;
  if (above == bearings_.begin() || above == bearings_.end()) {  // across the +-pi cut
    lo = bearings_.size() - 1;
    hi = 0;
    gap = bearings_.front() + 2.0 * M_PI - bearings_.back();
  } else {
    hi = static_cast<std::size_t>(above - bearings_.begin());
    lo = hi - 1;
    gap = bearings_[hi] - bearings_[lo];
  }
  return gap <= max_gap_;
}

double RangeView::rangeAt(double bearing) const {
  std::size_t lo, hi;
  if (!bracket(bearing, lo, hi)) return -1.0;
  return std::min(ranges_[lo], ranges_[hi]);
}

double RangeView::distanceToSurface(const Eigen::Vector2d &point) const {
  std::size_t lo, hi;
  if (!bracket(approximateAtan2(point.y(), point.x()), lo, hi)) return -1.0;
  return distanceToSegment(point, points_[lo], points_[hi]);
}

RangeView::Sight RangeView::sightOf(const Eigen::Vector2d &point, double margin) const {
  const double measured = rangeAt(approximateAtan2(point.y(), point.x()));
  if (measured < 0.0) return Sight::kNoEvidence;
  const double range = point.norm();
  if (range < measured - margin) return Sight::kSeenThrough;
  return range > measured + margin ? Sight::kHidden : Sight::kNotThrough;
}

bool RangeView::reaches(const Eigen::Vector2d &point) const {
  if (bearings_.empty()) return false;
  const double bearing = approximateAtan2(point.y(), point.x());
  return bearing >= bearings_.front() && bearing <= bearings_.back() && point.norm() <= farthest_;
}

FreeSpaceEvidence freeSpaceEvidence(const ContourFeatures &source, const RangeView &target_view,
                                    const Eigen::Matrix3d &motion, const FreeSpaceParams &params,
                                    std::vector<Eigen::Vector2d> *contradicted) {
  FreeSpaceEvidence evidence;
  const Eigen::Matrix2d rotation = motion.topLeftCorner<2, 2>();
  const Eigen::Vector2d translation = motion.topRightCorner<2, 1>();
  for (const EqualizedContour &contour : source.contours) {
    const ComplexSequence &points = contour.vertices;
    // The contour's vertices about kSampleStep apart.
    const std::size_t stride =
        contour.step > 0.0 ? std::max<std::size_t>(1, static_cast<std::size_t>(kSampleStep / contour.step)) : 1;
    const double sample_length = static_cast<double>(stride) * contour.step;
    // A small object may have moved between the scans: its contradictions do not count. Its
    // size (the farthest of its points from its first) is measured only for a contour with a
    // point seen through: most contours have none.
    std::optional<bool> small_object;
    const auto mayHaveMoved = [&] {
      if (!small_object) {
        double extent = 0.0;
        for (const Complex &p : points) extent = std::max(extent, magnitude(p - points.front()));
        small_object = extent < params.min_object_length;
      }
      return *small_object;
    };
    bool in_run = false;
    // The margin holds across the surface: along a beam that meets the contour at a glancing
    // angle, a small offset of the contour moves the crossing far along the beam. A sine below
    // 1e-3 (a contour in line with the beam) makes the margin too wide to contradict.
    const std::size_t span =
        std::max(stride, contour.step > 0.0 ? static_cast<std::size_t>(kTangentHalfSpan / contour.step) : 1);
    const auto marginAlongBeam = [&](std::size_t n, const Eigen::Vector2d &moved, double range) {
      const Complex along = points[std::min(n + span, points.size() - 1)] - points[n >= span ? n - span : 0];
      const Eigen::Vector2d tangent = rotation * Eigen::Vector2d(along.real(), along.imag());
      const double sine =
          std::abs(tangent.x() * moved.y() - tangent.y() * moved.x()) / std::max(tangent.norm() * range, 1e-12);
      return params.margin / std::max(sine, 1e-3);
    };
    for (std::size_t n = 0; n < points.size(); n += stride) {
      const Eigen::Vector2d moved = rotation * Eigen::Vector2d(points[n].real(), points[n].imag()) + translation;
      const double measured = target_view.rangeAt(approximateAtan2(moved.y(), moved.x()));
      if (measured < 0.0) {  // no evidence at this bearing
        in_run = false;
        continue;
      }
      evidence.tested_length += sample_length;
      // Clearly in front of the measured range: by the margin along the beam, then across the contour.
      const double range = moved.norm();
      const bool seen_through = range < measured - params.margin && range < measured - marginAlongBeam(n, moved, range);
      if (seen_through && !mayHaveMoved()) {
        evidence.contradicted_length += sample_length;
        if (!in_run) ++evidence.contradicted_runs;
        if (contradicted) contradicted->push_back(moved);
      }
      in_run = seen_through;
    }
  }
  return evidence;
}

FreeSpaceEvidence mutualFreeSpaceEvidence(const ContourFeatures &source, const RangeView &source_view,
                                          const ContourFeatures &target, const RangeView &target_view,
                                          const Eigen::Matrix3d &motion, const FreeSpaceParams &params,
                                          std::vector<Eigen::Vector2d> *contradicted) {
  FreeSpaceEvidence evidence = freeSpaceEvidence(source, target_view, motion, params, contradicted);
  const std::size_t first_target_point = contradicted ? contradicted->size() : 0;
  evidence += freeSpaceEvidence(target, source_view, rigidInverse(motion), params, contradicted);
  if (contradicted)  // the target's points were moved into the source frame: back into their own
    for (std::size_t k = first_target_point; k < contradicted->size(); ++k)
      (*contradicted)[k] = transformPoint(motion, (*contradicted)[k]);
  return evidence;
}

namespace {

struct ReturnCounts {
  int tested = 0, contradicted = 0;
};

// The finite points of `returns` moved by `motion` against `view`.
void countReturns(const ComplexSequence &returns, const RangeView &view, const Eigen::Matrix3d &motion, double margin,
                  ReturnCounts &counts) {
  for (const Complex &p : returns) {
    if (!isFinite(p)) continue;
    const RangeView::Sight sight = view.sightOf(transformPoint(motion, toEigen(p)), margin);
    if (sight == RangeView::Sight::kNoEvidence) continue;
    ++counts.tested;
    counts.contradicted += sight == RangeView::Sight::kSeenThrough;
  }
}

}  // namespace

double contradictedReturnShare(const ComplexSequence &source_returns, const RangeView &target_view,
                               const ComplexSequence &target_returns, const RangeView &source_view,
                               const Eigen::Matrix3d &motion, double margin) {
  ReturnCounts counts;
  countReturns(source_returns, target_view, motion, margin, counts);
  countReturns(target_returns, source_view, rigidInverse(motion), margin, counts);
  return counts.tested > 0 ? static_cast<double>(counts.contradicted) / counts.tested : 0.0;
}

}  // namespace contour_reg
