#include "judge.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "contour_reg/core/transform_estimation.h"
#include "generate.h"
#include "refine.h"
#include "repetition.h"

namespace contour_reg::decision {

namespace {

// A probe has settled back when it ends within this fraction of the probe distance.
constexpr double kSettledBack = 0.25;

// How many times the contours' best may give way to a clearly better motion a probe found.
constexpr int kMaxPromotions = 2;

// A share (0-1) as a whole percentage, for a verdict's reason: "12 %".
std::string percent(double share) { return std::to_string(static_cast<int>(std::lround(100 * share))) + " %"; }

// How far `motion` lies from `best` (x m, y m, yaw as metres of arc at best's RMS range).
Eigen::Vector3d offsetFrom(const RefinementResult &best, const Eigen::Matrix3d &motion) {
  return {motion(0, 2) - best.transform(0, 2), motion(1, 2) - best.transform(1, 2),
          std::remainder(yawOf(motion) - yawOf(best.transform), 2.0 * M_PI) * best.rms_range};
}

// Whether `motion` differs from `best` along best's weakest direction only: by at most a
// quarter of the distance of distinct motions across it, rotation in metres of arc at the
// RMS range.
bool onlyAlongWeakestDirection(const RefinementResult &best, const Eigen::Matrix3d &motion) {
  const Eigen::Vector3d along = best.weakest_direction.cwiseProduct(Eigen::Vector3d(1.0, 1.0, best.rms_range));
  if (!(along.norm() > 0.0)) return false;
  const Eigen::Vector3d offset = offsetFrom(best, motion);
  const Eigen::Vector3d unit = along.normalized();
  return (offset - offset.dot(unit) * unit).norm() <= kDistinctMotions / 4;
}

// Whether a refinement has come within a quarter of the distinct-motion distance of `best`:
// it leads back to `best`, and can stop there (the `arrived` of ContourRefiner::refine).
std::function<bool(const Eigen::Matrix3d &)> backTo(const Eigen::Matrix3d &best) {
  return [&best](const Eigen::Matrix3d &m) { return motionDistance(best, m) <= kDistinctMotions / 4; };
}

// A corner motion that puts less than this share of the source contour on the target must
// stand against the contours' hypotheses (standsAgainstContours): "most of the contour".
constexpr double kMostOfTheContour = 0.5;

// The best's spots of some source samples (spotsOf), computed on first use: the same for every
// motion weighed against the best. `spots` is working memory kept between registrations.
struct BestSpots {
  SampleSpots &spots;
  bool computed = false;
};

// How `best` and `motion` fit the part of the source `samples` both let the target see, on its
// surface: its contour and the walls between its returns (sharedViewFit,
// TargetSight::kReturnsAtBearing). `best_spots` are the best's spots of `samples`.
SharedViewFit fitOnWhatBothSaw(const std::vector<Eigen::Vector2d> &samples, BestSpots &best_spots,
                               const RefinementResult &best, const Eigen::Matrix3d &motion,
                               const RegistrationParams &params, RegistrationBuffers &buffers, Scorer &scorer) {
  const RangeView &view = scorer.targetReturnsView();
  const double on_surface = params.refinement.min_distance, hidden = params.free_space.margin;
  if (!best_spots.computed) {
    spotsOf(samples, buffers.refiner, view, best.transform, on_surface, hidden, TargetSight::kReturnsAtBearing,
            best_spots.spots);
    best_spots.computed = true;
  }
  return sharedViewFit(best_spots.spots, samples, buffers.refiner, view, motion, on_surface, hidden,
                       TargetSight::kReturnsAtBearing);
}

// Keeps `motion`, scored `score`, among the distinct motions that fit what both scans saw as
// well as the best (Judged::ties); the first of them is the rival.
void keepTie(Judged &found, const RefinementResult &motion, double score) {
  if (found.ties.empty()) found.rival = ScoredMotion{motion, true, score};
  if (std::none_of(found.ties.begin(), found.ties.end(), [&](const ScoredMotion &tie) {
        return motionDistance(tie.refined.transform, motion.transform) <= kDistinctMotions;
      }))
    found.ties.push_back(ScoredMotion{motion, true, score});
}

// Whether `moved`, where a probe settled and scored `moved_score`, fits worse than the best on
// the part of the source within the target's reach under both (sharedViewFit,
// TargetSight::kContoursWithinReach): the share of that part on the target contour less the
// free space's contradiction, lower by more than the tie. Moved along a corridor, the source's
// walls reach past where the target's range ended or before its field of view began: the
// overlap drops there though nothing the target could see disagrees. Such ends of the view
// move with the sensor and pin no motion.
bool fitsWorseWithinReach(ScoredMotion &best, const RefinementResult &moved, double moved_score,
                          const RegistrationParams &params, RegistrationBuffers &buffers, Scorer &scorer) {
  const SharedViewFit fit =
      sharedViewFit(buffers.samples, buffers.refiner, scorer.targetView(), best.refined.transform, moved.transform,
                    params.refinement.min_distance, params.free_space.margin, TargetSight::kContoursWithinReach);
  if (!(fit.shared > 0.0)) return false;
  // A score is the overlap less the contradiction: each motion's contradiction is known from it.
  const double best_contradiction = best.refined.overlap - scorer.score(best);
  const double moved_contradiction = moved.overlap - moved_score;
  return fit.second - moved_contradiction <= fit.first - best_contradiction - kScoreTie;
}

// Whether the best is pinned along its weakest direction (RefinementResult::weakest_direction):
// started `probe_distance` m off along it, both ways, the refinement of the source's samples
// must settle back on it, or where it settles score worse and fit worse on what the target saw
// (fitsWorseWithinReach). A probe distance of 0 turns the check off.
bool settlesBack(Judged &found, const RegistrationParams &params, RegistrationBuffers &buffers, Scorer &scorer) {
  const RefinementResult &best = found.best.refined;
  const double probe = params.probe_distance;
  if (!(probe > 0.0)) return true;
  if (best.weakest_direction.isZero()) return false;
  // Each probe starts `probe` m off: its first pairing distance reaches that much further.
  RefinementParams from_probe = params.refinement;
  from_probe.max_distance = params.refinement.max_distance + probe;
  const double x = best.transform(0, 2), y = best.transform(1, 2), yaw = yawOf(best.transform);
  const auto from_best = [&](const Eigen::Matrix3d &m) { return offsetFrom(best, m).norm(); };
  for (const double sign : {1.0, -1.0}) {
    const Eigen::Vector3d off = sign * probe * best.weakest_direction;
    // A probe that has come back halfway into the settled radius has settled back: stop there.
    const RefinementResult r =
        buffers.refiner.refine(buffers.samples, rigidTransform(x + off(0), y + off(1), yaw + off(2)), from_probe,
                               [&](const Eigen::Matrix3d &m) { return from_best(m) <= 0.5 * kSettledBack * probe; });
    const double left = from_best(r.transform);
    if (left <= kSettledBack * probe) continue;
    const double score = scorer.score(r);
    found.consider(r, score);
    if (score > scorer.score(found.best) - kScoreTie ||
        !fitsWorseWithinReach(found.best, r, score, params, buffers, scorer))
      return false;
  }
  return true;
}

// m: the sweep along the weakest direction (unrivalledAlongWeakestDirection) starts a
// refinement every this far, pairing from half of it beyond the refinement's first pairing
// distance, so that every offset within its reach lies within pairing distance of a start.
constexpr double kSweepStep = 0.5;

// Whether no distinct motion along the best's weakest direction, within the scan's reach,
// scores within the tie of the best or fits what both scans saw better. The probes
// (settlesBack) see the basin of the best alone; along a corridor another optimum metres away
// can fit as well: the true motion, where the contours' best laid door frames and wall ends on
// others further along, or a second alias. The score can favour the alias: along a corridor a
// LIDAR's beams meet the walls ahead at a glancing angle, its returns there lie too far apart
// to form a contour, and the true motion lays the source's near walls on those sparse returns,
// off the target's contour, while the alias lays contour on contour. On the part of the source
// both motions let the target see, its surface taken as its contour and the walls between its
// returns (sharedViewFit, as the check for repeated structure weighs it), the truth fits
// better: a distinct motion that lays more than the tie's share more of that part on the target,
// and that the free space contradicts no more than the best (give or take the tie), rivals the best.
// Refinements start every kSweepStep m along the direction, both ways, from twice that out to
// the RMS range of the best's paired points (RefinementResult::rms_range): farther, a moved
// scan shares little of what the other saw. Each is screened as the hypotheses are (refine.h:
// kScreeningIterations on samples twice as sparse); one that heads for a distinct motion and
// already scores within twice the tie of the best, or fits what both scans saw within twice the
// tie of it (after the screening it has not settled yet), is refined in full from there, scored
// and weighed on what both scans saw.
bool unrivalledAlongWeakestDirection(Judged &found, const RegistrationParams &params, RegistrationBuffers &buffers,
                                     Scorer &scorer) {
  const RefinementResult &best = found.best.refined;
  const double best_score = scorer.score(found.best);
  const double against_best = best.overlap - best_score;  // a score is the overlap less the contradiction
  // Whether the shared view of `samples`, where most of the source lies in it, favours `motion`
  // by more than `lead` (`spots`: the best's, fitOnWhatBothSaw).
  const auto sharedViewFavours = [&](const std::vector<Eigen::Vector2d> &samples, BestSpots &spots,
                                     const Eigen::Matrix3d &motion, double lead) {
    if (!params.free_space.enabled) return false;
    const SharedViewFit fit = fitOnWhatBothSaw(samples, spots, best, motion, params, buffers, scorer);
    return fit.shared >= kMostOfTheContour && fit.second > fit.first + lead;
  };
  thread_local SampleSpots sparse_memory, full_memory;
  BestSpots sparse_spots{sparse_memory}, full_spots{full_memory};
  RefinementParams from_start = params.refinement;
  from_start.max_distance = params.refinement.max_distance + 0.5 * kSweepStep;
  RefinementParams screening = from_start;
  screening.max_iterations = kScreeningIterations;
  const std::vector<Eigen::Vector2d> &sparse = screeningSamplesOf(scorer.source(), buffers);
  // A start that has come back near the best leads to the best: stop there.
  const auto near_best = backTo(best.transform);
  const double x = best.transform(0, 2), y = best.transform(1, 2), yaw = yawOf(best.transform);
  for (double along = 2.0 * kSweepStep; along <= best.rms_range; along += kSweepStep)
    for (const double sign : {1.0, -1.0}) {
      const Eigen::Vector3d off = sign * along * best.weakest_direction;
      const RefinementResult quick =
          buffers.refiner.refine(sparse, rigidTransform(x + off(0), y + off(1), yaw + off(2)), screening, near_best);
      if (motionDistance(quick.transform, best.transform) <= kDistinctMotions) continue;
      // A score is never above the overlap: only a start that overlaps enough pays for the free space.
      const bool scores_near =
          quick.overlap > best_score - 2.0 * kScoreTie && scorer.score(quick) > best_score - 2.0 * kScoreTie;
      if (!scores_near && !sharedViewFavours(sparse, sparse_spots, quick.transform, -2.0 * kScoreTie)) continue;
      const RefinementResult r = buffers.refiner.refine(buffers.samples, quick.transform, from_start, near_best);
      if (motionDistance(r.transform, best.transform) <= kDistinctMotions) continue;
      const double score = scorer.score(r);
      found.consider(r, score);
      if (score > best_score - kScoreTie) return false;
      if (r.overlap - score <= against_best + kScoreTie &&
          sharedViewFavours(buffers.samples, full_spots, r.transform, kScoreTie)) {
        keepTie(found, r, score);
        return false;
      }
    }
  return true;
}

// Whether the best is pinned along its weakest direction (settlesBack). Where a probe settles
// on a motion that scores clearly better (by more than the tie) along that direction from the
// best, the refinement of the best had stopped short of it (a slow slide along a corridor):
// that motion becomes the best and is probed in turn, at most kMaxPromotions times. A better
// motion elsewhere says only that the fit has several optima: not pinned.
bool pinnedAfterPromotions(Judged &found, const RegistrationParams &params, RegistrationBuffers &buffers,
                           Scorer &scorer) {
  for (int promoted = 0;; ++promoted) {
    const RefinementResult &best = found.best.refined;
    if (!best.degenerate && settlesBack(found, params, buffers, scorer)) return true;
    if (best.degenerate || promoted == kMaxPromotions || !found.rival ||
        !(found.rival->score > scorer.score(found.best) + kScoreTie) ||
        !onlyAlongWeakestDirection(best, found.rival->refined.transform))
      return false;
    found.promoteRival();
  }
}

// Whether the best stands against the contours' own answer, the guess (none: no motion)
// refined from the wider pairing distance: they agree, or that answer scores clearly worse.
// A few corners along repeated structure (a door every few metres) can match one period off,
// where the contours fit about as well as at the true motion.
bool standsAgainstGuess(Judged &found, const RegistrationParams &params, const Checks &checks,
                        const Eigen::Matrix3d *guess, RegistrationBuffers &buffers, Scorer &scorer) {
  // A refinement from the guess that has come a quarter of the distinct-motion distance near
  // the best agrees with it: stop there. Where it leads shows on samples twice as sparse, as in
  // the screening of hypotheses; one that leads elsewhere goes on from there on all samples, so
  // that the motion it scores is refined as fully as the best.
  const Eigen::Matrix3d &best = found.best.refined.transform;
  const auto near_best = backTo(best);
  const RefinementResult quick = buffers.refiner.refine(screeningSamplesOf(scorer.source(), buffers),
                                                        guess ? rigidPart(*guess) : Eigen::Matrix3d::Identity(),
                                                        widened(params, checks), near_best);
  if (motionDistance(best, quick.transform) <= kDistinctMotions) return true;
  RefinementParams polish = params.refinement;  // the sparse refinement ended at the smallest pairing distance
  polish.max_distance = polish.min_distance;
  const RefinementResult from_guess = buffers.refiner.refine(buffers.samples, quick.transform, polish, near_best);
  if (motionDistance(best, from_guess.transform) <= kDistinctMotions) return true;
  const double score = scorer.score(from_guess);
  found.consider(from_guess, score);
  return score <= scorer.score(found.best) - kScoreTie;
}

// Whether the free space contradicts the best by more than the tie (its score that far below its overlap).
bool contradicted(Judged &found, Scorer &scorer) {
  return found.best.refined.overlap - scorer.score(found.best) > kScoreTie;
}

// Whether the free space refutes the best: it contradicts the best by more than the tie, and
// each scan saw through some of the other's contour. A surface only one scan has (a car
// parked or gone between the scans) contradicts the right motion one way only; a wrong motion
// misplaces the surfaces of both. If refuted, `what` says how much.
bool refuted(Judged &found, Scorer &scorer, std::string &what) {
  if (!contradicted(found, scorer)) return false;
  // Computed again: only a best contradicted by more than the tie, rare, needs it each way.
  const auto [seen_by_target, seen_by_source] = scorer.evidenceEachWay(found.best.refined.transform);
  if (seen_by_target.contradicted_runs == 0 || seen_by_source.contradicted_runs == 0) return false;
  const FreeSpaceEvidence evidence = seen_by_target + seen_by_source;
  what = percent(evidence.fraction()) + " of the contours it aligns, in " + std::to_string(evidence.contradicted_runs) +
         " stretches";
  return true;
}

// Whether the best stands against the contours' own hypotheses (contourHypotheses: the guess,
// single corner pairs, contour directions): none that refines to a distinct motion scores
// within the tie of it. Searched only for a best that leaves room for such a rival:
// - one the free space contradicts by more than the tie: a rival as well supported but not
//   contradicted would win outright, and a wrong motion the corners agree on (one door off
//   along a corridor) is contradicted most;
// - one that puts less than kMostOfTheContour of the source contour on the target: two
//   distinct motions can each put most of a contour on the target only where the structure
//   repeats along the motion between them, which the free space contradicts; below it, a few
//   corners (a cupboard, the posts of a fence) may agree on a motion the rest of the scan
//   does not share, and the walls' own motion can explain more.
bool standsAgainstContours(Judged &found, const RegistrationParams &params, const Checks &checks,
                           const Eigen::Matrix3d *guess, const std::vector<Correspondence> &pairs,
                           RegistrationBuffers &buffers, Scorer &scorer) {
  if (found.best.refined.overlap >= kMostOfTheContour && !contradicted(found, scorer)) return true;
  const double best = scorer.score(found.best);
  const RefinementParams wide = widened(params, checks);
  contourHypotheses(scorer.source(), scorer.target(), params, checks, guess, pairs, wide, buffers.starts);
  for (const RefinementResult &rival : refineHypotheses(scorer.source(), scorer.target(), buffers.starts, buffers)) {
    if (motionDistance(found.best.refined.transform, rival.transform) <= kDistinctMotions) continue;
    const double score = scorer.score(rival);
    found.consider(rival, score);
    if (score > best - kScoreTie) return false;
  }
  return true;
}

// Whether the best stands against the motions a period of repeated structure off it
// (repetition.h): none that refines to a distinct motion scores higher than the best, and none,
// contradicted no more than the best, lays nearly as much of the view both share on the
// target's surface (its contour and the walls between its returns: TargetSight::
// kReturnsAtBearing). The second is weighed with the free space only: what the target saw
// decides what the two share. A motion that scores higher is the rival (Judged::rival) when
// this says no.
bool standsAgainstRepetition(Judged &found, const RegistrationParams &params, RegistrationBuffers &buffers,
                             Scorer &scorer) {
  if (!params.free_space.enabled) return true;
  const RefinementResult &best = found.best.refined;
  periodShifts(best.transform, scorer.source(), scorer.target(), buffers.repetition);
  if (buffers.repetition.shifted.empty()) return true;
  const double best_score = scorer.score(found.best);
  const double against_best = best.overlap - best_score;
  const auto near_best = backTo(best.transform);  // a start that leads back to the best stops there
  thread_local SampleSpots memory;
  BestSpots best_spots{memory};
  for (const Eigen::Matrix3d &start : buffers.repetition.shifted) {
    const RefinementResult rival = buffers.refiner.refine(buffers.samples, start, params.refinement, near_best);
    if (motionDistance(rival.transform, best.transform) <= kDistinctMotions) continue;
    const double score = scorer.score(rival);
    found.consider(rival, score);
    if (score > best_score) return false;  // the best is not the best of what the judge weighed
    if (rival.overlap - score > against_best + kScoreTie) continue;
    const SharedViewFit fit =
        fitOnWhatBothSaw(buffers.samples, best_spots, best, rival.transform, params, buffers, scorer);
    if (fit.shared >= kMostOfTheContour && fit.second > fit.first - kScoreTie) keepTie(found, rival, score);
  }
  return found.ties.empty();
}

// A rival that scores within this of the best fits nearly as well: the contours' lead is small
// enough for the beams to decide (beamsSideWithRival).
constexpr double kNearlyAsWell = 2.0 * kScoreTie;

// Whether the beams side with the rival: a distinct motion the judge weighed scores within
// kNearlyAsWell of the best, and the best puts more than the tie's share more of both scans'
// returns, beam by beam, in the other scan's free space than the rival does
// (contradictedReturns). The score weighs stretches of contour where both contours have
// returns; the beams are all each scan saw through, sparse returns between the contours
// included, and what moved between the scans (people) stands in both motions' way alike. If
// they side with the rival, `what` gives both shares.
bool beamsSideWithRival(Judged &found, Scorer &scorer, std::string &what) {
  if (!found.rival || found.rival->score <= scorer.score(found.best) - kNearlyAsWell) return false;
  const double against_best = scorer.contradictedReturns(found.best.refined.transform);
  if (!(against_best > kScoreTie)) return false;  // no rival's share can be lower by the tie
  const double against_rival = scorer.contradictedReturns(found.rival->refined.transform);
  if (!(against_best > against_rival + kScoreTie)) return false;
  what = "it puts " + percent(against_best) + " of the scans' returns in the other's free space, the rival " +
         percent(against_rival);
  return true;
}

}  // namespace

void Judged::promoteRival() {
  const ScoredMotion demoted = best;
  best = *rival;
  rival.reset();
  consider(demoted.refined, demoted.score);
  ambiguous = rival && rival->score > best.score - kScoreTie;
  ties.clear();  // they tied with the motion demoted
}

void Judged::consider(const RefinementResult &motion, double score) {
  if (motionDistance(motion.transform, best.refined.transform) <= kDistinctMotions) return;
  if (!rival || score > rival->score) rival = ScoredMotion{motion, true, score};
}

Judged chooseBest(const std::vector<RefinementResult> &refined, const Eigen::Matrix3d *guess, Scorer &scorer) {
  Judged result;
  if (refined.size() == 1) {
    result.best.refined = refined.front();
    return result;
  }
  const Eigen::Matrix3d prior = guess ? rigidPart(*guess) : Eigen::Matrix3d::Identity();
  std::vector<double> scores;
  for (const RefinementResult &r : refined) scores.push_back(scorer.score(r));
  std::size_t best = 0;
  for (std::size_t k = 1; k < refined.size(); ++k) {
    const bool better = scores[k] > scores[best] + kScoreTie ||
                        (scores[k] > scores[best] - kScoreTie &&
                         motionDistance(refined[k].transform, prior) < motionDistance(refined[best].transform, prior));
    if (better) best = k;
  }
  result.best = ScoredMotion{refined[best], true, scores[best]};
  for (std::size_t k = 0; k < refined.size(); ++k) {
    result.consider(refined[k], scores[k]);
    if (scores[k] > scores[best] - kScoreTie &&
        motionDistance(refined[k].transform, refined[best].transform) > kDistinctMotions)
      result.ambiguous = true;
  }
  return result;
}

RegistrationStatus judgeCornerMotion(Judged &found, std::size_t corners, const RegistrationParams &params,
                                     const Checks &checks, const Eigen::Matrix3d *guess,
                                     const std::vector<Correspondence> &pairs, RegistrationBuffers &buffers,
                                     Scorer &scorer, std::string &against) {
  const RefinementResult &refined = found.best.refined;
  const auto verdict = [&](RegistrationStatus status, std::string what) {
    against = std::move(what);
    return status;
  };
  if (found.ambiguous)
    return verdict(RegistrationStatus::kAmbiguous, ", but the contours fit a distinct motion of other corners as well");
  // Two corners need a large overlap, more a modest one.
  const double min_overlap = corners == 2 ? checks.two_inlier_min_overlap : checks.corner_min_overlap;
  if (refined.overlap < min_overlap)
    return verdict(RegistrationStatus::kLowOverlap, " agree, but the contours overlap only " +
                                                        std::to_string(static_cast<int>(100 * refined.overlap)) +
                                                        " % after alignment");
  // A few corners, often along one wall, pin the motion no better than they are spread:
  // the contours must pin it too.
  if (corners <= static_cast<std::size_t>(checks.probe_max_inliers) && !settlesBack(found, params, buffers, scorer))
    return verdict(RegistrationStatus::kUnconstrained, ", and the contours leave a direction weakly constrained");
  if (corners <= static_cast<std::size_t>(checks.guess_check_max_inliers) &&
      !standsAgainstGuess(found, params, checks, guess, buffers, scorer))
    return verdict(RegistrationStatus::kAmbiguous, ", and the contours fit a distinct motion from the guess as well");
  if (!standsAgainstContours(found, params, checks, guess, pairs, buffers, scorer))
    return verdict(RegistrationStatus::kAmbiguous,
                   contradicted(found, scorer)
                       ? ", but the other scan saw through part of it and the contours fit a distinct motion as well"
                       : ", but they put only " + std::to_string(static_cast<int>(100 * refined.overlap)) +
                             " % of the contour on the target and the contours fit a distinct motion as well");
  std::string seen_through;
  if (refuted(found, scorer, seen_through))
    return verdict(RegistrationStatus::kContradicted, ", but the other scan saw through " + seen_through);
  if (!standsAgainstRepetition(found, params, buffers, scorer))
    return verdict(RegistrationStatus::kAmbiguous,
                   ", and a motion a period along repeated structure fits what both scans saw as well");
  std::string beams;
  if (beamsSideWithRival(found, scorer, beams))
    return verdict(RegistrationStatus::kAmbiguous,
                   ", but a distinct motion fits nearly as well and the beams side with it: " + beams);
  against.clear();
  return RegistrationStatus::kConverged;
}

RegistrationStatus judgeContourMotion(Judged &found, const RegistrationParams &params, const Checks &checks,
                                      RegistrationBuffers &buffers, Scorer &scorer, std::string &why) {
  const RefinementResult &refined = found.best.refined;
  // Support: local_fallback_min_overlap of the source contour on the target; where the views
  // share less, down to beam_agreed_overlap_share of it when the beams of both scans agree
  // with the motion (below).
  const double least_overlap =
      params.local_fallback_min_overlap * (params.free_space.enabled ? checks.beam_agreed_overlap_share : 1.0);
  double weak_overlap = 1.0;  // the least overlap of a best on the way, when one was weakly supported
  const auto weaklySupported = [&] { return weak_overlap < params.local_fallback_min_overlap; };
  const auto lowOverlapText = [&] {
    return "at best " + std::to_string(static_cast<int>(100 * weak_overlap)) +
           " % of the source contour lies on the target";
  };
  const auto decline = [&](RegistrationStatus status, const std::string &finding) {
    // A weakly supported fallback stays declined for its low overlap, whatever else it failed.
    if (weaklySupported() && status != RegistrationStatus::kLowOverlap) {
      why = "refined on the contours, " + lowOverlapText() + ", and " + finding;
      return RegistrationStatus::kLowOverlap;
    }
    why = "refined on the contours, " + finding;
    return status;
  };
  const auto overlapsTooLittle = [&] {
    weak_overlap = std::min(weak_overlap, refined.overlap);
    return refined.overlap < least_overlap;
  };
  // A motion that was supported only weakly must agree with everything both scans saw: at most
  // the tie's share of their returns, beam by beam, in the other scan's free space. The score's
  // evidence counts stretches of contour; a cluttered room's table legs, posts and short pieces
  // of wall are returns too.
  const auto beamsDisagree = [&](std::string &finding) {
    if (!weaklySupported()) return false;
    const double share = scorer.contradictedReturns(refined.transform);
    if (share < kScoreTie) return false;
    finding = std::to_string(static_cast<int>(100 * share)) + " % of the scans' returns lie in the other's free space";
    return true;
  };
  // A motion a period along repeated structure, or along the weakest direction, that scores
  // clearly better than the best (by more than the tie) takes its place and is judged in turn,
  // at most kMaxPromotions times: the contours' hypotheses can all lie a period off along a
  // corridor of evenly spaced doors.
  for (int promoted = 0;; ++promoted) {
    const auto promotes = [&] {
      if (promoted == kMaxPromotions || !found.rival || !(found.rival->score > scorer.score(found.best) + kScoreTie))
        return false;
      found.promoteRival();
      return true;
    };
    if (overlapsTooLittle()) return decline(RegistrationStatus::kLowOverlap, lowOverlapText());
    if (!pinnedAfterPromotions(found, params, buffers, scorer))
      return decline(RegistrationStatus::kUnconstrained, "a direction stays weakly constrained (corridor, circle)");
    if (overlapsTooLittle())  // a motion a probe found
      return decline(RegistrationStatus::kLowOverlap, lowOverlapText());
    if (found.ambiguous)
      return decline(RegistrationStatus::kAmbiguous, "distinct motions fit equally well (repeated structure)");
    std::string finding;
    if (refuted(found, scorer, finding))
      return decline(RegistrationStatus::kContradicted, "the other scan saw through " + finding);
    if (!standsAgainstRepetition(found, params, buffers, scorer)) {
      if (promotes()) continue;
      return decline(RegistrationStatus::kAmbiguous,
                     "a motion a period along repeated structure fits what both scans saw as well");
    }
    if (params.probe_distance > 0.0 && !unrivalledAlongWeakestDirection(found, params, buffers, scorer)) {
      if (promotes()) continue;
      return decline(RegistrationStatus::kAmbiguous,
                     "a distinct motion along the weakest direction fits as well, or better on what both scans saw");
    }
    if (beamsDisagree(finding)) return decline(RegistrationStatus::kLowOverlap, lowOverlapText() + ", and " + finding);
    if (beamsSideWithRival(found, scorer, finding))
      return decline(RegistrationStatus::kAmbiguous,
                     "a distinct motion fits nearly as well and the beams side with it: " + finding);
    why.clear();
    return RegistrationStatus::kConverged;
  }
}

std::optional<PinnedMotion> pinnedPart(const RefinementResult &refined, const RefinementModel &model) {
  const Eigen::Vector3d &free = refined.weakest_direction;
  const Eigen::Matrix3d &information = refined.information;
  const double along = free.dot(information * free);
  if (free.isZero() || !information.allFinite() || information.isZero()) return std::nullopt;
  PinnedMotion pinned;
  pinned.transform = refined.transform;
  pinned.free_direction = free;
  // Marginalising the motion along `free`: I - I f f^T I / (f^T I f) has f in its null space.
  pinned.information = information;
  if (along > 0.0) pinned.information -= (information * free) * (information * free).transpose() / along;
  // The turn term adds yaw variance t^2; in information form a rank-one update (Woodbury).
  const double turn = model.turn_noise * std::abs(yawOf(refined.transform));
  if (turn > 0.0) {
    const Eigen::Vector3d yaw_column = pinned.information.col(2);
    pinned.information -= yaw_column * yaw_column.transpose() / (1.0 / (turn * turn) + pinned.information(2, 2));
  }
  pinned.information = 0.5 * (pinned.information + pinned.information.transpose());
  return pinned;
}

}  // namespace contour_reg::decision
