#include "soup_shells.h"

#include <algorithm>
#include <utility>

namespace massprops::internal {
namespace {

std::uint32_t Find(std::uint32_t* parent, std::uint32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];  // path halving
    x = parent[x];
  }
  return x;
}

bool Join(std::uint32_t* parent, std::uint32_t a, std::uint32_t b) {
  a = Find(parent, a);
  b = Find(parent, b);
  if (a == b) return false;
  if (a < b) std::swap(a, b);
  parent[a] = b;  // the smaller index is the root
  return true;
}

inline std::size_t Slot(std::uint64_t h, std::size_t mask) { return static_cast<std::size_t>(h ^ (h >> 29)) & mask; }

}  // namespace

void JoinBlock(const std::uint64_t* corner_hash, int triangles, BlockPieces& out) {
  const int corners = 3 * triangles;
  std::size_t slots = 64;
  while (4 * slots < 5 * static_cast<std::size_t>(corners)) slots *= 2;  // at most 3/4 full
  // A slot is empty unless stamped with this call's number: no clearing between blocks.
  struct TableSlot {
    std::uint64_t key;
    std::uint32_t stamp;
    std::int32_t id;
  };
  struct Scratch {
    std::vector<TableSlot> table;
    std::uint32_t stamp = 0;
    std::vector<std::int32_t> id;
    std::vector<std::uint32_t> parent, piece;
    std::vector<std::uint64_t> hash, fan;
  };
  thread_local Scratch scratch;
  Scratch& s = scratch;
  if (s.table.size() < slots || ++s.stamp == 0) {
    s.table.assign(std::max(slots, s.table.size()), TableSlot{0, 0, 0});
    s.stamp = 1;
  }
  const std::uint32_t stamp = s.stamp;
  s.id.resize(static_cast<std::size_t>(corners));
  s.hash.clear();
  const std::size_t mask = slots - 1;
  TableSlot* table = s.table.data();
  for (int i = 0; i < corners; ++i) {
    const std::uint64_t h = corner_hash[i];
    std::size_t at = Slot(h, mask);
    while (table[at].stamp == stamp && table[at].key != h) at = (at + 1) & mask;
    if (table[at].stamp != stamp) table[at] = {h, stamp, static_cast<std::int32_t>(s.hash.size())}, s.hash.push_back(h);
    s.id[static_cast<std::size_t>(i)] = table[at].id;
  }
  const std::size_t unique = s.hash.size();
  s.parent.resize(unique);
  for (std::size_t u = 0; u < unique; ++u) s.parent[u] = static_cast<std::uint32_t>(u);
  s.fan.assign(unique, 0);
  std::uint32_t* parent = s.parent.data();
  const std::uint64_t* hash = s.hash.data();
  std::uint64_t* fan = s.fan.data();
  for (int t = 0; t < triangles; ++t) {
    const int* c = s.id.data() + 3 * t;
    const auto a = static_cast<std::uint32_t>(c[0]), b = static_cast<std::uint32_t>(c[1]),
               d = static_cast<std::uint32_t>(c[2]);
    Join(parent, a, b);
    Join(parent, a, d);
    // Around each corner, the next corner counted +, the previous −: a closed fan sums to 0.
    fan[a] += hash[b] - hash[d];
    fan[b] += hash[d] - hash[a];
    fan[d] += hash[a] - hash[b];
  }
  // Pieces numbered in the order of their smallest corner, which is their set's root.
  s.piece.resize(unique);
  std::uint32_t pieces = 0;
  out.open.clear();
  for (std::size_t u = 0; u < unique; ++u) {
    const std::uint32_t r = Find(parent, static_cast<std::uint32_t>(u));
    s.piece[u] = r == u ? pieces++ : s.piece[r];
    if (fan[u] != 0) out.open.push_back({hash[u], fan[u], s.piece[u]});
  }
  out.pieces = pieces;
}

// Open corners met so far: hash → (piece, fan sum). Linear probing, at most half full, removal
// by shifting back (no tombstones); the hash 0 marks an empty slot (a corner hashing to 0 is
// stored as 1: at worst two corners joined by a 2⁻⁶⁴ chance).
struct ShellCounter::Frontier {
  struct Entry {
    std::uint64_t hash = 0, fan = 0;
    std::uint32_t piece = 0;
  };
  std::vector<Entry> slots = std::vector<Entry>(1024);
  std::size_t size = 0;

  void Grow() {
    std::vector<Entry> old(slots.size() * 2);
    old.swap(slots);
    const std::size_t mask = slots.size() - 1;
    for (const Entry& e : old) {
      if (e.hash == 0) continue;
      std::size_t at = Slot(e.hash, mask);
      while (slots[at].hash != 0) at = (at + 1) & mask;
      slots[at] = e;
    }
  }
  void Erase(std::size_t at) {
    const std::size_t mask = slots.size() - 1;
    std::size_t hole = at;
    for (std::size_t next = (hole + 1) & mask; slots[next].hash != 0; next = (next + 1) & mask) {
      const std::size_t home = Slot(slots[next].hash, mask);
      // Move the entry back into the hole unless its home lies cyclically in (hole, next].
      const bool stays = hole < next ? (home > hole && home <= next) : (home > hole || home <= next);
      if (!stays) {
        slots[hole] = slots[next];
        hole = next;
      }
    }
    slots[hole] = Entry{};
    --size;
  }
};

ShellCounter::ShellCounter() : frontier_(new Frontier) {}
ShellCounter::~ShellCounter() { delete frontier_; }

void ShellCounter::Add(std::int64_t block, BlockPieces&& pieces) {
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    pending_.emplace(block, std::move(pieces));
  }
  // Whoever finds the merger free merges what is ready; blocks left behind are merged by Shells().
  std::unique_lock<std::mutex> merging(merge_mutex_, std::try_to_lock);
  if (merging.owns_lock()) MergeReady();
}

void ShellCounter::MergeReady() {
  for (;;) {
    BlockPieces b;
    {
      std::lock_guard<std::mutex> lock(pending_mutex_);
      auto it = pending_.find(next_);
      if (it == pending_.end()) return;
      b = std::move(it->second);
      pending_.erase(it);
      ++next_;
    }
    const std::uint64_t base = parent_.size();
    if (overflow_ || base + b.pieces > 0xFFFFFFFFull) {
      overflow_ = true;
      continue;
    }
    for (std::uint32_t p = 0; p < b.pieces; ++p) parent_.push_back(static_cast<std::uint32_t>(base + p));
    Frontier& f = *frontier_;
    for (const BlockPieces::Corner& c : b.open) {
      const std::uint64_t h = c.hash == 0 ? 1 : c.hash;
      const auto piece = static_cast<std::uint32_t>(base + c.piece);
      std::size_t mask = f.slots.size() - 1;
      std::size_t at = Slot(h, mask);
      while (f.slots[at].hash != 0 && f.slots[at].hash != h) at = (at + 1) & mask;
      if (f.slots[at].hash == h) {
        if (Join(parent_.data(), f.slots[at].piece, piece)) ++joins_;
        f.slots[at].fan += c.fan;
        if (f.slots[at].fan == 0) f.Erase(at);  // its fans are closed: no later block has it
        continue;
      }
      f.slots[at] = {h, c.fan, piece};
      if (2 * ++f.size > f.slots.size()) f.Grow();
    }
  }
}

std::int64_t ShellCounter::Shells() {
  std::lock_guard<std::mutex> merging(merge_mutex_);
  MergeReady();
  if (overflow_ || !pending_.empty()) return -1;
  return static_cast<std::int64_t>(parent_.size()) - joins_;
}

}  // namespace massprops::internal
