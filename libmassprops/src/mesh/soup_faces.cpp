// The definitions of soup_faces.h: repeated faces of a triangle soup, found from 64-bit keys of
// each triangle's corner positions.

#include "mesh/soup_faces.h"

#include <algorithm>
#include <atomic>
#include <cstring>

#include "massprops/parallel.h"

namespace massprops::internal {
namespace {

// A thread's table, kept from bucket to bucket without clearing: the keys of bucket b all have b
// as their top bits, so a slot holding another bucket's key is as good as empty. Cleared once in
// each search (an earlier search's keys of the same bucket would otherwise count).
struct BucketTable {
  std::vector<std::uint64_t> slots;
  std::uint64_t search = 0;  ///< the search it was cleared for
};

std::atomic<std::uint64_t> searches{0};

}  // namespace

FaceKeyBuckets::FaceKeyBuckets(std::int64_t triangles, std::int64_t group_size)
    : group_size_(group_size), groups_((triangles + group_size - 1) / group_size) {
  // About 4 096 keys a bucket (a 64 KB table), 16 to 4 096 buckets.
  bits_ = 4;
  while (bits_ < 12 && (triangles >> bits_) > 4096) ++bits_;
  buckets_ = std::size_t{1} << bits_;
  keys_ = LargeArray<std::uint64_t>(static_cast<std::size_t>(triangles));
  bounds_.resize(static_cast<std::size_t>(groups_) * (buckets_ + 1));
}

void FaceKeyBuckets::Put(std::int64_t group, const std::uint64_t* keys, int n, std::vector<std::uint32_t>& at) {
  const int shift = 64 - bits_;
  at.assign(buckets_ + 1, 0);
  for (int i = 0; i < n; ++i) ++at[(keys[i] >> shift) + 1];
  for (std::size_t b = 0; b < buckets_; ++b) at[b + 1] += at[b];
  std::memcpy(bounds_.data() + static_cast<std::size_t>(group) * (buckets_ + 1), at.data(),
              (buckets_ + 1) * sizeof(std::uint32_t));
  std::uint64_t* out = keys_.data() + group * group_size_;
  for (int i = 0; i < n; ++i) out[at[keys[i] >> shift]++] = keys[i];
}

bool FaceKeyBuckets::AnyRepeated(int num_threads) const {
  // Consecutive buckets on one thread: each group's bounds for them share a cache line, and their
  // keys follow each other in the group's stretch.
  constexpr std::size_t kRun = 16;
  std::atomic<bool> repeated{false};
  const auto runs = static_cast<std::int64_t>((buckets_ + kRun - 1) / kRun);
  const std::uint64_t search = ++searches;
  const int shift = 64 - bits_;
  ParallelForBlocks(runs, num_threads, [&](std::int64_t run) {
    BucketTable& scratch = ThreadScratch<BucketTable>();
    std::vector<std::uint64_t>& table = scratch.slots;
    if (scratch.search != search) {
      std::fill(table.begin(), table.end(), 0);
      scratch.search = search;
    }
    for (std::size_t b = static_cast<std::size_t>(run) * kRun; b < std::min(buckets_, (run + 1) * kRun); ++b) {
      if (repeated.load(std::memory_order_relaxed)) return;
      std::size_t total = 0;
      for (std::int64_t g = 0; g < groups_; ++g) {
        const std::uint32_t* bounds = bounds_.data() + static_cast<std::size_t>(g) * (buckets_ + 1);
        total += bounds[b + 1] - bounds[b];
      }
      std::size_t slots = 16;
      while (slots < 2 * total) slots *= 2;
      if (table.size() < slots) table.resize(slots, 0);
      // Empty: 0 (a key of 0 is stored as 1: two keys confused, a 2⁻⁶⁴ chance), or another bucket's.
      std::uint64_t* t = table.data();
      auto empty = [b, shift](std::uint64_t k) { return k == 0 || (k >> shift) != b; };
      const std::size_t mask = slots - 1;
      for (std::int64_t g = 0; g < groups_; ++g) {
        const std::uint32_t* bounds = bounds_.data() + static_cast<std::size_t>(g) * (buckets_ + 1);
        const std::uint64_t* keys = keys_.data() + g * group_size_;
        for (std::uint32_t i = bounds[b]; i < bounds[b + 1]; ++i) {
          const std::uint64_t k = keys[i] == 0 ? 1 : keys[i];
          std::size_t at = static_cast<std::size_t>(k) & mask;  // the low bits: the top ones chose the bucket
          for (; !empty(t[at]); at = (at + 1) & mask) {
            if (t[at] == k) {
              repeated.store(true, std::memory_order_relaxed);
              return;
            }
          }
          t[at] = k;
        }
      }
    }
  });
  return repeated.load();
}

}  // namespace massprops::internal
