#include "mcap.h"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <array>
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
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kSummaryOffset = 0x0E,
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

// Writes an MCAP file: the data section's chunks, each followed by the index of each channel's
// messages in it, then the summary section a seeking reader starts from (the schemas,
// channels, statistics and each chunk's index) and the offsets of its groups.
class Writer {
 public:
  Writer(std::string compression, const std::vector<StoredTopic> &topics)
      : compression_(std::move(compression)), topics_(topics), out_(std::begin(kMagic), std::end(kMagic)) {
    record(out_, kHeader, [](std::vector<std::uint8_t> &c) {
      put(c, std::string("ros2"));
      put(c, std::string("contour_reg"));
    });
    for (std::uint16_t id = 1; id <= topics_.size(); ++id) {
      schema(out_, id);
      channel(out_, id);
    }
  }

  void message(const StoredMessage &message) {
    const auto channel = static_cast<std::uint16_t>(message.topic + 1);
    if (records_.empty()) first_ = last_ = message.log_time;
    first_ = std::min(first_, message.log_time);
    last_ = std::max(last_, message.log_time);
    indexes_[channel].push_back({message.log_time, records_.size()});
    ++counts_[channel];
    record(records_, kMessage, [&](std::vector<std::uint8_t> &c) {
      put<std::uint16_t>(c, channel);
      put<std::uint32_t>(c, sequence_++);
      put<std::uint64_t>(c, message.log_time);
      put<std::uint64_t>(c, message.log_time);
      c.insert(c.end(), message.data.begin(), message.data.end());
    });
    if (records_.size() >= (1u << 20)) chunk();
  }

  // The file's bytes: the last chunk, the data end, the summary and the footer.
  const std::vector<std::uint8_t> &finish() {
    if (!records_.empty()) chunk();
    record(out_, kDataEnd, [](std::vector<std::uint8_t> &c) { put<std::uint32_t>(c, 0); });
    const std::uint64_t summary = out_.size();
    std::vector<std::array<std::uint64_t, 3>> groups;  // opcode, start, length
    const auto group = [&](std::uint8_t opcode, const auto &records) {
      const std::uint64_t start = out_.size();
      records();
      if (out_.size() > start) groups.push_back({opcode, start, out_.size() - start});
    };
    group(kSchema, [&] {
      for (std::uint16_t id = 1; id <= topics_.size(); ++id) schema(out_, id);
    });
    group(kChannel, [&] {
      for (std::uint16_t id = 1; id <= topics_.size(); ++id) channel(out_, id);
    });
    group(kStatistics, [&] { statistics(); });
    group(kChunkIndex, [&] { out_.insert(out_.end(), chunk_indexes_.begin(), chunk_indexes_.end()); });
    const std::uint64_t offsets = out_.size();
    for (const std::array<std::uint64_t, 3> &offset : groups)  // opcode, start, length
      record(out_, kSummaryOffset, [&](std::vector<std::uint8_t> &c) {
        put<std::uint8_t>(c, static_cast<std::uint8_t>(offset[0]));
        put<std::uint64_t>(c, offset[1]);
        put<std::uint64_t>(c, offset[2]);
      });
    // The footer's CRC covers the summary up to the footer's own CRC field.
    out_.push_back(kFooter);
    put<std::uint64_t>(out_, 20);
    put<std::uint64_t>(out_, summary);
    put<std::uint64_t>(out_, offsets);
    put<std::uint32_t>(
        out_, static_cast<std::uint32_t>(crc32(0, out_.data() + summary, static_cast<uInt>(out_.size() - summary))));
    out_.insert(out_.end(), std::begin(kMagic), std::end(kMagic));
    return out_;
  }

 private:
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
  // A map or an array of pairs: the entries' byte length, then each pair as First, Second.
  template <typename First, typename Second, typename Pairs>
  static void putPairs(std::vector<std::uint8_t> &out, const Pairs &pairs) {
    std::vector<std::uint8_t> entries;
    for (const auto &[first, second] : pairs) {
      put<First>(entries, first);
      put<Second>(entries, second);
    }
    put<std::uint32_t>(out, static_cast<std::uint32_t>(entries.size()));
    out.insert(out.end(), entries.begin(), entries.end());
  }

  // The schema and the channel of topic `id` (from 1), under the same id.
  void schema(std::vector<std::uint8_t> &out, std::uint16_t id) const {
    record(out, kSchema, [&](std::vector<std::uint8_t> &c) {
      put<std::uint16_t>(c, id);
      put(c, topics_[id - 1].type);
      put(c, std::string("ros2msg"));
      put(c, messageDefinition(topics_[id - 1].type));
    });
  }
  void channel(std::vector<std::uint8_t> &out, std::uint16_t id) const {
    record(out, kChannel, [&](std::vector<std::uint8_t> &c) {
      put<std::uint16_t>(c, id);
      put<std::uint16_t>(c, id);
      put(c, topics_[id - 1].name);
      put(c, topics_[id - 1].message_encoding);
      put<std::uint32_t>(c, 0);  // metadata: none
    });
  }

