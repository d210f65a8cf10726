#pragma once
// Subcommands of the contour_reg tool. Each registers itself on the CLI11 app and
// runs when chosen; the run functions return the process exit code.

#include <cstdio>
#include <functional>

#include <CLI/CLI.hpp>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::cli {

/// Runs a subcommand body: a non-zero exit code or an unreadable file ends the program
/// with that code (2 for files), the error printed once.
inline void runCommand(const std::function<int()> &body) {
  try {
    if (const int code = body(); code != 0) throw CLI::RuntimeError(code);
  } catch (const io::ReadError &error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    throw CLI::RuntimeError(2);
  }
}

void addFeaturesCommand(CLI::App &app);
void addSimulateCommand(CLI::App &app);
void addRelationsCommand(CLI::App &app);
void addOdometryCommand(CLI::App &app);
void addEvaluateCommand(CLI::App &app);
void addCompareCommand(CLI::App &app);
void addDebugCommand(CLI::App &app);
void addExperimentCommand(CLI::App &app);

}  // namespace contour_reg::cli
