#pragma once
/// @file
/// Numbers as text, one home for every printer of the project.

#include <string>

namespace massprops {

/// printf-style formatting of one double, e.g. FormatDouble(v, "%.4g").
std::string FormatDouble(double v, const char* printf_format);

/// Shortest decimal text that reads back as the same double ("%.17g" trimmed); "nan", "inf".
std::string ExactDecimal(double v);

}  // namespace massprops