  // The chunk of the messages since the last, the index of each channel's messages in it, and
  // the chunk's index for the summary.
  void chunk() {
    std::vector<std::uint8_t> stored;
    if (compression_ == "zstd") {
      stored.resize(ZSTD_compressBound(records_.size()));
      const std::size_t size = ZSTD_compress(stored.data(), stored.size(), records_.data(), records_.size(), 3);
      if (ZSTD_isError(size)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(size));
      stored.resize(size);
    } else if (compression_ == "lz4") {
      stored.resize(LZ4F_compressFrameBound(records_.size(), nullptr));
      const std::size_t size =
          LZ4F_compressFrame(stored.data(), stored.size(), records_.data(), records_.size(), nullptr);
      if (LZ4F_isError(size)) throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(size));
      stored.resize(size);
    } else {
      stored = records_;
    }
    const std::uint64_t start = out_.size();
    record(out_, kChunk, [&](std::vector<std::uint8_t> &c) {
      put<std::uint64_t>(c, first_);
      put<std::uint64_t>(c, last_);
      put<std::uint64_t>(c, records_.size());
      put<std::uint32_t>(c, static_cast<std::uint32_t>(crc32(0, records_.data(), static_cast<uInt>(records_.size()))));
      put(c, compression_);
      put<std::uint64_t>(c, stored.size());
      c.insert(c.end(), stored.begin(), stored.end());
    });
    const std::uint64_t length = out_.size() - start;
    std::vector<std::pair<std::uint16_t, std::uint64_t>> index_offsets;  // channel -> its message index
    for (const auto &channel : indexes_) {                               // id, (time, offset) of each message
      index_offsets.push_back({channel.first, out_.size()});
      record(out_, kMessageIndex, [&](std::vector<std::uint8_t> &c) {
        put<std::uint16_t>(c, channel.first);
        putPairs<std::uint64_t, std::uint64_t>(c, channel.second);
      });
    }
    record(chunk_indexes_, kChunkIndex, [&](std::vector<std::uint8_t> &c) {
      put<std::uint64_t>(c, first_);
      put<std::uint64_t>(c, last_);
      put<std::uint64_t>(c, start);
      put<std::uint64_t>(c, length);
      putPairs<std::uint16_t, std::uint64_t>(c, index_offsets);
      put<std::uint64_t>(c, out_.size() - start - length);
      put(c, compression_);
      put<std::uint64_t>(c, stored.size());
      put<std::uint64_t>(c, records_.size());
    });
    all_first_ = chunks_ == 0 ? first_ : std::min(all_first_, first_);
    all_last_ = std::max(all_last_, last_);
    ++chunks_;
    records_.clear();
    indexes_.clear();
  }

  void statistics() {
    record(out_, kStatistics, [&](std::vector<std::uint8_t> &c) {
      put<std::uint64_t>(c, sequence_);
      put<std::uint16_t>(c, static_cast<std::uint16_t>(topics_.size()));  // schemas
      put<std::uint32_t>(c, static_cast<std::uint32_t>(topics_.size()));  // channels
      put<std::uint32_t>(c, 0);                                           // attachments
      put<std::uint32_t>(c, 0);                                           // metadata
      put<std::uint32_t>(c, chunks_);
      put<std::uint64_t>(c, all_first_);
      put<std::uint64_t>(c, all_last_);
      putPairs<std::uint16_t, std::uint64_t>(c, counts_);
    });
  }

  std::string compression_;
  const std::vector<StoredTopic> &topics_;
  std::vector<std::uint8_t> out_;       // the file so far
  std::vector<std::uint8_t> records_;   // the messages of the chunk being filled
  std::uint64_t first_ = 0, last_ = 0;  // their first and last log time
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> indexes_;  // channel -> time, offset
  std::vector<std::uint8_t> chunk_indexes_;        // the summary's chunk index records
  std::map<std::uint16_t, std::uint64_t> counts_;  // messages of each channel
  std::uint32_t sequence_ = 0, chunks_ = 0;
  std::uint64_t all_first_ = 0, all_last_ = 0;
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
  Writer writer(compression, topics);
  for (const StoredMessage &message : messages) writer.message(message);
  const std::vector<std::uint8_t> &out = writer.finish();
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file.write(reinterpret_cast<const char *>(out.data()), static_cast<std::streamsize>(out.size())))
    throw ReadError(path + ": cannot write the bag");
}

}  // namespace contour_reg::io::detail
