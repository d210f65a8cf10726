// The paper's experiment as a library: arrivals run in parallel, and one that fails ends it
// with its own error.
#include <stdexcept>

#include <gtest/gtest.h>

#include "contour_reg/experiment/paper_experiment.h"

namespace contour_reg::experiment {
namespace {

using V = Eigen::Vector2d;

TEST(PaperExperiment, AnArrivalThatThrowsEndsTheExperimentWithItsError) {
  simulation::World box;
  box.addBox({-5.0, -5.0}, {5.0, 5.0});
  const std::map<std::string, std::vector<V>> paths = {{"line", {V(-2, 0), V(2, 0)}}};
  ExperimentSettings settings;
  settings.methods = {"icp"};
  settings.rates = {2.0};
  settings.arrivals = 4;
  settings.jobs = 2;
  settings.run.odometry_rate = 1e12;  // more wheel odometry samples than a run holds (simulateRun)
  EXPECT_THROW(runExperiment(box, paths, settings), std::invalid_argument);
}

}  // namespace
}  // namespace contour_reg::experiment
