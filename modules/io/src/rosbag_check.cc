#include "rosbag_check.h"

#ifdef CONTOUR_REG_HAVE_ROSBAG

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <vector>

#include <rosbag/chunked_file.h>

namespace contour_reg::io::detail {

namespace {

// The record kinds (the "op" field; rosbag/constants.h).
constexpr std::uint8_t kMessageData = 0x02, kBagHeader = 0x03, kIndexData = 0x04, kChunk = 0x05, kChunkInfo = 0x06,
                       kConnection = 0x07;

// Bytes of an index entry (time: seconds and nanoseconds, offset in the chunk) and of a chunk
// info's count of messages per connection.
constexpr std::uint64_t kIndexEntryBytes = 12, kChunkInfoEntryBytes = 8;

// Bytes the version line may take ("#ROSBAG V2.0" takes 12).
constexpr std::uint64_t kMaxVersionLine = 4096;

// A record's data (a chunk's, decompressed or not) larger than kMaxChunkBytes, or a record's
// header larger than kMaxHeaderBytes, is taken as a corrupt length (a header holds a few short
// fields; ROS refuses a field of a megabyte).
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t(1) << 30, kMaxHeaderBytes = std::uint64_t(1) << 24;

using Fields = std::map<std::string, std::string>;

// Bags store integers little-endian, as rosbag_storage reads them on the hosts it runs on.
std::uint64_t unsignedAt(const std::uint8_t *p, std::size_t bytes) {
  std::uint64_t value = 0;
  std::memcpy(&value, p, bytes);
  return value;
}

// The fields of `size` bytes: each a 4-byte length and "name=value". "" when they fit.
std::string parseFields(const std::uint8_t *data, std::uint64_t size, Fields &fields) {
  fields.clear();
  for (std::uint64_t at = 0; at < size;) {
    if (size - at < 4) return "a header field's length runs past the header";
    const std::uint64_t length = unsignedAt(data + at, 4);
    at += 4;
    if (length > size - at) return "a header field runs past the header";
    const std::string field(reinterpret_cast<const char *>(data + at), length);
    at += length;
    const std::size_t equals = field.find('=');
    if (equals == std::string::npos) return "a header field without '='";
    fields[field.substr(0, equals)] = field.substr(equals + 1);
  }
  return "";
}

// The value of the fixed-size field `name`, in `value`; "" when present with that size.
std::string numberField(const Fields &fields, const std::string &name, std::size_t bytes, std::uint64_t &value) {
  const auto it = fields.find(name);
  if (it == fields.end()) return "no '" + name + "' field";
  if (it->second.size() != bytes) return "field '" + name + "' of " + std::to_string(it->second.size()) + " bytes";
  value = unsignedAt(reinterpret_cast<const std::uint8_t *>(it->second.data()), bytes);
  return "";
}

// A record: its header's fields, where its data lies, and where it ends.
struct Record {
  Fields fields;
  std::uint8_t op = 0;
  std::uint64_t data_start = 0, data_length = 0, end = 0;
};

// Reads the record at `at` of `size` bytes that `bytes(from, count, out)` gives.
template <typename Bytes>
std::string readRecord(Bytes &&bytes, std::uint64_t size, std::uint64_t at, Record &record,
                       std::vector<std::uint8_t> &scratch) {
  if (size - at < 4) return "a record's header length runs past the end";
  if (!bytes(at, 4, scratch)) return "cannot read";
  const std::uint64_t header_length = unsignedAt(scratch.data(), 4);
  if (header_length > size - at - 4) return "a record's header runs past the end";
  if (header_length > kMaxHeaderBytes) return "a record's header of " + std::to_string(header_length) + " bytes";
  if (!bytes(at + 4, header_length, scratch)) return "cannot read";
  if (std::string problem = parseFields(scratch.data(), header_length, record.fields); !problem.empty()) return problem;
  std::uint64_t op = 0;
  if (std::string problem = numberField(record.fields, "op", 1, op); !problem.empty()) return problem;
  record.op = static_cast<std::uint8_t>(op);
  const std::uint64_t length_at = at + 4 + header_length;
  if (size - length_at < 4) return "a record's data length runs past the end";
  if (!bytes(length_at, 4, scratch)) return "cannot read";
  record.data_length = unsignedAt(scratch.data(), 4);
  record.data_start = length_at + 4;
  if (record.data_length > size - record.data_start) return "a record's data runs past the end";
  record.end = record.data_start + record.data_length;
  return "";
}

// The chunk `chunk` (its data in `compressed`) decompressed, walked record by record: the
// starts of its message records into `messages`, up to the first record that does not fit (the
// rest cannot be found). "" when all fit it exactly, else what is wrong.
std::string checkChunk(const Record &chunk, std::vector<std::uint8_t> &compressed, std::set<std::uint64_t> &messages) {
  messages.clear();
  const auto compression = chunk.fields.find("compression");
  if (compression == chunk.fields.end()) return "a chunk without 'compression' field";
  rosbag::CompressionType type;
  if (compression->second == "none")
    type = rosbag::compression::Uncompressed;
  else if (compression->second == "bz2")
    type = rosbag::compression::BZ2;
  else if (compression->second == "lz4")
    type = rosbag::compression::LZ4;
  else
    return "a chunk of unknown compression '" + compression->second + "'";
  std::uint64_t size = 0;
  if (std::string problem = numberField(chunk.fields, "size", 4, size); !problem.empty()) return "chunk: " + problem;
  if (size > kMaxChunkBytes) return "a chunk of " + std::to_string(size) + " bytes";
  // Zeros where the data decompresses short: no record begins with a zero length.
  std::vector<std::uint8_t> records(size, 0);
  try {
    rosbag::ChunkedFile decompressor;
    decompressor.decompress(type, records.data(), static_cast<unsigned int>(size), compressed.data(),
                            static_cast<unsigned int>(compressed.size()));
  } catch (const std::exception &error) {
    return std::string("a chunk that does not decompress: ") + error.what();
  }
  const auto bytes = [&](std::uint64_t from, std::uint64_t count, std::vector<std::uint8_t> &out) {
    out.assign(records.begin() + static_cast<std::ptrdiff_t>(from),
               records.begin() + static_cast<std::ptrdiff_t>(from + count));
    return true;
  };
  Record record;
  std::vector<std::uint8_t> scratch;
  for (std::uint64_t at = 0; at < size; at = record.end) {
    const auto fail = [&](const std::string &what) {
      return "a chunk whose record at its byte " + std::to_string(at) + " is corrupt: " + what;
    };
    if (std::string problem = readRecord(bytes, size, at, record, scratch); !problem.empty()) return fail(problem);
    if (record.op == kConnection) {
      Fields connection;
      if (std::string problem = parseFields(records.data() + record.data_start, record.data_length, connection);
          !problem.empty())
        return fail("connection: " + problem);
    } else if (record.op != kMessageData) {
      return fail("a record of kind " + std::to_string(record.op));
    } else {
      messages.insert(at);
    }
  }
  return "";
}

// The index data record `index` (its entries in `entries`) of the chunk before it, whose
// message records are `messages` and whose problem, if any, is `chunk_problem`: the stamps of
// the entries that point at no message record of it into `unsafe`, with their connection
// number. "" when the record is sound.
std::string checkIndex(const Record &index, const std::vector<std::uint8_t> &entries,
                       const std::set<std::uint64_t> &messages, const std::string &chunk_problem,
                       std::uint64_t chunk_position,
                       std::map<std::pair<std::uint32_t, std::uint64_t>, std::string> &unsafe) {
  std::uint64_t version = 0, connection = 0, count = 0;
  for (const auto &[name, value] :
       {std::pair<const char *, std::uint64_t *>{"ver", &version}, {"conn", &connection}, {"count", &count}})
    if (std::string problem = numberField(index.fields, name, 4, *value); !problem.empty())
      return "index data: " + problem;
  if (version != 1) return "index data of version " + std::to_string(version);
  if (index.data_length != count * kIndexEntryBytes) return "index data whose length disagrees with its count";
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::uint8_t *entry = entries.data() + k * kIndexEntryBytes;
    if (messages.count(unsignedAt(entry + 8, 4))) continue;
    const std::uint64_t stamp = stampKey(unsignedAt(entry, 4), unsignedAt(entry + 4, 4));
    unsafe.emplace(
        std::make_pair(static_cast<std::uint32_t>(connection), stamp),
        "byte " + std::to_string(chunk_position) + ": " +
            (chunk_problem.empty() ? "an index entry that points at no message of its chunk" : chunk_problem));
  }
  return "";
}

}  // namespace

