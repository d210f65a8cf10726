#include "contour_reg/core/matched_filter.h"
#include "validation.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace contour_reg {

bool CornerFilterParams::validate(std::string *why) const {
  if (arm_elements < 2) return invalid(why, "corner_filter.arm_elements must be >= 2");
  if (corner_angles_deg.empty()) return invalid(why, "corner_filter.corner_angles_deg must not be empty");
  for (double a : corner_angles_deg)
    if (!(a > 0.0 && a < 180.0)) return invalid(why, "corner_filter.corner_angles_deg must lie in (0, 180)");
  return true;
}

void CornerBank::build(const CornerFilterParams &params) {
  elements.clear();
  arm_elements = params.arm_elements;
  double smallest_turn = M_PI;
  for (double degrees : params.corner_angles_deg) {
    const double angle = degrees * M_PI / 180.0;
    const double tau = M_PI - angle;  // the turn between the arms
    smallest_turn = std::min(smallest_turn, tau);
    for (std::int8_t turn : {std::int8_t{1}, std::int8_t{-1}})
      elements.push_back({std::polar(1.0, -turn * tau), angle, turn});
  }
  // 1e-3 rad of margin: the bank's outputs then fall short of the line's by far more than rounding.
  const double half = std::max(0.0, 0.5 * smallest_turn - 1e-3);
  straight_cos2 = std::cos(half) * std::cos(half);
}

ComplexSequence referenceCorner(int arm_elements, double corner_angle, int turn) {
  ComplexSequence reference(2 * static_cast<std::size_t>(arm_elements), Complex(1.0, 0.0));
  const Complex second_arm = std::polar(1.0, turn * (M_PI - corner_angle));
  for (int m = arm_elements; m < 2 * arm_elements; ++m) reference[m] = second_arm;
  return reference;
}

// Eq. (12): eta = |(G, T)| / (|G| |T|), with (A, B) = sum a(m) conj(b(m)).
double matchedFilterOutput(const ComplexSequence &window, const ComplexSequence &reference) {
  Complex product = 0.0;
  double norm_g = 0.0, norm_t = 0.0;
  for (std::size_t m = 0; m < window.size() && m < reference.size(); ++m) {
    product += window[m] * std::conj(reference[m]);
    norm_g += squaredMagnitude(window[m]);
    norm_t += squaredMagnitude(reference[m]);
  }
  if (norm_g <= 0.0 || norm_t <= 0.0) return 0.0;
  return magnitude(product) / std::sqrt(norm_g * norm_t);
}

CornerResponse filterCorners(const EqualizedContour &contour, const CornerFilterParams &params) {
  CornerBank bank;
  bank.build(params);
  CornerResponse out;
  filterCorners(contour, bank, out);
  return out;
}

void filterCorners(const EqualizedContour &contour, const CornerBank &bank, CornerResponse &out) {
  const std::size_t vertices = contour.vertices.size();
  out.response.assign(vertices, 0.0);
  out.corner_angle.assign(vertices, M_PI);
  out.turn.assign(vertices, 0);
  const std::size_t s = static_cast<std::size_t>(bank.arm_elements);
  if (s == 0 || vertices < 2 * s + 1) return;

  // |G(n)|^2, the energy of the window's 2s elements, slides along with the window.
  double energy = 0.0;
  for (std::size_t r = 0; r + 1 < 2 * s; ++r) energy += squaredMagnitude(contour.element(r));
  const double norm_t = std::sqrt(2.0 * static_cast<double>(s));  // |T|: 2s unit vectors
  for (std::size_t n = s; n + s < vertices; ++n) {
    energy += squaredMagnitude(contour.element(n + s - 1));              // enters the window
    if (n > s) energy -= squaredMagnitude(contour.element(n - s - 1));   // leaves it
    const Complex arm1 = contour.vertices[n] - contour.vertices[n - s];  // sum of the first arm's vectors
    const Complex arm2 = contour.vertices[n + s] - contour.vertices[n];  // sum of the second arm's vectors
    // The best bank element c has the largest |arm1 + c arm2|^2 = |arm1|^2 + |arm2|^2 +
    // 2 Re(c conj(arm1) arm2): the largest real part of c w, two products per element. Where
    // the arms turn by less than half the bank's smallest turn, the line (c = 1) has the
    // largest: no corner here, as along most of a wall.
    const Complex w = std::conj(arm1) * arm2;
    if (w.real() > 0.0 && w.real() * w.real() > bank.straight_cos2 * std::norm(w)) continue;
    const double norm_g = std::sqrt(std::max(0.0, energy));
    if (norm_g <= 0.0) continue;
    const double scale = 1.0 / (norm_g * norm_t);
    const double eta_line = magnitude(arm1 + arm2) * scale;  // eq. (13): straight-line output
    double best_real = -std::numeric_limits<double>::infinity();
    const CornerBank::Element *best_element = nullptr;
    for (const CornerBank::Element &element : bank.elements) {
      const double real = element.conj_arm2.real() * w.real() - element.conj_arm2.imag() * w.imag();
      if (real > best_real) {
        best_real = real;
        best_element = &element;
      }
    }
    if (best_element == nullptr) continue;
    const double best_square = squaredMagnitude(arm1 + best_element->conj_arm2 * arm2);
    const double eta_corner = std::sqrt(best_square) * scale;  // eq. (12)
    const double best = eta_corner - eta_line;
    if (best <= 0.0) continue;
    out.corner_angle[n] = best_element->angle;
    out.turn[n] = best_element->turn;
    out.response[n] = best;
  }
}

}  // namespace contour_reg
