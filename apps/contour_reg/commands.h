#pragma once
// Subcommands of the contour_reg tool. Each registers itself on the CLI11 app and
// runs when chosen; the run functions return the process exit code.

#include <CLI/CLI.hpp>

namespace contour_reg::cli {

void addFeaturesCommand(CLI::App &app);
void addSimulateCommand(CLI::App &app);
void addRelationsCommand(CLI::App &app);

}  // namespace contour_reg::cli
