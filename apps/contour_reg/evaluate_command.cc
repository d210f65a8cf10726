// contour_reg evaluate: accuracy of a TUM trajectory against ground truth or relations.
#include <cstdio>
#include <memory>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/evaluation/metrics.h"
#include "contour_reg/io/trajectory.h"

namespace contour_reg::cli {

namespace {

struct EvaluateOptions {
  std::string trajectory, ground_truth, relations;
  double local_dt = 5.0;
};

int runEvaluate(const EvaluateOptions &options) {
  const io::Trajectory estimate = io::readTum(options.trajectory);
  io::Trajectory ground_truth;
  std::vector<io::Relation> relations;
  if (!options.ground_truth.empty()) ground_truth = io::readTum(options.ground_truth);
  if (!options.relations.empty()) relations = io::readRelations(options.relations);
  const evaluation::Evaluation e =
      evaluation::evaluate(estimate, options.ground_truth.empty() ? nullptr : &ground_truth,
                           options.relations.empty() ? nullptr : &relations, options.local_dt);
  std::printf("%s: %zu poses, path %.2f m\n", options.trajectory.c_str(), estimate.size(),
              evaluation::pathLength(estimate));
  int code = 0;
  // Stamps that do not increase cannot find poses: no metric of them then.
  if (e.estimate_stamps_not_increasing > 0) {
    std::fprintf(stderr, "error: %s: %s\n", options.trajectory.c_str(),
                 stampsDoNotIncrease(e.estimate_stamps_not_increasing, estimate.size(), "").c_str());
    return 1;
  }
  if (e.ground_truth_stamps_not_increasing > 0) {
    std::fprintf(
        stderr, "error: %s: %s\n", options.ground_truth.c_str(),
        stampsDoNotIncrease(e.ground_truth_stamps_not_increasing, ground_truth.size(), "ground-truth ").c_str());
    code = 1;
  }
  if (!options.ground_truth.empty() && code == 0) {
    if (e.ate) {
      std::printf("ground truth: %zu of %zu poses matched by stamp\n", e.matched_poses, e.estimate_poses);
      if (e.end_point)
        std::printf("end-point error: %.3f m over %.2f m of ground-truth path = %.2f %%\n", e.end_point->error,
                    e.end_point->path_length, e.end_point->percent);
      else
        std::printf("end-point error: - (the ground truth does not move)\n");
      if (e.drift)
        std::printf("drift over 10 m windows: %.2f %% (%zu windows)\n", e.drift->mean_percent, e.drift->windows);
      else
        std::printf("drift over 10 m windows: - (the ground-truth path is shorter than 10 m)\n");
      std::printf("ATE after SE(2) alignment: %.3f m RMSE\n", *e.ate);
    } else {
      std::fprintf(stderr,
                   "error: %s and %s share %zu stamps (within 1 s); need 2: is it the ground truth of this run?\n",
                   options.trajectory.c_str(), options.ground_truth.c_str(), e.matched_poses);
      code = 1;
    }
  }
  if (e.relations_all) {
    const evaluation::RelationErrors &all = *e.relations_all;
    if (e.relations_local) {
      auto print_relations = [](const char *label, const evaluation::RelationErrors &r) {
        std::printf("relations %s: %zu of %zu used, translation %.4f +- %.4f m, rotation %.3f +- %.3f deg\n", label,
                    r.count, r.count + r.missing, r.translation_mean, r.translation_std, r.rotation_mean,
                    r.rotation_std);
      };
      print_relations("all", all);
      char label[32];
      std::snprintf(label, sizeof label, "local (<= %.0f s)", options.local_dt);
      print_relations(label, *e.relations_local);
    } else {
      std::fprintf(stderr, "error: %s covers none of the %zu relations of %s: is it the log they belong to?\n",
                   options.trajectory.c_str(), all.missing, options.relations.c_str());
      code = 1;
    }
  }
  return code;
}

}  // namespace

void addEvaluateCommand(CLI::App &app) {
  auto options = std::make_shared<EvaluateOptions>();
  CLI::App *command = app.add_subcommand("evaluate", "Accuracy of a TUM trajectory against ground truth or relations");
  command->add_option("trajectory", options->trajectory, "Estimated trajectory (TUM)")
      ->required()
      ->check(CLI::ExistingFile);
  auto *gt = command->add_option("--gt", options->ground_truth, "Ground truth (TUM)")->check(CLI::ExistingFile);
  auto *rel = command->add_option("--relations", options->relations, "Kuemmerle et al. relations file")
                  ->check(CLI::ExistingFile);
  command->add_option("--local-dt", options->local_dt, "Relations at most this far apart are local (s)")
      ->capture_default_str()
      ->check(positive());
  command->callback([options, gt, rel]() {
    if (gt->count() == 0 && rel->count() == 0) throw CLI::ValidationError("evaluate", "give --gt or --relations");
    runCommand([&] { return runEvaluate(*options); });
  });
}

}  // namespace contour_reg::cli
