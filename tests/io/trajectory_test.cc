#include <cmath>

#include <gtest/gtest.h>

#include "contour_reg/io/trajectory.h"
#include "temp_dir.h"

namespace contour_reg::io {
namespace {

TEST(Tum, WrittenTrajectoriesReadBack) {
  test::TempDir dir;
  const Trajectory written{{1.5, {1.0, 2.0, 0.5}}, {2.5, {-3.0, 4.0, -3.0}}};
  writeTum(dir.file("t.tum"), written);
  const Trajectory read = readTum(dir.file("t.tum"));
  ASSERT_EQ(read.size(), 2u);
  EXPECT_NEAR(read[1].stamp, 2.5, 1e-9);
  EXPECT_NEAR(read[1].pose.x, -3.0, 1e-6);
  EXPECT_NEAR(read[1].pose.yaw, -3.0, 1e-6);
  EXPECT_NEAR(read[0].pose.yaw, 0.5, 1e-6);
}

TEST(Tum, ABadLineIsAnErrorNamingFileAndLine) {
  test::TempDir dir;
  const auto path = dir.write("t.tum", "# header\n1 0 0 0 0 0 0 1\n2 0 0 0 zero 0 0 1\n");
  try {
    readTum(path);
    FAIL();
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find(path + ":3"), std::string::npos) << error.what();
  }
}

TEST(Relations, MotionIsTheSecondPoseInTheFrameOfTheFirst) {
  test::TempDir dir;
  const auto relations = readRelations(dir.write("r.relations", "10.5 12.0 0.3 -0.1 0 0 0 0.25\n"));
  ASSERT_EQ(relations.size(), 1u);
  EXPECT_DOUBLE_EQ(relations[0].t1, 10.5);
  EXPECT_DOUBLE_EQ(relations[0].t2, 12.0);
  EXPECT_DOUBLE_EQ(relations[0].motion.x, 0.3);
  EXPECT_DOUBLE_EQ(relations[0].motion.yaw, 0.25);
}

}  // namespace
}  // namespace contour_reg::io