BagCheck checkBagStructure(const std::string &path) {
  BagCheck check;
  std::ifstream in(path, std::ios::binary);
  if (!in) return check;  // rosbag_storage names what it cannot open
  in.seekg(0, std::ios::end);
  const auto end = in.tellg();
  if (end < 0) return check;
  const std::uint64_t size = static_cast<std::uint64_t>(end);
  // rosbag_storage reads the version from the first line with this sscanf format, and the bag
  // header record after it.
  std::string line(std::min<std::uint64_t>(size, kMaxVersionLine), '\0');
  in.seekg(0);
  if (!in.read(line.data(), static_cast<std::streamsize>(line.size()))) return check;
  const std::size_t newline = line.find('\n');
  if (newline == std::string::npos && size > kMaxVersionLine) {
    check.fatal = "byte 0: a first line longer than a version line";
    return check;
  }
  line.resize(std::min({newline, line.find('\0'), line.size()}));
  char name[100];
  int major = 0, minor = 0;
  if (newline == std::string::npos || std::sscanf(line.c_str(), "#ROS%99s V%d.%d", name, &major, &minor) != 3 ||
      major != 2 || minor != 0)
    return check;
  const std::uint64_t first = newline + 1;  // the bag header record
  const auto bytes = [&](std::uint64_t from, std::uint64_t count, std::vector<std::uint8_t> &out) {
    out.resize(count);
    in.clear();
    in.seekg(static_cast<std::streamoff>(from));
    return count == 0 || bool(in.read(reinterpret_cast<char *>(out.data()), static_cast<std::streamsize>(count)));
  };
  std::set<std::uint64_t> records, chunks;
  // The last chunk's message records, its problem, and where it lies (none yet: -1).
  std::set<std::uint64_t> chunk_messages;
  std::string chunk_problem;
  std::int64_t chunk_position = -1;
  std::uint64_t index_position = 0;
  std::vector<std::uint8_t> scratch, data;
  Record record;
  for (std::uint64_t at = first; at < size; at = record.end) {
    const auto fail = [&](const std::string &what) {
      check.fatal = "byte " + std::to_string(at) + ": " + what;
      check.unsafe.clear();
      return check;
    };
    if (std::string problem = readRecord(bytes, size, at, record, scratch); !problem.empty()) return fail(problem);
    records.insert(at);
    if (record.op != kMessageData && record.data_length > kMaxChunkBytes)
      return fail("a record of " + std::to_string(record.data_length) + " bytes");
    if (record.op != kMessageData && !bytes(record.data_start, record.data_length, data)) return fail("cannot read");
    if (at == first) {
      std::uint64_t count = 0;
      if (record.op != kBagHeader) return fail("the first record is not the bag header");
      if (std::string problem = numberField(record.fields, "index_pos", 8, index_position); !problem.empty())
        return fail("bag header: " + problem);
      for (const char *name : {"conn_count", "chunk_count"})
        if (std::string problem = numberField(record.fields, name, 4, count); !problem.empty())
          return fail("bag header: " + problem);
    } else if (record.op == kChunk) {
      chunk_problem = checkChunk(record, data, chunk_messages);
      chunk_position = static_cast<std::int64_t>(at);
      chunks.insert(at);
    } else if (record.op == kIndexData) {
      if (chunk_position < 0) return fail("index data before any chunk");
      if (std::string problem = checkIndex(record, data, chunk_messages, chunk_problem,
                                           static_cast<std::uint64_t>(chunk_position), check.unsafe);
          !problem.empty())
        return fail(problem);
    } else if (record.op == kConnection) {
      Fields connection;
      if (std::string problem = parseFields(data.data(), record.data_length, connection); !problem.empty())
        return fail("connection: " + problem);
    } else if (record.op == kChunkInfo) {
      std::uint64_t version = 0, position = 0, time = 0, count = 0;
      if (std::string problem = numberField(record.fields, "ver", 4, version); !problem.empty())
        return fail("chunk info: " + problem);
      if (std::string problem = numberField(record.fields, "chunk_pos", 8, position); !problem.empty())
        return fail("chunk info: " + problem);
      for (const char *name : {"start_time", "end_time"})
        if (std::string problem = numberField(record.fields, name, 8, time); !problem.empty())
          return fail("chunk info: " + problem);
      if (std::string problem = numberField(record.fields, "count", 4, count); !problem.empty())
        return fail("chunk info: " + problem);
      if (version != 1) return fail("chunk info of version " + std::to_string(version));
      if (record.data_length != count * kChunkInfoEntryBytes)
        return fail("chunk info whose length disagrees with its count");
      if (!chunks.count(position)) return fail("chunk info that points at no chunk");
    } else if (record.op != kMessageData && record.op != kBagHeader) {
      return fail("a record of kind " + std::to_string(record.op));
    }
  }
  // 0: an unindexed bag (a recording cut short), which rosbag_storage reports.
  if (index_position != 0 && index_position != size && !records.count(index_position)) {
    check.fatal = "the bag header's index position " + std::to_string(index_position) + " points at no record";
    check.unsafe.clear();
  }
  return check;
}

}  // namespace contour_reg::io::detail

#endif
