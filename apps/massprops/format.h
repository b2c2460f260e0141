#pragma once
// massprops' output formats: each turns pipeline results (massprops/load.h) into text, and
// computes nothing. One file per format.

#include <string>
#include <vector>

#include "massprops/load.h"

namespace massprops::cli {

enum class Format { kTable, kJson, kCsv, kUrdf, kSdf, kMjcf };
/// Which frames the inertia is reported in besides the center of mass.
enum class Frame { kCenterOfMass, kOrigin };

struct FormatOptions {
  Format format = Format::kTable;
  Frame frame = Frame::kCenterOfMass;
  /// JSON: an array (several inputs were given, whether or not each succeeded), else one object.
  bool json_array = false;
};

std::string FormatTable(const SolidResult& r, const FormatOptions& options);
/// One object, or an array when options.json_array.
std::string FormatJson(const std::vector<SolidResult>& results, const FormatOptions& options);
std::string FormatCsv(const std::vector<SolidResult>& results, const FormatOptions& options);
/// The inertial element of a URDF, SDFormat or MJCF file, with a comment naming the source.
std::string FormatRobot(const SolidResult& r, Format format);

/// The command line's words for the options the library's messages advise (wording.h).
const Vocabulary& CliVocabulary();

}  // namespace massprops::cli
