#pragma once
/// @file judge.h
/// The decision, stage 4 of 4 (generate, refine, score, judge): accept the best motion or say why not.
///
/// Of the refined candidates the best score wins (score.h); where scores tie, the motion
/// nearest the guess (no motion without one). The best is accepted only when it is
/// - supported: enough of the source contour lies on the target contour after alignment (for
///   the contours' own motion, less where the beams of both scans agree with it);
/// - pinned in every direction: refined again from `probe_distance` off along its weakest
///   direction, both ways, it settles back or fits worse where it settles, also on the part
///   of the source within the target's reach under both motions (its field of view and its
///   range, whose ends move with the sensor and pin nothing) (a room passes; a bare corridor,
///   a circle seen from inside, a corridor only a short stub closes, a corridor whose end is
///   out of range do not);
/// - unrivalled: no distinct motion scores within the tie, among the refined candidates and,
///   for a motion few corners decide, the contours' own answer from the guess; for a motion
///   the free space contradicts by more than the tie, among all the contours' hypotheses
///   (generate.h) too: a rival as well supported and not contradicted would win outright;
/// - not contradicted: it puts at most the tie's share of both contours in the other scan's
///   free space, or one scan sees through none of the other's contour (what one scan alone
///   has, a car parked or gone between the scans, contradicts the right motion one way only).
///   A best that nothing rivals but both scans contradict is no answer: the true motion was
///   not among the candidates (a symmetric building seen after a large turn).
/// - not repeated: no motion a period of repeated structure off it (a door further along a
///   row of doors) lays nearly as much of what both scans saw on the target (repetition.h);
/// - for the contours' own motion, the best along its weakest direction: refinements started
///   along it out to the scan's RMS range reach no distinct motion that scores as well, nor one
///   that lays clearly more of what both scans saw on the target (its contour and the walls
///   between its returns: along a corridor the truth lays the source's near walls on the sparse
///   returns ahead, off the target's contour, and scores below an alias of contour on contour);
/// - not outvoted by the beams: where a distinct motion scores nearly as well (within twice the
///   tie), the best puts no more of both scans' returns, beam by beam, in the other scan's free
///   space than that rival, give or take the tie. The contours' stretches miss what the beams
///   between them saw (a 180 deg LIDAR's sparse returns, what lies between two contours), and a
///   room's corner seen from elsewhere, turned 90 deg, can lay two walls on the target nearly as
///   well as the truth does.
/// Free-space evidence enters through the score: a rival that puts walls where the other scan
/// looked through empty space scores lower and is no rival.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "checks.h"
#include "contour_reg/core/registration.h"
#include "score.h"

namespace contour_reg::decision {

/// The best of the refined candidates, and whether a distinct motion scores about as well.
struct Judged {
  ScoredMotion best;
  bool ambiguous = false;
  /// The best-scoring motion distinct from `best` (motionDistance > kDistinctMotions) that the
  /// judge scored: among the candidates and in its checks (probes, the guess, the contours'
  /// hypotheses); the motion a period along repeated structure that fits what both scans saw
  /// as well, or one along the weakest direction that fits it better, when the checks find one.
  /// None when it scored no such motion.
  std::optional<ScoredMotion> rival;
  /// The distinct motions a period along repeated structure that fit what both scans saw as
  /// well as the best, or one along its weakest direction that fits it better, when the checks
  /// find any (the first is the rival).
  std::vector<ScoredMotion> ties;
  /// Keeps `motion`, scored `score`, as the rival when it is distinct from the best and scores higher.
  void consider(const RefinementResult &motion, double score);
  /// Makes the rival (scored) the best and the best a rival; ambiguous when that rival scores
  /// within the tie of the new best. The ties, found against the motion demoted, are dropped.
  void promoteRival();
};

/// Picks the best of `refined` (not empty). A single candidate is not scored: nothing to compare.
Judged chooseBest(const std::vector<RefinementResult> &refined, const Eigen::Matrix3d *guess, Scorer &scorer);

/// The verdict on a motion that `corners` distinct inlier special points agree on: converged
/// when the contours confirm it, otherwise low overlap, unconstrained, ambiguous or
/// contradicted, with what they found against it in `against` (to follow "N special points").
/// `pairs` are the candidate pairs of special points, from which the contours' hypotheses are
/// drawn when the free space contradicts the motion.
RegistrationStatus judgeCornerMotion(Judged &found, std::size_t corners, const RegistrationParams &params,
                                     const Checks &checks, const Eigen::Matrix3d *guess,
                                     const std::vector<Correspondence> &pairs, RegistrationBuffers &buffers,
                                     Scorer &scorer, std::string &against);

/// The verdict on the contours' own best motion when the corners did not decide: converged,
/// low overlap, unconstrained, ambiguous or contradicted, with the reason in `why`.
RegistrationStatus judgeContourMotion(Judged &found, const RegistrationParams &params, const Checks &checks,
                                      RegistrationBuffers &buffers, Scorer &scorer, std::string &why);

/// What `refined` pins when its weakest direction is taken as free (RegistrationResult::pinned):
/// its information with that direction marginalised out, and the turn term of its covariance
/// (RefinementModel::turn_noise) added. None when the refinement paired too few points.
std::optional<PinnedMotion> pinnedPart(const RefinementResult &refined, const RefinementModel &model);

}  // namespace contour_reg::decision
