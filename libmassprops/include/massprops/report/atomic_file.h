#pragma once
// Output files that are written whole or not at all: the bytes go to a temporary name in the same
// directory, which is renamed over the final name only once everything is flushed and closed.
// An interrupted run leaves at most a "*.tmp-<pid>" file, never a truncated file under the final
// name.

#include <fstream>
#include <string>
#include <vector>

namespace massprops::report {

class AtomicFile {
 public:
  /// Opens PATH.tmp-<pid> for writing. @throws std::runtime_error naming the path on failure.
  explicit AtomicFile(std::string path);
  /// Removes the temporary file unless Commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return out_; }
  const std::string& path() const { return path_; }
  /// Flushes, closes and renames onto the final name. @throws std::runtime_error naming the path.
  void Commit();
  /// Drops the temporary file (also done by the destructor).
  void Abandon();

 private:
  std::string path_;
  std::string tmp_;
  std::ofstream out_;
  bool done_ = false;
};

/// Refuses an output path that exists and is not a regular file (a device node such as
/// /dev/null, a FIFO, a directory) or that names one of the inputs. @throws std::runtime_error.
void CheckOutputPath(const std::string& output, const std::vector<std::string>& inputs);

/// Writes TEXT to PATH whole or not at all. @throws std::runtime_error naming the path.
void WriteFileAtomically(const std::string& path, const std::string& text);

}  // namespace massprops::report
