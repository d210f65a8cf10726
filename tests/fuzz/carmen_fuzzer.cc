// libFuzzer target: arbitrary bytes as a CARMEN log. The reader must return scans or throw
// io::ReadError; anything else (a crash, a sanitizer report, a hang) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include <unistd.h>

#include "contour_reg/io/carmen.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  static const std::string path = "/tmp/contour_reg_fuzz_" + std::to_string(getpid()) + ".clf";
  std::FILE *file = std::fopen(path.c_str(), "wb");
  if (!file) return 0;
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  try {
    const contour_reg::io::ScanLog log = contour_reg::io::readCarmen(path);
    for (const auto &entry : log.entries)
      if (entry.scan.ranges.size() > 100000) __builtin_trap();  // absurd beam counts must be refused
  } catch (const contour_reg::io::ReadError &) {
  }
  return 0;
}
