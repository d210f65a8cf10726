#pragma once
// CDR (OMG XCDR1), the encoding in which ROS 2 stores messages in its bags: a 4-byte
// encapsulation header (0x00 0x01 little endian, 0x00 0x00 big endian, two option bytes), then
// the fields in order, each primitive aligned to its own size counted from the end of that
// header; a string is its length with the terminating NUL (uint32), its bytes and the NUL; a
// sequence its element count (uint32) and its elements. Every read is checked against the
// message's bytes, and a sequence's count against what is left, before anything is allocated.
// Internal to the io module.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace contour_reg::io::detail {

inline bool hostIsLittleEndian() {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

/// `bytes` of a value in the other byte order, turned around.
template <std::size_t N>
void turnAround(unsigned char (&bytes)[N]) {
  for (std::size_t k = 0; k < N / 2; ++k) std::swap(bytes[k], bytes[N - 1 - k]);
}

class CdrReader {
 public:
  /// Throws std::runtime_error when the header is missing or names another encoding.
  CdrReader(const std::uint8_t *data, std::size_t size) : data_(data), size_(size) {
    if (size < 4 || data[0] != 0x00 || data[1] > 0x01)
      throw std::runtime_error("not a CDR message (encapsulation header)");
    little_endian_ = data[1] == 0x01;
    at_ = 4;
  }

  template <typename T>
  T read() {
    static_assert(std::is_arithmetic_v<T>);
    align(sizeof(T));
    need(sizeof(T));
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_ + at_, sizeof(T));
    at_ += sizeof(T);
    if (little_endian_ != hostIsLittleEndian()) turnAround(bytes);
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

  std::string readString() {
    const std::uint32_t length = read<std::uint32_t>();
    need(length);
    // The length counts the terminating NUL; a writer that leaves it out is read as well.
    std::size_t characters = length;
    if (characters > 0 && data_[at_ + characters - 1] == 0) --characters;
    std::string text(reinterpret_cast<const char *>(data_ + at_), characters);
    at_ += length;
    return text;
  }

  /// The count of a sequence whose elements take at least `smallest` bytes each, checked
  /// against the bytes left.
  std::uint32_t readCount(std::size_t smallest) {
    const std::uint32_t count = read<std::uint32_t>();
    if (std::size_t{count} * smallest > size_ - at_) throw std::runtime_error("a sequence longer than the message");
    return count;
  }

  /// A sequence of `T`: its count checked against the bytes left before it is allocated.
  template <typename T>
  std::vector<T> readSequence() {
    const std::uint32_t count = read<std::uint32_t>();
    if (count == 0) return {};
    align(sizeof(T));
    const std::size_t bytes = std::size_t{count} * sizeof(T);
    if (at_ > size_ || bytes > size_ - at_) throw std::runtime_error("a sequence longer than the message");
    std::vector<T> values(count);
    std::memcpy(values.data(), data_ + at_, bytes);
    at_ += bytes;
    if (little_endian_ != hostIsLittleEndian())
      for (T &value : values) {
        unsigned char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        turnAround(raw);
        std::memcpy(&value, raw, sizeof(T));
      }
    return values;
  }

 private:
  void align(std::size_t size) {
    const std::size_t offset = at_ - 4;
    at_ += (size - offset % size) % size;
  }
  void need(std::size_t bytes) const {
    if (at_ > size_ || bytes > size_ - at_) throw std::runtime_error("the message ends inside a field");
  }

  const std::uint8_t *data_;
  std::size_t size_, at_ = 0;
  bool little_endian_ = true;
};

/// Writes little-endian CDR, as ROS 2 on common hardware does.
class CdrWriter {
 public:
  CdrWriter() : bytes_{0x00, 0x01, 0x00, 0x00} {}

  template <typename T>
  void write(T value) {
    static_assert(std::is_arithmetic_v<T>);
    align(sizeof(T));
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (!hostIsLittleEndian()) turnAround(raw);
    bytes_.insert(bytes_.end(), raw, raw + sizeof(T));
  }
  void writeString(const std::string &text) {
    write(static_cast<std::uint32_t>(text.size() + 1));
    bytes_.insert(bytes_.end(), text.begin(), text.end());
    bytes_.push_back(0);
  }
  template <typename T>
  void writeSequence(const std::vector<T> &values) {
    write(static_cast<std::uint32_t>(values.size()));
    for (const T &value : values) write(value);
  }
  const std::vector<std::uint8_t> &bytes() const { return bytes_; }

 private:
  void align(std::size_t size) {
    const std::size_t offset = bytes_.size() - 4;
    bytes_.resize(bytes_.size() + (size - offset % size) % size, 0);
  }
  std::vector<std::uint8_t> bytes_;
};

}  // namespace contour_reg::io::detail
