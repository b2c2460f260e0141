#pragma once
/// @file
/// Work that may crash or hang, run where it cannot take the caller down: each item in a forked
/// child process with a time limit, several at a time (POSIX). Third-party readers (assimp) and
/// the batch mode over datasets use it; a crash or a timeout becomes that item's outcome.

#include <cstddef>
#include <functional>
#include <string>

namespace massprops {

/// How an isolated item ended.
enum class IsolatedEnd {
  kFinished,  ///< the child returned its output and exited 0
  kCrashed,   ///< killed by a signal (a segfault, an abort) before finishing
  kTimedOut,  ///< still running at the time limit: killed
  kFailed,    ///< exited non-zero (the work threw, or the child could not report)
};

struct IsolatedOutcome {
  IsolatedEnd end = IsolatedEnd::kFinished;
  std::string output;  ///< what the child sent: whole when kFinished, what came before the end otherwise
  int signal = 0;      ///< kCrashed: the signal's number
  double seconds = 0;  ///< wall time of the child
};

/// Runs work(i) for every i in [0, count), each in its own forked child process, at most `jobs`
/// at a time, each stopped after `seconds_limit` seconds. `done(i, outcome)` is called in this
/// process in the order of i (outcomes that finish early wait for the ones before them), so what
/// the caller writes does not depend on `jobs`. Call it from a single-threaded point of the
/// program: a forked child has only the forking thread. `work` runs in the child only; what it
/// returns is sent back through a pipe. @throws std::runtime_error if a process or pipe cannot be
/// made.
void RunIsolated(std::size_t count, int jobs, double seconds_limit, const std::function<std::string(std::size_t)>& work,
                 const std::function<void(std::size_t, IsolatedOutcome&&)>& done);

/// As RunIsolated, with each child computing a run of up to `items_per_child` consecutive items
/// one after the other: where starting a process costs more than an item (many small files), a
/// few processes do the work. The time limit is per item. A child that crashes or is stopped ends
/// only the item it was on; the rest of its run go to a new child. A crashed item is computed once
/// more alone in a fresh child, and that outcome is the one given (a crash caused by an earlier
/// item of the same child is not blamed on it). `done` is called in the order of i, as above.
void RunIsolatedInRuns(std::size_t count, int jobs, double seconds_limit, std::size_t items_per_child,
                       const std::function<std::string(std::size_t)>& work,
                       const std::function<void(std::size_t, IsolatedOutcome&&)>& done);

/// Sends bytes from a streaming child to the parent as they are made.
using IsolatedSend = std::function<void(const std::string& bytes)>;

/// As RunIsolated, for work that sends its output piece by piece (`send`) and may take long in
/// all: the time limit runs from the last piece received (or the start), so a child that keeps
/// sending keeps running, and one that falls silent for `seconds_silent` is stopped. What it sent
/// before a crash or a stop is in the outcome's output.
void RunIsolatedStreaming(std::size_t count, int jobs, double seconds_silent,
                          const std::function<void(std::size_t, const IsolatedSend&)>& work,
                          const std::function<void(std::size_t, IsolatedOutcome&&)>& done);

}  // namespace massprops
