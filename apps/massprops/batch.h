#pragma once
// `massprops batch` and `massprops merge`: many files, nothing lost. Each file is computed in its
// own child process (massprops/io/isolation.h), so a crash or a hang becomes that file's record;
// records are appended one whole line at a time, in file order, so an interrupted run keeps what
// it wrote and --resume goes on from there; --shard i/n takes a deterministic slice for job arrays,
// and merge joins the slices, checking that no file is missing or repeated.

#include <string>
#include <vector>

#include "massprops/io/load.h"

namespace massprops::cli {

struct BatchOptions {
  std::string input;   ///< a folder (walked recursively for mesh files) or a manifest (a path a line)
  std::string output;  ///< the JSON Lines file, appended to
  int jobs = 0;        ///< files computed at a time (0: one per core)
  int shard_index = 0, shard_count = 1;
  bool resume = false;
  double timeout_seconds = 600;
  bool summary_json = false;  ///< print the summary as JSON on stdout
  bool quiet = false;
  bool threads_given = false;
  /// A folder for each file's picture (created if missing; empty: none), and their format.
  std::string pictures;
  std::string picture_extension = ".svg";
  LoadOptions load;
};

/// Parses "i/n" (0 <= i < n). @throws std::invalid_argument naming the fault.
void ParseShard(const std::string& text, int& index, int& count);

/// Runs the batch; returns the exit status (0: every file has a record, whatever its status;
/// 1: the run itself failed; 2: bad arguments).
int RunBatch(const BatchOptions& options);

/// massprops merge OUT SHARD...: returns the exit status.
int RunMerge(const std::string& output, const std::vector<std::string>& shards);

}  // namespace massprops::cli
