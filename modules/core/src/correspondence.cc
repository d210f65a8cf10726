#include "contour_reg/core/correspondence.h"
#include "validation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <flann/flann.hpp>

namespace contour_reg {

namespace {

bool compatible(const SpecialPoint &a, const SpecialPoint &b) {
  return a.turn == b.turn && std::abs(a.corner_angle - b.corner_angle) <= kMaxCornerAngleDifference;
}

// The fragment as real numbers for the kd-tree. For the rotation-invariant form it is
// turned so that the corner's bisector points along +x, which makes the Euclidean
// distance approximate the |(G, N)| form of eq. (14).
void descriptor(const SpecialPoint &p, FragmentDistance form, float *out) {
  const Complex turn = form == FragmentDistance::kModulus ? std::polar(1.0, -p.orientation) : Complex(1.0, 0.0);
  for (std::size_t m = 0; m < p.fragment.size(); ++m) {
    const Complex v = p.fragment[m] * turn;
    out[2 * m] = static_cast<float>(v.real());
    out[2 * m + 1] = static_cast<float>(v.imag());
  }
}

// The nearest fragments' target indices for each source point, `k` per point in a row-major
// matrix, from a kd-tree over the targets' descriptors.
std::vector<int> nearestTargets(const std::vector<SpecialPoint> &source, const std::vector<SpecialPoint> &target,
                                const CorrespondenceParams &params, std::size_t k) {
  const std::size_t dims = 2 * target.front().fragment.size();
  std::vector<float> data(target.size() * dims), query(source.size() * dims);
  for (std::size_t t = 0; t < target.size(); ++t) descriptor(target[t], params.distance, &data[t * dims]);
  for (std::size_t s = 0; s < source.size(); ++s) descriptor(source[s], params.distance, &query[s * dims]);
  flann::Index<flann::L2<float>> index(flann::Matrix<float>(data.data(), target.size(), dims),
                                       flann::KDTreeSingleIndexParams(10));
  index.buildIndex();
  std::vector<int> indices(source.size() * k);
  std::vector<float> distances(source.size() * k);
  flann::Matrix<int> index_matrix(indices.data(), source.size(), k);
  flann::Matrix<float> distance_matrix(distances.data(), source.size(), k);
  index.knnSearch(flann::Matrix<float>(query.data(), source.size(), dims), index_matrix, distance_matrix, k,
                  flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED));
  return indices;
}

}  // namespace

bool CorrespondenceParams::validate(std::string *why) const {
  if (candidates_per_point < 1) return invalid(why, "correspondence.candidates_per_point must be >= 1");
  return true;
}

// Eq. (14): R^2 = |G|^2 + |N|^2 - 2 Re (G, N), or with |(G, N)| for the invariant form.
double fragmentDistanceSquared(const ComplexSequence &source, const ComplexSequence &target, FragmentDistance form,
                               double *rotation) {
  Complex product = 0.0;  // (N, G) = sum n conj(g)
  double norm_g = 0.0, norm_n = 0.0;
  for (std::size_t m = 0; m < source.size() && m < target.size(); ++m) {
    product += target[m] * std::conj(source[m]);
    norm_g += squaredMagnitude(source[m]);
    norm_n += squaredMagnitude(target[m]);
  }
  if (rotation) *rotation = std::arg(product);
  const double overlap = form == FragmentDistance::kReal ? product.real() : magnitude(product);
  return std::max(0.0, norm_g + norm_n - 2.0 * overlap);
}

std::vector<Correspondence> findCorrespondences(const std::vector<SpecialPoint> &source,
                                                const std::vector<SpecialPoint> &target,
                                                const CorrespondenceParams &params, CandidateSearch search) {
  std::vector<Correspondence> pairs;
  CorrespondenceScratch scratch;
  findCorrespondences(source, target, params, pairs, scratch, search);
  return pairs;
}

void findCorrespondences(const std::vector<SpecialPoint> &source, const std::vector<SpecialPoint> &target,
                         const CorrespondenceParams &params, std::vector<Correspondence> &pairs,
                         CorrespondenceScratch &scratch, CandidateSearch search) {
  pairs.clear();
  if (source.empty() || target.empty()) return;
  // Candidate targets of each source point: every target (small sets) or the nearest
  // fragments from a kd-tree (large sets). The tree holds fragments as vectors of one length:
  // fragments of other lengths (other extraction settings, points made by hand) are compared
  // over all pairs, over the shorter fragment.
  const std::size_t length = target.front().fragment.size();
  const auto ofLength = [length](const std::vector<SpecialPoint> &points) {
    return std::all_of(points.begin(), points.end(),
                       [&](const SpecialPoint &p) { return p.fragment.size() == length; });
  };
  const bool large = source.size() >= kKdTreeMinPoints && target.size() >= kKdTreeMinPoints;
  const bool use_tree = search != CandidateSearch::kAllPairs && (large || search == CandidateSearch::kKdTree) &&
                        length > 0 && ofLength(source) && ofLength(target);
  const std::size_t per_source =
      use_tree ? std::min<std::size_t>(target.size(), 4 * static_cast<std::size_t>(params.candidates_per_point) + 4)
               : target.size();
  const std::vector<int> nearest = use_tree ? nearestTargets(source, target, params, per_source) : std::vector<int>{};
  const bool one_to_one = params.candidates_per_point == 1;
  std::vector<Correspondence> &best_for_target = scratch.best_for_target;
  best_for_target.assign(target.size(), Correspondence{-1, -1, std::numeric_limits<double>::infinity(), 0.0});

  std::vector<Correspondence> &ranked = scratch.ranked;
  for (std::size_t s = 0; s < source.size(); ++s) {
    ranked.clear();
    for (std::size_t j = 0; j < per_source; ++j) {
      const int t = use_tree ? nearest[s * per_source + j] : static_cast<int>(j);
      if (!compatible(source[s], target[t])) continue;
      double rotation = 0.0;
      const double r2 = fragmentDistanceSquared(source[s].fragment, target[t].fragment, params.distance, &rotation);
      ranked.push_back({static_cast<int>(s), t, std::sqrt(r2), rotation});
    }
    if (ranked.empty()) continue;
    const std::size_t keep = std::min<std::size_t>(ranked.size(), params.candidates_per_point);
    std::partial_sort(ranked.begin(), ranked.begin() + keep, ranked.end(),
                      [](const Correspondence &a, const Correspondence &b) { return a.distance < b.distance; });
    if (one_to_one) {
      if (ranked.size() > 1) {
        const double second = std::min_element(ranked.begin() + 1, ranked.end(), [](auto &a, auto &b) {
                                return a.distance < b.distance;
                              })->distance;
        if (!(ranked[0].distance < kUniquenessRatio * second)) continue;  // ratio test
      }
      Correspondence &held = best_for_target[ranked[0].target];
      if (ranked[0].distance < held.distance) held = ranked[0];
      continue;
    }
    pairs.insert(pairs.end(), ranked.begin(), ranked.begin() + keep);
  }
  if (one_to_one)  // mutual best: the target's best source must be this source
    for (const Correspondence &c : best_for_target)
      if (c.source >= 0) pairs.push_back(c);
}

}  // namespace contour_reg
