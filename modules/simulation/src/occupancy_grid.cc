#include "contour_reg/simulation/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <system_error>

#include <yaml-cpp/yaml.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::simulation {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// A point lies within half a cell diagonal of its cell centre, and so does every point of
// an occupied cell of its centre: clearance between centres overstates by at most this.
constexpr double kCentreSlack = 1.4143;

}  // namespace

OccupancyGrid::OccupancyGrid(int width, int height, double resolution, const Eigen::Vector2d &origin,
                             std::vector<Cell> cells)
    : width_(width), height_(height), resolution_(resolution), origin_(origin), cells_(std::move(cells)) {
  if (width < 0 || height < 0 || cells_.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::invalid_argument("OccupancyGrid: cells do not match width x height");
  if (!(resolution > 0.0) || !std::isfinite(resolution))
    throw std::invalid_argument("OccupancyGrid: resolution must be positive");
  clearance_cells_.assign(cells_.size(), std::numeric_limits<float>::infinity());
  if (cells_.empty() || std::none_of(cells_.begin(), cells_.end(), [](Cell c) { return c == Cell::kOccupied; })) return;
  // Distance transform: zero pixels are the obstacles.
  cv::Mat not_occupied(height_, width_, CV_8U);
  for (int row = 0; row < height_; ++row)
    for (int col = 0; col < width_; ++col)
      not_occupied.at<std::uint8_t>(row, col) = cells_[index(col, row)] == Cell::kOccupied ? 0 : 255;
  cv::Mat distance;
  cv::distanceTransform(not_occupied, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  for (int row = 0; row < height_; ++row)
    for (int col = 0; col < width_; ++col) clearance_cells_[index(col, row)] = distance.at<float>(row, col);
}

Eigen::Vector2i OccupancyGrid::cellOf(const Eigen::Vector2d &p) const {
  const Eigen::Vector2d q = (p - origin_) / resolution_;
  return {static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y()))};
}

double OccupancyGrid::clearance(const Eigen::Vector2d &p) const {
  const Eigen::Vector2i c = cellOf(p);
  if (!contains(c.x(), c.y())) return kInf;
  const double cells = clearance_cells_[index(c.x(), c.y())];
  return std::max(0.0, (cells - kCentreSlack) * resolution_);
}

bool OccupancyGrid::isFree(const Eigen::Vector2d &p) const {
  const Eigen::Vector2i c = cellOf(p);
  return contains(c.x(), c.y()) && cell(c.x(), c.y()) == Cell::kFree;
}

double OccupancyGrid::castRay(const Eigen::Vector2d &origin, const Eigen::Vector2d &direction) const {
  if (cells_.empty()) return kInf;
  // Work in cell units: p + t d, with t in cells along the ray.
  const Eigen::Vector2d p = (origin - origin_) / resolution_;
  const Eigen::Vector2d d = direction;
  const double size[2] = {static_cast<double>(width_), static_cast<double>(height_)};
  double t_enter = 0.0, t_exit = kInf;
  for (int axis = 0; axis < 2; ++axis) {  // clip the ray to the grid box
    if (std::abs(d[axis]) < 1e-12) {
      if (p[axis] < 0.0 || p[axis] >= size[axis]) return kInf;
      continue;
    }
    double t1 = -p[axis] / d[axis], t2 = (size[axis] - p[axis]) / d[axis];
    if (t1 > t2) std::swap(t1, t2);
    t_enter = std::max(t_enter, t1);
    t_exit = std::min(t_exit, t2);
  }
  if (t_enter >= t_exit) return kInf;

  const int step_x = d.x() > 0.0 ? 1 : -1, step_y = d.y() > 0.0 ? 1 : -1;
  const double delta_x = std::abs(d.x()) > 1e-12 ? std::abs(1.0 / d.x()) : kInf;
  const double delta_y = std::abs(d.y()) > 1e-12 ? std::abs(1.0 / d.y()) : kInf;
  double t = t_enter;
  while (t < t_exit) {
    const Eigen::Vector2d q = p + (t + 1e-9) * d;
    int col = std::clamp(static_cast<int>(std::floor(q.x())), 0, width_ - 1);
    int row = std::clamp(static_cast<int>(std::floor(q.y())), 0, height_ - 1);
    if (cells_[index(col, row)] == Cell::kOccupied) return t * resolution_;
    // Far from every obstacle: jump ahead by the clearance.
    const double free_cells = clearance_cells_[index(col, row)];
    if (free_cells > 3.0) {
      t += free_cells - 1.5;
      continue;
    }
    // Near obstacles: walk cell by cell (Amanatides and Woo), then look at the clearance again.
    double next_x = std::isfinite(delta_x) ? (col + (step_x > 0 ? 1 : 0) - p.x()) / d.x() : kInf;
    double next_y = std::isfinite(delta_y) ? (row + (step_y > 0 ? 1 : 0) - p.y()) / d.y() : kInf;
    for (int k = 0; k < 8; ++k) {
      if (next_x < next_y) {
        t = next_x;
        next_x += delta_x;
        col += step_x;
      } else {
        t = next_y;
        next_y += delta_y;
        row += step_y;
      }
      if (!contains(col, row) || t >= t_exit) return kInf;
      if (cells_[index(col, row)] == Cell::kOccupied) return t * resolution_;
    }
  }
  return kInf;
}

