// The contact step's worker threads (workers.h).

#include "workers.h"

#include <algorithm>

#include "massprops/parallel.h"

namespace dynamics::contact {

Workers::Workers(int threads) {
  for (int t = 1; t < massprops::ThreadCount(threads); ++t) pool_.emplace_back([this] { Work(); });
}

Workers::~Workers() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : pool_) t.join();
}

// Items are taken one at a time under the lock: the items are whole islands or pairs of bodies,
// far costlier than the lock.
void Workers::RunItems() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (next_ < count_) {
    const std::size_t i = next_++;
    void* const job = job_;
    const Call call = call_;
    lock.unlock();
    try {
      call(job, i);
    } catch (...) {
      lock.lock();
      if (!error_) error_ = std::current_exception();
      next_ = count_;  // stop handing out items
      continue;
    }
    lock.lock();
  }
}

void Workers::Work() {
  unsigned long seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    RunItems();
    std::lock_guard<std::mutex> lock(mutex_);
    if (--running_ == 0) finished_.notify_one();
  }
}

void Workers::Run(std::size_t n, void* fn, Call call) {
  if (pool_.empty() || n <= 1) {
    for (std::size_t i = 0; i < n; ++i) call(fn, i);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = fn;
    call_ = call;
    count_ = n;
    next_ = 0;
    running_ = static_cast<int>(pool_.size());
    error_ = nullptr;
    ++generation_;
  }
  wake_.notify_all();
  RunItems();
  std::unique_lock<std::mutex> lock(mutex_);
  finished_.wait(lock, [&] { return running_ == 0; });
  job_ = nullptr;
  if (error_) std::rethrow_exception(error_);
}

}  // namespace dynamics::contact
