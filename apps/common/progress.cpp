// The definitions of progress.h: progress on stderr for work that takes more than a second, shared
// by both commands.

#include "progress.h"

#include <cstdio>

#include <unistd.h>

namespace massprops::app {

Progress::Progress(std::string program, std::string what, bool enabled)
    : program_(std::move(program)), what_(std::move(what)) {
  if (enabled) thread_ = std::thread([this] { Run(); });
}

Progress::~Progress() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Progress::Stage(const char* stage) {
  std::lock_guard<std::mutex> lock(mutex_);
  stage_ = stage;
}

void Progress::Show(double seconds, bool tty) {
  const double f = fraction_.load(std::memory_order_relaxed);
  const std::string head = program_ + (what_.empty() ? "" : ": " + what_);
  if (f >= 0) {
    const int decile = static_cast<int>(f * 10);
    if (!tty && decile == shown_decile_) return;
    shown_decile_ = decile;
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(f * kWidth);
    const double eta = f > 0 ? seconds * (1 - f) / f : 0;
    std::fprintf(stderr, "%s%s [%.*s%*s] %3.0f%%  %.0f s elapsed, ~%.0f s left%s", tty ? "\r" : "", head.c_str(),
                 filled, "##############################", kWidth - filled, "", 100 * f, seconds, eta,
                 tty ? "\033[K" : "\n");
  } else if (tty) {
    std::fprintf(stderr, "\r%s: %s (%.0f s)\033[K", head.c_str(), stage_.c_str(), seconds);
  } else if (stage_ != shown_) {
    std::fprintf(stderr, "%s: %s (%.0f s)\n", head.c_str(), stage_.c_str(), seconds);
    shown_ = stage_;
  }
  printed_ = printed_ || tty;
  std::fflush(stderr);
}

void Progress::Run() {
  using namespace std::chrono_literals;
  const auto start = std::chrono::steady_clock::now();
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  std::unique_lock<std::mutex> lock(mutex_);
  if (cv_.wait_for(lock, 1s, [this] { return done_; })) return;  // quick: say nothing
  while (!done_) {
    Show(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), tty);
    cv_.wait_for(lock, tty ? 200ms : 500ms, [this] { return done_; });
  }
  if (printed_) std::fprintf(stderr, "\r\033[K");
}

}  // namespace massprops::app
