// What users meet: the zero-guess scan pairs of the Kümmerle relations (at most 5 s apart) of
// the real logs in ../shared/datasets, registered end to end as a downstream PCL user would:
// a new registration object per pair, both clouds set, align(). The contour method and PCL's
// ICP (TransformationEstimation2D, 0.5 m correspondence distance) run on the same pairs in
// one process. Logs that are absent are skipped. Counters: median and p95 microseconds per
// pair, and the share of pairs recovered (within 10 cm and 2 deg of the relation).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <pcl/console/print.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/transformation_estimation_2D.h>

#include "contour_reg/contour_registration.h"
#include "contour_reg/core/contour.h"
#include "contour_reg/io/read_log.h"
#include "contour_reg/io/trajectory.h"

namespace contour_reg::bench {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

struct Pair {
  Cloud::Ptr target, source;  // beam order with NaN beams; ICP gets the finite points
  Cloud::Ptr finite_target, finite_source;
  io::Pose2D truth;
};

Cloud::Ptr toCloud(const LaserScan &scan, bool finite_only) {
  auto cloud = pcl::make_shared<Cloud>();
  for (const Complex &c : polarCode(scan))
    if (!finite_only || isFinite(c)) cloud->push_back(pcl::PointXYZ(float(c.real()), float(c.imag()), 0.f));
  cloud->is_dense = finite_only;
  return cloud;
}

std::vector<Pair> relationPairs(const std::string &log_path, const std::string &relations_path) {
  const io::ScanLog log = io::readLog(log_path);
  std::vector<Pair> pairs;
  for (const io::Relation &r : io::readRelations(relations_path)) {
    if (std::abs(r.t2 - r.t1) > 5.0) continue;
    const LaserScan &target = log.entries[io::nearestEntry(log, r.t1)].scan;
    const LaserScan &source = log.entries[io::nearestEntry(log, r.t2)].scan;
    pairs.push_back(
        {toCloud(target, false), toCloud(source, false), toCloud(target, true), toCloud(source, true), r.motion});
  }
  return pairs;
}

using Factory = pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>::Ptr (*)();

pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>::Ptr makeContour() {
  return pcl::make_shared<ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>>();
}

pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>::Ptr makeIcp() {
  auto icp = pcl::make_shared<pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>>();
  icp->setTransformationEstimation(
      pcl::make_shared<pcl::registration::TransformationEstimation2D<pcl::PointXYZ, pcl::PointXYZ>>());
  icp->setMaxCorrespondenceDistance(0.5);
  icp->setMaximumIterations(50);
  icp->setTransformationEpsilon(1e-8);
  return icp;
}

void runPairs(benchmark::State &state, const std::vector<Pair> &pairs, Factory make, bool beam_order) {
  std::vector<double> us;
  std::size_t recovered = 0;
  for (auto _ : state) {
    us.clear();
    recovered = 0;
    double total = 0.0;
    for (const Pair &pair : pairs) {
      Cloud aligned;
      const auto start = std::chrono::steady_clock::now();
      const auto registration = make();
      registration->setInputTarget(beam_order ? pair.target : pair.finite_target);
      registration->setInputSource(beam_order ? pair.source : pair.finite_source);
      registration->align(aligned);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      total += seconds;
      us.push_back(1e6 * seconds);
      const Eigen::Matrix4f t = registration->getFinalTransformation();
      const double error = std::hypot(t(0, 3) - pair.truth.x, t(1, 3) - pair.truth.y);
      const double turn = std::abs(std::remainder(std::atan2(t(1, 0), t(0, 0)) - pair.truth.yaw, 2 * M_PI));
      recovered += registration->hasConverged() && error <= 0.1 && turn <= 2.0 * M_PI / 180.0;
    }
    state.SetIterationTime(total);
  }
  std::sort(us.begin(), us.end());
  state.counters["pairs"] = double(pairs.size());
  state.counters["median_us"] = us.empty() ? 0.0 : us[us.size() / 2];
  state.counters["p95_us"] = us.empty() ? 0.0 : us[us.size() * 95 / 100];
  state.counters["recovered_pct"] = pairs.empty() ? 0.0 : 100.0 * double(recovered) / double(pairs.size());
}

}  // namespace
}  // namespace contour_reg::bench

int main(int argc, char **argv) {
  using namespace contour_reg::bench;
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const std::filesystem::path shared = std::filesystem::path(CONTOUR_REG_SHARED_DIR) / "datasets";
  static std::vector<std::vector<Pair>> logs;  // kept alive for the registered benchmarks
  logs.reserve(3);
  for (const std::string name : {"intel", "fr079", "mit-csail"}) {
    const auto log = shared / name / (name + ".clf"), relations = shared / name / (name + ".relations");
    if (!std::filesystem::exists(log) || !std::filesystem::exists(relations)) continue;
    const std::vector<Pair> &pairs = logs.emplace_back(relationPairs(log.string(), relations.string()));
    benchmark::RegisterBenchmark(("BM_RelationPairs/contour/" + name).c_str(),
                                 [&pairs](benchmark::State &s) { runPairs(s, pairs, makeContour, true); })
        ->Iterations(1)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_RelationPairs/icp/" + name).c_str(),
                                 [&pairs](benchmark::State &s) { runPairs(s, pairs, makeIcp, false); })
        ->Iterations(1)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
