#include "contour_reg/core/refinement.h"
#include "validation.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include <Eigen/Dense>

#include "contour_reg/core/bearing_buckets.h"
#include "contour_reg/core/equalization.h"
#include "contour_reg/core/transform_estimation.h"

namespace contour_reg {

namespace {

// `contour` as the refinement sees it: its raw segment equalized at `step` centred on it
// (equalizeCentred), so that the points do not depend on which way the beams ran along the
// surface; features without their segments give the contour's own vertices, every
// step / contour.step-th. `out` and `arc` are working memory.
const EqualizedContour &centred(const ContourFeatures &features, const EqualizedContour &contour, double step,
                                EqualizedContour &out, std::vector<double> &arc) {
  if (contour.segment >= 0 && static_cast<std::size_t>(contour.segment) < features.segments.size()) {
    equalizeCentred(features.segments[contour.segment].points, step, out, arc);
  } else {
    const std::size_t stride =
        contour.step > 0.0 ? static_cast<std::size_t>(std::max(1.0, std::round(step / contour.step))) : 1;
    out.step = static_cast<double>(stride) * contour.step;
    out.vertices.clear();
    out.spacing.clear();
    for (std::size_t r = 0; r < contour.vertices.size(); r += stride) {
      out.vertices.push_back(contour.vertices[r]);
      out.spacing.push_back(r < contour.spacing.size() ? contour.spacing[r] : 0.0);
    }
  }
  out.segment = contour.segment;
  return out;
}

// The target's contours, equalized centred (centred()), their vertices sorted by bearing, with
// their contour, for projective search. The vertices lie on the raw polyline one step apart,
// however sparse the raw points are (distant walls, 1 deg beams): a source sample between two
// raw points still finds a partner, and a normal spans the same arc length everywhere.
struct BearingIndex {
  std::vector<Eigen::Vector2d> points;
  std::vector<int> segment;  // the contour of each point
  std::vector<int> vertex;   // its vertex number in that contour
  std::vector<int> contour_size;
  std::vector<double> contour_step;
  std::vector<double> bearing;
  std::vector<Eigen::Vector2d> normals;  // computeNormal of each point, once per target
  std::vector<char> has_normal;
  std::vector<double> spacing;                                // m between the raw returns the point lies between
  std::vector<char> at_end;                                   // the first or last vertex of its contour
  std::vector<std::pair<double, std::pair<int, int>>> order;  // bearing, (contour, vertex): kept for the next build
  BearingBuckets buckets;
  // The target's contours, centred, one after another: contour k's vertices and spacings
  // start at first[k]; `scratch` and `arc` are working memory.
  ComplexSequence centred_vertices;
  std::vector<double> centred_spacing;
  std::vector<std::size_t> first;
  EqualizedContour scratch;
  std::vector<double> arc;

  // Indexes `target`, reusing the buffers of the last build.
  void build(const ContourFeatures &target) {
    centred_vertices.clear();
    centred_spacing.clear();
    first.clear();
    contour_size.clear();
    contour_step.clear();
    for (const EqualizedContour &contour : target.contours) {
      centred(target, contour, contour.step, scratch, arc);
      first.push_back(centred_vertices.size());
      centred_vertices.insert(centred_vertices.end(), scratch.vertices.begin(), scratch.vertices.end());
      centred_spacing.insert(centred_spacing.end(), scratch.spacing.begin(), scratch.spacing.end());
      contour_size.push_back(static_cast<int>(scratch.vertices.size()));
      contour_step.push_back(scratch.step);
    }
    const std::size_t vertices = centred_vertices.size();
    order.clear();
    order.reserve(vertices);
    for (std::size_t k = 0; k < first.size(); ++k)
      for (int n = 0; n < contour_size[k]; ++n)
        order.push_back({std::arg(centred_vertices[first[k] + n]), {int(k), n}});
    // A scan's contours follow its beams, so the vertices usually come in bearing order already.
    if (!std::is_sorted(order.begin(), order.end())) std::sort(order.begin(), order.end());
    points.clear();
    segment.clear();
    vertex.clear();
    vertex.reserve(vertices);
    bearing.clear();
    points.reserve(vertices);
    segment.reserve(vertices);
    bearing.reserve(vertices);
    spacing.clear();
    spacing.reserve(vertices);
    at_end.clear();
    at_end.reserve(vertices);
    for (const auto &[b, where] : order) {
      const std::size_t at = first[where.first] + where.second;
      at_end.push_back(where.second == 0 || where.second + 1 == contour_size[where.first]);
      spacing.push_back(centred_spacing[at]);
      points.push_back(toEigen(centred_vertices[at]));
      segment.push_back(where.first);
      vertex.push_back(where.second);
      bearing.push_back(b);
    }
    normals.assign(points.size(), Eigen::Vector2d::Zero());
    has_normal.assign(points.size(), 0);
    for (std::size_t j = 0; j < points.size(); ++j) has_normal[j] = computeNormal(static_cast<int>(j), normals[j]);
    buckets.build(bearing, 4);
  }

