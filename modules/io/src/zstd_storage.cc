#include "zstd_storage.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io::detail {

namespace {

constexpr std::uint8_t kZstdMagic[4] = {0x28, 0xB5, 0x2F, 0xFD};
constexpr char kZstdExtension[] = ".zstd";
// A file compressed whole decompresses to at most this many times its size, or kSmallestLimit.
constexpr std::uintmax_t kLargestRatio = 1000;
constexpr std::uintmax_t kSmallestLimit = std::uintmax_t{64} << 20;

// Decompresses `input` into `write(bytes, size)`; `last` is ZSTD_decompressStream's last
// answer, 0 once a frame has ended and all its bytes are out.
template <typename Write>
void decompressInto(ZSTD_DCtx *context, ZSTD_inBuffer &input, std::vector<char> &buffer, std::size_t &last,
                    Write write) {
  bool full = false;  // the output filled the buffer: more may wait in the context
  while (input.pos < input.size || (full && last != 0)) {
    ZSTD_outBuffer output{buffer.data(), buffer.size(), 0};
    last = ZSTD_decompressStream(context, &output, &input);
    if (ZSTD_isError(last)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(last));
    write(buffer.data(), output.pos);
    full = output.pos == output.size;
  }
}

}  // namespace

bool isZstdFrame(const std::uint8_t *data, std::size_t size) {
  return size >= sizeof kZstdMagic && std::memcmp(data, kZstdMagic, sizeof kZstdMagic) == 0;
}

bool isZstdFile(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  char magic[sizeof kZstdMagic] = {};
  return in.read(magic, sizeof magic) && isZstdFrame(reinterpret_cast<const std::uint8_t *>(magic), sizeof magic);
}

ZstdDecompressor::ZstdDecompressor() : context_(ZSTD_createDCtx(), &ZSTD_freeDCtx), buffer_(ZSTD_DStreamOutSize()) {
  if (!context_) throw std::runtime_error("zstd: no decompression context");
}

void ZstdDecompressor::decompress(const std::uint8_t *data, std::size_t size, std::size_t limit,
                                  std::vector<std::uint8_t> &out) {
  out.clear();
  ZSTD_DCtx_reset(context_.get(), ZSTD_reset_session_only);  // whatever the last input left
  ZSTD_inBuffer input{data, size, 0};
  std::size_t last = 0;
  decompressInto(context_.get(), input, buffer_, last, [&](const char *bytes, std::size_t count) {
    if (count > limit - out.size())
      throw std::runtime_error("it decompresses to more than " + std::to_string(limit) + " bytes");
    out.insert(out.end(), bytes, bytes + count);
  });
  if (last != 0) throw std::runtime_error("zstd: the data ends inside a frame");
}

DecompressedFile::DecompressedFile(const std::string &from) {
  if (!isZstdFile(from)) throw ReadError(from + ": cannot open, or not a zstd file");
  std::ifstream in(from, std::ios::binary);
  std::string pattern = (std::filesystem::temp_directory_path() / "contour_reg-bag-XXXXXX").string();
  const int descriptor = mkstemp(pattern.data());
  if (descriptor < 0) throw ReadError(from + ": cannot create a temporary file to decompress it into");
  close(descriptor);
  path_ = pattern;
  try {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    const std::unique_ptr<ZSTD_DCtx, std::size_t (*)(ZSTD_DCtx *)> context(ZSTD_createDCtx(), &ZSTD_freeDCtx);
    if (!context) throw std::runtime_error("zstd: no decompression context");
    std::vector<char> chunk(ZSTD_DStreamInSize()), buffer(ZSTD_DStreamOutSize());
    std::size_t last = 0;
    // A bag's messages do not compress much further: a file that decompresses to far more than
    // its size is broken or hostile, not a bag, and is not written out to the end.
    const std::uintmax_t limit =
        std::max<std::uintmax_t>(kSmallestLimit, kLargestRatio * std::filesystem::file_size(from));
    std::uintmax_t written = 0;
    while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
      ZSTD_inBuffer input{chunk.data(), static_cast<std::size_t>(in.gcount()), 0};
      decompressInto(context.get(), input, buffer, last, [&](const char *bytes, std::size_t count) {
        written += count;
        if (written > limit)
          throw std::runtime_error("it decompresses to more than " + std::to_string(kLargestRatio) +
                                   " times its size: not a compressed bag");
        if (!out.write(bytes, static_cast<std::streamsize>(count)))
          throw std::runtime_error("cannot write the temporary file " + path_);
      });
    }
    if (last != 0) throw std::runtime_error("the file ends inside a zstd frame (cut short?)");
    out.close();
    if (!out) throw std::runtime_error("cannot write the temporary file " + path_);
  } catch (const std::runtime_error &error) {
    std::remove(path_.c_str());
    throw ReadError(from + ": " + error.what());
  }
}

DecompressedFile::~DecompressedFile() { std::remove(path_.c_str()); }

std::string withoutZstd(const std::string &path) {
  const std::size_t length = sizeof kZstdExtension - 1;
  if (path.size() > length && path.compare(path.size() - length, length, kZstdExtension) == 0)
    return path.substr(0, path.size() - length);
  return path;
}

}  // namespace contour_reg::io::detail
