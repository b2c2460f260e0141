// The definitions of massprops/report/atomic_file.h: output files that are written whole or not at
// all.

#include "massprops/report/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <unistd.h>

namespace massprops::report {

namespace {

// Output goes to regular files only: never over a device node, a FIFO or a directory.
void RequireRegularOrAbsent(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return;
  if (!std::filesystem::is_regular_file(status)) {
    throw std::runtime_error(path +
                             ": not a regular file (a device, FIFO or directory); output is written only to "
                             "regular files");
  }
}

}  // namespace

void CheckOutputPath(const std::string& output, const std::vector<std::string>& inputs) {
  RequireRegularOrAbsent(output);
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (std::filesystem::equivalent(output, in, ec) && !ec) {
      throw std::runtime_error(output + ": is also an input; refusing to overwrite it (choose another -o)");
    }
  }
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), tmp_(path_ + ".tmp-" + std::to_string(::getpid())) {
  RequireRegularOrAbsent(path_);
  out_.open(tmp_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    throw std::runtime_error(path_ + ": cannot open for writing (" + std::strerror(errno) + ")");
  }
}

AtomicFile::~AtomicFile() { Abandon(); }

void AtomicFile::Abandon() {
  if (done_) return;
  done_ = true;
  if (out_.is_open()) out_.close();
  std::remove(tmp_.c_str());
}

void AtomicFile::Commit() {
  if (done_) throw std::runtime_error(path_ + ": already committed or abandoned");
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail()) {
    Abandon();
    throw std::runtime_error(path_ + ": write failed (disk full?)");
  }
  try {
    RequireRegularOrAbsent(path_);  // it may have been replaced since the file was opened
  } catch (...) {
    Abandon();
    throw;
  }
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    Abandon();
    throw std::runtime_error(path_ + ": cannot rename the finished file into place (" + reason + ")");
  }
  done_ = true;
}

void WriteFileAtomically(const std::string& path, const std::string& text) {
  AtomicFile file(path);
  file.stream() << text;
  file.Commit();
}

}  // namespace massprops::report
