#include "mcap.h"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>

#include "contour_reg/io/scan_log.h"
#include "message_definitions.h"

namespace contour_reg::io::detail {

namespace {

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kDataEnd = 0x0F,
};
// Bytes of a record's opcode and length.
constexpr std::size_t kRecordHead = 9;
// No chunk of a ROS 2 bag decompresses to more (rosbag2 writes chunks of about 1 MB).
constexpr std::uint64_t kLargestChunk = std::uint64_t{1} << 30;

// Little-endian fields of a record, each checked against the record's bytes.
class Cursor {
 public:
  Cursor(const std::uint8_t *data, std::size_t size) : data_(data), size_(size) {}
  template <typename T>
  T get() {
    need(sizeof(T));
    T value = 0;
    for (std::size_t k = 0; k < sizeof(T); ++k) value |= static_cast<T>(static_cast<T>(data_[at_ + k]) << (8 * k));
    at_ += sizeof(T);
    return value;
  }
  std::string string() {
    const auto length = get<std::uint32_t>();
    need(length);
    std::string text(reinterpret_cast<const char *>(data_ + at_), length);
    at_ += length;
    return text;
  }
  // `length` bytes from here.
  const std::uint8_t *bytes(std::uint64_t length) {
    need(length);
    const std::uint8_t *start = data_ + at_;
    at_ += static_cast<std::size_t>(length);
    return start;
  }
  std::size_t left() const { return size_ - at_; }

 private:
  void need(std::uint64_t bytes) const {
    if (bytes > size_ - at_) throw std::runtime_error("a field runs past its record");
  }
  const std::uint8_t *data_;
  std::size_t size_, at_ = 0;
};

class Reader {
 public:
  explicit Reader(const StorageVisitor &visitor) : visitor_(visitor) {}

  // One record of the data section or of a chunk; throws std::runtime_error when a field
  // does not fit in it.
  void record(std::uint8_t opcode, const std::uint8_t *data, std::size_t size) {
    Cursor in(data, size);
    if (opcode == kSchema) {
      const auto id = in.get<std::uint16_t>();
      schemas_[id] = in.string();
    } else if (opcode == kChannel) {
      StoredTopic channel;
      channel.id = in.get<std::uint16_t>();
      const auto schema = in.get<std::uint16_t>();
      channel.name = in.string();
      channel.message_encoding = in.string();
      const auto found = schemas_.find(schema);
      if (found != schemas_.end()) channel.type = found->second;
      if (visitor_.topic) visitor_.topic(channel);
    } else if (opcode == kMessage) {
      const auto channel = in.get<std::uint16_t>();
      in.get<std::uint32_t>();  // sequence
      in.get<std::uint64_t>();  // log time
      in.get<std::uint64_t>();  // publish time
      const std::size_t rest = in.left();
      if (visitor_.message) visitor_.message(channel, in.bytes(rest), rest);
    }
  }

  // The records of the chunk whose record is `data`, at `byte` of the file.
  void chunk(std::uint64_t byte, const std::uint8_t *data, std::size_t size) {
    std::string why;
    try {
      Cursor in(data, size);
      in.get<std::uint64_t>();  // message start time
      in.get<std::uint64_t>();  // message end time
      const auto uncompressed_size = in.get<std::uint64_t>();
      const auto crc = in.get<std::uint32_t>();
      const std::string compression = in.string();
      const auto length = in.get<std::uint64_t>();
      const std::uint8_t *records = in.bytes(length);
      if (compression.empty()) {
        walk(records, static_cast<std::size_t>(length), crc);
        return;
      }
      if (uncompressed_size > kLargestChunk)
        throw std::runtime_error("it claims " + std::to_string(uncompressed_size) + " bytes decompressed");
      buffer_.resize(static_cast<std::size_t>(uncompressed_size));
      if (compression == "zstd") {
        const std::size_t got = ZSTD_decompress(buffer_.data(), buffer_.size(), records, length);
        if (ZSTD_isError(got)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(got));
        if (got != buffer_.size()) throw std::runtime_error("it decompresses to fewer bytes than it claims");
      } else if (compression == "lz4") {
        decompressLz4(records, static_cast<std::size_t>(length));
      } else {
        throw std::runtime_error("compression '" + compression + "' is not read");
      }
      walk(buffer_.data(), buffer_.size(), crc);
      return;
    } catch (const std::exception &error) {
      why = error.what();
    }
    if (visitor_.lost) visitor_.lost(byte, why);
  }

