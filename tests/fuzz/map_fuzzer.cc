// libFuzzer target: arbitrary bytes as a map. The first byte chooses what they are: the
// map_server YAML file of a fixed 8 x 8 PGM, or the image itself read with default options.
// The reader must return a grid or throw io::ReadError; a grid it returns must take rays and
// clearance queries. (Path placement in a vast map: tests/simulation.)
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "contour_reg/io/scan_log.h"
#include "contour_reg/simulation/occupancy_grid.h"
#include "contour_reg/simulation/world.h"

namespace {

void writeFile(const std::string &path, const std::uint8_t *data, std::size_t size) {
  std::FILE *file = std::fopen(path.c_str(), "wb");
  if (!file) return;
  std::fwrite(data, 1, size, file);
  std::fclose(file);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  namespace sim = contour_reg::simulation;
  static const std::string folder = "/tmp/contour_reg_fuzz_map_" + std::to_string(getpid());
  static const bool made = [] {
    std::filesystem::create_directories(folder);
    std::string pgm = "P5\n8 8\n255\n";
    for (int k = 0; k < 64; ++k) pgm += static_cast<char>(k % 8 == 0 || k % 8 == 7 || k < 8 || k >= 56 ? 0 : 254);
    writeFile(folder + "/fixed.pgm", reinterpret_cast<const std::uint8_t *>(pgm.data()), pgm.size());
    return true;
  }();
  (void)made;
  if (size < 1) return 0;
  const bool yaml = data[0] % 2 == 0;
  const std::string path = folder + (yaml ? "/map.yaml" : "/map.pgm");
  writeFile(path, data + 1, size - 1);
  try {
    sim::World world;
    world.setGrid(std::make_shared<sim::OccupancyGrid>(sim::readOccupancyGrid(path)));
    const Eigen::Vector2d middle =
        world.grid()->origin() + 0.5 * world.grid()->resolution() * Eigen::Vector2d(world.grid()->width(), 0.0);
    for (int k = 0; k < 8; ++k) (void)world.castRay(middle, Eigen::Vector2d(std::cos(k * 0.8), std::sin(k * 0.8)));
    for (int k = 0; k < 8; ++k) (void)world.clearance(middle + Eigen::Vector2d(k, -k));
  } catch (const contour_reg::io::ReadError &) {
  }
  return 0;
}
