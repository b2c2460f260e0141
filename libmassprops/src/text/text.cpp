// The definitions of massprops/text.h: numbers as text, one home for every printer of the project.

#include "massprops/text.h"

#include <charconv>
#include <cstdio>

namespace massprops {

std::string FormatDouble(double v, const char* printf_format) {
  char buf[128];
  std::snprintf(buf, sizeof buf, printf_format, v);
  return buf;
}

std::string ExactDecimal(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  return std::string(buf, res.ptr);
}

}  // namespace massprops
