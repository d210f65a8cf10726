#pragma once
// rosbag2's compression (rosbag2_compression, `ros2 bag record --compression-format zstd`):
// in file mode each storage file is compressed whole after it is closed and renamed
// `name.db3.zstd` or `name.mcap.zstd`; in message mode each message's bytes are compressed
// on their own. Both are zstd frames, told apart from a storage file or a CDR message by
// the frame's magic number. Internal to the io module.

#include <zstd.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace contour_reg::io::detail {

/// Whether `data` begins with a zstd frame's magic number (a CDR message begins with its
/// encapsulation, 00 00 or 00 01).
bool isZstdFrame(const std::uint8_t *data, std::size_t size);

/// Whether the file at `path` begins with a zstd frame (false when it cannot be read).
bool isZstdFile(const std::string &path);

/// Decompresses zstd frames one input at a time (a bag's messages, each compressed on its own),
/// keeping its context and buffer from one input to the next.
class ZstdDecompressor {
 public:
  ZstdDecompressor();
  /// The zstd frames of `data` decompressed into `out`; throws std::runtime_error saying why
  /// when they do not decompress, end inside a frame or hold more than `limit` bytes.
  void decompress(const std::uint8_t *data, std::size_t size, std::size_t limit, std::vector<std::uint8_t> &out);

 private:
  std::unique_ptr<ZSTD_DCtx, std::size_t (*)(ZSTD_DCtx *)> context_;
  std::vector<char> buffer_;
};

/// A storage file compressed in file mode: `from` decompressed into a new temporary file,
/// removed again when this goes out of scope. Throws ReadError naming `from` when it is not a
/// zstd file, does not decompress or is cut short, or the temporary file cannot be written.
class DecompressedFile {
 public:
  explicit DecompressedFile(const std::string &from);
  ~DecompressedFile();
  DecompressedFile(const DecompressedFile &) = delete;
  DecompressedFile &operator=(const DecompressedFile &) = delete;
  /// The decompressed file.
  const std::string &path() const { return path_; }

 private:
  std::string path_;
};

/// `path` without a final ".zstd": the storage file a file-mode compressed one holds.
std::string withoutZstd(const std::string &path);

}  // namespace contour_reg::io::detail
