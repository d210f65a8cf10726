#include "text_lines.h"

#include <cstring>

namespace contour_reg::io::detail {

LineReader::LineReader(const std::string &path) : file_(gzopen(path.c_str(), "rb")) {
  if (file_) gzbuffer(file_, 1 << 16);
}

LineReader::~LineReader() {
  if (file_) gzclose(file_);
}

bool LineReader::next(std::string &line) {
  line.clear();
  if (!file_) return false;
  char buffer[1 << 14];
  bool got_any = false;
  bool ended = true;
  while (gzgets(file_, buffer, sizeof buffer) != nullptr) {
    got_any = true;
    const std::size_t length = std::strlen(buffer);
    line.append(buffer, length);
    if (length > 0 && buffer[length - 1] == '\n') {
      ended = false;
      break;
    }
  }
  if (ended && error_.empty()) {
    int code = Z_OK;
    const char *message = gzerror(file_, &code);
    if (code != Z_OK && code != Z_STREAM_END)
      error_ = "the compressed file is cut short or corrupt (" +
               (message ? std::string(message) : "zlib error " + std::to_string(code)) + ")";
  }
  if (!got_any) return false;
  ++line_number_;
  unterminated_ = line.empty() || line.back() != '\n';
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  return true;
}

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (start < line.size()) {
    while (start < line.size() && (line[start] == ' ' || line[start] == '\t')) ++start;
    std::size_t end = start;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t') ++end;
    if (end > start) fields.push_back(line.substr(start, end - start));
    start = end;
  }
  return fields;
}

}  // namespace contour_reg::io::detail
