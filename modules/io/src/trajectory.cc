#include "contour_reg/io/trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "text_lines.h"

namespace contour_reg::io {

namespace {

// Reads a whitespace table of at least `columns` numbers per line, skipping '#' lines; a row
// for which `check` says what is wrong is an error naming the line.
std::vector<std::vector<double>> readTable(const std::string &path, std::size_t columns,
                                           const char *(*check)(const std::vector<double> &) = nullptr) {
  detail::LineReader reader(path);
  if (!reader.isOpen()) throw ReadError(path + ": cannot open");
  std::vector<std::vector<double>> rows;
  std::string line;
  while (reader.next(line)) {
    const auto fields = detail::splitFields(line);
    if (fields.empty() || fields[0][0] == '#') continue;
    std::vector<double> row(columns);
    bool ok = fields.size() >= columns;
    for (std::size_t k = 0; ok && k < columns; ++k)
      ok = detail::parseNumber(fields[k], row[k]) && std::isfinite(row[k]);
    if (!ok)
      throw ReadError(path + ":" + std::to_string(reader.lineNumber()) + ": expected " + std::to_string(columns) +
                      " numbers");
    if (const char *wrong = check ? check(row) : nullptr)
      throw ReadError(path + ":" + std::to_string(reader.lineNumber()) + ": " + wrong);
    rows.push_back(std::move(row));
  }
  if (!reader.error().empty())
    throw ReadError(path + ":" + std::to_string(reader.lineNumber() + 1) + ": " + reader.error());
  return rows;
}

}  // namespace

void writeTum(const std::string &path, const Trajectory &trajectory, const std::string &comment) {
  std::FILE *file = std::fopen(path.c_str(), "w");
  if (!file) throw ReadError(path + ": cannot write");
  if (!comment.empty()) std::fprintf(file, "# %s\n", comment.c_str());
  std::fprintf(file, "# timestamp x y z qx qy qz qw\n");
  for (const StampedPose &p : trajectory)
    std::fprintf(file, "%.6f %.6f %.6f 0 0 0 %.9f %.9f\n", p.stamp, p.pose.x, p.pose.y, std::sin(0.5 * p.pose.yaw),
                 std::cos(0.5 * p.pose.yaw));
  const bool ok = std::fflush(file) == 0;
  std::fclose(file);
  if (!ok) throw ReadError(path + ": write failed");
}

// A TUM row's quaternion (qx qy qz qw, columns 4-7) has no rotation when its norm is zero (or
// too small to square in double precision).
const char *withoutRotation(const std::vector<double> &r) {
  const double squared_norm = r[4] * r[4] + r[5] * r[5] + r[6] * r[6] + r[7] * r[7];
  return squared_norm > 1e-300 && std::isfinite(squared_norm) ? nullptr : "the quaternion (qx qy qz qw) is no rotation";
}

Trajectory readTum(const std::string &path) {
  Trajectory trajectory;
  for (const auto &r : readTable(path, 8, withoutRotation)) {
    const double qx = r[4], qy = r[5], qz = r[6], qw = r[7];
    // The yaw of the rotation q / |q|: the form that does not assume |q| = 1.
    const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), qw * qw + qx * qx - qy * qy - qz * qz);
    trajectory.push_back({r[0], {r[1], r[2], yaw}});
  }
  std::stable_sort(trajectory.begin(), trajectory.end(),
                   [](const StampedPose &a, const StampedPose &b) { return a.stamp < b.stamp; });
  return trajectory;
}

std::vector<Relation> readRelations(const std::string &path) {
  std::vector<Relation> relations;
  for (const auto &r : readTable(path, 8)) relations.push_back({r[0], r[1], {r[2], r[3], r[7]}});
  return relations;
}

}  // namespace contour_reg::io
