#pragma once
// Reading text files line by line, plain or gzip, and splitting lines into numbers.
// Internal to the io module.

#include <charconv>
#include <string>
#include <string_view>
#include <vector>

#include <zlib.h>

namespace contour_reg::io::detail {

/// Reads lines of a plain or gzip-compressed text file (zlib reads both).
class LineReader {
 public:
  explicit LineReader(const std::string &path);
  ~LineReader();
  LineReader(const LineReader &) = delete;
  LineReader &operator=(const LineReader &) = delete;

  bool isOpen() const { return file_ != nullptr; }
  /// Next line without its end-of-line characters; false at the end of the file.
  bool next(std::string &line);
  /// True when the file ended without a newline after its last line (a truncated log).
  bool lastLineUnterminated() const { return unterminated_; }
  std::size_t lineNumber() const { return line_number_; }
  /// Why the lines stopped before the end of the file ("the compressed file is cut short or
  /// corrupt (zlib's reason)"); empty when they reached it.
  const std::string &error() const { return error_; }

 private:
  gzFile file_ = nullptr;
  std::size_t line_number_ = 0;
  bool unterminated_ = false;
  std::string error_;
};

/// Splits on blanks and tabs.
std::vector<std::string_view> splitFields(std::string_view line);

/// Parses a whole field as a number; false on anything else.
inline bool parseNumber(std::string_view field, double &value) {
  const char *end = field.data() + field.size();
  auto [ptr, error] = std::from_chars(field.data(), end, value);
  if (error == std::errc::result_out_of_range) {  // denormals and huge values: keep the field's sign
    value = (field.size() && field[0] == '-') ? -0.0 : 0.0;
    return ptr == end;
  }
  return error == std::errc() && ptr == end;
}

}  // namespace contour_reg::io::detail
