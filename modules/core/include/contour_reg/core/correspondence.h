#pragma once
/// @file correspondence.h
/// Stage D: one-to-one correspondence of special points (paper eq. 14).
///
/// With G the local fragment of a special point of the current (source) contour and N
/// that of a point of the previous (target) contour, both taken around their vertex,
///
///     R^2 = |G|^2 + |N|^2 - 2 Re (G, N)                            (eq. 14)
///
/// `Re` makes R depend on the rotation between the scans. The rotation-invariant form
/// replaces Re (G, N) by |(G, N)|; then arg (N, G) is the rotation that takes the
/// source fragment onto the target one, a free check on each candidate pair. Pairs are
/// kept that match in turn direction and corner angle (within kMaxCornerAngleDifference);
/// each source point keeps its best `candidates_per_point` targets (with one, only mutual
/// best matches that pass the ratio test, kUniquenessRatio: the paper's one-to-one
/// correspondence). From kKdTreeMinPoints special points in both scans a FLANN kd-tree over
/// the fragments finds the candidates (n log n); below, all pairs are compared, which is
/// faster for the few dozen corners of a typical scan. Fragments of
/// different lengths (special points of other extraction settings) are always compared over
/// all pairs, over the shorter fragment.

#include <string>
#include <vector>

#include "contour_reg/core/special_points.h"

namespace contour_reg {

enum class FragmentDistance {
  kReal,     ///< the paper: Re (G, N); depends on the rotation between scans
  kModulus,  ///< |(G, N)|: rotation invariant; arg (N, G) gives each pair's rotation
};

struct CorrespondenceParams {
  FragmentDistance distance = FragmentDistance::kModulus;
  int candidates_per_point = 3;  ///< best targets kept per source point

  bool validate(std::string *why = nullptr) const;
};

/// rad (20 deg): the corner angles of a pair must agree this well. A corner seen from two
/// places keeps its angle, up to the noise of the arms fitted to it.
constexpr double kMaxCornerAngleDifference = 0.35;
/// One candidate per point: the best fragment distance R must be below this times the second
/// best, as in Lowe's ratio test, or the point is left unpaired (the match is not unique).
constexpr double kUniquenessRatio = 0.9;
/// special points: from this many in both scans a kd-tree over the fragments proposes each
/// source point's 4 x candidates_per_point + 4 nearest targets; below, comparing all pairs is
/// faster.
constexpr std::size_t kKdTreeMinPoints = 128;

/// How the candidates are searched: by size (kKdTreeMinPoints), or forced either way.
enum class CandidateSearch { kBySize, kAllPairs, kKdTree };

/// A candidate pair of special points.
struct Correspondence {
  int source = -1;        ///< index into the source special points
  int target = -1;        ///< index into the target special points
  double distance = 0.0;  ///< R of eq. (14), in metres of fragment
  double rotation = 0.0;  ///< rad, arg (N, G): rotation of the source fragment onto the target's
};

/// R^2 of eq. (14) between two fragments of equal length; `rotation` gets arg (N, G).
double fragmentDistanceSquared(const ComplexSequence &source, const ComplexSequence &target, FragmentDistance form,
                               double *rotation = nullptr);

/// Candidate pairs between two sets of special points, best first per source point.
std::vector<Correspondence> findCorrespondences(const std::vector<SpecialPoint> &source,
                                                const std::vector<SpecialPoint> &target,
                                                const CorrespondenceParams &params,
                                                CandidateSearch search = CandidateSearch::kBySize);

/// Working memory of findCorrespondences, kept between calls.
struct CorrespondenceScratch {
  std::vector<Correspondence> ranked, best_for_target;
};

/// The same into `pairs`; `pairs` and `scratch` keep their buffers between calls, so that
/// below kKdTreeMinPoints nothing is allocated once they are large enough.
void findCorrespondences(const std::vector<SpecialPoint> &source, const std::vector<SpecialPoint> &target,
                         const CorrespondenceParams &params, std::vector<Correspondence> &pairs,
                         CorrespondenceScratch &scratch, CandidateSearch search = CandidateSearch::kBySize);

}  // namespace contour_reg
