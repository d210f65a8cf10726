// Per-stage and end-to-end cost of the contour pipeline, and PCL's ICP, NDT2D and NDT on
// the same scan pairs, at 360, 720 and 1081 beams.
#include <cstdint>
#include <random>

#include <benchmark/benchmark.h>
#include <pcl/console/print.h>

#include "allocation_counter.h"
#include "contour_reg/contour_registration.h"
#include "contour_reg/core/contour.h"
#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/correspondence.h"
#include "contour_reg/core/deskew.h"
#include "contour_reg/core/direction_histogram.h"
#include "contour_reg/core/registration.h"
#include "contour_reg/odometry/scan_matcher.h"
#include "scenes.h"

namespace contour_reg::bench {
namespace {

const ContourParams kParams;

void BM_ContourCode(benchmark::State &state) {  // stage A: polar code and segmentation (eqs. 1-2)
  const ScanPair pair = scanPair(int(state.range(0)));
  for (auto _ : state) {
    auto segments = splitIntoSegments(polarCode(pair.source), kParams.segmentation);
    benchmark::DoNotOptimize(segments);
  }
}

// Deskewing (deskew.h) in place of stage A's polar code: every beam moved by the motion over
// the sweep, for a scan taken at 10 Hz while driving 1 m/s and beginning to turn, as 50 Hz
// wheel odometry gives it: a new twist every 20 ms, the turn rate rising by 0.25 rad/s each.
void BM_Deskew(benchmark::State &state) {
  ScanPair pair = scanPair(int(state.range(0)));
  pair.source.time_increment = 0.1 * pair.source.angle_increment / (2.0 * M_PI);
  SweepMotion motion(Twist2D{1.0, 0.0, 0.0});
  for (int i = 1; i < 5; ++i) motion.changes.push_back({0.02 * i, Twist2D{1.0, 0.0, 0.25 * i}});
  ComplexSequence code;
  for (auto _ : state) {
    deskewedPolarCode(pair.source, motion, code);
    benchmark::DoNotOptimize(code.data());
  }
}

void BM_Equalization(benchmark::State &state) {  // stage B
  const ScanPair pair = scanPair(int(state.range(0)));
  const auto segments = splitIntoSegments(polarCode(pair.source), kParams.segmentation);
  for (auto _ : state) {
    auto contours = equalizeSegments(segments, kParams.equalization);
    benchmark::DoNotOptimize(contours);
  }
}

void BM_MatchedFilter(benchmark::State &state) {  // stage C: corner filter bank (eqs. 12-13)
  const ScanPair pair = scanPair(int(state.range(0)));
  const auto contours =
      equalizeSegments(splitIntoSegments(polarCode(pair.source), kParams.segmentation), kParams.equalization);
  for (auto _ : state)
    for (const EqualizedContour &c : contours) benchmark::DoNotOptimize(filterCorners(c, kParams.corner_filter));
}

void BM_SpecialPoints(benchmark::State &state) {  // stage C: maxima, vertex refinement, fragments
  const ScanPair pair = scanPair(int(state.range(0)));
  const auto segments = splitIntoSegments(polarCode(pair.source), kParams.segmentation);
  const auto contours = equalizeSegments(segments, kParams.equalization);
  std::vector<CornerResponse> responses;
  for (const EqualizedContour &c : contours) responses.push_back(filterCorners(c, kParams.corner_filter));
  for (auto _ : state)
    for (std::size_t k = 0; k < contours.size(); ++k)
      benchmark::DoNotOptimize(findSpecialPoints(segments[k].points, contours[k], responses[k], kParams.corner_filter,
                                                 kParams.special_points));
}

void BM_Features(benchmark::State &state) {  // stages A-C of one scan
  const ScanPair pair = scanPair(int(state.range(0)));
  ContourFeatures features;
  const ComplexSequence code = polarCode(pair.source);
  extractContourFeatures(code, kParams, features);  // warm: the buffers reach their size
  const std::size_t allocations = allocationCount();
  for (auto _ : state) {
    extractContourFeatures(code, kParams, features);
    benchmark::DoNotOptimize(features.special_points.data());
  }
  state.counters["special_points"] = double(features.special_points.size());
  state.counters["allocations"] = double(allocationCount() - allocations) / double(state.iterations());
}

void BM_Correspondence(benchmark::State &state) {  // stage D (eq. 14)
  const ScanPair pair = scanPair(int(state.range(0)));
  const ContourFeatures a = extractContourFeatures(pair.target, kParams),
                        b = extractContourFeatures(pair.source, kParams);
  const CorrespondenceParams params;
  const std::size_t allocations = allocationCount();
  for (auto _ : state) benchmark::DoNotOptimize(findCorrespondences(b.special_points, a.special_points, params));
  state.counters["allocations"] = double(allocationCount() - allocations) / double(state.iterations());
}

void BM_RansacAndRefinement(benchmark::State &state) {  // stages D-F + refinement, features given
  const ScanPair pair = scanPair(int(state.range(0)));
  const ContourFeatures a = extractContourFeatures(pair.target, kParams),
                        b = extractContourFeatures(pair.source, kParams);
  RegistrationParams params;
  params.refinement.enabled = state.range(1) != 0;
  std::mt19937 rng;
  const std::size_t allocations = allocationCount();
  RegistrationResult result;
  for (auto _ : state) {
    rng.seed(42);
    result = registerContours(b, a, params, rng);
    benchmark::DoNotOptimize(result);
  }
  state.counters["allocations"] = double(allocationCount() - allocations) / double(state.iterations());
  state.counters["inliers"] = double(result.inliers.size());
  state.counters["from_local_fallback"] = result.from_local_fallback;
}

void BM_DirectionHypotheses(benchmark::State &state) {  // the fallback's corner-free motion hypotheses
  const ScanPair pair = scanPair(int(state.range(0)));
  const ContourFeatures a = extractContourFeatures(pair.target, kParams),
                        b = extractContourFeatures(pair.source, kParams);
  const DirectionHistogramParams params;
  std::size_t count = 0;
  for (auto _ : state) {
    const auto hypotheses = directionHypotheses(b, a, params);
    count = hypotheses.size();
    benchmark::DoNotOptimize(hypotheses.data());
  }
  state.counters["hypotheses"] = double(count);
}

void BM_LocalFallback(benchmark::State &state) {  // registration when the corners cannot decide
  const ScanPair pair = scanPair(int(state.range(0)));
  const ContourFeatures a = extractContourFeatures(pair.target, kParams),
                        b = extractContourFeatures(pair.source, kParams);
  RegistrationParams params;
  params.min_special_points = 1 << 20;  // no scan has that many: the corners stand aside
  std::mt19937 rng;
  RegistrationResult result;
  for (auto _ : state) {
    rng.seed(42);
    result = registerContours(b, a, params, rng);
    benchmark::DoNotOptimize(result.transform.data());
  }
  state.counters["converged"] = result.converged;
  state.counters["error_mm"] =
      1000.0 * std::hypot(result.transform(0, 2) - pair.truth.x(), result.transform(1, 2) - pair.truth.y());
}

// A matcher on a pair whose clouds are new every iteration (nothing cached): both scans'
// features are computed, as for a single pair.
void runPair(benchmark::State &state, const std::string &method) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const ScanPair pair = scanPair(int(state.range(0)));
  auto matcher = odometry::makeScanMatcher(method);
  // Copies at fresh addresses each iteration defeat the per-scan cache.
  std::vector<LaserScan> targets(2, pair.target), sources(2, pair.source);
  std::size_t k = 0, converged = 0, iterations = 0;
  double error = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    targets[k % 2].stamp = sources[k % 2].stamp = double(k);  // a new scan for the cache
    state.ResumeTiming();
    const odometry::MatchResult r = matcher->match(targets[k % 2], sources[k % 2]);
    converged += r.converged;
    error = std::hypot(r.transform(0, 2) - pair.truth.x(), r.transform(1, 2) - pair.truth.y());
    ++k;
    ++iterations;
  }
  state.counters["converged"] = double(converged) / double(std::max<std::size_t>(1, iterations));
  state.counters["error_mm"] = 1000.0 * error;
}