 private:
  void decompressLz4(const std::uint8_t *source, std::size_t size) {
    LZ4F_dctx *context = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION)))
      throw std::runtime_error("lz4: no decompression context");
    std::size_t written = 0, read = 0, hint = 1;
    std::string error;
    while (hint != 0 && read < size) {
      std::size_t out = buffer_.size() - written, in = size - read;
      hint = LZ4F_decompress(context, buffer_.data() + written, &out, source + read, &in, nullptr);
      if (LZ4F_isError(hint)) {
        error = std::string("lz4: ") + LZ4F_getErrorName(hint);
        break;
      }
      written += out;
      read += in;
      if (out == 0 && in == 0) break;  // the buffer is full and the frame goes on
    }
    LZ4F_freeDecompressionContext(context);
    if (!error.empty()) throw std::runtime_error(error);
    if (hint != 0 || written != buffer_.size())
      throw std::runtime_error("lz4: it does not decompress to the bytes it claims");
  }

  // The records of a chunk, its CRC checked first when it has one.
  void walk(const std::uint8_t *data, std::size_t size, std::uint32_t crc) {
    if (crc != 0 && crc32(0, data, static_cast<uInt>(size)) != crc)
      throw std::runtime_error("its records do not match its CRC");
    Cursor in(data, size);
    while (in.left() > 0) {
      const auto opcode = in.get<std::uint8_t>();
      const auto length = in.get<std::uint64_t>();
      record(opcode, in.bytes(length), static_cast<std::size_t>(length));
    }
  }

  const StorageVisitor &visitor_;
  std::map<std::uint16_t, std::string> schemas_;  // id -> name
  std::vector<std::uint8_t> buffer_;              // a chunk decompressed
};

class Writer {
 public:
  explicit Writer(std::string compression) : compression_(std::move(compression)) {}

  // A record of `opcode` with the content of `fields` appended to `out`.
  template <typename Fields>
  static void record(std::vector<std::uint8_t> &out, std::uint8_t opcode, Fields fields) {
    std::vector<std::uint8_t> content;
    fields(content);
    out.push_back(opcode);
    put<std::uint64_t>(out, content.size());
    out.insert(out.end(), content.begin(), content.end());
  }
  template <typename T>
  static void put(std::vector<std::uint8_t> &out, T value) {
    for (std::size_t k = 0; k < sizeof(T); ++k) out.push_back(static_cast<std::uint8_t>(value >> (8 * k)));
  }
  static void put(std::vector<std::uint8_t> &out, const std::string &text) {
    put<std::uint32_t>(out, static_cast<std::uint32_t>(text.size()));
    out.insert(out.end(), text.begin(), text.end());
  }

  // The chunk of `records` (message records) appended to `out`.
  void chunk(std::vector<std::uint8_t> &out, const std::vector<std::uint8_t> &records, std::uint64_t first,
             std::uint64_t last) const {
    std::vector<std::uint8_t> stored;
    if (compression_ == "zstd") {
      stored.resize(ZSTD_compressBound(records.size()));
      const std::size_t size = ZSTD_compress(stored.data(), stored.size(), records.data(), records.size(), 3);
      if (ZSTD_isError(size)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(size));
      stored.resize(size);
    } else if (compression_ == "lz4") {
      stored.resize(LZ4F_compressFrameBound(records.size(), nullptr));
      const std::size_t size =
          LZ4F_compressFrame(stored.data(), stored.size(), records.data(), records.size(), nullptr);
      if (LZ4F_isError(size)) throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(size));
      stored.resize(size);
    } else {
      stored = records;
    }
    record(out, kChunk, [&](std::vector<std::uint8_t> &c) {
      put<std::uint64_t>(c, first);
      put<std::uint64_t>(c, last);
      put<std::uint64_t>(c, records.size());
      put<std::uint32_t>(c, static_cast<std::uint32_t>(crc32(0, records.data(), static_cast<uInt>(records.size()))));
      put(c, compression_);
      put<std::uint64_t>(c, stored.size());
      c.insert(c.end(), stored.begin(), stored.end());
    });
  }

 private:
  std::string compression_;
};

}  // namespace

