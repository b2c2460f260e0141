#pragma once
// A progress line on stderr for work that takes more than a second: silent for quick files, then
// "massprops: FILE: STAGE (N s)" refreshed in place on a terminal, or one line per stage when
// stderr is a file or pipe.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

#include <unistd.h>

namespace massprops::app {

class Progress {
 public:
  Progress(std::string file, bool enabled) : file_(std::move(file)) {
    if (enabled) thread_ = std::thread([this] { Run(); });
  }
  ~Progress() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void Stage(const char* stage) {
    std::lock_guard<std::mutex> lock(mutex_);
    stage_ = stage;
  }

 private:
  void Run() {
    using namespace std::chrono_literals;
    const auto start = std::chrono::steady_clock::now();
    const bool tty = ::isatty(STDERR_FILENO) != 0;
    std::string shown;
    bool printed = false;
    std::unique_lock<std::mutex> lock(mutex_);
    if (cv_.wait_for(lock, 1s, [this] { return done_; })) return;  // quick: say nothing
    while (!done_) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (tty) {
        std::fprintf(stderr, "\rmassprops: %s: %s (%.0f s)\033[K", file_.c_str(), stage_.c_str(), s);
        printed = true;
      } else if (stage_ != shown) {
        std::fprintf(stderr, "massprops: %s: %s (%.0f s)\n", file_.c_str(), stage_.c_str(), s);
        shown = stage_;
      }
      std::fflush(stderr);
      cv_.wait_for(lock, 500ms, [this] { return done_; });
    }
    if (printed) std::fprintf(stderr, "\r\033[K");
  }

  std::string file_;
  std::string stage_ = "reading";
  bool done_ = false;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::thread thread_;
};

}  // namespace massprops::app
