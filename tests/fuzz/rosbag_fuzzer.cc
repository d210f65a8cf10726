// libFuzzer target: arbitrary bytes as a ROS 1 bag. The reader must return scans or throw
// io::ReadError, whatever the bag's records say.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include <unistd.h>

#include "contour_reg/io/rosbag.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  static const std::string path = "/tmp/contour_reg_fuzz_" + std::to_string(getpid()) + ".bag";
  std::FILE *file = std::fopen(path.c_str(), "wb");
  if (!file) return 0;
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  try {
    (void)contour_reg::io::readRosbag(path);
  } catch (const contour_reg::io::ReadError &) {
  }
  return 0;
}