namespace {

// Where a map's resolution and origin were given, for its messages: "file:line: " in a YAML
// file, "file: " for an image read with options.
struct MapSettingsAt {
  std::string resolution, origin;
};

// Doubles resolve a coordinate x to about 2e-16 |x|. Cells narrower than this share of the
// map's largest coordinate are nearer to that limit than a grid can work with: where a point
// falls, a step along a path or a ray would round away.
constexpr double kLeastCellPerCoordinate = 1e-9;

// Refuses a grid of `size` cells of `resolution` m from `origin` that doubles cannot hold:
// a coordinate not finite, or cells too narrow for the map's coordinates.
void checkGeometry(const cv::Size &size, double resolution, const Eigen::Vector2d &origin, const MapSettingsAt &at) {
  if (!(resolution > 0.0) || !std::isfinite(resolution))
    throw io::ReadError(at.resolution + "the map resolution must be a positive number of metres per pixel");
  if (!origin.allFinite()) throw io::ReadError(at.origin + "the map origin must be finite");
  const Eigen::Vector2d far_corner = origin + resolution * Eigen::Vector2d(size.width, size.height);
  if (!far_corner.allFinite())
    throw io::ReadError(at.resolution + "the map, " + std::to_string(size.width) + " x " + std::to_string(size.height) +
                        " pixels of " + std::to_string(resolution) + " m, reaches beyond any finite coordinate");
  const double largest = std::max(origin.cwiseAbs().maxCoeff(), far_corner.cwiseAbs().maxCoeff());
  if (resolution < kLeastCellPerCoordinate * largest) {
    char message[160];
    std::snprintf(message, sizeof message, "cells of %g m cannot be told apart %g m from the origin of coordinates",
                  resolution, largest);
    throw io::ReadError(at.origin + message);
  }
}

OccupancyGrid gridFromImage(const std::string &path, const MapReadOptions &options, const MapSettingsAt &at) {
  std::error_code unreadable;  // a name the file system refuses (too long) is no such image either
  if (!std::filesystem::is_regular_file(path, unreadable)) throw io::ReadError(path + ": no such map image");
  cv::Mat image;
  try {
    image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception &error) {  // e.g. more pixels than OpenCV reads
    throw io::ReadError(path + ": OpenCV cannot read the image: " + error.err);
  }
  if (image.empty()) throw io::ReadError(path + ": not an image OpenCV can read (PGM, PNG, ...)");
  checkGeometry(image.size(), options.resolution, options.origin, at);
  std::vector<OccupancyGrid::Cell> cells(static_cast<std::size_t>(image.cols) * static_cast<std::size_t>(image.rows));
  for (int row = 0; row < image.rows; ++row) {
    const int grid_row = image.rows - 1 - row;  // the image's top row is the grid's last
    for (int col = 0; col < image.cols; ++col) {
      const double value = image.at<std::uint8_t>(row, col) / 255.0;
      const double occupancy = options.negate ? value : 1.0 - value;
      auto &c = cells[static_cast<std::size_t>(grid_row) * static_cast<std::size_t>(image.cols) +
                      static_cast<std::size_t>(col)];
      c = occupancy > options.occupied_threshold ? OccupancyGrid::Cell::kOccupied
          : occupancy < options.free_threshold   ? OccupancyGrid::Cell::kFree
                                                 : OccupancyGrid::Cell::kUnknown;
    }
  }
  return OccupancyGrid(image.cols, image.rows, options.resolution, options.origin, std::move(cells));
}

OccupancyGrid gridFromYaml(const std::string &path, MapReadOptions options) {
  YAML::Node node;
  try {
    node = YAML::LoadFile(path);
  } catch (const YAML::BadFile &) {
    throw io::ReadError(path + ": cannot open the map file");
  } catch (const YAML::Exception &error) {
    throw io::ReadError(path + ":" + std::to_string(error.mark.line + 1) + ": " + error.msg);
  }
  auto field = [&](const char *key) -> YAML::Node {
    if (!node.IsMap() || !node[key]) throw io::ReadError(path + ": the map file has no '" + key + "'");
    return node[key];
  };
  const auto lineOf = [&](const YAML::Node &value) {
    return path + ":" + std::to_string(value.Mark().line + 1) + ": ";
  };
  std::string image;
  MapSettingsAt at;
  try {
    image = field("image").as<std::string>();
    options.resolution = field("resolution").as<double>();
    at.resolution = lineOf(field("resolution"));
    const YAML::Node origin = field("origin");
    if (!origin.IsSequence() || origin.size() < 2) throw io::ReadError(lineOf(origin) + "origin must be [x, y, yaw]");
    options.origin = {origin[0].as<double>(), origin[1].as<double>()};
    at.origin = lineOf(origin);
    if (node["negate"]) options.negate = node["negate"].as<int>() != 0;
    if (node["occupied_thresh"]) options.occupied_threshold = node["occupied_thresh"].as<double>();
    if (node["free_thresh"]) options.free_threshold = node["free_thresh"].as<double>();
    for (const char *key : {"occupied_thresh", "free_thresh"})
      if (node[key] && !(node[key].as<double>() >= 0.0 && node[key].as<double>() <= 1.0))
        throw io::ReadError(lineOf(node[key]) + key + " must be an occupancy within 0-1");
  } catch (const YAML::Exception &error) {
    throw io::ReadError(path + ":" + std::to_string(error.mark.line + 1) + ": " + error.msg);
  }
  std::filesystem::path image_path(image);
  if (image_path.is_relative()) image_path = std::filesystem::path(path).parent_path() / image_path;
  return gridFromImage(image_path.string(), options, at);
}

}  // namespace

OccupancyGrid readOccupancyGrid(const std::string &path, const MapReadOptions &options) {
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension == ".yaml" || extension == ".yml") return gridFromYaml(path, options);
  return gridFromImage(path, options, {path + ": ", path + ": "});
}

}  // namespace contour_reg::simulation
