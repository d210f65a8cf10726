#include <cmath>

#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include "contour_reg/core/contour.h"
#include "contour_reg/io/pcd_folder.h"
#include "contour_reg/io/read_log.h"
#include "temp_dir.h"

namespace contour_reg::io {
namespace {

LaserScan sampleScan(double shift) {
  LaserScan scan;
  scan.angle_min = -2.0;
  scan.angle_increment = 0.01;
  for (int k = 0; k < 300; ++k)
    scan.ranges.push_back(k % 37 == 5 ? std::nanf("") : float(3.0 + shift + std::sin(k * 0.05)));
  return scan;
}

void savePcd(const std::string &path, const LaserScan &scan, bool keep_invalid) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (const Complex &c : polarCode(scan)) {
    if (!keep_invalid && !isFinite(c)) continue;
    cloud.push_back(pcl::PointXYZ(float(c.real()), float(c.imag()), 0.f));
  }
  cloud.is_dense = !keep_invalid;
  pcl::io::savePCDFileBinary(path, cloud);
}

TEST(PcdFolder, BeamOrderCloudsGiveBackTheScan) {
  test::TempDir dir;
  const LaserScan a = sampleScan(0.0), b = sampleScan(0.5);
  savePcd(dir.file("2.5.pcd"), b, true);   // organized, NaN kept
  savePcd(dir.file("1.0.pcd"), a, false);  // dense: invalid beams dropped
  const ScanLog log = readLog(dir.path().string());
  ASSERT_EQ(log.entries.size(), 2u);
  EXPECT_DOUBLE_EQ(log.entries[0].scan.stamp, 1.0);
  EXPECT_DOUBLE_EQ(log.entries[1].scan.stamp, 2.5);
  EXPECT_TRUE(log.report.problems.empty()) << log.report.problems.front();
  for (std::size_t e = 0; e < 2; ++e) {
    const LaserScan &want = e == 0 ? a : b, &got = log.entries[e].scan;
    EXPECT_NEAR(got.angle_increment, want.angle_increment, 1e-6);
    // Both layouts give the same points back (the dense one without its invalid beams).
    const ComplexSequence p = polarCode(want), q = polarCode(got);
    std::size_t matched = 0;
    for (const Complex &x : q)
      if (isFinite(x))
        for (const Complex &y : p)
          if (isFinite(y) && std::abs(x - y) < 1e-4) {
            ++matched;
            break;
          }
    EXPECT_EQ(matched, 300u - 8u);  // beams 5, 42, ..., 264 are invalid
  }
}

TEST(PcdFolder, UnreadableFilesAreReportedAndSkipped) {
  test::TempDir dir;
  savePcd(dir.file("1.pcd"), sampleScan(0.0), false);
  dir.write("2.pcd", "this is not a point cloud\n");
  const ScanLog log = readPcdFolder(dir.path().string());
  EXPECT_EQ(log.entries.size(), 1u);
  EXPECT_EQ(log.report.skipped, 1u);
}

// Found by tests/fuzz: field sizes that disagree with their types (and a zero count) made
// PCL's point conversion read past its buffer. Such files are skipped and named.
TEST(PcdFolder, HeadersWithInconsistentFieldsAreSkipped) {
  test::TempDir dir;
  savePcd(dir.file("1.pcd"), sampleScan(0.0), false);
  dir.write("2.pcd",
            "# .PCD v0.7\nFIELDS x y z\nSIZE 8 4 4\nTYPE F F F\nCOUNT 0 0 1\nWIDTH 4\nHEIGHT 1\n"
            "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n1 0 0\n0 1 0\n0.5 0.5 0\nnan nan nan\n");
  dir.write("3.pcd",
            "# .PCD v0.7\nFIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
            "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n1 0 0\n0 1 0\n");
  const ScanLog log = readPcdFolder(dir.path().string());
  EXPECT_EQ(log.entries.size(), 1u);
  EXPECT_EQ(log.report.skipped, 2u);
  ASSERT_FALSE(log.report.problems.empty());
  EXPECT_NE(log.report.problems.front().find("2.pcd"), std::string::npos);
}

// Found by tests/fuzz: PCL's header reader goes on reading lines after the DATA line while
// they begin with a header keyword, so binary data that begins with one (here "COLUMNS",
// PCL's old name of FIELDS) was read as a second FIELDS line and the reader overran its
// buffers. Such files are skipped and named, with the line.
TEST(PcdFolder, DataThatReadsAsAHeaderLineIsSkipped) {
  test::TempDir dir;
  savePcd(dir.file("1.pcd"), sampleScan(0.0), false);
  const std::string header =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\nHEIGHT 1\n"
      "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA binary\n";
  dir.write("2.pcd", header + "COLUMNSx" + std::string(40, '\0'));
  const ScanLog log = readPcdFolder(dir.path().string());
  EXPECT_EQ(log.entries.size(), 1u);
  EXPECT_EQ(log.report.skipped, 1u);
  ASSERT_EQ(log.report.problems.size(), 1u);
  EXPECT_NE(log.report.problems.front().find("2.pcd:12"), std::string::npos) << log.report.problems.front();
  EXPECT_NE(log.report.problems.front().find("header line"), std::string::npos) << log.report.problems.front();
}

// Found by tests/fuzz: PCL's reader skips any number of comment lines after the DATA line
// before the keyword, so binary data of many short lines that begin with '#' and then a
// FIELDS line overran its buffers just the same.
TEST(PcdFolder, AHeaderLineAfterManyCommentLinesInTheDataIsSkipped) {
  test::TempDir dir;
  savePcd(dir.file("1.pcd"), sampleScan(0.0), false);
  const std::string header =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\nHEIGHT 1\nPOINTS 4\nDATA binary\n";
  std::string data;
  for (int k = 0; k < 100; ++k) data += "#\xf9\n";
  dir.write("2.pcd", header + data + "FIELDS\n" + std::string(1, '\0'));
  const ScanLog log = readPcdFolder(dir.path().string());
  EXPECT_EQ(log.entries.size(), 1u);
  EXPECT_EQ(log.report.skipped, 1u);
  ASSERT_EQ(log.report.problems.size(), 1u);
  EXPECT_NE(log.report.problems.front().find("2.pcd:109"), std::string::npos) << log.report.problems.front();
  EXPECT_NE(log.report.problems.front().find("header line 'FIELDS'"), std::string::npos) << log.report.problems.front();
}

TEST(PcdFolder, AFolderWithoutScansIsAnError) {
  test::TempDir dir;
  EXPECT_THROW(readPcdFolder(dir.path().string()), ReadError);
  EXPECT_THROW(readPcdFolder(dir.file("missing")), ReadError);
}

}  // namespace
}  // namespace contour_reg::io
