#pragma once
/// @file equalization.h
/// Stage B: equalization of a contour segment (paper eqs. 3-11).
///
/// Contour-analysis filters assume elementary vectors of one length. The paper
/// cuts the contour into p pieces of equal length e = (1/p) sum |y(n)| (eq. 3)
/// and joins the ends of the pieces: the new elementary vector e(r) is the
/// chord from arc length r*e to (r+1)*e along the raw polyline. Eqs. 4-11 walk
/// the raw vectors (the rest of the previous one, whole ones passed over, the
/// used part of the last one); here that walk is a resampling at equal arc
/// length followed by differences.
///
/// Two modes: the paper's fixed count p (e changes from scan to scan), and a
/// fixed metric step e, so a filter window covers the same length in every scan.

#include <string>
#include <vector>

#include "contour_reg/core/contour.h"
#include "contour_reg/core/types.h"

namespace contour_reg {

enum class EqualizationMode {
  kFixedCount,  ///< the paper: p elements over the scan's contour, e = total length / p
  kFixedStep,   ///< e metres per element in every segment
};

struct EqualizationParams {
  EqualizationMode mode = EqualizationMode::kFixedStep;
  double step = 0.05;  ///< m, element arc length in kFixedStep mode (kLeastStep-kLongestStep)
  int count = 400;     ///< p, elements over the whole scan in kFixedCount mode (1-kMostElements)

  /// m: finer than any LIDAR's range noise; a scan's 100 m of contour in 10^5 elements.
  static constexpr double kLeastStep = 0.001;
  /// m: an element longer than a room's wall leaves no corner to find.
  static constexpr double kLongestStep = 10.0;
  static constexpr int kMostElements = 100000;

  bool validate(std::string *why = nullptr) const;
};

/// An equalized segment: vertices at equal arc-length steps along the raw polyline.
struct EqualizedContour {
  ComplexSequence vertices;  ///< Q(0..p); elementary vector e(r) = Q(r+1) - Q(r)
  /// m, for each vertex: the length of the raw vector it lies on, how far apart the two raw
  /// points it is interpolated between are (a sparse stretch: a distant or oblique wall).
  std::vector<double> spacing;
  double step = 0.0;  ///< m of raw arc length per element
  int segment = -1;   ///< index of the raw segment it came from

  std::size_t elementCount() const { return vertices.empty() ? 0 : vertices.size() - 1; }
  Complex element(std::size_t r) const { return vertices[r + 1] - vertices[r]; }
};

/// Cumulative arc length at each point of a polyline (0 at the first point).
std::vector<double> arcLengths(const ComplexSequence &points);

/// The same into `arc`, reusing its buffer.
void arcLengths(const ComplexSequence &points, std::vector<double> &arc);

/// Point at arc length s along the polyline (clamped to its ends).
/// `arc` must be arcLengths(points); `hint` speeds up increasing queries.
Complex pointAtArcLength(const ComplexSequence &points, const std::vector<double> &arc, double s,
                         std::size_t *hint = nullptr);

/// Resamples `points` into `count` elements of equal arc length (eqs. 3-11).
EqualizedContour equalizeByCount(const ComplexSequence &points, int count);

/// Resamples `points` into elements of arc length `step`; the remainder shorter
/// than one step at the end of the segment is dropped.
EqualizedContour equalizeByStep(const ComplexSequence &points, double step);

/// Elements of arc length `step` centred on the polyline: the remainder shorter than one step
/// is dropped half at each end, so the vertices do not depend on which way the points run.
/// The paper's elements (equalizeByStep) start at the first point and leave the whole
/// remainder at the last, at the same end of every contour of a scan (its segments run in
/// beam order): a registration that pairs such vertices turns its estimate a little one way,
/// a heading drift over a drive. The refinement (refinement.h) pairs centred ones. `arc` is
/// working memory.
void equalizeCentred(const ComplexSequence &points, double step, EqualizedContour &contour, std::vector<double> &arc);

/// Equalizes every segment of one scan with the chosen mode. In kFixedCount mode
/// e = (total length of all segments) / p, and each segment gets round(length / e)
/// elements (at least one), so a scan of one segment gets exactly p.
std::vector<EqualizedContour> equalizeSegments(const std::vector<ContourSegment> &segments,
                                               const EqualizationParams &params);

/// The same into `contours`, whose elements' buffers (and those kept in `spare`) are reused;
/// `arc` is working memory for each segment's arc lengths.
void equalizeSegments(const std::vector<ContourSegment> &segments, const EqualizationParams &params,
                      std::vector<EqualizedContour> &contours, SpareElements<EqualizedContour> &spare,
                      std::vector<double> &arc);

}  // namespace contour_reg
