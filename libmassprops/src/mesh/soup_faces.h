#pragma once
// Repeated faces of a triangle soup, found from 64-bit keys of each triangle's corner positions.
// Each group of triangles sorts its keys by their top bits while they are in cache and writes
// them, bucket by bucket, into its own stretch of one array, with the bucket bounds; the repeats
// are then looked for bucket by bucket across the groups, each bucket in a small table that stays
// in cache. The keys cross memory once each way: 8 bytes a triangle (in 2 MB pages where the
// kernel allows).

#include <cstdint>
#include <vector>

#include "core/large_array.h"

namespace massprops::internal {

class FaceKeyBuckets {
 public:
  /// For `triangles` keys arriving in groups of `group_size` (the last may be shorter).
  FaceKeyBuckets(std::int64_t triangles, std::int64_t group_size);
  /// The keys of group g, from any thread, each group once. `scratch` is the caller's (per thread).
  void Put(std::int64_t group, const std::uint64_t* keys, int n, std::vector<std::uint32_t>& scratch);
  /// Whether any key is there twice, once every group is in.
  bool AnyRepeated(int num_threads) const;

 private:
  std::int64_t group_size_, groups_;
  int bits_ = 0;
  std::size_t buckets_ = 0;
  LargeArray<std::uint64_t> keys_;
  std::vector<std::uint32_t> bounds_;  ///< per group, buckets_ + 1 offsets into its stretch
};

}  // namespace massprops::internal
