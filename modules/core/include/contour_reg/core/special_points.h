#pragma once
/// @file special_points.h
/// Stage C, continued: special points are the local maxima of the corner
/// response above a threshold (paper, end of section II-C). Each carries what
/// the next stages need: its vertex, the corner's angle and orientation, and
/// its local fragment of 2L elementary vectors (section II-D, eq. 14).

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/core/contour.h"
#include "contour_reg/core/equalization.h"
#include "contour_reg/core/matched_filter.h"

namespace contour_reg {

struct SpecialPointParams {
  double threshold = 0.08;       ///< minimum corner response c(n)
  int suppression_radius = 0;    ///< elements either side for non-maximum suppression (0: the arm length s)
  int fragment_half_length = 8;  ///< L: elements taken on each side of the vertex for matching
  bool refine_vertex = true;     ///< intersect lines fitted to the raw points of both arms
  double max_arm_length = 1.0;   ///< m, how far a fitted arm may grow while it stays straight
  double max_arm_rms = 0.015;    ///< m, an arm stops growing when its fit residual exceeds this

  bool validate(std::string *why = nullptr) const;
};

/// A corner found on a contour.
struct SpecialPoint {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< m, corner vertex in the scan frame
  double corner_angle = 0.0;                           ///< rad, angle between the two arms (pi: straight)
  double orientation = 0.0;  ///< rad, direction of the bisector, from the vertex into the opening
  double response = 0.0;     ///< c(n), eq. (13)
  std::int8_t turn = 0;      ///< +1 left, -1 right, along the contour (beam order)
  int contour = -1;          ///< index of the equalized contour (= segment)
  int vertex = -1;           ///< vertex index on that contour
  double sub_element = 0.0;  ///< offset of the response peak from `vertex`, in elements
  /// The 2L elementary vectors around the vertex, e(vertex - L .. vertex + L - 1),
  /// zero where the contour ends (eq. 14 compares these).
  ComplexSequence fragment;
};

/// Finds the special points of one equalized contour.
/// `raw_points` is the raw segment the contour was equalized from (for vertex refinement).
std::vector<SpecialPoint> findSpecialPoints(const ComplexSequence &raw_points, const EqualizedContour &contour,
                                            const CornerResponse &response, const CornerFilterParams &filter,
                                            const SpecialPointParams &params);

/// The same, appended to `points`, reusing the elements kept in `spare` and `arc` (the raw
/// points' arc lengths) as buffers.
void findSpecialPoints(const ComplexSequence &raw_points, const EqualizedContour &contour,
                       const CornerResponse &response, const CornerFilterParams &filter,
                       const SpecialPointParams &params, std::vector<SpecialPoint> &points,
                       SpareElements<SpecialPoint> &spare, std::vector<double> &arc);

}  // namespace contour_reg
