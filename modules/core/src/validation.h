#pragma once
/// @file validation.h
/// The shared shape of the settings structs' validate(): report the first bad value.

#include <string>

namespace contour_reg {

/// Stores `message` in `why` (when given) and returns false, for validate() functions.
inline bool invalid(std::string *why, const char *message) {
  if (why) *why = message;
  return false;
}

}  // namespace contour_reg
