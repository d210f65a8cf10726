#pragma once
/// @file matched_filter.h
/// Stage C: the matched filter for the "corner" reference form (paper eqs. 12-13).
///
/// A corner of angle dphi is two straight arms of s elementary vectors. The
/// reference T is s unit vectors along the first arm followed by s unit
/// vectors turned by tau = pi - dphi (left turn) or -tau (right turn). With
/// G(n) the 2s equalized vectors of the window whose middle vertex is n, the
/// normalized output is
///
///     eta(n) = |(G(n), T)| / (|G(n)| |T|)        in [0, 1],     (eq. 12)
///
/// 1 exactly when the window is that corner at any orientation and scale. A
/// straight line partly matches a wide corner, so the output of the filter
/// matched to a straight piece of the same length is subtracted (eq. 13):
///
///     c(n) = max(0, eta_corner(n) - eta_line(n)).
///
/// T is constant along each arm, so (G, T) = A1 + conj(t2) A2 with A1, A2 the
/// sums of the window's two arms; prefix sums make every window O(1) and a
/// bank of angles cheap.

#include <cstdint>
#include <string>
#include <vector>

#include "contour_reg/core/equalization.h"

namespace contour_reg {

struct CornerFilterParams {
  int arm_elements = 5;  ///< s: elements per arm; the window is 2s elements
  /// The bank of reference corner angles dphi in degrees, each used with both turn directions.
  std::vector<double> corner_angles_deg = {60.0, 75.0, 90.0, 105.0, 120.0, 135.0};

  bool validate(std::string *why = nullptr) const;
};

/// Filter output along one equalized contour, indexed by vertex (the window's middle).
struct CornerResponse {
  std::vector<double> response;      ///< c(n) of eq. (13); 0 where the window does not fit
  std::vector<double> corner_angle;  ///< rad, angle of the bank element that matched best
  std::vector<std::int8_t> turn;     ///< +1 left turn, -1 right turn, 0 none
};

/// Runs the bank of corner filters along one equalized contour.
CornerResponse filterCorners(const EqualizedContour &contour, const CornerFilterParams &params);

/// The bank of reference corners, prepared once for the contours of a scan: per bank element,
/// the conjugate of its second arm's unit vector, conj(t2).
struct CornerBank {
  struct Element {
    Complex conj_arm2;
    double angle;      ///< rad, the corner angle dphi
    std::int8_t turn;  ///< +1 left, -1 right
  };
  std::vector<Element> elements;
  int arm_elements = 0;  ///< s
  /// cos^2 of half the bank's smallest turn (pi - the largest corner angle), less a margin far
  /// above rounding. A window whose arms turn by less than that fits the straight line better
  /// than any bank element: the filter answers it before searching the bank.
  double straight_cos2 = 1.0;

  /// Fills the bank for `params`, reusing its buffer.
  void build(const CornerFilterParams &params);
};

/// The same as filterCorners with a prepared bank, into `out`, reusing its buffers.
void filterCorners(const EqualizedContour &contour, const CornerBank &bank, CornerResponse &out);

/// Normalized output of one reference form T on one window G, eq. (12): |(G,T)| / (|G||T|).
/// Exposed for tests and for other reference forms.
double matchedFilterOutput(const ComplexSequence &window, const ComplexSequence &reference);

/// The reference corner: s unit vectors, then s unit vectors turned by turn * (pi - angle).
ComplexSequence referenceCorner(int arm_elements, double corner_angle, int turn);

}  // namespace contour_reg
