#pragma once
// A strict check of a PCD file's header (and of the size of its data) before PCL reads it:
// PCL's reader trusts the header and writes out of bounds on some malformed ones.

#include <string>

namespace contour_reg::io::detail {

/// "" when `path` is a PCD file with x and y as single floats and data that fits its
/// header; otherwise what is wrong, for a "file:line: what" report (`line` set to the line).
std::string checkPcdHeader(const std::string &path, std::size_t &line);

}  // namespace contour_reg::io::detail