  // Nearest point to p among those near p's bearing; -1 when none within max_distance: walks
  // outwards from p's bearing while the points get closer, and four points more.
  int nearest(const Eigen::Vector2d &p, double max_distance) const {
    long at = -1;
    return nearest(p, max_distance, at);
  }

  // The same, with `at` the first point at or above p's bearing as found for a point near p
  // (negative: none), set to p's: a point that moved a little finds it a step or two away,
  // without the buckets.
  int nearest(const Eigen::Vector2d &p, double max_distance, long &at) const {
    if (points.empty()) return -1;
    const double b = approximateAtan2(p.y(), p.x());
    const long size = static_cast<long>(points.size());
    const long start = at < 0 ? buckets.firstAtOrAbove(bearing, b) : BearingBuckets::firstAtOrAboveFrom(bearing, b, at);
    at = start;
    const Eigen::Vector2d *point = points.data();
    long best = -1;
    double best_d2 = max_distance * max_distance;
    // Down from p's bearing, then up, each way in a loop of its own over the points' array.
    const auto visit = [&](long j, long &worse) {
      const double d2 = (point[j] - p).squaredNorm();
      const bool closer = d2 < best_d2;
      best_d2 = closer ? d2 : best_d2;
      best = closer ? j : best;
      worse = closer ? 0 : worse + 1;
    };
    for (long j = start - 1, worse = 0; worse < 4 && j >= 0; --j) visit(j, worse);
    for (long j = start, worse = 0; worse < 4 && j < size; ++j) visit(j, worse);
    return static_cast<int>(best);
  }

  // Unit normal of the target contour at point j (false where it has none).
  bool normalAt(int j, Eigen::Vector2d &normal) const {
    normal = normals[j];
    return has_normal[j];
  }

