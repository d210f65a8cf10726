// contour_reg relations: registers the scan pairs of a relations file from a zero guess
// with several methods and reports how many each recovers, and how fast.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <map>
#include <numeric>

#include <pcl/console/print.h>
#include <pcl/filters/filter.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt_2d.h>
#include <pcl/registration/transformation_estimation_2D.h>

#include "commands.h"
#include "contour_reg/contour_registration.h"
#include "contour_reg/io/carmen.h"
#include "contour_reg/io/trajectory.h"

namespace contour_reg::cli {

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using Registration = pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>;

struct RelationsOptions {
  std::string input, relations;
  std::vector<std::string> methods = {"contour", "icp", "ndt2d"};
  double max_dt = 5.0, max_range = 40.0, tolerance = 0.10, tolerance_deg = 2.0;
  std::size_t limit = 0;
  // Contour method settings worth studying on real data.
  double contour_step = 0.05, threshold = 0.08;
  int candidates = 3, arm_elements = 5;
};

// Beam-order cloud with NaN for invalid beams (what ContourRegistration takes).
Cloud::Ptr beamCloud(const LaserScan &scan) {
  auto cloud = pcl::make_shared<Cloud>();
  for (const Complex &c : polarCode(scan)) cloud->push_back(pcl::PointXYZ(float(c.real()), float(c.imag()), 0.f));
  cloud->is_dense = false;
  return cloud;
}

// ICP and NDT need the invalid beams removed.
Cloud::Ptr finiteCloud(const Cloud &cloud) {
  auto out = pcl::make_shared<Cloud>();
  pcl::Indices kept;
  pcl::removeNaNFromPointCloud(cloud, *out, kept);
  return out;
}

Registration::Ptr makeMethod(const std::string &name, const RelationsOptions &options) {
  if (name == "contour") {
    auto contour = pcl::make_shared<ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>>();
    ContourParams params;
    params.equalization.step = options.contour_step;
    params.special_points.threshold = options.threshold;
    params.corner_filter.arm_elements = options.arm_elements;
    contour->setContourParams(params);
    RegistrationParams registration;
    registration.correspondence.candidates_per_point = options.candidates;
    contour->setRegistrationParams(registration);
    return contour;
  }
  if (name == "icp") {
    auto icp = pcl::make_shared<pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>>();
    icp->setTransformationEstimation(
        pcl::make_shared<pcl::registration::TransformationEstimation2D<pcl::PointXYZ, pcl::PointXYZ>>());
    icp->setMaxCorrespondenceDistance(1.0);
    icp->setMaximumIterations(50);
    icp->setTransformationEpsilon(1e-8);
    return icp;
  }
  if (name == "ndt2d") {
    auto ndt = pcl::make_shared<pcl::NormalDistributionsTransform2D<pcl::PointXYZ, pcl::PointXYZ>>();
    ndt->setGridCentre(Eigen::Vector2f(0, 0));
    ndt->setGridExtent(Eigen::Vector2f(40, 40));
    ndt->setGridStep(Eigen::Vector2f(1.0, 1.0));
    ndt->setMaximumIterations(50);
    ndt->setTransformationEpsilon(1e-6);
    return ndt;
  }
  return nullptr;
}

std::size_t nearestScan(const io::ScanLog &log, double stamp) {
  auto it = std::lower_bound(log.entries.begin(), log.entries.end(), stamp,
                             [](const io::LogEntry &e, double t) { return e.scan.stamp < t; });
  std::size_t k = static_cast<std::size_t>(it - log.entries.begin());
  if (k == log.entries.size() || (k > 0 && stamp - log.entries[k - 1].scan.stamp < it->scan.stamp - stamp)) --k;
  return k;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1))];
}

