#pragma once
// A small pool of worker threads kept between contact steps (internal to ContactWorld): starting
// threads each step costs more than a small step's work. ForEach's items are independent;
// Together's run at once and may wait on each other. Which thread runs which item never changes a
// result.

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace dynamics::contact {

class Workers {
 public:
  /// `threads` in all, the caller's included (0: one per core).
  explicit Workers(int threads);
  ~Workers();
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;

  int threads() const { return static_cast<int>(pool_.size()) + 1; }
  /// fn(i) for every i in [0, n), on the caller and the workers; returns when all are done.
  /// Rethrows the first exception an item threw. (fn is called through a pointer: nothing is
  /// allocated to hand it over.)
  template <class F>
  void ForEach(std::size_t n, F&& fn) {
    using Fn = std::remove_reference_t<F>;
    Run(n, const_cast<void*>(static_cast<const void*>(&fn)), [](void* f, std::size_t i) { (*static_cast<Fn*>(f))(i); });
  }
  /// fn(i) for every i in [0, n), n from 2 to threads(), each on a thread of its own, all at once:
  /// an item may wait for another's progress (sweep_lanes.h). A thread takes an item only after
  /// finishing its last, and none finishes while another waits for it, so the n threads each take
  /// one. fn must not throw (an item that stopped would leave the others waiting).
  template <class F>
  void Together(std::size_t n, F&& fn) {
    if (n < 2 || n > static_cast<std::size_t>(threads())) throw std::logic_error("Workers::Together: bad item count");
    ForEach(n, std::forward<F>(fn));
  }

 private:
  using Call = void (*)(void*, std::size_t);
  void Run(std::size_t n, void* fn, Call call);
  void Work();
  void RunItems();

  std::vector<std::thread> pool_;
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  void* job_ = nullptr;  // the present job's callable, called through call_
  Call call_ = nullptr;
  std::size_t count_ = 0, next_ = 0;
  int running_ = 0;  // workers still on the present job
  unsigned long generation_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace dynamics::contact
