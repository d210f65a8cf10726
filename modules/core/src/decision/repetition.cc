#include "repetition.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "contour_reg/core/transform_estimation.h"
#include "score.h"

namespace contour_reg::decision {

namespace {

// m, spacing of the contour points that vote, and the width of a lag bin.
constexpr double kVoteStep = 0.1;

// The axis (k = 0) or the direction across it (k = 1).
Eigen::Vector2d direction(const Eigen::Vector2d &axis, int k) {
  return k == 0 ? axis : Eigen::Vector2d(-axis.y(), axis.x());
}

// The points of `scan`'s contours, moved by `motion`, every kVoteStep m, whose contour runs
// more across direction k of `axis` than along it (door frames, corners, the ends of walls),
// as (along, across) that direction, into out[k]: a point runs across one direction at most.
void crossings(const ContourFeatures &scan, const Eigen::Matrix3d &motion, const Eigen::Vector2d &axis,
               std::vector<Eigen::Vector2d> (&out)[2]) {
  const Eigen::Vector2d along[2] = {direction(axis, 0), direction(axis, 1)};
  const Eigen::Vector2d across[2] = {along[1], -along[0]};
  for (std::vector<Eigen::Vector2d> &points : out) points.clear();
  const Eigen::Matrix2d rotation = motion.topLeftCorner<2, 2>();
  for (const EqualizedContour &contour : scan.contours) {
    if (contour.step <= 0.0 || contour.vertices.size() < 2) continue;
    const auto stride = static_cast<std::size_t>(std::max(1.0, std::round(kVoteStep / contour.step)));
    for (std::size_t r = 0; r < contour.vertices.size(); r += stride) {
      const std::size_t a = r >= stride ? r - stride : 0, b = std::min(r + stride, contour.vertices.size() - 1);
      const Eigen::Vector2d chord = rotation * toEigen(contour.vertices[b] - contour.vertices[a]);
      const double on_axis = std::abs(chord.dot(along[0])), across_axis = std::abs(chord.dot(along[1]));
      if (on_axis == across_axis) continue;  // as much along as across: neither
      const int k = on_axis < across_axis ? 0 : 1;
      const Eigen::Vector2d p = transformPoint(motion, toEigen(contour.vertices[r]));
      out[k].emplace_back(p.dot(along[k]), p.dot(across[k]));
    }
  }
}

// The axis of `scan`'s contours: the mean of their elementary vectors' doubled angles, every
// kVoteStep m (a corridor's axis). The vectors of an equalized contour are equally long.
Eigen::Vector2d axisOf(const ContourFeatures &scan) {
  Complex doubled = 0.0;
  for (const EqualizedContour &contour : scan.contours) {
    if (contour.step <= 0.0) continue;
    const auto stride = static_cast<std::size_t>(std::max(1.0, std::round(kVoteStep / contour.step)));
    for (std::size_t r = stride; r < contour.vertices.size(); r += stride) {
      const Complex e = contour.vertices[r] - contour.vertices[r - 1];
      doubled += e * e / (contour.step * contour.step);
    }
  }
  const double angle = 0.5 * std::atan2(doubled.imag(), doubled.real());
  return {std::cos(angle), std::sin(angle)};
}

}  // namespace

void periodShifts(const Eigen::Matrix3d &best, const ContourFeatures &source, const ContourFeatures &target,
                  RegistrationBuffers::Repetition &scratch) {
  std::vector<Eigen::Matrix3d> &shifted = scratch.shifted;
  std::vector<double> &votes = scratch.votes;
  std::vector<std::pair<double, int>> &peaks = scratch.peaks;
  shifted.clear();
  // The target's side depends on the target alone: kept while it is the same extraction.
  if (target.extraction == 0 || scratch.crossed_target != target.extraction) {
    scratch.axis = axisOf(target);
    crossings(target, Eigen::Matrix3d::Identity(), scratch.axis, scratch.target_crossings);
    for (std::vector<Eigen::Vector2d> &points : scratch.target_crossings)
      std::sort(points.begin(), points.end(),
                [](const Eigen::Vector2d &a, const Eigen::Vector2d &b) { return a.y() < b.y(); });
    scratch.crossed_target = target.extraction;
  }
  crossings(source, best, scratch.axis, scratch.source_crossings);
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d u = direction(scratch.axis, k);
    const std::vector<Eigen::Vector2d> &from_target = scratch.target_crossings[k];
    const std::vector<Eigen::Vector2d> &from_source = scratch.source_crossings[k];
    if (from_source.empty() || from_target.empty()) continue;
    // Votes for each lag along u: pairs of crossings in the same lane across it (the target's sorted across it).
    double lo = INFINITY, hi = -INFINITY;
    for (const std::vector<Eigen::Vector2d> *set : {&from_source, &from_target})
      for (const Eigen::Vector2d &c : *set) {
        lo = std::min(lo, c.x());
        hi = std::max(hi, c.x());
      }
    const int half = static_cast<int>(std::ceil((hi - lo) / kVoteStep)) + 1;
    votes.assign(2 * half + 1, 0.0);
    for (const Eigen::Vector2d &s : from_source) {
      auto t = std::lower_bound(from_target.begin(), from_target.end(), s.y() - kVoteStep,
                                [](const Eigen::Vector2d &c, double v) { return c.y() < v; });
      for (; t != from_target.end() && t->y() <= s.y() + kVoteStep; ++t) {
        const double lag = (t->x() - s.x()) / kVoteStep + half;
        const int bin = static_cast<int>(lag);
        if (bin < 0 || bin + 1 >= static_cast<int>(votes.size())) continue;
        votes[bin] += bin + 1 - lag;  // shared between the two nearest bins
        votes[bin + 1] += lag - bin;
      }
    }
    // Lags voted for by about as many crossings as lag 0 (the best's own alignment): the
    // distinct ones (beyond kDistinctMotions) that are local maxima, best first.
    const auto window = [&](int b) {
      double sum = 0.0;
      for (int c = std::max(0, b - 1); c <= std::min<int>(votes.size() - 1, b + 1); ++c) sum += votes[c];
      return sum;
    };
    const double aligned = window(half);
    peaks.clear();
    for (int b = 1; b + 1 < static_cast<int>(votes.size()); ++b) {
      if (std::abs(b - half) * kVoteStep <= kDistinctMotions) continue;
      const double w = window(b);
      if (w >= kPeriodVotes * aligned && w >= window(b - 1) && w > window(b + 1)) peaks.emplace_back(w, b);
    }
    std::sort(peaks.begin(), peaks.end(), std::greater<>());
    for (std::size_t q = 0; q < peaks.size() && q < kMaxPeriods; ++q) {
      Eigen::Matrix3d motion = best;
      motion.topRightCorner<2, 1>() += (peaks[q].second - half) * kVoteStep * u;
      shifted.push_back(motion);
    }
  }
}

