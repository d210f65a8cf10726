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
/// kept that match in turn direction and corner angle; each source point keeps its best
/// `candidates_per_point` targets (with one, only mutual best matches that pass the ratio
/// test, the paper's one-to-one correspondence). Above `kdtree_min_points` special points
/// a FLANN kd-tree over the fragments finds the candidates (n log n); below, all pairs
/// are compared, which is faster for the few dozen corners of a typical scan. Fragments of
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
  int candidates_per_point = 3;         ///< best targets kept per source point
  double ratio = 0.9;                   ///< with one candidate: best R must be below ratio * second best R
  double max_angle_difference = 0.35;   ///< rad, corner angles of a pair must agree this well
  std::size_t kdtree_min_points = 128;  ///< use the kd-tree when both scans have at least this many points

  bool validate(std::string *why = nullptr) const;
};

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
                                                const CorrespondenceParams &params);

/// Working memory of findCorrespondences, kept between calls.
struct CorrespondenceScratch {
  std::vector<Correspondence> ranked, best_for_target;
};

/// The same into `pairs`; `pairs` and `scratch` keep their buffers between calls, so that
/// below kdtree_min_points nothing is allocated once they are large enough.
void findCorrespondences(const std::vector<SpecialPoint> &source, const std::vector<SpecialPoint> &target,
                         const CorrespondenceParams &params, std::vector<Correspondence> &pairs,
                         CorrespondenceScratch &scratch);

}  // namespace contour_reg
