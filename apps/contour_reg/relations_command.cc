// contour_reg relations: registers the scan pairs of a relations file from a zero guess
// with several methods and reports how many each recovers, and how fast.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>

#include <pcl/console/print.h>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/core/transform_estimation.h"
#include "contour_reg/evaluation/free_space_check.h"
#include "contour_reg/evaluation/metrics.h"
#include "contour_reg/io/pose2d.h"
#include "contour_reg/io/read_log.h"
#include "contour_reg/io/trajectory.h"
#include "contour_reg/odometry/odometry.h"
#include "contour_reg/odometry/scan_matcher.h"

namespace contour_reg::cli {

namespace {

struct RelationsOptions {
  std::string input, relations;
  std::vector<std::string> methods = {"contour", "contour+icp", "icp", "icp-pl", "ndt2d"};
  double max_dt = 5.0, tolerance = 0.10, tolerance_deg = 2.0;
  std::vector<double> reference_sigma = {0.02, 0.5};  // m, deg: the reference's own error, for the NEES
  std::size_t limit = 0;
  std::string pairs_csv;         // one row per relation and method, when set
  std::size_t log_pose_gap = 0;  // > 0: pairs k, k + gap referenced by the log's own poses
  std::string ground_truth;      // set: pairs k, k + gt_gap referenced by this TUM trajectory
  std::size_t gt_gap = 1;
  std::string frame = "robot";
  bool deskew = true;
  io::LogReadOptions read;
  MethodOptions method_options;
};

// A scan pair to register and its reference motion (the second scan's pose in the first's frame).
struct ReferencedPair {
  std::size_t first = 0, second = 0;
  io::Relation reference;
};

// One method's answer to one pair.
struct Answer {
  bool converged = false, wrong = false;
  Eigen::Matrix3d transform = Eigen::Matrix3d::Identity();
};

// Whether two methods find a motion in independent ways. The methods that start with the
// contour stage share its answer (contour+icp refines contour's); the others (ICP, point-to-line
// ICP, GICP, NDT) each descend from the guess into its basin, and from one guess two of them
// easily land in the same wrong one. A contour-based method and a local one are independent.
bool independent(const std::string &a, const std::string &b) {
  const auto contour_based = [](const std::string &name) { return name.rfind("contour", 0) == 0; };
  return contour_based(a) != contour_based(b);
}

// For each method's converged-but-wrong answers: how many an independent method, registering
// the same pair from the same zero guess, converged within `agree` of. Two independent methods
// that agree against the reference point at an error of the reference.
std::vector<std::string> agreementLines(const std::vector<std::string> &methods,
                                        const std::vector<std::vector<Answer>> &answers, const Apart &agree) {
  std::vector<std::string> lines;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    if (std::none_of(methods.begin(), methods.end(), [&](const std::string &o) { return independent(methods[m], o); }))
      continue;  // no witness
    std::size_t wrong = 0, agreed = 0;
    std::map<std::string, int> by;
    for (std::size_t k = 0; k < answers[m].size(); ++k) {
      const Answer &a = answers[m][k];
      if (!a.wrong) continue;
      ++wrong;
      bool any = false;
      for (std::size_t o = 0; o < methods.size(); ++o) {
        const Answer &b = answers[o][k];
        if (!independent(methods[m], methods[o]) || !b.converged) continue;
        const Apart d = apart(a.transform, b.transform);
        if (d.metres > agree.metres || d.degrees > agree.degrees) continue;
        any = true;
        ++by[methods[o]];
      }
      agreed += any;
    }
    std::string names;
    for (const auto &[name, count] : by) names += (names.empty() ? "" : ", ") + name + " " + std::to_string(count);
    lines.push_back(methods[m] + ": " + std::to_string(wrong) +
                    " converged but wrong; an independent method converged within " +
                    std::to_string(static_cast<int>(std::lround(100 * agree.metres))) + " cm and " +
                    std::to_string(static_cast<int>(std::lround(agree.degrees))) + " deg of " + std::to_string(agreed) +
                    " of them" + (names.empty() ? "" : " (" + names + ")"));
  }
  return lines;
}

// The CSV's motion the judge did not take (x m, y m, yaw rad), in the declined columns or in the
// rival columns as the registration converged, empty fields elsewhere.
std::string rejectedFields(const odometry::MatchResult &match) {
  if (!match.rejected) return ",,,,,";
  const Eigen::Matrix3d &m = *match.rejected;
  const std::string fields = printed("%.4f,%.4f,%.5f", m(0, 2), m(1, 2), yawOf(m));
  return match.converged ? ",,," + fields : fields + ",,,";
}

// The CSV's est_overlap and est_score: the judge's figures of a converged contour answer, empty otherwise.
std::string scoreFields(const odometry::MatchResult &match) {
  if (!match.overlap || !match.score) return ",";
  return printed("%.4f,%.4f", *match.overlap, *match.score);
}

// A relation's stamp this close to a scan's stamp is the scan's (s).
constexpr double kStampMatch = 0.01;

// The scan pairs to register against their reference motions, and how the report names them.
struct References {
  std::vector<ReferencedPair> pairs;
  std::string kind;          // "relations with |t2 - t1| <= 5.0 s", "pairs of scans 1 apart, referenced by ..."
  std::string none;          // why there is no pair, when there is none
  std::size_t left_out = 0;  // relations short enough without a scan at both stamps
};

// Scan k and scan k + gap for every k where `poses` (one per log entry) has both poses.
std::vector<ReferencedPair> pairsFromPoses(const io::ScanLog &log, const std::vector<std::optional<io::Pose2D>> &poses,
                                           std::size_t gap) {
  std::vector<ReferencedPair> pairs;
  for (std::size_t k = 0; k + gap < log.entries.size(); ++k) {
    const std::optional<io::Pose2D> &a = poses[k], &b = poses[k + gap];
    if (a && b)
      pairs.push_back({k, k + gap, {log.entries[k].scan.stamp, log.entries[k + gap].scan.stamp, io::between(*a, *b)}});
  }
  return pairs;
}

// The pairs of one of the three references: a relations file (each relation whose two stamps
// are a scan's, within kStampMatch), the log's own poses (in the GMapping-corrected Radish
// logs, the corrected pose; in a raw log, wheel odometry), or a ground-truth trajectory (a
// simulated log's .gt.tum, interpolated at the scans' stamps as `evaluate` does).
References referencePairs(const io::ScanLog &log, const RelationsOptions &options) {
  References references;
  if (!options.ground_truth.empty()) {
    // As for evaluate, none is found in a ground truth whose stamps do not increase.
    const auto poses = groundTruthAtScans(options.ground_truth, log, references.none);
    if (!poses) return references;
    references.pairs = pairsFromPoses(log, *poses, options.gt_gap);
    references.kind =
        printed("pairs of scans %zu apart, referenced by %s", options.gt_gap, options.ground_truth.c_str());
    references.none = printed("%s has no pose at the stamps of scans %zu apart in %s", options.ground_truth.c_str(),
                              options.gt_gap, options.input.c_str());
  } else if (options.log_pose_gap > 0) {
    std::vector<std::optional<io::Pose2D>> poses;
    for (const io::LogEntry &entry : log.entries) poses.push_back(entry.odometry);
    references.pairs = pairsFromPoses(log, poses, options.log_pose_gap);
    references.kind = printed("pairs of scans %zu apart, referenced by the log's poses", options.log_pose_gap);
    references.none =
        printed("%s has no poses of its own for scans %zu apart", options.input.c_str(), options.log_pose_gap);
  } else {
    const std::vector<io::Relation> relations = io::readRelations(options.relations);
    const auto scanAt = [&](double stamp) -> std::optional<std::size_t> {
      if (log.entries.empty()) return std::nullopt;
      const std::size_t k = io::nearestEntry(log, stamp);
      if (std::abs(log.entries[k].scan.stamp - stamp) > kStampMatch) return std::nullopt;
      return k;
    };
    for (const io::Relation &r : relations) {
      if (std::abs(r.t2 - r.t1) > options.max_dt) continue;
      const std::optional<std::size_t> first = scanAt(r.t1), second = scanAt(r.t2);
      if (first && second)
        references.pairs.push_back({*first, *second, r});
      else
        ++references.left_out;
    }
    references.kind = printed("relations with |t2 - t1| <= %.1f s", options.max_dt);
    references.none = printed(
        "none of the %zu relations has a scan of %s at both stamps (within %.0f ms), at most "
        "%.1f s apart",
        relations.size(), options.input.c_str(), 1000 * kStampMatch, options.max_dt);
  }
  return references;
}

int runRelations(const RelationsOptions &options) {
  // PCL's classes print a line per failed pair; the table counts them instead.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const io::ScanLog log = io::readLog(options.input, options.read);
  printReadReport(log);
  References references = referencePairs(log, options);
  std::vector<ReferencedPair> &pairs = references.pairs;
  if (pairs.empty()) {  // references of another run: say so rather than score nothing
    std::fprintf(stderr, "error: no scan pair: %s\n", references.none.c_str());
    return 1;
  }
  if (options.limit > 0 && pairs.size() > options.limit) pairs.resize(options.limit);
  const bool robot_frame = options.frame == "robot" && log.laser_pose.has_value();
  std::printf("%s%s: %zu %s, zero guess, success = within %.2f m and %.1f deg\n\n", options.input.c_str(),
              beamsRead(options.read).c_str(), pairs.size(), references.kind.c_str(), options.tolerance,
              options.tolerance_deg);
  if (references.left_out > 0)
    std::printf("%zu more relations have no scan within %.0f ms of a stamp: left out\n\n", references.left_out,
                1000 * kStampMatch);
  std::printf("estimates in %s\n\n",
              odometry::frameDescription(robot_frame ? odometry::Frame::kRobot : odometry::Frame::kLaser, log).c_str());
  std::FILE *csv = nullptr;
  if (!options.pairs_csv.empty()) {
    csv = std::fopen(options.pairs_csv.c_str(), "w");
    if (!csv) throw std::runtime_error("cannot write " + options.pairs_csv);
    std::fprintf(
        csv,
        "method,first,second,t1_s,t2_s,ref_x_m,ref_y_m,ref_yaw_rad,est_x_m,est_y_m,est_yaw_rad,converged,"
        "recovered,error_m,error_deg,ms,status,reason,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,cov_yawyaw,"
        "ref_free_space,est_free_space,declined_x_m,declined_y_m,declined_yaw_rad,rival_x_m,rival_y_m,rival_yaw_rad,"
        "est_overlap,est_score\n");
  }
  std::printf(
      "| method | recovered | converged | converged but wrong | mean err m (recovered) | median ms | p95 ms |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  const double usual_interval = odometry::medianScanInterval(log);
  const auto sweep = [&](std::size_t k) { return sweepToDeskew(log, k, options.deskew, usual_interval); };
  std::fflush(stdout);
  std::vector<std::string> failures;          // printed after the table
  std::vector<std::string> gross_lines;       // likewise
  std::vector<std::string> covariance_lines;  // likewise
  std::vector<std::string> rival_lines;       // likewise
  std::vector<std::vector<Answer>> answers;
  const auto within = [&](const Apart &d) {
    return d.metres <= options.tolerance && d.degrees <= options.tolerance_deg;
  };
  for (const std::string &name : options.methods) {
    std::vector<Answer> &answered = answers.emplace_back();
    auto matcher = odometry::makeScanMatcher(name, options.method_options.settings());
    std::map<std::string, int> reasons;
    std::map<std::string, int> declined_right;  // per failure: the motion declined was within tolerance
    ProgressBar progress(name);
    std::size_t recovered = 0, converged = 0, wrong = 0, gross = 0;
    // Answers converged but wrong, and gross errors, with a reference the scans contradict.
    std::size_t wrong_against_reference = 0, gross_against_reference = 0;
    std::size_t with_rival = 0, rival_right = 0;  // converged pairs whose judge weighed a distinct rival
    double error_sum = 0.0;
    std::vector<double> ms;
    std::vector<double> nees;  // of the converged pairs with a covariance
    for (const ReferencedPair &pair : pairs) {
      progress(ms.size(), pairs.size());
      const io::Relation &r = pair.reference;
      const LaserScan &first = log.entries[pair.first].scan, &second = log.entries[pair.second].scan;
      odometry::MatchResult match =
          matcher->match(first, second, Eigen::Matrix3d::Identity(), sweep(pair.first), sweep(pair.second));
      const Eigen::Matrix3d laser_transform = match.transform;  // in the scans' frame
      // The references are the robot's motions.
      if (robot_frame) toRobotFrame(match, *log.laser_pose);
      ms.push_back(match.milliseconds);
      const Eigen::Matrix3d &t = match.transform;
      const double yaw = yawOf(t);
      const auto [et, er] = apart(t, io::toMatrix(r.motion));
      const bool ok = within({et, er});
      converged += match.converged;
      if (!match.converged) ++reasons[match.status];
      if (match.rejected) {
        const bool right = within(apart(*match.rejected, io::toMatrix(r.motion)));
        if (match.converged) {
          ++with_rival;
          rival_right += right;
        } else {
          declined_right[match.status] += right;
        }
      }
      const bool silently_wrong = match.converged && !ok;
      wrong += silently_wrong;
      answered.push_back({match.converged, silently_wrong, t});
      const bool gross_error = match.converged && isGross(et, er);
      // Each motion's evidence in the scans themselves, in the laser's frame like the scans:
      // for the CSV, the answers converged but wrong and the gross errors.
      double est_free_space = 0.0, ref_free_space = 0.0;
      if (csv || silently_wrong || gross_error) {
        const evaluation::FreeSpaceCheck free_space(first, second);
        est_free_space = free_space.contradictedShare(laser_transform);
        ref_free_space = free_space.contradictedShare(
            io::toMatrix(robot_frame ? io::laserMotion(r.motion, *log.laser_pose) : r.motion));
      }
      // The scans contradict the reference and not the estimate: an error of the reference.
      const bool against_reference = est_free_space < evaluation::kFreeSpaceShareTie &&
                                     ref_free_space > est_free_space + evaluation::kFreeSpaceShareTie;
      wrong_against_reference += silently_wrong && against_reference;
      gross += gross_error;
      gross_against_reference += gross_error && against_reference;
      if (csv) {
        const Eigen::Matrix3d &c = match.covariance;
        std::fprintf(csv,
                     "%s,%zu,%zu,%.6f,%.6f,%.4f,%.4f,%.5f,%.4f,%.4f,%.5f,%d,%d,%.4f,%.3f,%.4f,%s,\"%s\","
                     "%.4e,%.4e,%.4e,%.4e,%.4e,%.4e,%.4f,%.4f,%s,%s\n",
                     name.c_str(), pair.first, pair.second, r.t1, r.t2, r.motion.x, r.motion.y, r.motion.yaw, t(0, 2),
                     t(1, 2), yaw, match.converged ? 1 : 0, match.converged && ok ? 1 : 0, et, er, match.milliseconds,
                     match.converged ? "converged" : match.status.c_str(), match.reason.c_str(), c(0, 0), c(0, 1),
                     c(0, 2), c(1, 1), c(1, 2), c(2, 2), ref_free_space, est_free_space, rejectedFields(match).c_str(),
                     scoreFields(match).c_str());
      }
      if (match.converged && !match.covariance.isZero())
        nees.push_back(evaluation::normalisedErrorSquared(io::toPose(t), r.motion, match.covariance,
                                                          options.reference_sigma[0],
                                                          options.reference_sigma[1] * M_PI / 180.0));
      if (match.converged && ok) {
        ++recovered;
        error_sum += et;
      }
    }
    progress.finish();
    const double n = std::max<double>(1.0, pairs.size());
    std::printf("| %s | %.1f %% | %.1f %% | %.1f %% | %.3f | %.3f | %.3f |\n", name.c_str(), 100 * recovered / n,
                100 * converged / n, 100 * wrong / n, recovered ? error_sum / recovered : 0.0, percentile(ms, 0.5),
                percentile(ms, 0.95));
    gross_lines.push_back(
        name + ": " + std::to_string(gross) + " gross error(s) (converged, over " +
        std::to_string(static_cast<int>(100 * kGrossMetres)) + " cm or " +
        std::to_string(static_cast<int>(kGrossDegrees)) + " deg off), " + std::to_string(gross_against_reference) +
        " with a reference the scans contradict and an estimate they do not (returns in the other "
        "scan's free space; --pairs-csv: ref_free_space, est_free_space); such a reference on " +
        std::to_string(wrong_against_reference) + " of all " + std::to_string(wrong) + " converged but wrong");
    if (with_rival > 0)
      rival_lines.push_back(
          printed("%s: the judge weighed a distinct rival on %zu of %zu converged pairs; %zu of those "
                  "rivals lie within the tolerance of the reference (--pairs-csv: rival_x_m, "
                  "rival_y_m, rival_yaw_rad)",
                  name.c_str(), with_rival, converged, rival_right));
    if (!nees.empty()) {
      const auto outside = std::count_if(nees.begin(), nees.end(), [](double v) { return v > evaluation::kNees99; });
      covariance_lines.push_back(
          printed("%s: covariance: mean NEES %.2f over %zu converged pairs, %.1f %% above %.2f (outside the 99 %% "
                  "ellipsoid); an honest covariance gives 3 and 1 %%. The reference's own error, %.3g m / %.3g deg, is "
                  "added (--reference-sigma)",
                  name.c_str(), std::accumulate(nees.begin(), nees.end(), 0.0) / static_cast<double>(nees.size()),
                  nees.size(), 100.0 * static_cast<double>(outside) / static_cast<double>(nees.size()),
                  evaluation::kNees99, options.reference_sigma[0], options.reference_sigma[1]));
    }
    for (const auto &[reason, count] : reasons)
      failures.push_back(name + " failed: " + reason + ": " + std::to_string(count) +
                         (declined_right.count(reason) ? "; the motion it declined was within the tolerance on " +
                                                             std::to_string(declined_right[reason])
                                                       : ""));
    std::fflush(stdout);
  }
  if (csv) std::fclose(csv);
  std::printf("\n");
  for (const std::string &line : gross_lines) std::printf("%s\n", line.c_str());
  for (const std::string &line : covariance_lines) std::printf("%s\n", line.c_str());
  for (const std::string &line : rival_lines) std::printf("%s\n", line.c_str());
  // Two estimates within half the recovery tolerance of each other agree.
  for (const std::string &line :
       agreementLines(options.methods, answers, {options.tolerance / 2, options.tolerance_deg / 2}))
    std::printf("%s\n", line.c_str());
  for (const std::string &line : failures) std::fprintf(stderr, "%s\n", line.c_str());
  return 0;
}

}  // namespace

void addRelationsCommand(CLI::App &app) {
  auto options = std::make_shared<RelationsOptions>();
  CLI::App *command = app.add_subcommand("relations", "Register the scan pairs of a relations file from a zero guess");
  command->add_option("input", options->input, "CARMEN log, ROS 1 or ROS 2 bag or PCD folder")
      ->required()
      ->check(CLI::ExistingPath);
  auto *relations = command->add_option("--relations", options->relations, "Kuemmerle et al. relations file")
                        ->check(CLI::ExistingFile);
  auto *gap = command->add_option("--log-poses", options->log_pose_gap,
                                  "Instead of a relations file: scans k and k + N, referenced by the poses in the log "
                                  "(the corrected poses of the Radish logs)");
  auto *truth = command
                    ->add_option("--gt", options->ground_truth,
                                 "Instead of a relations file: scans k and k + 1 (--gt-gap), referenced by this TUM "
                                 "ground truth (a simulated log's .gt.tum), interpolated at the scans' stamps")
                    ->check(CLI::ExistingFile);
  command->add_option("--gt-gap", options->gt_gap, "With --gt: pairs of scans this many apart")
      ->capture_default_str()
      ->check(positive())
      ->needs(truth);
  relations->excludes(gap)->excludes(truth);
  gap->excludes(relations)->excludes(truth);
  truth->excludes(relations)->excludes(gap);
  command->add_option("--methods", options->methods, "Methods to run")->check(methodCheck())->capture_default_str();
  command->add_option("--max-dt", options->max_dt, "Only relations at most this far apart (s)")
      ->capture_default_str()
      ->check(positive());
  addReadOptions(*command, options->read);
  addFrameOption(*command, options->frame, "the motions and covariances");
  addMethodOptions(*command, options->method_options);
  command->add_option("--pairs-csv", options->pairs_csv, "Write one row per relation and method to this CSV file");
  addReferenceSigmaOption(*command, options->reference_sigma, "the NEES line");
  command->add_option("--limit", options->limit, "At most this many relations (0: all)")->capture_default_str();
  addDeskewOption(*command, options->deskew);
  command->callback([options, relations, gap, truth]() {
    if (relations->count() == 0 && gap->count() == 0 && truth->count() == 0)
      throw CLI::RequiredError("--relations, --log-poses or --gt");
    if (gap->count() > 0 && options->log_pose_gap == 0) throw CLI::ValidationError("--log-poses", "must be >= 1");
    validateMethodOptions(options->method_options);
    if (!options->pairs_csv.empty()) checkOutputFile("--pairs-csv", options->pairs_csv);
    runCommand([&] { return runRelations(*options); });
  });
}

}  // namespace contour_reg::cli
