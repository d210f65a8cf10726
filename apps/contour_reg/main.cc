// contour_reg: 2-D LIDAR scan registration and laser odometry by contour analysis.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "fan_out.h"

namespace {

// Edit distance between two words (insertions, deletions, substitutions).
std::size_t editDistance(const std::string &a, const std::string &b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The first argument when it names no subcommand and is no option: a mistyped command.
bool reportUnknownCommand(const CLI::App &app, int argc, char **argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  const std::string word = argv[1];
  std::string nearest;
  std::size_t best = std::string::npos;
  for (const CLI::App *command : app.get_subcommands({})) {
    if (command->get_name() == word) return false;
    const std::size_t d = editDistance(word, command->get_name());
    if (d < best) best = d, nearest = command->get_name();
  }
  std::fprintf(stderr, "error: unknown command '%s'", word.c_str());
  if (best <= 3) std::fprintf(stderr, "; did you mean '%s'?", nearest.c_str());
  std::fprintf(stderr, "\nRun with --help for the list of commands.\n");
  return true;
}

}  // namespace

int main(int argc, char **argv) {
  contour_reg::cli::rememberCommandLine(argc, argv);
  CLI::App app{"contour_reg: 2-D LIDAR scan registration and odometry by contour analysis"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("contour_reg ") + CONTOUR_REG_VERSION);
  app.footer(
      "Exit codes: 0 done; 1 the command ran but found nothing to report (no stamps or relations in common); "
      "2 invalid command line, unreadable input or unwritable output (the message names the option or the file).");
  contour_reg::cli::addFeaturesCommand(app);
  contour_reg::cli::addSimulateCommand(app);
  contour_reg::cli::addConvertCommand(app);
  contour_reg::cli::addOdometryCommand(app);
  contour_reg::cli::addEvaluateCommand(app);
  contour_reg::cli::addCompareCommand(app);
  contour_reg::cli::addRegisterCommand(app);
  contour_reg::cli::addRelationsCommand(app);
  contour_reg::cli::addClosureCommand(app);
  contour_reg::cli::addDebugCommand(app);
  contour_reg::cli::addExperimentCommand(app);
  if (reportUnknownCommand(app, argc, argv)) return 2;
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError &error) {  // a command's own exit code, its message already printed
    return error.get_exit_code();
  } catch (const CLI::ParseError &error) {
    const int code = app.exit(error);  // prints help, the version or the message
    return code == 0 ? 0 : 2;
  }
  return 0;
}
