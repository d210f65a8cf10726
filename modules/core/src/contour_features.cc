#include "contour_reg/core/contour_features.h"

#include <algorithm>

namespace contour_reg {

bool ContourParams::validate(std::string *why) const {
  return segmentation.validate(why) && equalization.validate(why) && corner_filter.validate(why) &&
         special_points.validate(why);
}

void ContourFeatures::clear() {
  segments.clear();
  contours.clear();
  responses.clear();
  special_points.clear();
}

void extractContourFeatures(const ComplexSequence &polar_code, const ContourParams &params,
                            ContourFeatures &features) {
  features.clear();
  features.segments = splitIntoSegments(polar_code, params.segmentation);             // stage A
  features.contours = equalizeSegments(features.segments, params.equalization);       // stage B
  features.responses.reserve(features.contours.size());
  for (std::size_t k = 0; k < features.contours.size(); ++k) {
    const EqualizedContour &contour = features.contours[k];
    features.responses.push_back(filterCorners(contour, params.corner_filter));      // stage C
    std::vector<SpecialPoint> found =
        findSpecialPoints(features.segments[k].points, contour, features.responses.back(),
                          params.corner_filter, params.special_points);
    features.special_points.insert(features.special_points.end(),
                                   std::make_move_iterator(found.begin()),
                                   std::make_move_iterator(found.end()));
  }
}

ContourFeatures extractContourFeatures(const ComplexSequence &polar_code, const ContourParams &params) {
  ContourFeatures features;
  extractContourFeatures(polar_code, params, features);
  return features;
}

ContourFeatures extractContourFeatures(const LaserScan &scan, const ContourParams &params) {
  ContourParams tightened = params;
  SegmentationParams &seg = tightened.segmentation;
  seg.range_min = std::max(seg.range_min, scan.range_min);
  if (scan.range_max > 0.0) seg.range_max = seg.range_max > 0.0 ? std::min(seg.range_max, scan.range_max)
                                                                : scan.range_max;
  return extractContourFeatures(polarCode(scan), tightened);
}

}  // namespace contour_reg
