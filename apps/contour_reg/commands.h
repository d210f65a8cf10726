#pragma once
// Subcommands of the contour_reg tool. Each registers itself on the CLI11 app and
// runs when chosen; the run functions return the process exit code.

#include <cstdio>
#include <filesystem>
#include <functional>
#include <new>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::cli {

/// Runs a subcommand body: a non-zero exit code ends the program with that code; an
/// unreadable file, a filesystem error (it names the path), settings a library call refuses
/// (std::invalid_argument) or exhausted memory with 2, the error printed once.
inline void runCommand(const std::function<int()> &body) {
  int code = 0;
  try {
    code = body();
  } catch (const io::ReadError &error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    code = 2;
  } catch (const std::filesystem::filesystem_error &error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    code = 2;
  } catch (const std::invalid_argument &error) {  // settings a library call refuses, e.g. a run too long to simulate
    std::fprintf(stderr, "error: %s\n", error.what());
    code = 2;
  } catch (const std::bad_alloc &) {
    std::fprintf(stderr, "error: out of memory (are the settings in range?)\n");
    code = 2;
  }
  if (code != 0) throw CLI::RuntimeError(code);
}

void addFeaturesCommand(CLI::App &app);
void addSimulateCommand(CLI::App &app);
void addConvertCommand(CLI::App &app);
void addRegisterCommand(CLI::App &app);
void addRelationsCommand(CLI::App &app);
void addClosureCommand(CLI::App &app);
void addOdometryCommand(CLI::App &app);
void addEvaluateCommand(CLI::App &app);
void addCompareCommand(CLI::App &app);
void addDebugCommand(CLI::App &app);
void addExperimentCommand(CLI::App &app);

}  // namespace contour_reg::cli
