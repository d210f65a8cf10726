// contour_reg: 2-D LIDAR scan registration and laser odometry by contour analysis.
#include <cstdio>

#include <CLI/CLI.hpp>

#include "commands.h"

int main(int argc, char **argv) {
  CLI::App app{"contour_reg: 2-D LIDAR scan registration and odometry by contour analysis"};
  app.require_subcommand(1);
  contour_reg::cli::addFeaturesCommand(app);
  contour_reg::cli::addSimulateCommand(app);
  contour_reg::cli::addOdometryCommand(app);
  contour_reg::cli::addEvaluateCommand(app);
  contour_reg::cli::addCompareCommand(app);
  contour_reg::cli::addRelationsCommand(app);
  contour_reg::cli::addDebugCommand(app);
  contour_reg::cli::addExperimentCommand(app);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
