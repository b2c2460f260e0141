// The definitions of soup_shells.h: shells of a triangle soup, counted as it streams.

#include "mesh/soup_shells.h"

#include <algorithm>

namespace massprops::internal {

void GroupJoiner::Begin(int triangles) {
  std::size_t slots = 64;
  while (slots < 2 * static_cast<std::size_t>(triangles)) slots *= 2;  // a closed surface: ~½ corner a triangle
  if (table_.size() != slots)
    table_.assign(slots, 0);
  else
    std::memset(table_.data(), 0, slots * sizeof(std::uint32_t));
  mask_ = slots - 1;
  hash_.clear();
  fan_.clear();
  parent_.clear();
  std::fill(std::begin(recent_id_), std::end(recent_id_), kNone);
}

void GroupJoiner::Grow() {
  table_.assign(2 * table_.size(), 0);
  mask_ = table_.size() - 1;
  for (std::size_t id = 0; id < hash_.size(); ++id) {
    std::size_t at = Slot(hash_[id], mask_);
    while (table_[at] != 0) at = (at + 1) & mask_;
    table_[at] = static_cast<std::uint32_t>(id + 1);
  }
}

void GroupJoiner::Finish(BlockPieces& out) {
  // Pieces numbered in the order of their smallest corner, which is their set's root.
  const std::size_t unique = hash_.size();
  piece_.resize(unique);
  std::uint32_t pieces = 0;
  out.open.clear();
  for (std::size_t u = 0; u < unique; ++u) {
    const std::uint32_t r = Find(parent_.data(), static_cast<std::uint32_t>(u));
    piece_[u] = r == u ? pieces++ : piece_[r];
    if (fan_[u] != 0) out.open.push_back({hash_[u], fan_[u], piece_[u]});
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