void BM_PairContour(benchmark::State &state) { runPair(state, "contour"); }
void BM_PairContourIcp(benchmark::State &state) { runPair(state, "contour+icp"); }
void BM_PairIcp(benchmark::State &state) { runPair(state, "icp"); }
void BM_PairNdt2d(benchmark::State &state) { runPair(state, "ndt2d"); }
void BM_PairNdt(benchmark::State &state) { runPair(state, "ndt"); }

// How many extractions of stages A-C have run in this process so far (each takes the next number).
std::uint64_t extractionsSoFar() { return extractContourFeatures(ComplexSequence{}, kParams).extraction - 1; }

// Odometry's steady state: the previous source is the new target, its features reused.
void BM_OdometryStepContour(benchmark::State &state) {
  const ScanPair pair = scanPair(int(state.range(0)));
  auto matcher = odometry::makeScanMatcher("contour");
  std::vector<LaserScan> scans{pair.target, pair.source};
  const std::uint64_t extractions = extractionsSoFar();
  std::size_t k = 0, allocations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    LaserScan &next = scans[(k + 1) % 2];
    next.stamp = double(k + 1);
    const std::size_t before = allocationCount();
    state.ResumeTiming();
    benchmark::DoNotOptimize(matcher->match(scans[k % 2], next));
    state.PauseTiming();
    allocations += allocationCount() - before;
    state.ResumeTiming();
    ++k;
  }
  state.counters["allocations"] = double(allocations) / double(state.iterations());
  // One per step: the new scan's; the target's features come from the step before (the
  // first step reads both scans, and the count itself is one more).
  state.counters["extractions"] = double(extractionsSoFar() - extractions - 2) / double(state.iterations());
}

