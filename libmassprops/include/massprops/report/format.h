#pragma once
// massprops' output formats: each turns pipeline results (massprops/io/load.h) into text, and
// computes nothing. One file per format; the Python module prints its to_dict() through the same
// JSON formatter, so the schema has one home.

#include <optional>
#include <string>
#include <vector>

#include "massprops/io/load.h"
#include "massprops/principal_axes.h"
#include "massprops/report/words.h"
#include "massprops/robot/robot.h"
#include "massprops/units.h"

namespace massprops::report {

enum class Format { kTable, kJson, kCsv, kUrdf, kSdf, kMjcf };
/// Which frames the inertia is reported in besides the center of mass.
enum class Frame { kCenterOfMass, kOrigin };

struct FormatOptions {
  Format format = Format::kTable;
  Frame frame = Frame::kCenterOfMass;
  /// JSON: an array (several inputs were given, whether or not each succeeded), else one object.
  bool json_array = false;
  /// The words for options that warnings advise; null: the command line's (CliVocabulary).
  const Vocabulary* vocabulary = nullptr;
  /// The units the table, JSON and CSV are read in (SI by default); URDF, SDF and MJCF are SI.
  ReportUnits units;
  /// Also report the inertia tensor about this point, in these axes (--about, --axes). The point
  /// is in the coordinates of each input file, in the unit that file is read in (a file that
  /// declares millimetres takes --about in millimetres): ReferenceOf scales it per result.
  std::optional<ReferenceFrame> reference;
};

/// options.reference for the result r: its point turned into metres with r's unit.
inline ReferenceFrame ReferenceOf(const SolidResult& r, const FormatOptions& options) {
  ReferenceFrame f = *options.reference;
  if (f.point) f.point = *f.point * MetresPerUnit(r.unit);
  return f;
}

std::string FormatTable(const SolidResult& r, const FormatOptions& options);
/// One object, or an array when options.json_array.
std::string FormatJson(const std::vector<SolidResult>& results, const FormatOptions& options);
/// One object on one line, no newline (a record of `massprops batch`).
std::string FormatJsonLine(const SolidResult& r, const FormatOptions& options);
std::string FormatCsv(const std::vector<SolidResult>& results, const FormatOptions& options);
/// The inertial element of a URDF, SDFormat or MJCF file, with a comment naming the source.
std::string FormatRobot(const SolidResult& r, Format format);

/// The report of `massprops fill` (and the Python module's fill): the file, the output, the
/// format, and each link with its status, mass properties or message, and notes.
std::string FormatFillJson(const std::string& file, const std::string& output, const FillResult& r,
                           const Vocabulary& words);

/// options.vocabulary, or the command line's.
inline const Vocabulary& WordsOf(const FormatOptions& options) {
  return options.vocabulary ? *options.vocabulary : CliVocabulary();
}

}  // namespace massprops::report
