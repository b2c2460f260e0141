#pragma once
// Progress on stderr for work that takes more than a second, shared by both commands: silent for
// quick work, then "PROGRAM: WHAT: STAGE (N s)" — or a bar with the fraction done and the time
// left, once a fraction is known — refreshed in place on a terminal, or one line per stage (per
// tenth) when stderr is a file or pipe.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace massprops::app {

class Progress {
 public:
  /// `program` and `what` prefix every line ("massprops", the file); nothing is shown unless
  /// `enabled`.
  Progress(std::string program, std::string what, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// The stage now running (shown instead of a bar).
  void Stage(const char* stage);
  /// The fraction done, 0..1 (shown as a bar with the time left). Cheap: call it as often as you like.
  void Fraction(double fraction) { fraction_.store(fraction, std::memory_order_relaxed); }

 private:
  void Run();
  void Show(double seconds, bool tty);

  std::string program_, what_;
  std::string stage_;
  std::string shown_;
  int shown_decile_ = -1;
  bool printed_ = false;
  std::atomic<double> fraction_{-1.0};
  bool done_ = false;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::thread thread_;
};

}  // namespace massprops::app