int runRelations(const RelationsOptions &options) {
  // PCL's classes print a line per failed pair; the table counts them instead.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  io::CarmenOptions carmen;
  carmen.max_range = options.max_range;
  const io::ScanLog log = io::readCarmen(options.input, carmen);
  std::vector<io::Relation> relations;
  for (const io::Relation &r : io::readRelations(options.relations))
    if (std::abs(r.t2 - r.t1) <= options.max_dt) relations.push_back(r);
  if (options.limit > 0 && relations.size() > options.limit) relations.resize(options.limit);
  std::printf("%s: %zu relations with |t2 - t1| <= %.1f s, zero guess, success = within %.2f m and %.1f deg\n\n",
              options.input.c_str(), relations.size(), options.max_dt, options.tolerance, options.tolerance_deg);
  std::printf("| method | recovered | converged | converged but wrong | mean err m (recovered) | median ms | p95 ms |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const std::string &name : options.methods) {
    Registration::Ptr method = makeMethod(name, options);
    std::map<std::string, int> reasons;
    if (!method) {
      std::fprintf(stderr, "error: unknown method %s\n", name.c_str());
      return 2;
    }
    const bool beam_order = name == "contour";
    std::size_t recovered = 0, converged = 0, wrong = 0;
    double error_sum = 0.0;
    std::vector<double> ms;
    for (const io::Relation &r : relations) {
      const LaserScan &a = log.entries[nearestScan(log, r.t1)].scan, &b = log.entries[nearestScan(log, r.t2)].scan;
      Cloud::Ptr target = beamCloud(a), source = beamCloud(b);
      if (!beam_order) {
        target = finiteCloud(*target);
        source = finiteCloud(*source);
      }
      method->setInputTarget(target);
      method->setInputSource(source);
      Cloud aligned;
      const auto start = std::chrono::steady_clock::now();
      method->align(aligned);
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      const Eigen::Matrix4f t = method->getFinalTransformation();
      const double et = std::hypot(t(0, 3) - r.motion.x, t(1, 3) - r.motion.y);
      const double er = std::abs(std::remainder(std::atan2(t(1, 0), t(0, 0)) - r.motion.yaw, 2 * M_PI)) * 180 / M_PI;
      const bool ok = et <= options.tolerance && er <= options.tolerance_deg;
      converged += method->hasConverged();
      if (auto *contour = dynamic_cast<ContourRegistration<pcl::PointXYZ, pcl::PointXYZ> *>(method.get()))
        ++reasons[toString(contour->getResult().status)];
      wrong += method->hasConverged() && !ok;
      if (method->hasConverged() && ok) {
        ++recovered;
        error_sum += et;
      }
    }
    const double n = std::max<double>(1.0, relations.size());
    std::printf("| %s | %.1f %% | %.1f %% | %.1f %% | %.3f | %.3f | %.3f |\n", name.c_str(), 100 * recovered / n,
                100 * converged / n, 100 * wrong / n, recovered ? error_sum / recovered : 0.0, percentile(ms, 0.5),
                percentile(ms, 0.95));
    for (const auto &[reason, count] : reasons) std::fprintf(stderr, "  %s: %d\n", reason.c_str(), count);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

void addRelationsCommand(CLI::App &app) {
  auto options = std::make_shared<RelationsOptions>();
  CLI::App *command = app.add_subcommand("relations", "Register the scan pairs of a relations file from a zero guess");
  command->add_option("input", options->input, "CARMEN log")->required()->check(CLI::ExistingFile);
  command->add_option("--relations", options->relations, "Kuemmerle et al. relations file")->required()->check(CLI::ExistingFile);
  command->add_option("--methods", options->methods, "contour, icp, ndt2d")->capture_default_str();
  command->add_option("--max-dt", options->max_dt, "Only relations at most this far apart (s)")->capture_default_str();
  command->add_option("--max-range", options->max_range, "Readings at or above are no-return (m)")->capture_default_str();
  command->add_option("--contour-step", options->contour_step, "Contour: equalized element length (m)")->capture_default_str();
  command->add_option("--threshold", options->threshold, "Contour: corner response threshold")->capture_default_str();
  command->add_option("--candidates", options->candidates, "Contour: candidate targets per special point")->capture_default_str();
  command->add_option("--arm", options->arm_elements, "Contour: elements per corner arm (s)")->capture_default_str();
  command->add_option("--limit", options->limit, "At most this many relations (0: all)")->capture_default_str();
  command->callback([options]() { runCommand([&] { return runRelations(*options); }); });
}

}  // namespace contour_reg::cli
