#include "contour_reg/core/direction_histogram.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "contour_reg/core/transform_estimation.h"
#include "validation.h"

namespace contour_reg {

namespace {

// Smooths a histogram with a Gaussian of `sigma` bins; circular or clamped at the ends.
std::vector<double> smooth(const std::vector<double> &h, double sigma, bool circular) {
  if (sigma <= 0.0 || h.empty()) return h;
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<double> kernel(2 * radius + 1);
  for (int k = -radius; k <= radius; ++k) kernel[k + radius] = std::exp(-0.5 * k * k / (sigma * sigma));
  const int n = static_cast<int>(h.size());
  std::vector<double> out(h.size(), 0.0);
  for (int b = 0; b < n; ++b) {
    if (h[b] == 0.0) continue;
    for (int k = -radius; k <= radius; ++k) {
      int j = b + k;
      if (circular)
        j = (j % n + n) % n;
      else if (j < 0 || j >= n)
        continue;
      out[j] += h[b] * kernel[k + radius];
    }
  }
  return out;
}

// The highest local maxima of `c`, at least `separation` bins apart, with a parabolic
// sub-bin position.
std::vector<double> peaks(const std::vector<double> &c, int count, int separation, bool circular) {
  const int n = static_cast<int>(c.size());
  auto at = [&](int i) { return circular ? c[(i % n + n) % n] : c[std::clamp(i, 0, n - 1)]; };
  std::vector<int> maxima;
  for (int i = 0; i < n; ++i)
    if (c[i] > 0.0 && c[i] >= at(i - 1) && c[i] > at(i + 1)) maxima.push_back(i);
  std::sort(maxima.begin(), maxima.end(), [&](int a, int b) { return c[a] > c[b]; });
  std::vector<int> kept;
  for (int i : maxima) {
    if (static_cast<int>(kept.size()) >= count) break;
    const bool apart = std::all_of(kept.begin(), kept.end(), [&](int k) {
      const int d = std::abs(i - k);
      return (circular ? std::min(d, n - d) : d) >= separation;
    });
    if (apart) kept.push_back(i);
  }
  std::vector<double> positions;
  for (int i : kept) {
    const double left = at(i - 1), middle = c[i], right = at(i + 1);
    const double curvature = left - 2.0 * middle + right;
    double position = i + (curvature < 0.0 ? 0.5 * (left - right) / curvature : 0.0);
    if (circular) position = std::fmod(position + n, static_cast<double>(n));  // within [0, n)
    positions.push_back(position);
  }
  return positions;
}

// Offsets d (m, within +-max_offset) at which the source projections, moved by d, best
// overlap the target's: the translation along `normal`.
std::vector<double> normalOffsets(const std::vector<Eigen::Vector2d> &source,
                                  const std::vector<Eigen::Vector2d> &target, const Eigen::Vector2d &normal,
                                  const DirectionHistogramParams &params) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto *points : {&source, &target})
    for (const Eigen::Vector2d &p : *points) {
      lo = std::min(lo, normal.dot(p));
      hi = std::max(hi, normal.dot(p));
    }
  const int shifts = static_cast<int>(std::ceil(params.max_offset / params.offset_bin));
  lo -= (shifts + 1) * params.offset_bin;
  const int bins = static_cast<int>((hi - lo) / params.offset_bin) + shifts + 3;
  auto histogram = [&](const std::vector<Eigen::Vector2d> &points) {
    std::vector<double> h(bins, 0.0);
    for (const Eigen::Vector2d &p : points) {  // linear interpolation between the two nearest bins
      const double x = (normal.dot(p) - lo) / params.offset_bin;
      const int b = static_cast<int>(x);
      if (b < 0 || b + 1 >= bins) continue;
      h[b] += b + 1 - x;
      h[b + 1] += x - b;
    }
    return smooth(h, 1.0, false);
  };
  const std::vector<double> hs = histogram(source), ht = histogram(target);
  // The histograms are padded by `shifts` bins below (lo) and above (bins): no shift leaves them.
  std::vector<double> correlation(2 * shifts + 1, 0.0);
  const double floor = 1e-3 * *std::max_element(hs.begin(), hs.end());
  for (int b = shifts; b + shifts < bins; ++b) {
    if (hs[b] <= floor) continue;
    for (int d = -shifts; d <= shifts; ++d) correlation[d + shifts] += hs[b] * ht[b + d];
  }
  std::vector<double> offsets;
  for (double position : peaks(correlation, params.offsets, 3, false))
    offsets.push_back((position - shifts) * params.offset_bin);
  return offsets;
}

std::vector<Eigen::Vector2d> vertices(const std::vector<EqualizedContour> &contours) {
  std::vector<Eigen::Vector2d> points;
  for (const EqualizedContour &contour : contours)
    for (const Complex &v : contour.vertices) points.push_back(toEigen(v));
  return points;
}

}  // namespace

