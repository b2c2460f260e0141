#pragma once
// Shells of a triangle soup, counted as it streams. The triangles of each group (a few blocks in
// file order) are joined by their corners' position hashes as they are read, in a hash table and
// union–find that stay in cache; a group hands on only the corners whose fan of triangles it did
// not close, with the piece each is in. The groups are then merged in file order through a
// frontier of corners still open, which for the usual file orders (strips, patches) stays small
// and in cache. A second shell — nested, overlapping or apart — is what a per-triangle balance
// cannot see (two nested tori close every edge as one does).

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

namespace massprops::internal {

/// Union–find over corner or piece numbers, for the groups and their merge alike.
inline std::uint32_t Find(std::uint32_t* parent, std::uint32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];  // path halving
    x = parent[x];
  }
  return x;
}

/// Joins the sets of a and b, the smaller root staying the root; false if they were one already.
inline bool Join(std::uint32_t* parent, std::uint32_t a, std::uint32_t b) {
  a = Find(parent, a);
  b = Find(parent, b);
  if (a == b) return false;
  if (a < b) std::swap(a, b);
  parent[a] = b;
  return true;
}

/// A corner hash's slot in a table of mask + 1 slots (a power of two).
inline std::size_t Slot(std::uint64_t h, std::size_t mask) { return static_cast<std::size_t>(h ^ (h >> 29)) & mask; }

/// What one group hands on: its pieces (connected sets of its triangles) and its open corners.
struct BlockPieces {
  struct Corner {
    std::uint64_t hash;
    std::uint64_t fan;  ///< Σ over the corner's triangles in the group of h(next) − h(previous): 0 when closed
    std::uint32_t piece;
  };
  std::vector<Corner> open;  ///< the corners whose fan the group leaves open, each once
  std::uint32_t pieces = 0;
};

/// Joins one group's triangles by their corners, one triangle at a time (reused group after group).
class GroupJoiner {
 public:
  /// Starts a group of about `triangles` triangles (the table grows if they share few corners).
  void Begin(int triangles);
  /// One triangle, by its corners' hashes in order.
  void Add(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    const std::uint32_t ia = Id(a), ib = Id(b), ic = Id(c);
    Join(parent_.data(), ia, ib);
    Join(parent_.data(), ia, ic);
    // Around each corner, the next corner counted +, the previous −: a closed fan sums to 0.
    fan_[ia] += b - c;
    fan_[ib] += c - a;
    fan_[ic] += a - b;
  }
  /// Triangles by their corners' hashes, 3 a triangle: the table slots are fetched ahead.
  void AddAll(const std::uint64_t* hash, int triangles) {
    constexpr int kAhead = 8;
    const int corners = 3 * triangles;
    for (int i = 0; i < std::min(corners, 3 * kAhead); ++i) __builtin_prefetch(&table_[Slot(hash[i], mask_)]);
    for (int t = 0; t < triangles; ++t) {
      if (t + kAhead < triangles) {
        const std::uint64_t* ahead = hash + 3 * (t + kAhead);
        __builtin_prefetch(&table_[Slot(ahead[0], mask_)]);
        __builtin_prefetch(&table_[Slot(ahead[1], mask_)]);
        __builtin_prefetch(&table_[Slot(ahead[2], mask_)]);
      }
      Add(hash[3 * t], hash[3 * t + 1], hash[3 * t + 2]);
    }
  }
  /// The group's pieces, numbered in the order of their first corner, and its open corners.
  void Finish(BlockPieces& out);

 private:
  std::uint32_t Id(std::uint64_t h) {
    // Files list triangles in strips and patches: most corners were among the last few seen.
    for (int k = 0; k < kRecent; ++k) {
      if (recent_hash_[k] == h && recent_id_[k] != kNone) return recent_id_[k];
    }
    const std::uint32_t id = Lookup(h);
    recent_hash_[next_recent_] = h;
    recent_id_[next_recent_] = id;
    next_recent_ = (next_recent_ + 1) % kRecent;
    return id;
  }
  std::uint32_t Lookup(std::uint64_t h) {
    std::size_t at = Slot(h, mask_);
    for (std::uint32_t s; (s = table_[at]) != 0; at = (at + 1) & mask_) {
      if (hash_[s - 1] == h) return s - 1;
    }
    const auto id = static_cast<std::uint32_t>(hash_.size());
    table_[at] = id + 1;
    hash_.push_back(h);
    parent_.push_back(id);
    fan_.push_back(0);
    if (2 * hash_.size() > table_.size()) Grow();
    return id;
  }
  void Grow();

  static constexpr int kRecent = 8;
  std::uint64_t recent_hash_[kRecent] = {};
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;  ///< an unused entry of the recent corners
  std::uint32_t recent_id_[kRecent] = {kNone, kNone, kNone, kNone, kNone, kNone, kNone, kNone};
  int next_recent_ = 0;
  std::vector<std::uint32_t> table_;  ///< corner id + 1 by hash slot; 0 is empty (at most half full)
  std::size_t mask_ = 0;
  std::vector<std::uint64_t> hash_, fan_;  ///< by corner id, in order of first appearance
  std::vector<std::uint32_t> parent_, piece_;
};

/// Merges groups in order as they are added (from any thread, in any order) and counts shells.
class ShellCounter {
 public:
  ShellCounter();
  ~ShellCounter();
  void Add(std::int64_t group, BlockPieces&& pieces);
  /// Connected shells of all groups added (0..n−1 each once); −1 beyond 2³² pieces (not counted).
  /// Corners are equal when their hashes are; the same count whatever the order of Add.
  std::int64_t Shells();

 private:
  struct Frontier;
  void MergeReady();
  std::mutex pending_mutex_, merge_mutex_;
  std::map<std::int64_t, BlockPieces> pending_;
  std::int64_t next_ = 0;
  std::vector<std::uint32_t> parent_;
  std::int64_t joins_ = 0;
  bool overflow_ = false;
  Frontier* frontier_;
};

}  // namespace massprops::internal
