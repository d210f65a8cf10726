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
  extraction = 0;
}

void extractContourFeatures(const ComplexSequence &polar_code, const ContourParams &params,
                            ContourFeatures &features) {
  static std::atomic<std::uint64_t> extractions{0};
  features.extraction = ++extractions;
  ContourFeatures::Buffers &buffers = features.buffers;
  splitIntoSegments(polar_code, params.segmentation, features.segments, buffers.segments);           // stage A
  equalizeSegments(features.segments, params.equalization, features.contours, buffers.contours);     // stage B
  buffers.bank.build(params.corner_filter);                                                          // stage C
  buffers.responses.resize(features.responses, features.contours.size());
  buffers.special_points.clear(features.special_points);
  for (std::size_t k = 0; k < features.contours.size(); ++k) {
    filterCorners(features.contours[k], buffers.bank, features.responses[k]);
    findSpecialPoints(features.segments[k].points, features.contours[k], features.responses[k], params.corner_filter,
                      params.special_points, features.special_points, buffers.special_points, buffers.arc);
  }
}

ContourFeatures extractContourFeatures(const ComplexSequence &polar_code, const ContourParams &params) {
  ContourFeatures features;
  extractContourFeatures(polar_code, params, features);
  return features;
}

namespace {

// The segmentation's range limits tightened by the scan's own.
ContourParams withScanLimits(const LaserScan &scan, const ContourParams &params) {
  ContourParams tightened = params;
  SegmentationParams &seg = tightened.segmentation;
  seg.range_min = std::max(seg.range_min, scan.range_min);
  if (scan.range_max > 0.0) seg.range_max = seg.range_max > 0.0 ? std::min(seg.range_max, scan.range_max)
                                                                : scan.range_max;
  return tightened;
}

}  // namespace

ContourFeatures extractContourFeatures(const LaserScan &scan, const ContourParams &params) {
  ContourFeatures features;
  extractContourFeatures(scan, params, features);
  return features;
}

void extractContourFeatures(const LaserScan &scan, const ContourParams &params, ContourFeatures &features) {
  ComplexSequence code = std::move(features.buffers.polar_code);
  polarCode(scan, code);
  extractContourFeatures(code, withScanLimits(scan, params), features);
  features.buffers.polar_code = std::move(code);
}

}  // namespace contour_reg
