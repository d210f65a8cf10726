#pragma once
// A check of a ROS 1 bag's structure (format 2.0) before rosbag_storage reads it: the library
// trusts the lengths its records give and reads out of bounds on corrupt ones, and it
// decompresses a chunk that does not decompress once more for every message in it.
//
// The check reads the version line as rosbag_storage does, then walks the file record by
// record: every record (a header of "name=value" fields, each with its length, then the data
// with its length) must fit where it lies, the bag header's index position and each chunk
// info's chunk position must point at a record, and each index entry at a record of the chunk
// before it. A chunk must decompress to records that fit it exactly: a message whose index
// entry points into a chunk that does not decompress, or at or past a record that does not
// fit, is unsafe to read; the others of that chunk are not. Built with rosbag_storage only.

#include <cstdint>
#include <map>
#include <string>
#include <utility>

namespace contour_reg::io::detail {

struct BagCheck {
  /// What makes the whole bag unreadable, beginning with the byte of the file where it is;
  /// "" when nothing does, or the bag is not of format 2.0 (rosbag_storage decides then).
  std::string fatal;
  /// The messages not to read, by connection number and stamp (stampKey, as the index gives
  /// them): why, with the byte of the file of their chunk. A message of the same connection
  /// and stamp elsewhere is not read either.
  std::map<std::pair<std::uint32_t, std::uint64_t>, std::string> unsafe;
};

/// Checks the bag at `path` as above.
BagCheck checkBagStructure(const std::string &path);

/// The key of BagCheck::unsafe of a message stamped `seconds`, `nanoseconds`, normalised as
/// ros::Time normalises them (nanoseconds of a second or more carry into the seconds).
inline std::uint64_t stampKey(std::uint64_t seconds, std::uint64_t nanoseconds) {
  constexpr std::uint64_t kSecond = 1'000'000'000;
  return (seconds + nanoseconds / kSecond) << 32 | nanoseconds % kSecond;
}

}  // namespace contour_reg::io::detail
