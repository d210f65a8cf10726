// libFuzzer target: arbitrary bytes as the MCAP file of a ROS 2 bag. The reader must return
// scans or throw io::ReadError, whatever the file's records and chunks declare.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include <unistd.h>

#include "contour_reg/io/rosbag2.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  static const std::string path = "/tmp/contour_reg_fuzz_" + std::to_string(getpid()) + ".mcap";
  std::FILE *file = std::fopen(path.c_str(), "wb");
  if (!file) return 0;
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  try {
    (void)contour_reg::io::readRosbag2(path);
  } catch (const contour_reg::io::ReadError &) {
  }
  return 0;
}
