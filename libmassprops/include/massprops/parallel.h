#pragma once
/// @file
/// The project's one parallel loop and its one thread-count rule (libmassprops, libdynamics and
/// the front ends use them for every parallel loop). Deterministic block-parallel reduction: the work is cut into
/// blocks whose boundaries depend on
// the problem size only, each block is reduced by one thread in order, and the block results are
// added pairwise in a fixed tree. The bits of the result therefore do not depend on how many
// threads ran or which thread took which block.

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace massprops {

/// The threads a request means: `requested` when positive, else every core (at least one).
inline int ThreadCount(int requested) {
  if (requested > 0) return requested;
  static const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return cores;
}

/// The threads worth starting for `num_blocks` blocks: ThreadCount(requested), at most one a block.
inline int ResolveThreadCount(int requested, std::int64_t num_blocks) {
  return static_cast<int>(std::min<std::int64_t>(ThreadCount(requested), std::max<std::int64_t>(num_blocks, 1)));
}

/// The threads worth starting for `items` items of a few nanoseconds each: one per 2^15 (starting
/// a thread costs about what 2^13 of them do), at most ThreadCount(requested).
inline int ThreadsForItems(int requested, std::int64_t items) { return ResolveThreadCount(requested, items >> 15); }

/// Calls block_fn(b) for b in [0, num_blocks) on up to num_threads threads. If a call throws,
/// the remaining blocks are skipped and the exception of the lowest-numbered failing block seen is
/// rethrown on the calling thread.
template <typename BlockFn>
void ParallelForBlocks(std::int64_t num_blocks, int num_threads, const BlockFn& block_fn) {
  const int threads = ResolveThreadCount(num_threads, num_blocks);
  if (threads <= 1) {
    for (std::int64_t b = 0; b < num_blocks; ++b) block_fn(b);
    return;
  }
  std::atomic<std::int64_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  std::int64_t error_block = num_blocks;
  auto worker = [&]() {
    for (std::int64_t b = next.fetch_add(1); b < num_blocks; b = next.fetch_add(1)) {
      try {
        block_fn(b);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (b < error_block) {
          error_block = b;
          error = std::current_exception();
        }
        next.store(num_blocks);
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

/// This thread's T, made on first use and kept for the thread's life: per-thread scratch reused
/// block after block (one T per thread: give each use its own type). Out of line on purpose: in a shared library a
/// thread_local named inside a hot loop is looked up again (__tls_get_addr) at every use; the reference this returns is
/// not.
template <typename T>
[[gnu::noinline]] T& ThreadScratch() {
  thread_local T scratch;
  return scratch;
}

/// Adds partial results pairwise in a fixed tree (error grows as log2 of the count).
template <typename T>
T PairwiseSum(std::vector<T>& parts) {
  if (parts.empty()) return T{};
  for (std::size_t width = 1; width < parts.size(); width *= 2) {
    for (std::size_t i = 0; i + width < parts.size(); i += 2 * width) parts[i] += parts[i + width];
  }
  return parts[0];
}

}  // namespace massprops