namespace {

// Whether a point (target frame) lies on the target's surface, and whether the target saw its
// spot: on its surface, or where it could have seen it and not behind what it saw (sharedViewFit).
struct Spot {
  bool on_surface, seen;
};
Spot spotOf(const Eigen::Vector2d &point, const ContourRefiner &refiner, const RangeView &target_view,
            double on_surface, double hidden_margin, TargetSight sight) {
  if (refiner.pairs(point, on_surface)) return Spot{true, true};
  const bool between_returns = sight == TargetSight::kReturnsAtBearing;
  const RangeView::Sight seen = target_view.sightOf(point, hidden_margin);
  const bool in_view = between_returns ? seen != RangeView::Sight::kNoEvidence : target_view.reaches(point);
  if (!in_view || seen == RangeView::Sight::kHidden) return Spot{false, false};
  if (!between_returns) return Spot{false, true};
  const double off = target_view.distanceToSurface(point);
  return Spot{off >= 0.0 && off <= on_surface, true};
}

}  // namespace

SharedViewFit sharedViewFit(const std::vector<Eigen::Vector2d> &samples, const ContourRefiner &refiner,
                            const RangeView &target_view, const Eigen::Matrix3d &first, const Eigen::Matrix3d &second,
                            double on_surface, double hidden_margin, TargetSight sight) {
  thread_local SampleSpots first_spots;  // working memory, kept between calls (each thread its own)
  spotsOf(samples, refiner, target_view, first, on_surface, hidden_margin, sight, first_spots);
  return sharedViewFit(first_spots, samples, refiner, target_view, second, on_surface, hidden_margin, sight);
}

void spotsOf(const std::vector<Eigen::Vector2d> &samples, const ContourRefiner &refiner, const RangeView &target_view,
             const Eigen::Matrix3d &motion, double on_surface, double hidden_margin, TargetSight sight,
             SampleSpots &spots) {
  spots.seen.resize(samples.size());
  spots.on_surface.resize(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const Spot spot =
        spotOf(transformPoint(motion, samples[k]), refiner, target_view, on_surface, hidden_margin, sight);
    spots.seen[k] = spot.seen;
    spots.on_surface[k] = spot.on_surface;
  }
}

SharedViewFit sharedViewFit(const SampleSpots &first, const std::vector<Eigen::Vector2d> &samples,
                            const ContourRefiner &refiner, const RangeView &target_view, const Eigen::Matrix3d &second,
                            double on_surface, double hidden_margin, TargetSight sight) {
  SharedViewFit fit;
  if (samples.empty()) return fit;
  int shared = 0, on_first = 0, on_second = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (!first.seen[k]) continue;  // the second motion's spot is asked only where the target saw the first's
    const Spot b = spotOf(transformPoint(second, samples[k]), refiner, target_view, on_surface, hidden_margin, sight);
    if (!b.seen) continue;
    ++shared;
    on_first += first.on_surface[k] != 0;
    on_second += b.on_surface;
  }
  fit.shared = static_cast<double>(shared) / static_cast<double>(samples.size());
  if (shared > 0) {
    fit.first = static_cast<double>(on_first) / shared;
    fit.second = static_cast<double>(on_second) / shared;
  }
  return fit;
}

}  // namespace contour_reg::decision
