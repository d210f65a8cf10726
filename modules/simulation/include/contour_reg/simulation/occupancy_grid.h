#pragma once
/// @file occupancy_grid.h
/// Occupancy maps as ROS map_server writes them (an image and a YAML file) or as a bare
/// PGM with a resolution, and ray casting through them.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace contour_reg::simulation {

/// How to read a map image when no YAML file says it (map_server's defaults).
struct MapReadOptions {
  double resolution = 0.05;                          ///< m per pixel
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< m, world position of the lower-left pixel's corner
  double occupied_threshold = 0.65;                  ///< occupancy p = (255 - value) / 255 above it: obstacle
  double free_threshold = 0.196;                     ///< p below it: free; between the two: unknown
  bool negate = false;                               ///< white is occupied
};

/// A grid of cells, row 0 at the bottom (lowest y) as in ROS; an image's top row is the
/// grid's last row.
class OccupancyGrid {
 public:
  enum class Cell : std::uint8_t { kFree, kUnknown, kOccupied };

  OccupancyGrid() = default;
  /// A grid of `width` x `height` cells given row by row from the bottom row; throws
  /// std::invalid_argument when `cells` has another size or the resolution is not positive.
  OccupancyGrid(int width, int height, double resolution, const Eigen::Vector2d &origin, std::vector<Cell> cells);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  const Eigen::Vector2d &origin() const { return origin_; }

  Cell cell(int col, int row) const { return cells_[index(col, row)]; }
  bool contains(int col, int row) const { return col >= 0 && row >= 0 && col < width_ && row < height_; }
  /// The cell holding world point `p` (may lie outside the grid).
  Eigen::Vector2i cellOf(const Eigen::Vector2d &p) const;

  /// Distance from `p` to the nearest occupied cell, m (a lower bound, exact to one cell);
  /// 0 inside an obstacle, +inf when the grid has none.
  double clearance(const Eigen::Vector2d &p) const;
  /// True when `p` lies in a free cell.
  bool isFree(const Eigen::Vector2d &p) const;

  /// Distance along the ray from `origin` in unit direction `direction` to the boundary of
  /// the first occupied cell, or +inf when the ray leaves the grid first.
  double castRay(const Eigen::Vector2d &origin, const Eigen::Vector2d &direction) const;

 private:
  std::size_t index(int col, int row) const {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(col);
  }

  int width_ = 0, height_ = 0;
  double resolution_ = 0.05;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  std::vector<Cell> cells_;
  // Distance in cells from each cell centre to the nearest occupied cell centre: it lets
  // rays skip open space.
  std::vector<float> clearance_cells_;
};

/// Reads a map: a map_server YAML file (image, resolution, origin, negate, occupied_thresh,
/// free_thresh; the image path relative to the YAML file), or an image (PGM, PNG) read with
/// `options`. Throws io::ReadError naming the file (and the line, for YAML) when it cannot.
OccupancyGrid readOccupancyGrid(const std::string &path, const MapReadOptions &options = {});

}  // namespace contour_reg::simulation
