// The definitions of massprops/report/record.h: one file's record in a dataset run (massprops
// batch, the Python module's dask.map_files).

#include "massprops/report/record.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include <nlohmann/json.hpp>

#include "massprops/report/format.h"
#include "massprops/report/picture.h"

namespace massprops::report {

using Json = nlohmann::ordered_json;

std::string ComputeRecord(const std::string& file, std::size_t index, std::size_t of, const LoadOptions& options,
                          const std::string& picture) {
  Json rec = {{"file", file}, {"index", index}, {"of", of}};
  FormatOptions format;
  format.format = Format::kJson;
  try {
    const SolidResult r = LoadSolid(file, options);
    rec["status"] = "ok";
    rec["result"] = Json::parse(FormatJsonLine(r, format));
    if (!picture.empty()) {
      try {
        WritePicture(picture, r);
        rec["picture"] = picture;
      } catch (const std::exception& e) {
        rec["picture_error"] = e.what();
      }
    }
  } catch (const LoadError& e) {
    rec["status"] = "refused";
    rec["message"] = WordedError(e, CliVocabulary());
  } catch (const std::exception& e) {  // unreadable, malformed, or an option the file cannot take
    rec["status"] = "error";
    rec["message"] = WordedError(e, CliVocabulary());
  }
  return rec.dump();
}

std::string RecordOf(const std::string& file, std::size_t index, std::size_t of, IsolatedOutcome&& o,
                     double timeout_seconds) {
  if (o.end == IsolatedEnd::kFinished) return std::move(o.output);
  Json rec = {{"file", file}, {"index", index}, {"of", of}};
  if (o.end == IsolatedEnd::kCrashed) {
    rec["status"] = "crashed";
    rec["message"] =
        "the process computing it crashed (signal " + std::to_string(o.signal) + ", " + ::strsignal(o.signal) + ")";
  } else if (o.end == IsolatedEnd::kTimedOut) {
    rec["status"] = "timeout";
    rec["message"] =
        "not finished within " + std::to_string(static_cast<long long>(timeout_seconds)) + " s (--timeout): stopped";
  } else {
    rec["status"] = "error";
    rec["message"] = "the process computing it failed";
  }
  return rec.dump();
}

std::string IsolatedRecord(const std::string& file, std::size_t index, std::size_t of, const LoadOptions& options,
                           double timeout_seconds) {
  std::string line;
  RunIsolated(
      1, 1, timeout_seconds, [&](std::size_t) { return ComputeRecord(file, index, of, options); },
      [&](std::size_t, IsolatedOutcome&& o) { line = RecordOf(file, index, of, std::move(o), timeout_seconds); });
  return line;
}

}  // namespace massprops::report
