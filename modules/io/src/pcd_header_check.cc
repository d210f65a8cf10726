#include "pcd_header_check.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace contour_reg::io::detail {

namespace {

constexpr std::size_t kMaxHeaderLines = 64;
constexpr std::size_t kMaxPoints = 10'000'000;

bool positiveInteger(const std::string &token, std::size_t limit, std::size_t &value) {
  if (token.empty() || token.size() > 12 || token.find_first_not_of("0123456789") != std::string::npos) return false;
  value = std::stoull(token);
  return value >= 1 && value <= limit;
}

}  // namespace

std::string checkPcdHeader(const std::string &path, std::size_t &line) {
  std::ifstream in(path, std::ios::binary);
  line = 0;
  if (!in) return "cannot open the file";
  std::map<std::string, std::vector<std::string>> header;
  std::string text, data;
  while (data.empty()) {
    if (!std::getline(in, text)) return "the header ends before its DATA line";
    if (++line > kMaxHeaderLines) return "no DATA line in the first 64 lines";
    if (text.empty() || text[0] == '#') continue;
    std::istringstream fields(text);
    std::string key;
    fields >> key;
    static const char *known[] = {"VERSION", "FIELDS", "SIZE",      "TYPE",   "COUNT",
                                  "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
    if (std::find(std::begin(known), std::end(known), key) == std::end(known))
      return "unknown header line '" + key + "'";
    if (header.count(key)) return "header line " + key + " given twice";
    std::vector<std::string> values;
    for (std::string v; fields >> v;) values.push_back(v);
    header[key] = values;
    if (key == "DATA") data = values.empty() ? "?" : values[0];
  }
  for (const char *required : {"FIELDS", "SIZE", "TYPE", "WIDTH", "HEIGHT"})
    if (!header.count(required)) return std::string("no ") + required + " line";
  if (data != "ascii" && data != "binary" && data != "binary_compressed")
    return "DATA must be ascii, binary or binary_compressed";
  const auto &names = header["FIELDS"], &sizes = header["SIZE"], &types = header["TYPE"];
  std::vector<std::string> counts =
      header.count("COUNT") ? header["COUNT"] : std::vector<std::string>(names.size(), "1");
  if (names.empty() || sizes.size() != names.size() || types.size() != names.size() || counts.size() != names.size())
    return "FIELDS, SIZE, TYPE and COUNT differ in length";
  std::size_t point_step = 0, values_per_point = 0;
  bool x = false, y = false;
  for (std::size_t k = 0; k < names.size(); ++k) {
    std::size_t size = 0, count = 0;
    if (!positiveInteger(sizes[k], 8, size) || (size != 1 && size != 2 && size != 4 && size != 8))
      return "bad SIZE of field " + names[k];
    if (types[k] != "F" && types[k] != "I" && types[k] != "U") return "bad TYPE of field " + names[k];
    if (types[k] == "F" && size != 4 && size != 8) return "float field " + names[k] + " must have SIZE 4 or 8";
    if (!positiveInteger(counts[k], 1'000'000, count)) return "bad COUNT of field " + names[k];
    const bool single_float = types[k] == "F" && size == 4 && count == 1;
    if (names[k] == "x") x = single_float;
    if (names[k] == "y") y = single_float;
    point_step += size * count;
    values_per_point += count;
  }
  if (!x || !y) return "no x and y fields of single floats (SIZE 4, TYPE F, COUNT 1)";
  std::size_t width = 0, height = 0, points = 0;
  if (header["WIDTH"].size() != 1 || !positiveInteger(header["WIDTH"][0], kMaxPoints, width)) return "bad WIDTH";
  if (header["HEIGHT"].size() != 1 || !positiveInteger(header["HEIGHT"][0], kMaxPoints, height)) return "bad HEIGHT";
  if (width * height > kMaxPoints) return "too many points";
  if (header.count("POINTS") && (header["POINTS"].size() != 1 ||
                                 !positiveInteger(header["POINTS"][0], kMaxPoints, points) || points != width * height))
    return "POINTS differs from WIDTH x HEIGHT";
  if (header.count("VIEWPOINT") && header["VIEWPOINT"].size() != 7) return "VIEWPOINT needs 7 numbers";
  const std::size_t header_line = line;
  // PCL's header reader goes on after the DATA line over any number of empty lines, comments
  // and VERSION lines, and reads any line that begins with a header keyword as one, whatever
  // the data; a line of blanks or of anything else ends it.
  const std::streampos data_start = in.tellg();
  for (std::size_t after = 0; std::getline(in, text); ++after) {
    if (text.empty()) continue;
    std::istringstream fields(text);
    std::string key;
    if (!(fields >> key)) break;
    if (key[0] == '#' || key.rfind("VERSION", 0) == 0) continue;
    static const char *pcl_keys[] = {"FIELDS", "COLUMNS", "SIZE",      "TYPE",   "COUNT",
                                     "WIDTH",  "HEIGHT",  "VIEWPOINT", "POINTS", "DATA"};
    for (const char *pcl_key : pcl_keys)
      if (key.rfind(pcl_key, 0) == 0) {
        line = header_line + after + 1;
        return "the data after the DATA line reads as a header line '" + std::string(pcl_key) + "'";
      }
    break;
  }
  in.clear();
  in.seekg(data_start);
  if (data == "ascii") {
    std::size_t rows = 0;
    while (std::getline(in, text)) {
      ++line;
      std::istringstream fields(text);
      std::size_t tokens = 0;
      for (std::string v; fields >> v;) ++tokens;
      if (tokens == 0) continue;
      if (tokens != values_per_point)
        return "a point has " + std::to_string(tokens) + " values, the header says " + std::to_string(values_per_point);
      ++rows;
    }
    if (rows != width * height) {
      line = header_line;
      return "the header announces " + std::to_string(width * height) + " points, the data has " + std::to_string(rows);
    }
  } else if (data == "binary") {
    const std::streamoff start = in.tellg();
    in.seekg(0, std::ios::end);
    const std::streamoff end = in.tellg();
    if (start < 0 || end < start || static_cast<std::size_t>(end - start) < point_step * width * height)
      return "binary data shorter than the header announces";
  }
  return "";
}

}  // namespace contour_reg::io::detail