void visitMcap(const std::string &path, const StorageVisitor &visitor) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw ReadError(path + ": cannot open");
  const auto size = static_cast<std::uint64_t>(file.tellg());
  file.seekg(0);
  std::uint8_t magic[sizeof kMagic] = {};
  if (!file.read(reinterpret_cast<char *>(magic), sizeof magic) || std::memcmp(magic, kMagic, sizeof magic) != 0)
    throw ReadError(path + ": not an MCAP file (it does not begin with the MCAP magic)");
  Reader reader(visitor);
  std::vector<std::uint8_t> content;
  std::uint64_t at = sizeof kMagic;
  while (size - at >= kRecordHead) {
    std::uint8_t head[kRecordHead];
    file.read(reinterpret_cast<char *>(head), sizeof head);
    Cursor in(head, sizeof head);
    const auto opcode = in.get<std::uint8_t>();
    const auto length = in.get<std::uint64_t>();
    if (!file || length > size - at - kRecordHead)
      throw ReadError(path + ": byte " + std::to_string(at) + ": a record longer than the file (cut short?)");
    if (opcode == kDataEnd || opcode == kFooter) return;
    if (opcode == kSchema || opcode == kChannel || opcode == kMessage || opcode == kChunk) {
      content.resize(static_cast<std::size_t>(length));
      file.read(reinterpret_cast<char *>(content.data()), static_cast<std::streamsize>(length));
      if (!file) throw ReadError(path + ": byte " + std::to_string(at) + ": cannot read the record");
      if (opcode == kChunk) {
        reader.chunk(at, content.data(), content.size());
      } else {
        try {
          reader.record(opcode, content.data(), content.size());
        } catch (const std::runtime_error &error) {
          throw ReadError(path + ": byte " + std::to_string(at) + ": " + error.what());
        }
      }
    } else {
      file.seekg(static_cast<std::streamoff>(length), std::ios::cur);
    }
    at += kRecordHead + length;
  }
  throw ReadError(path + ": byte " + std::to_string(at) + ": the file ends before its data end record (cut short?)");
}

void writeMcap(const std::string &path, const std::vector<StoredTopic> &topics,
               const std::vector<StoredMessage> &messages, const std::string &compression) {
  std::vector<std::uint8_t> out(std::begin(kMagic), std::end(kMagic));
  Writer::record(out, kHeader, [](std::vector<std::uint8_t> &c) {
    Writer::put(c, std::string("ros2"));
    Writer::put(c, std::string("contour_reg"));
  });
  for (std::size_t k = 0; k < topics.size(); ++k) {
    const auto id = static_cast<std::uint16_t>(k + 1);
    Writer::record(out, kSchema, [&](std::vector<std::uint8_t> &c) {
      Writer::put<std::uint16_t>(c, id);
      Writer::put(c, topics[k].type);
      Writer::put(c, std::string("ros2msg"));
      Writer::put(c, messageDefinition(topics[k].type));
    });
    Writer::record(out, kChannel, [&](std::vector<std::uint8_t> &c) {
      Writer::put<std::uint16_t>(c, id);
      Writer::put<std::uint16_t>(c, id);
      Writer::put(c, topics[k].name);
      Writer::put(c, topics[k].message_encoding);
      Writer::put<std::uint32_t>(c, 0);  // metadata: none
    });
  }
  const Writer writer(compression);
  std::vector<std::uint8_t> records;
  std::uint64_t first = 0, last = 0;
  std::uint32_t sequence = 0;
  for (const StoredMessage &message : messages) {
    if (records.empty()) first = message.log_time;
    last = std::max(last, message.log_time);
    Writer::record(records, kMessage, [&](std::vector<std::uint8_t> &c) {
      Writer::put<std::uint16_t>(c, static_cast<std::uint16_t>(message.topic + 1));
      Writer::put<std::uint32_t>(c, sequence++);
      Writer::put<std::uint64_t>(c, message.log_time);
      Writer::put<std::uint64_t>(c, message.log_time);
      c.insert(c.end(), message.data.begin(), message.data.end());
    });
    if (records.size() >= (1u << 20)) {
      writer.chunk(out, records, first, last);
      records.clear();
    }
  }
  if (!records.empty()) writer.chunk(out, records, first, last);
  Writer::record(out, kDataEnd, [](std::vector<std::uint8_t> &c) { Writer::put<std::uint32_t>(c, 0); });
  Writer::record(out, kFooter, [](std::vector<std::uint8_t> &c) {
    Writer::put<std::uint64_t>(c, 0);  // no summary section
    Writer::put<std::uint64_t>(c, 0);
    Writer::put<std::uint32_t>(c, 0);
  });
  out.insert(out.end(), std::begin(kMagic), std::end(kMagic));
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file.write(reinterpret_cast<const char *>(out.data()), static_cast<std::streamsize>(out.size())))
    throw ReadError(path + ": cannot write the bag");
}

}  // namespace contour_reg::io::detail