bool DirectionHistogramParams::validate(std::string *why) const {
  if (chord_elements < 1) return invalid(why, "direction_histogram.chord_elements must be >= 1");
  if (angle_bins < 8) return invalid(why, "direction_histogram.angle_bins must be >= 8");
  if (!(angle_smoothing >= 0.0)) return invalid(why, "direction_histogram.angle_smoothing must be >= 0");
  if (rotations < 1 || offsets < 1) return invalid(why, "direction_histogram.rotations and offsets must be >= 1");
  if (!(offset_bin > 0.0) || !(max_offset > 0.0)) return invalid(why, "direction_histogram offsets must be > 0");
  if (!(min_direction_separation > 0.0 && min_direction_separation <= M_PI_2))
    return invalid(why, "direction_histogram.min_direction_separation must be in (0, pi/2]");
  return true;
}

std::vector<double> angleHistogram(const std::vector<EqualizedContour> &contours,
                                   const DirectionHistogramParams &params) {
  const int bins = params.angle_bins;
  std::vector<double> h(bins, 0.0);
  const auto chord = static_cast<std::size_t>(params.chord_elements);
  for (const EqualizedContour &contour : contours)
    for (std::size_t r = 0; r + chord < contour.vertices.size(); ++r) {
      const Complex d = contour.vertices[r + chord] - contour.vertices[r];
      const double angle = approximateAtan2(d.imag(), d.real());
      const int b = static_cast<int>(std::floor((angle + M_PI) / (2.0 * M_PI) * bins));
      h[(b % bins + bins) % bins] += 1.0;
    }
  return smooth(h, params.angle_smoothing, true);
}

std::vector<Eigen::Matrix3d> directionHypotheses(const ContourFeatures &source, const ContourFeatures &target,
                                                 const DirectionHistogramParams &params, const Eigen::Matrix3d *guess) {
  std::vector<Eigen::Matrix3d> hypotheses;
  if (!params.validate()) return hypotheses;
  const std::vector<double> hs = angleHistogram(source.contours, params), ht = angleHistogram(target.contours, params);
  const int n = params.angle_bins;
  const double bin = 2.0 * M_PI / n;

  // 1. Rotation: target directions are source directions turned by the robot's turn.
  std::vector<double> twice(ht);  // the target histogram twice over: shifts without wrapping
  twice.insert(twice.end(), ht.begin(), ht.end());
  std::vector<double> correlation(n, 0.0);
  const double floor = 1e-3 * *std::max_element(hs.begin(), hs.end());
  for (int b = 0; b < n; ++b) {  // directions the source hardly has add nothing: skipped
    if (hs[b] <= floor) continue;
    for (int k = 0; k < n; ++k) correlation[k] += hs[b] * twice[b + k];
  }
  const std::vector<double> turns = peaks(correlation, params.rotations, static_cast<int>(std::ceil(0.1 / bin)), true);
  if (turns.empty()) return hypotheses;

  // 2. The target's wall directions: the folded histogram's peak and the strongest one far
  // enough from it, if it holds a fair share of the contour (a door frame across a corridor
  // is enough; noise around the first peak is not).
  constexpr double kMinShareOfFirst = 0.02;
  const int half = n / 2;
  std::vector<double> folded(half, 0.0);
  for (int b = 0; b < n; ++b) folded[b % half] += ht[b];
  const std::vector<double> walls = peaks(folded, half, 1, true);
  if (walls.empty()) return hypotheses;
  auto height = [&](double wall) { return folded[static_cast<int>(std::lround(wall)) % half]; };
  auto angleOf = [&](double wall) { return -M_PI + wall * bin; };
  std::vector<Eigen::Vector2d> normals;
  for (double wall : walls) {
    if (!normals.empty()) {
      if (std::abs(std::remainder(angleOf(wall) - angleOf(walls.front()), M_PI)) < params.min_direction_separation)
        continue;
      if (height(wall) < kMinShareOfFirst * height(walls.front())) break;
    }
    normals.emplace_back(-std::sin(angleOf(wall)), std::cos(angleOf(wall)));
    if (normals.size() == 2) break;
  }

  // 3. Translation along each wall normal, per rotation.
  const Eigen::Vector2d start = guess ? Eigen::Vector2d(guess->topRightCorner<2, 1>()) : Eigen::Vector2d::Zero();
  const std::vector<Eigen::Vector2d> source_points = vertices(source.contours),
                                     target_points = vertices(target.contours);
  std::vector<Eigen::Vector2d> turned(source_points.size());
  for (double turn : turns) {
    const double yaw = turn * bin;
    const Eigen::Rotation2Dd rotation(yaw);
    for (std::size_t i = 0; i < source_points.size(); ++i) turned[i] = rotation * source_points[i];
    const std::vector<double> first = normalOffsets(turned, target_points, normals[0], params);
    const std::vector<double> second =
        normals.size() > 1 ? normalOffsets(turned, target_points, normals[1], params) : std::vector<double>{};
    for (double d1 : first) {
      if (second.empty()) {  // one wall direction: along it, keep the guess
        const Eigen::Vector2d t = start + normals[0] * (d1 - normals[0].dot(start));
        hypotheses.push_back(rigidTransform(t.x(), t.y(), yaw));
        continue;
      }
      for (double d2 : second) {
        Eigen::Matrix2d across;
        across << normals[0].transpose(), normals[1].transpose();
        const Eigen::Vector2d t = across.inverse() * Eigen::Vector2d(d1, d2);
        hypotheses.push_back(rigidTransform(t.x(), t.y(), yaw));
      }
    }
  }
  return hypotheses;
}

}  // namespace contour_reg
