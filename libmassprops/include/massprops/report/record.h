#pragma once
// One file's record in a dataset run (massprops batch, the Python module's dask.map_files): what
// the isolated child computes, and what the parent makes of its outcome. One line of JSON:
//   {"file", "index", "of", "status": ok|refused|error|crashed|timeout, "result" | "message"}

#include <cstddef>
#include <string>

#include "massprops/io/isolation.h"
#include "massprops/io/load.h"

namespace massprops::report {

/// The child's work: the record of `file` (number `index` of `of` in sorted order). Refusals and
/// read errors are records, not exceptions. With a `picture` path, the result is also drawn there
/// (massprops/report/picture.h) and the record names it ("picture"), or says why it could not be
/// ("picture_error"; the mass properties stand).
std::string ComputeRecord(const std::string& file, std::size_t index, std::size_t of, const LoadOptions& options,
                          const std::string& picture = {});

/// The record for an isolated child's outcome: its own when it finished, else one that says it
/// crashed, timed out or failed.
std::string RecordOf(const std::string& file, std::size_t index, std::size_t of, IsolatedOutcome&& outcome,
                     double timeout_seconds);

/// ComputeRecord in an isolated child with a time limit, then RecordOf: one file, nothing shared.
std::string IsolatedRecord(const std::string& file, std::size_t index, std::size_t of, const LoadOptions& options,
                           double timeout_seconds);

}  // namespace massprops::report