  // The normal at point j from its neighbours in the same contour, two on each side (in the
  // contour's own order: contours that share bearings, as scans merged into one cloud do,
  // interleave in the bearing order).
  bool computeNormal(int j, Eigen::Vector2d &normal) const {
    const int contour = segment[j], lo = std::max(0, vertex[j] - 2),
              hi = std::min(contour_size[contour] - 1, vertex[j] + 2);
    const Eigen::Vector2d along =
        toEigen(centred_vertices[first[contour] + hi] - centred_vertices[first[contour] + lo]);
    if (hi == lo || along.norm() < 1e-6) return false;
    normal = Eigen::Vector2d(-along.y(), along.x()).normalized();
    return true;
  }
};

// Below this share of the source contour paired (RefinementResult::overlap), the two views
// share less of what they see than the covariance's terms assume.
constexpr double kSharedViewOverlap = 0.8;

// How much the covariance of a refinement that paired `overlap` of the source contour grows:
// (kSharedViewOverlap / overlap)^2 below kSharedViewOverlap, 1 above. Where two views share
// less, more of the samples paired lie on surfaces the other scan saw from elsewhere or not at
// all (occluded, moved, sampled sparsely at another angle), whose errors neither the residuals
// nor the stretches show. Calibrated on the triangle closure of the Radish logs
// (docs/reliability.md): on every log the closures leave their ellipsoid more often the less
// the views overlap.
double lessSharedViews(double overlap) {
  if (!(overlap > 0.0) || overlap >= kSharedViewOverlap) return 1.0;
  const double shortfall = kSharedViewOverlap / overlap;
  return shortfall * shortfall;
}

// Units that measure rotation in metres of arc at the RMS range of the paired points
// (1, 1, 1 / range), so that eigenvalues of translation and rotation compare.
Eigen::Vector3d arcUnits(double rms_range) { return {1.0, 1.0, rms_range > 1e-6 ? 1.0 / rms_range : 1.0}; }

double rmsRange(double lever_squares, double weight_sum) {
  return std::sqrt(lever_squares / std::max(weight_sum, 1e-12));
}

// Adds the upper triangle of a b^T to m; the lower is mirrored once after a pass.
inline void addUpperTriangle(Eigen::Matrix3d &m, const Eigen::Vector3d &a, const Eigen::Vector3d &b) {
  m(0, 0) += a(0) * b(0);
  m(0, 1) += a(0) * b(1);
  m(0, 2) += a(0) * b(2);
  m(1, 1) += a(1) * b(1);
  m(1, 2) += a(1) * b(2);
  m(2, 2) += a(2) * b(2);
}

// The covariance widened to cover how the stretches of contour disagree: the cluster-robust
// (sandwich) covariance hessian^-1 M hessian^-1, M the sum of each stretch's gradient times its
// transpose (scaled by G / (G - 3) for the 3 fitted parameters), wherever it exceeds
// `covariance`. Residuals of one stretch may share any error; stretches are taken as
// independent. None where nothing is added, or with fewer than 6 stretches paired (the
// sandwich says too little then).
std::optional<Eigen::Matrix3d> widenByStretches(const Eigen::Matrix3d &covariance, const Eigen::Matrix3d &hessian,
                                                const std::vector<Eigen::Vector3d> &stretch_gradient) {
  Eigen::Matrix3d meat = Eigen::Matrix3d::Zero();
  int stretches = 0;
  for (const Eigen::Vector3d &g : stretch_gradient) {
    if (g.isZero(0.0)) continue;
    meat += g * g.transpose();
    ++stretches;
  }
  Eigen::Matrix3d bread;
  bool invertible = false;
  hessian.computeInverseWithCheck(bread, invertible);
  if (stretches < 6 || !invertible) return std::nullopt;
  const Eigen::Matrix3d sandwich = bread * meat * bread * (double(stretches) / double(stretches - 3));
  const Eigen::Matrix3d excess = 0.5 * (sandwich - covariance + (sandwich - covariance).transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(excess);
  if (!(eigen.eigenvalues().maxCoeff() > 0.0)) return std::nullopt;
  return covariance +
         eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace

std::vector<Eigen::Vector2d> contourSamples(const ContourFeatures &source, double sample_step) {
  std::vector<Eigen::Vector2d> samples;
  contourSamples(source, sample_step, samples);
  return samples;
}

void contourSamples(const ContourFeatures &source, double sample_step, std::vector<Eigen::Vector2d> &samples) {
  samples.clear();
  // Working memory, kept between calls (each thread its own).
  thread_local EqualizedContour centred_contour;
  thread_local std::vector<double> arc;
  for (const EqualizedContour &contour : source.contours) {
    if (contour.vertices.empty() || contour.step <= 0.0) continue;
    // The samples as far apart along the contour as whole elements allow.
    const double step = std::max(1.0, std::round(sample_step / contour.step)) * contour.step;
    for (const Complex &p : centred(source, contour, step, centred_contour, arc).vertices)
      samples.push_back(toEigen(p));
  }
}

bool RefinementParams::validate(std::string *why) const {
  if (max_iterations < 0) return invalid(why, "refinement.max_iterations must be >= 0");
  if (!(min_distance > 0.0 && max_distance >= min_distance))
    return invalid(why, "refinement distances must be 0 < min <= max");
  if (!(stop_translation >= 0.0 && stop_rotation >= 0.0))
    return invalid(why, "refinement.stop_translation and stop_rotation must be >= 0");
  return true;
}

bool RefinementModel::validate(std::string *why) const {
  if (!(sample_step > 0.0)) return invalid(why, "refinement model: sample_step must be > 0");
  if (!(huber > 0.0)) return invalid(why, "refinement model: huber must be > 0");
  if (!(degeneracy_ratio >= 0.0 && degeneracy_ratio < 1.0))
    return invalid(why, "refinement model: degeneracy_ratio must lie in [0, 1)");
  if (!(covariance_scale > 0.0)) return invalid(why, "refinement model: covariance_scale must be > 0");
  if (!(turn_noise >= 0.0)) return invalid(why, "refinement model: turn_noise must be >= 0");
  if (!(correlation_length >= 0.0)) return invalid(why, "refinement model: correlation_length must be >= 0");
  return true;
}

struct ContourRefiner::Index {
  BearingIndex bearing;
  // The stretch of `stretch_length` m of target contour each indexed point lies on, numbered
  // over all contours (widenByStretches), and each stretch's gradient: working memory.
  double stretch_length = -1.0;
  std::vector<int> stretch;
  int stretches = 0;
  std::vector<Eigen::Vector3d> stretch_gradient;
  std::vector<int> stretch_first, stretch_span;  // numberStretches' working memory
  std::vector<long> search_start;                // refine's working memory: each sample's last search start

  void numberStretches(double length) {
    std::vector<int> &first = stretch_first, &span = stretch_span;
    first.assign(bearing.contour_size.size() + 1, 0);
    span.assign(bearing.contour_size.size(), 1);
    for (std::size_t k = 0; k < span.size(); ++k) {
      const double step = bearing.contour_step[k];
      if (step > 0.0) span[k] = std::max(1, static_cast<int>(std::lround(length / step)));
      first[k + 1] = first[k] + (bearing.contour_size[k] + span[k] - 1) / span[k];
    }
    stretch.resize(bearing.points.size());
    for (std::size_t j = 0; j < stretch.size(); ++j)
      stretch[j] = first[bearing.segment[j]] + bearing.vertex[j] / span[bearing.segment[j]];
    stretches = first.back();
    stretch_length = length;
  }
};

ContourRefiner::ContourRefiner() : index_(std::make_unique<Index>()) {}

ContourRefiner::ContourRefiner(const ContourFeatures &target, const RefinementParams &params,
                               const RefinementModel &model)
    : index_(std::make_unique<Index>()), params_(params), model_(model) {
  setTarget(target);
}

void ContourRefiner::setTarget(const ContourFeatures &target) {
  index_->bearing.build(target);
  index_->stretch_length = -1.0;
}

ContourRefiner::~ContourRefiner() = default;

RefinementResult refineOnContours(const ContourFeatures &source, const ContourFeatures &target,
                                  const Eigen::Matrix3d &initial, const RefinementParams &params,
                                  const RefinementModel &model) {
  return ContourRefiner(target, params, model).refine(source, initial);
}

RefinementResult ContourRefiner::refine(const ContourFeatures &source, const Eigen::Matrix3d &initial) const {
  return refine(source, initial, params_);
}

RefinementResult ContourRefiner::refine(const ContourFeatures &source, const Eigen::Matrix3d &initial,
                                        const RefinementParams &params) const {
  return refine(contourSamples(source, model_.sample_step), initial, params);
}

bool ContourRefiner::pairs(const Eigen::Vector2d &point, double distance) const {
  return index_->bearing.nearest(point, distance) >= 0;
}

RefinementResult ContourRefiner::refine(const std::vector<Eigen::Vector2d> &samples, const Eigen::Matrix3d &initial,
                                        const RefinementParams &params,
                                        const std::function<bool(const Eigen::Matrix3d &)> &arrived) const {
  const BearingIndex &index = index_->bearing;
  RefinementResult result;
  result.transform = initial;
  if (samples.empty() || index.points.empty()) return result;

  double x = initial(0, 2), y = initial(1, 2), yaw = yawOf(initial);
  // The last pass's sums, kept for the covariance: the information of every pair (h), the part
  // of it samples between the same two raw returns share (surplus), and the information the
  // step weighs its pairs by (step_h).
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero(), surplus = Eigen::Matrix3d::Zero(), step_h = Eigen::Matrix3d::Zero();
  double weighted_squares = 0.0;
  double weight_sum = 0.0;
  double lever_squares =
      0.0;  // sum of |rotated source point|^2: the rotation information if every normal were tangential
  double distance = params.max_distance;
  // Each stretch's share of the gradient, for the covariance (widenByStretches): counted in
  // the passes at the smallest pairing distance, where a refinement ends unless stopped early.
  const bool by_stretches = model_.correlation_length > 0.0;
  bool stretches_counted = false;
  Index &work = *index_;
  if (by_stretches && work.stretch_length != model_.correlation_length) work.numberStretches(model_.correlation_length);
  std::vector<Eigen::Vector3d> &stretch_gradient = work.stretch_gradient;
  stretch_gradient.resize(by_stretches ? work.stretches : 0);
  const int *stretch = work.stretch.data();
  Eigen::Vector3d last_step = Eigen::Vector3d::Zero(), step_before = Eigen::Vector3d::Zero();
  std::vector<long> &start = work.search_start;
  start.assign(samples.size(), -1);
  bool stopped = false;
  for (int iteration = 0; iteration < params.max_iterations; ++iteration) {
    result.iterations = iteration + 1;
    const Eigen::Rotation2Dd rotation(yaw);
    const Eigen::Vector2d translation(x, y);
    h.setZero();
    surplus.setZero();
    step_h.setZero();
    Eigen::Vector3d step_g = Eigen::Vector3d::Zero();
    weighted_squares = 0.0;
    lever_squares = 0.0;
    weight_sum = 0.0;
    int pairs = 0;
    stretches_counted = by_stretches && distance <= params.min_distance;
    if (stretches_counted) std::fill(stretch_gradient.begin(), stretch_gradient.end(), Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const Eigen::Vector2d &p = samples[i];
      const Eigen::Vector2d rotated = rotation * p;
      const Eigen::Vector2d moved = rotated + translation;
      // Each sample's search starts from where it started in the last pass.
      const int j = index.nearest(moved, distance, start[i]);
      Eigen::Vector2d normal;
      if (j < 0 || !index.normalAt(j, normal)) continue;
      const double residual = normal.dot(moved - index.points[j]);
      const double weight = std::abs(residual) <= model_.huber ? 1.0 : model_.huber / std::abs(residual);
      const Eigen::Vector3d jacobian(normal.x(), normal.y(), normal.dot(Eigen::Vector2d(-rotated.y(), rotated.x())));
      const Eigen::Vector3d weighted = weight * jacobian;
      addUpperTriangle(h, weighted, jacobian);
      // Samples between the same two raw returns share their noise: together they carry the
      // information of one sample per sample_step of the returns' spacing, so each counts
      // sample_step / spacing of its weight (`surplus` holds the rest).
      const double share = index.spacing[j] > model_.sample_step ? model_.sample_step / index.spacing[j] : 1.0;
      if (share < 1.0) addUpperTriangle(surplus, (1.0 - share) * weighted, jacobian);
      lever_squares += weight * rotated.squaredNorm();
      weight_sum += weight;
      // The step weighs each pair as the covariance counts it. A target vertex that ends its
      // contour is where the target's view of that surface ended (an occlusion, the range
      // limit): the source sample paired with it may lie on surface the target never saw, so
      // the pair counts for the overlap and the information but does not move the estimate.
      if (!index.at_end[j]) {
        const Eigen::Vector3d counted = share * weighted;
        const Eigen::Vector3d gradient = residual * counted;
        step_g += gradient;
        addUpperTriangle(step_h, counted, jacobian);
        if (stretches_counted) stretch_gradient[stretch[j]] += gradient;
      }
      weighted_squares += weight * residual * residual;
      ++pairs;
    }
    h.triangularView<Eigen::StrictlyLower>() = h.transpose();
    surplus.triangularView<Eigen::StrictlyLower>() = surplus.transpose();
    step_h.triangularView<Eigen::StrictlyLower>() = step_h.transpose();
    result.pairs = pairs;
    result.overlap = static_cast<double>(pairs) / static_cast<double>(samples.size());
    result.rmse = pairs > 0 ? std::sqrt(weighted_squares / pairs) : 0.0;
    if (pairs < 6) break;
    // Solve only along well-constrained directions, rotation measured in metres of arc.
    result.rms_range = rmsRange(lever_squares, weight_sum);
    const Eigen::Vector3d unit = arcUnits(result.rms_range);
    const Eigen::Matrix3d scaled_h = unit.asDiagonal() * h * unit.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(scaled_h);  // closed form for 3 x 3: scaled_h is in one unit, well scaled
    const Eigen::Vector3d values = eigen.eigenvalues();
    result.weakest_direction = unit.asDiagonal() * eigen.eigenvectors().col(0);
    Eigen::Matrix3d pinned = Eigen::Matrix3d::Zero();  // projector on the constrained directions
    for (int k = 0; k < 3; ++k) {
      if (values(k) <= model_.degeneracy_ratio * values(2)) continue;
      const Eigen::Vector3d v = eigen.eigenvectors().col(k);
      pinned += v * v.transpose();
    }
    const Eigen::Matrix3d scaled_step_h = unit.asDiagonal() * step_h * unit.asDiagonal();
    const Eigen::Matrix3d system = pinned * scaled_step_h * pinned + (Eigen::Matrix3d::Identity() - pinned);
    Eigen::Vector3d step = pinned * system.ldlt().solve(-pinned * (unit.asDiagonal() * step_g));
    if (!step.allFinite()) step.setZero();
    step = unit.asDiagonal() * step;
    x += step(0);
    y += step(1);
    yaw += step(2);
    const bool at_min_distance = distance <= params.min_distance;  // this pass paired at the smallest distance
    distance = std::max(params.min_distance, distance * 0.7);
    step_before = last_step;
    last_step = step.cwiseProduct(Eigen::Vector3d(1.0, 1.0, result.rms_range));
    stopped = (arrived && arrived(rigidTransform(x, y, yaw))) ||
              (step.head<2>().norm() < params.stop_translation && std::abs(step(2)) < params.stop_rotation &&
               at_min_distance);
    if (stopped) break;
  }
  result.sliding = !stopped && result.iterations == params.max_iterations && result.pairs >= 6 &&
                   last_step.dot(step_before) > 0.5 * last_step.norm() * step_before.norm();
  result.transform = rigidTransform(x, y, yaw);
  if (result.pairs >= 6) {
    // Translation and rotation have different units: judge degeneracy on the translation block
    // and on the rotation conditioned on it.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> translation(h.topLeftCorner<2, 2>());
    result.constraint_ratio =
        translation.eigenvalues()(1) > 0.0 ? translation.eigenvalues()(0) / translation.eigenvalues()(1) : 0.0;
    const Eigen::Matrix2d h_tt = h.topLeftCorner<2, 2>();
    const Eigen::Vector2d h_tr = h.topRightCorner<2, 1>();
    const double h_rr = h(2, 2);
    if (lever_squares > 0.0 && std::abs(h_tt.determinant()) > 1e-12)
      result.rotation_constraint_ratio = std::max(0.0, h_rr - h_tr.dot(h_tt.inverse() * h_tr)) / lever_squares;
    result.degenerate = result.constraint_ratio <= model_.degeneracy_ratio ||
                        result.rotation_constraint_ratio <= model_.degeneracy_ratio;
    const double sigma2 = weighted_squares / std::max(1, result.pairs - 3);
    const double less_shared = lessSharedViews(result.overlap);
    const Eigen::Matrix3d counted_information = h - surplus;
    if (sigma2 > 0.0) result.information = counted_information / (model_.covariance_scale * sigma2);
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(counted_information);
    if (lu.isInvertible()) {
      result.covariance = model_.covariance_scale * sigma2 * lu.inverse();
      if (stretches_counted && sigma2 > 0.0) {
        if (const std::optional<Eigen::Matrix3d> widened =
                widenByStretches(result.covariance, step_h, stretch_gradient)) {
          result.covariance = *widened;
          bool invertible = false;
          Eigen::Matrix3d inverse;
          widened->computeInverseWithCheck(inverse, invertible);
          if (invertible) result.information = inverse;
        }
      }
      result.covariance *= less_shared;
      const double turn = model_.turn_noise * std::abs(yawOf(result.transform));
      result.covariance(2, 2) += turn * turn;
    }
    result.information /= less_shared;
  } else {
    result.degenerate = true;
    result.rms_range = 0.0;  // an earlier iteration's, with too few pairs now
    result.weakest_direction.setZero();
  }
  return result;
}

}  // namespace contour_reg