// The same steady state on the core API: each new scan's features are extracted into the
// buffers of the scan before last, and registered against the previous scan's.
void BM_OdometryStepCore(benchmark::State &state) {
  const ScanPair pair = scanPair(int(state.range(0)));
  const ComplexSequence codes[2] = {polarCode(pair.target), polarCode(pair.source)};
  ContourFeatures features[2];
  const RegistrationParams params;
  std::mt19937 rng;
  RegistrationResult result;
  RegistrationBuffers buffers;
  extractContourFeatures(codes[0], kParams, features[0]);
  std::size_t k = 0, allocations = 0;
  for (auto _ : state) {
    const std::size_t before = allocationCount();
    ContourFeatures &target = features[k % 2], &source = features[(k + 1) % 2];
    extractContourFeatures(codes[(k + 1) % 2], kParams, source);
    rng.seed(42);
    registerContours(source, target, params, rng, nullptr, buffers, result);
    benchmark::DoNotOptimize(result.transform.data());
    if (k >= 2) allocations += allocationCount() - before;  // the first two steps size the buffers
    ++k;
  }
  state.counters["allocations"] = double(allocations) / double(std::max<std::size_t>(1, k - 2));
}

#define BEAMS ->Arg(360)->Arg(720)->Arg(1081)->Unit(benchmark::kMicrosecond)
BENCHMARK(BM_ContourCode) BEAMS;
BENCHMARK(BM_Deskew) BEAMS;
BENCHMARK(BM_Equalization) BEAMS;
BENCHMARK(BM_MatchedFilter) BEAMS;
BENCHMARK(BM_SpecialPoints) BEAMS;
BENCHMARK(BM_Features) BEAMS;
BENCHMARK(BM_Correspondence) BEAMS;
BENCHMARK(BM_RansacAndRefinement)->ArgsProduct({{360, 720, 1081}, {0, 1}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DirectionHypotheses) BEAMS;
BENCHMARK(BM_LocalFallback) BEAMS;
BENCHMARK(BM_PairContour) BEAMS;
BENCHMARK(BM_OdometryStepContour) BEAMS;
BENCHMARK(BM_OdometryStepCore) BEAMS;
BENCHMARK(BM_PairContourIcp) BEAMS;
BENCHMARK(BM_PairIcp) BEAMS;
BENCHMARK(BM_PairNdt2d) BEAMS;
BENCHMARK(BM_PairNdt) BEAMS;

}  // namespace
}  // namespace contour_reg::bench

BENCHMARK_MAIN();
