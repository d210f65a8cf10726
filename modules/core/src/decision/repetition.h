#pragma once
/// @file repetition.h
/// The judge's check for repeated structure: a motion a whole period off along a row of doors.
///
/// Along a row of equally spaced doors, the motion that lays the source's doors on the
/// target's next doors fits as well as the true motion wherever both scans saw the same
/// stretch of corridor. The overlap fraction cannot tell them apart fairly: the true motion
/// moves the part of the source the target could not see (beyond its range, past its field of
/// view) off the target's contour, the alias lays the whole scan on the whole scan. The check
/// therefore compares the two on the shared view only.
///
/// - Period-shifted motions: along the target contour's axis (the mean direction of its
///   elementary vectors, a corridor's axis) and across it, the contour points that run across
///   that direction (door frames, corners, the ends of walls), of the source moved by the best
///   and of the target, vote for the lag between them, pairs in the same lane only. A lag
///   beyond kDistinctMotions that gathers at least kPeriodVotes of the votes of lag 0 (what
///   the best itself aligns) and is a local maximum is a period of repeated structure, and the
///   best shifted by it a candidate. Corners alone do not find periods: a door frame seen
///   from another spot often yields other special points.
/// - Shared view: the source samples the target could have seen under both motions: on the
///   surface it measured, or at a bearing where it has a return and not hidden behind it
///   (free_space.h's margin). Its returns are all of them, isolated ones too, and its surface
///   is its contour and the segment between each two neighbouring returns, up to the margin
///   behind the nearer of them: along a wall its beams meet at a glancing angle, the returns
///   lie too far apart to form a contour (with 1 deg beams, 0.9 m apart at 8 m along a
///   corridor 2.4 m wide), and a motion that lays the source there lays it on what the target
///   saw; a segment across a depth jump, from an edge to what lies behind it, is hidden.
/// - The best is rivalled when a shifted motion, refined, lays nearly as large a share of the
///   shared view on the target's surface (within kScoreTie) and the free space contradicts it
///   no more than the best.

#include <vector>

#include <Eigen/Core>

#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/free_space.h"
#include "contour_reg/core/refinement.h"
#include "contour_reg/core/registration.h"

namespace contour_reg::decision {

/// Periods kept at most along each of the two directions.
constexpr std::size_t kMaxPeriods = 2;

/// A lag is a period when its votes reach this share of the best's own (lag 0).
constexpr double kPeriodVotes = 0.5;

/// The best motion `best` shifted by each period of repeated structure (see above), the
/// most voted first along each direction, into `scratch.shifted`.
void periodShifts(const Eigen::Matrix3d &best, const ContourFeatures &source, const ContourFeatures &target,
                  RegistrationBuffers::Repetition &scratch);

/// How two motions fit the part of the source both let the target see.
struct SharedViewFit {
  double shared = 0.0;  ///< share of the source samples the target sees under both motions
  double first = 0.0;   ///< share of the shared samples the first motion lays on the target's surface
  double second = 0.0;  ///< the same for the second
};

/// What of the target a shared view weighs: its returns, or its contours.
/// - kReturnsAtBearing: `target_view` is the view of all the target's returns, isolated ones
///   too (Scorer::targetReturnsView). The target saw a sample at a bearing where it has a
///   return, and its surface includes the segment between the two returns that bracket the
///   sample's bearing (where the sample is not hidden).
/// - kContoursWithinReach: `target_view` is the view of its contours (Scorer::targetView). It
///   could have seen a sample anywhere within their reach (RangeView::reaches: their field of
///   view and range, the gaps between them included), and its surface is its contour.
enum class TargetSight { kReturnsAtBearing, kContoursWithinReach };

/// The fit of `first` and `second` (source to target) on the shared view of the source
/// `samples`: a sample lies on the target's surface when the refiner pairs it with the target
/// contour within `on_surface` m or, with kReturnsAtBearing, it lies that close to the segment
/// between the target's returns around its bearing; the target saw it when it lies on its
/// surface, or where `sight` says the target could have seen it and no more than
/// `hidden_margin` m behind what it saw.
SharedViewFit sharedViewFit(const std::vector<Eigen::Vector2d> &samples, const ContourRefiner &refiner,
                            const RangeView &target_view, const Eigen::Matrix3d &first, const Eigen::Matrix3d &second,
                            double on_surface, double hidden_margin, TargetSight sight);

/// One motion's spots of the source samples as sharedViewFit weighs them: whether the target
/// saw each sample moved by it, and whether it lies on the target's surface. Computed once for
/// a motion weighed against many.
struct SampleSpots {
  std::vector<char> seen, on_surface;
};

/// The spots of `samples` moved by `motion` (sharedViewFit's test of each sample), into `spots`.
void spotsOf(const std::vector<Eigen::Vector2d> &samples, const ContourRefiner &refiner, const RangeView &target_view,
             const Eigen::Matrix3d &motion, double on_surface, double hidden_margin, TargetSight sight,
             SampleSpots &spots);

/// sharedViewFit with the first motion's spots given (spotsOf, on the same samples, view and settings).
SharedViewFit sharedViewFit(const SampleSpots &first, const std::vector<Eigen::Vector2d> &samples,
                            const ContourRefiner &refiner, const RangeView &target_view, const Eigen::Matrix3d &second,
                            double on_surface, double hidden_margin, TargetSight sight);

}  // namespace contour_reg::decision
