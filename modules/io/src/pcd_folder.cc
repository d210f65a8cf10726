#include "contour_reg/io/pcd_folder.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include "log_assembly.h"
#include "pcd_header_check.h"
#include "text_lines.h"

namespace contour_reg::io {

namespace {

namespace fs = std::filesystem;

struct Beam {
  double bearing, range;
  std::size_t index;
};

// Beam-order clouds (organized, NaN kept): bearing = a0 + index * increment exactly.
bool fitByIndex(const std::vector<Beam> &beams, std::size_t size, LaserScan &scan) {
  if (beams.size() < 2) return false;
  std::vector<double> unwrapped(beams.size());
  unwrapped[0] = beams[0].bearing;
  for (std::size_t k = 1; k < beams.size(); ++k)
    unwrapped[k] = unwrapped[k - 1] + std::remainder(beams[k].bearing - beams[k - 1].bearing, 2 * M_PI);
  const Beam &first = beams.front(), &last = beams.back();
  if (last.index == first.index) return false;
  const double increment = (unwrapped.back() - unwrapped.front()) / double(last.index - first.index);
  const double angle_min = unwrapped.front() - increment * double(first.index);
  for (std::size_t k = 0; k < beams.size(); ++k)
    if (std::abs(angle_min + increment * double(beams[k].index) - unwrapped[k]) > 1e-4) return false;
  scan.angle_min = angle_min;
  scan.angle_increment = increment;
  scan.ranges.assign(size, std::numeric_limits<float>::quiet_NaN());
  for (const Beam &b : beams) scan.ranges[b.index] = static_cast<float>(b.range);
  return increment != 0.0;
}

// Any other cloud: beams on a grid of the median bearing gap; false when points had to be moved.
bool binByBearing(std::vector<Beam> beams, LaserScan &scan) {
  std::sort(beams.begin(), beams.end(), [](const Beam &a, const Beam &b) { return a.bearing < b.bearing; });
  std::vector<double> gaps;
  for (std::size_t k = 1; k < beams.size(); ++k)
    if (beams[k].bearing - beams[k - 1].bearing > 1e-6) gaps.push_back(beams[k].bearing - beams[k - 1].bearing);
  if (gaps.empty()) gaps.push_back(M_PI / 180.0);
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  const double increment = gaps[gaps.size() / 2];
  const double angle_min = beams.front().bearing;
  const auto count = static_cast<std::size_t>(std::lround((beams.back().bearing - angle_min) / increment)) + 1;
  scan.angle_min = angle_min;
  scan.angle_increment = increment;
  scan.ranges.assign(count, std::numeric_limits<float>::quiet_NaN());
  bool exact = true;
  for (const Beam &b : beams) {
    const double position = (b.bearing - angle_min) / increment;
    const auto n = std::min<std::size_t>(count - 1, static_cast<std::size_t>(std::lround(position)));
    exact = exact && std::abs(position - double(n)) < 0.05;
    float &r = scan.ranges[n];
    if (!std::isfinite(r) || b.range < r) r = static_cast<float>(b.range);
  }
  return exact;
}

// A header the point conversion can trust: x and y as single floats, every field inside
// the point, no field of zero count (PCL's conversion overruns its buffers otherwise).
bool plainXYHeader(const pcl::PCLPointCloud2 &header) {
  bool x = false, y = false;
  for (const pcl::PCLPointField &field : header.fields) {
    const int size = pcl::getFieldSize(field.datatype);
    if (size <= 0 || field.count < 1) return false;
    if (std::size_t(field.offset) + std::size_t(size) * field.count > header.point_step) return false;
    if (field.name == "x") x = field.datatype == pcl::PCLPointField::FLOAT32 && field.count == 1;
    if (field.name == "y") y = field.datatype == pcl::PCLPointField::FLOAT32 && field.count == 1;
  }
  return x && y;
}

}  // namespace

ScanLog readPcdFolder(const std::string &folder, double max_range) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) throw ReadError(folder + ": not a folder");
  std::vector<fs::path> files;
  for (const auto &item : fs::directory_iterator(folder, error))
    if (item.path().extension() == ".pcd") files.push_back(item.path());
  std::sort(files.begin(), files.end());
  ScanLog log;
  log.source = folder;
  pcl::PCDReader reader;
  for (std::size_t k = 0; k < files.size(); ++k) {
    const std::string file = files[k].string();
    ++log.report.lines;
    pcl::PointCloud<pcl::PointXYZ> cloud;
    // Our own check of the header first: PCL's reader trusts it and is not safe on bad ones.
    std::size_t bad_line = 0;
    if (const std::string problem = detail::checkPcdHeader(file, bad_line); !problem.empty()) {
      log.report.add(file, bad_line, problem);
      continue;
    }
    bool read = false;
    try {
      pcl::PCLPointCloud2 header;
      Eigen::Vector4f origin;
      Eigen::Quaternionf orientation;
      int version = 0, data_type = 0;
      unsigned int data_index = 0;
      // Read untyped, check the very fields the conversion will use, then convert.
      pcl::PCLPointCloud2 blob;
      read = reader.readHeader(file, header, origin, orientation, version, data_type, data_index) == 0 &&
             std::size_t(header.width) * header.height > 0 && reader.read(file, blob) == 0 && plainXYHeader(blob) &&
             blob.data.size() >= std::size_t(blob.point_step) * blob.width * blob.height;
      if (read) pcl::fromPCLPointCloud2(blob, cloud);
    } catch (const std::exception &) {
      read = false;
    }
    if (!read) {
      log.report.add(file, 1, "not a readable PCD file with x and y fields");
      continue;
    }
    std::vector<Beam> beams;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const auto &p = cloud[i];
      const double range = std::hypot(double(p.x), double(p.y));
      if (std::isfinite(range) && range > 0.0 && range < max_range) beams.push_back({std::atan2(p.y, p.x), range, i});
    }
    if (beams.size() < 2) {
      log.report.add(file, 1, "fewer than 2 usable points");
      continue;
    }
    LogEntry entry;
    LaserScan &scan = entry.scan;
    scan.range_max = max_range;
    double stamp = 0.0;
    if (detail::parseNumber(files[k].stem().string(), stamp) && std::isfinite(stamp))
      scan.stamp = stamp;
    else if (cloud.header.stamp != 0)
      scan.stamp = double(cloud.header.stamp) * 1e-6;
    else
      scan.stamp = double(k);
    if (!fitByIndex(beams, cloud.size(), scan) && !binByBearing(beams, scan))
      log.report.problems.push_back(file + ": bearings not on a uniform grid; points moved to the nearest of " +
                                    std::to_string(scan.ranges.size()) + " beams");
    log.entries.push_back(std::move(entry));
  }
  if (log.entries.empty())
    throw ReadError(folder + ": no usable PCD scan among " + std::to_string(files.size()) + " .pcd files" +
                    (log.report.problems.empty() ? "" : " (first problem: " + log.report.problems.front() + ")"));
  detail::finishLog(log, {});  // stamp order; PCD scans carry no odometry
  return log;
}

}  // namespace contour_reg::io
