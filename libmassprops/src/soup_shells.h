#pragma once
// Shells of a triangle soup, counted as it streams. Each block of triangles joins its corners (by
// their position hashes) in a small union–find that stays in cache, and hands on only the corners
// whose fan of triangles it did not close, with the block-local piece each is in; the blocks are
// then merged in file order through a frontier of corners still open, which for the usual file
// orders (strips, patches) stays small and in cache. A second shell — nested, overlapping or
// apart — is what a per-triangle balance cannot see (two nested tori close every edge as one does).

#include <cstdint>
#include <map>
#include <mutex>
#include <vector>

namespace massprops::internal {

/// What one block hands on: its pieces (connected sets of its triangles) and its open corners.
struct BlockPieces {
  struct Corner {
    std::uint64_t hash;
    std::uint64_t fan;  ///< Σ over the corner's triangles in the block of h(next) − h(previous): 0 when closed
    std::uint32_t piece;
  };
  std::vector<Corner> open;  ///< the corners whose fan the block leaves open, each once
  std::uint32_t pieces = 0;
};

/// Joins a block's triangles by their corners: `corner_hash` holds 3 hashes per triangle.
void JoinBlock(const std::uint64_t* corner_hash, int triangles, BlockPieces& out);

/// Merges blocks in order as they are added (from any thread, in any order) and counts shells.
class ShellCounter {
 public:
  ShellCounter();
  ~ShellCounter();
  void Add(std::int64_t block, BlockPieces&& pieces);
  /// Connected shells of all blocks added (0..n−1 each once); −1 beyond 2³² pieces (not counted).
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
