#include "contour_reg/core/contour_features.h"

#include <algorithm>
#include <atomic>

namespace contour_reg {

bool ContourParams::validate(std::string *why) const {
  return segmentation.validate(why) && equalization.validate(why) && corner_filter.validate(why) &&
         special_points.validate(why);
}

void ContourFeatures::clear() {
  buffers.segments.clear(segments);
  buffers.contours.clear(contours);
  buffers.responses.clear(responses);
  buffers.special_points.clear(special_points);
  returns.clear();
  extraction = 0;
}

namespace {

// Stages A-C with the segmentation given apart from the other settings (a scan's own range
// limits tighten it).
void extract(const ComplexSequence &polar_code, const SegmentationParams &segmentation, const ContourParams &params,
             ContourFeatures &features) {
  static std::atomic<std::uint64_t> extractions{0};
  features.extraction = ++extractions;
  ContourFeatures::Buffers &buffers = features.buffers;
  splitIntoSegments(polar_code, segmentation, features.segments, buffers.segments);  // stage A
  usableReturns(polar_code, segmentation, features.returns);
  equalizeSegments(features.segments, params.equalization, features.contours, buffers.contours, buffers.arc);  // B
  buffers.bank.build(params.corner_filter);  // stage C
  buffers.responses.resize(features.responses, features.contours.size());
  buffers.special_points.clear(features.special_points);
  for (std::size_t k = 0; k < features.contours.size(); ++k) {
    filterCorners(features.contours[k], buffers.bank, features.responses[k]);
    findSpecialPoints(features.segments[k].points, features.contours[k], features.responses[k], params.corner_filter,
                      params.special_points, features.special_points, buffers.special_points, buffers.arc);
  }
}

}  // namespace

void extractContourFeatures(const ComplexSequence &polar_code, const ContourParams &params, ContourFeatures &features) {
  extract(polar_code, params.segmentation, params, features);
}

ContourFeatures extractContourFeatures(const ComplexSequence &polar_code, const ContourParams &params) {
  ContourFeatures features;
  extractContourFeatures(polar_code, params, features);
  return features;
}

ContourFeatures extractContourFeatures(const LaserScan &scan, const ContourParams &params) {
  ContourFeatures features;
  extractContourFeatures(scan, params, features);
  return features;
}

void extractContourFeatures(const LaserScan &scan, const ContourParams &params, ContourFeatures &features) {
  SegmentationParams segmentation = params.segmentation;  // tightened by the scan's own range limits
  segmentation.range_min = std::max(segmentation.range_min, scan.range_min);
  if (scan.range_max > 0.0)
    segmentation.range_max =
        segmentation.range_max > 0.0 ? std::min(segmentation.range_max, scan.range_max) : scan.range_max;
  ComplexSequence &code = features.buffers.polar_code;  // stages A-C read it, never write it
  polarCode(scan, code);
  extract(code, segmentation, params, features);
}

}  // namespace contour_reg
