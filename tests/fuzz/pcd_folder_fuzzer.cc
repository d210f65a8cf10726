// libFuzzer target: arbitrary bytes as the one PCD file of a scan folder. The reader must
// return scans or throw io::ReadError.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "contour_reg/io/pcd_folder.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  static const std::string folder = "/tmp/contour_reg_fuzz_pcd_" + std::to_string(getpid());
  std::filesystem::create_directories(folder);
  const std::string path = folder + "/0000000001.000000.pcd";
  std::FILE *file = std::fopen(path.c_str(), "wb");
  if (!file) return 0;
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  try {
    (void)contour_reg::io::readPcdFolder(folder);
  } catch (const contour_reg::io::ReadError &) {
  }
  return 0;
}
