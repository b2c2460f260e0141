#pragma once
// The weld (internal): corners with bit-identical positions (-0.0 == 0.0) become one vertex,
// numbered in order of first appearance. A template over a corner accessor, so that binary STL
// records are welded in place, without a copy of every coordinate.
//
// Two levels, for the cache and for threads: chunks of consecutive corners are welded on their own
// (file order has locality), their distinct positions are scattered into partitions by hash (each
// partition's table stays in cache) and welded there, and vertices are numbered by the rank of
// their first corner (a bitmap with prefix counts). Every step's result depends on the input only,
// so the vertex order is the same bits whatever the thread count — and the same as one hash table
// over all corners in order.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "core/large_array.h"
#include "io/io_internal.h"
#include "massprops/parallel.h"

namespace massprops::weld {

// Welds corners by bit-identical position (with -0.0 == 0.0): doubles (PositionKey), or the
// floats of a binary STL as it stores them (FloatKey: the same equality as the doubles they convert
// to exactly, in half the memory and with a cheaper hash).
template <typename T>
struct Position {
  T x, y, z;
  bool operator==(const Position& o) const { return x == o.x && y == o.y && z == o.z; }
  bool Finite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
};
using PositionKey = Position<double>;
using FloatKey = Position<float>;

// A well-mixed 64-bit hash of a position (-0.0 and 0.0 alike): float-derived doubles have many
// zero low bits, so the coordinates are combined and then mixed (Stafford's variant 13).
inline std::uint64_t Hash(const PositionKey& k) {
  auto bits = [](double d) {
    std::uint64_t u;
    d = d == 0.0 ? 0.0 : d;
    std::memcpy(&u, &d, sizeof u);
    return u;
  };
  std::uint64_t h = bits(k.x) * 0x9E3779B97F4A7C15ull;
  h ^= bits(k.y) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
  h ^= bits(k.z) + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
  h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
  return h ^ (h >> 31);
}

// The same for floats (-0.0f and 0.0f alike): their 96 bits, two multiplications and a mix.
inline std::uint64_t Hash(const FloatKey& k) {
  auto bits = [](float f) {
    std::uint32_t u;
    f = f == 0.0f ? 0.0f : f;
    std::memcpy(&u, &f, sizeof u);
    return static_cast<std::uint64_t>(u);
  };
  std::uint64_t h = (bits(k.x) | bits(k.y) << 32) * 0xD6E8FEB86659FD93ull ^
                    (bits(k.z) + 0x9E3779B97F4A7C15ull) * 0xA0761D6478BD642Full;
  h = (h ^ (h >> 31)) * 0xBF58476D1CE4E5B9ull;
  return h ^ (h >> 29);
}

/// Corners grouped by position.
struct Grouping {
  std::vector<std::int32_t> vertex_of;      ///< per corner: its vertex, numbered by first appearance
  std::vector<std::uint32_t> first_corner;  ///< per vertex: the corner where it first appears
  /// The first corner with a non-finite coordinate, or the corner count when there is none (the
  /// grouping is then not made).
  std::size_t first_non_finite = 0;
};

namespace detail {

// An open-addressing table (linear probing, at most half full) from positions to dense ids in
// order of insertion.
template <typename Key>
class PositionTable {
 public:
  explicit PositionTable(std::size_t expected) {
    while (slots_ < 2 * expected) slots_ *= 2;
    table_.assign(slots_, -1);
    keys_.reserve(expected);  // no copies while the table fills to what is expected
    hashes_.reserve(expected);
  }
  // The id of k, inserting it (with id = size()) when new; `inserted` tells which.
  std::uint32_t Find(const Key& k, std::uint64_t hash, bool& inserted) {
    std::size_t slot = static_cast<std::size_t>(hash) & (slots_ - 1);
    while (true) {
      const std::int32_t id = table_[slot];
      if (id < 0) break;
      if (keys_[static_cast<std::size_t>(id)] == k) {
        inserted = false;
        return static_cast<std::uint32_t>(id);
      }
      slot = (slot + 1) & (slots_ - 1);
    }
    inserted = true;
    const auto id = static_cast<std::uint32_t>(keys_.size());
    table_[slot] = static_cast<std::int32_t>(id);
    keys_.push_back(k);
    hashes_.push_back(hash);
    if (2 * keys_.size() > slots_) Grow();
    return id;
  }
  /// Hints that k (by its hash) is looked up soon: its slot now, and once the slot is in cache
  /// (`second`), the key it leads to.
  void Prefetch(std::uint64_t hash, bool second) const {
    const std::size_t slot = static_cast<std::size_t>(hash) & (slots_ - 1);
    if (!second) {
      __builtin_prefetch(&table_[slot]);
    } else if (const std::int32_t id = table_[slot]; id >= 0) {
      __builtin_prefetch(&keys_[static_cast<std::size_t>(id)]);
    }
  }
  std::vector<Key>& keys() { return keys_; }
  std::vector<std::uint64_t>& hashes() { return hashes_; }

 private:
  void Grow() {
    slots_ *= 2;
    table_.assign(slots_, -1);
    for (std::size_t v = 0; v < keys_.size(); ++v) {
      std::size_t s = static_cast<std::size_t>(hashes_[v]) & (slots_ - 1);
      while (table_[s] >= 0) s = (s + 1) & (slots_ - 1);
      table_[s] = static_cast<std::int32_t>(v);
    }
  }
  std::size_t slots_ = 64;
  std::vector<std::int32_t> table_;
  std::vector<Key> keys_;
  std::vector<std::uint64_t> hashes_;
};

// A thread's slot table for WeldThroughTable, kept from call to call (a fresh one's pages were
// faulted in again for every partition).
struct SlotTable {
  std::vector<std::int32_t> slots;
};

// Welds positions key_at(0 .. n), all finite, through one open-addressing table (linear probing,
// at most half full) of their vertex numbers in order of first appearance, each compared through
// key_at at its first index (nothing copied): calls each(i, vertex) and returns each vertex's
// first index.
template <typename KeyAt, typename Each>
std::vector<std::uint32_t> WeldThroughTable(std::size_t n, const KeyAt& key_at, const Each& each) {
  std::size_t slots = 64;
  while (slots < 2 * n) slots *= 2;
  std::vector<std::int32_t>& table = ThreadScratch<SlotTable>().slots;
  table.assign(slots, -1);
  std::vector<std::uint32_t> first;
  first.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = key_at(i);
    std::size_t slot = static_cast<std::size_t>(Hash(k)) & (slots - 1);
    std::int32_t id = table[slot];
    while (id >= 0 && !(key_at(first[static_cast<std::size_t>(id)]) == k)) {
      slot = (slot + 1) & (slots - 1);
      id = table[slot];
    }
    if (id < 0) {
      id = static_cast<std::int32_t>(first.size());
      table[slot] = id;
      first.push_back(static_cast<std::uint32_t>(i));
    }
    each(i, static_cast<std::uint32_t>(id));
  }
  if (slots > (std::size_t{1} << 18)) table = {};  // a large one is let go
  return first;
}

}  // namespace detail

// A vertex list of one chunk (mostly distinct positions): one table, nothing to scatter or
// number (a third of the general path's time for 10^4 vertices).
template <typename CornerAt>
Grouping GroupFewVertices(std::size_t n, const CornerAt& corner_at) {
  Grouping g;
  g.first_non_finite = n;
  for (std::size_t i = 0; i < n; ++i) {
    if (!corner_at(i).Finite()) {
      g.first_non_finite = i;
      return g;
    }
  }
  g.vertex_of.resize(n);
  g.first_corner = detail::WeldThroughTable(
      n, corner_at, [&](std::size_t i, std::uint32_t v) { g.vertex_of[i] = static_cast<std::int32_t>(v); });
  return g;
}

/// What the positions to weld are like: the corners of faces (each position several times, in
/// strips: most at the position of one of the last few), or a vertex list (mostly distinct).
enum class Positions { kCorners, kVertices };

namespace detail {
/// The rank of each first corner among all of them (step 4 of GroupByPosition): a bitmap of the
/// first corners with prefix counts.
class FirstCornerRanks {
 public:
  FirstCornerRanks(std::size_t n, const std::vector<std::vector<std::uint32_t>>& firsts)
      : is_first_((n + 63) / 64, 0), rank_before_((n + 63) / 64 + 1, 0) {
    for (const auto& first : firsts) {
      for (std::uint32_t c : first) is_first_[c >> 6] |= std::uint64_t{1} << (c & 63);
      count_ += first.size();
    }
    for (std::size_t w = 0; w < is_first_.size(); ++w) {
      rank_before_[w + 1] = rank_before_[w] + static_cast<std::uint32_t>(__builtin_popcountll(is_first_[w]));
    }
  }
  std::uint32_t operator()(std::uint32_t c) const {
    const std::uint64_t below = is_first_[c >> 6] & ((std::uint64_t{1} << (c & 63)) - 1);
    return rank_before_[c >> 6] + static_cast<std::uint32_t>(__builtin_popcountll(below));
  }
  std::size_t count() const { return count_; }

 private:
  std::vector<std::uint64_t> is_first_;
  std::vector<std::uint32_t> rank_before_;
  std::size_t count_ = 0;
};
}  // namespace detail

/// Step 1 of GroupByPosition for a chunk of face corners [lo, hi): its distinct positions (keys,
/// hashes, first corners, in order of their first corner) and each corner's entry (`local`); the
/// first corner that is not finite in `bad` (then the rest is not filled).
template <typename CornerAt, typename Key>
void WeldChunkCorners(const CornerAt& corner_at, std::size_t lo, std::size_t hi, std::int32_t* local,
                      std::vector<Key>& chunk_keys, std::vector<std::uint64_t>& chunk_hashes,
                      std::vector<std::uint32_t>& chunk_first, std::size_t& bad) {
  detail::PositionTable<Key> table((hi - lo) / 4);
  // Filled here and moved in at the end: neighbouring chunks' vectors share cache lines, and
  // two threads growing them in turn would pass those lines back and forth at every corner.
  std::vector<std::uint32_t> first;
  first.reserve((hi - lo) / 4);
  // Corners read and hashed kAhead ahead of their lookup, their table slots fetched then and the
  // keys those slots lead to half way (the lookups, in order, are those of before). A corner at
  // the position of one of the six corners before it (files list triangles in strips: most
  // corners were among the last few) takes that corner's entry, with no hash and no lookup.
  constexpr std::size_t kAhead = 16;
  constexpr std::size_t recent = 6;
  Key ahead_key[kAhead];
  std::uint64_t ahead_hash[kAhead];
  std::size_t ahead_same[kAhead];  // 0, or how many corners back the same position was
  auto read = [&](std::size_t j) {
    const Key k = corner_at(j);
    ahead_key[j % kAhead] = k;
    std::size_t same = 0;
    for (std::size_t d = 1; d <= recent && d <= j - lo && same == 0; ++d) {
      if (ahead_key[(j - d) % kAhead] == k) same = d;
    }
    ahead_same[j % kAhead] = same;
    if (same == 0) {
      ahead_hash[j % kAhead] = Hash(k);
      table.Prefetch(ahead_hash[j % kAhead], false);
    }
  };
  for (std::size_t j = lo; j < std::min(hi, lo + kAhead); ++j) read(j);
  for (std::size_t i = lo; i < hi; ++i) {
    const Key k = ahead_key[i % kAhead];
    const std::size_t same = ahead_same[i % kAhead];
    const std::uint64_t h = same == 0 ? ahead_hash[i % kAhead] : 0;  // (hashed only when looked up)
    if (i + kAhead < hi) read(i + kAhead);
    if (const std::size_t m = i + kAhead / 2; m < hi && ahead_same[m % kAhead] == 0) {
      table.Prefetch(ahead_hash[m % kAhead], true);
    }
    if (same != 0) {  // an earlier corner of the chunk, finite and looked up already
      local[i] = local[i - same];
      continue;
    }
    if (!k.Finite()) {
      bad = i;
      return;
    }
    bool inserted = false;
    local[i] = static_cast<std::int32_t>(table.Find(k, h, inserted));
    if (inserted) first.push_back(static_cast<std::uint32_t>(i));
  }
  chunk_first = std::move(first);
  chunk_keys = std::move(table.keys());
  chunk_hashes = std::move(table.hashes());
}

// `corner_at(i)` gives corner i's position: a PositionKey, or a FloatKey.
template <typename CornerAt>
Grouping GroupByPosition(std::size_t n, const CornerAt& corner_at, int num_threads = 0,
                         Positions kind = Positions::kCorners) {
  using Key = std::decay_t<decltype(corner_at(std::size_t{0}))>;
  constexpr std::size_t kChunk = std::size_t{1} << 16;
  if (kind == Positions::kVertices && n <= kChunk) return GroupFewVertices(n, corner_at);
  Grouping g;
  g.first_non_finite = n;
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw std::length_error("more than 2^31 corners");
  }
  // 1. Weld each chunk of consecutive corners on its own (read in file order; neighbouring faces
  // share most corners, so a chunk's distinct positions are few). Its distinct positions are
  // "entries", listed in order of their first corner. A vertex list's positions are mostly
  // distinct: each is an entry as it is (a chunk table found next to nothing, at the cost of a
  // lookup each: 5·10⁵ vertices welded in 38 ms with it, 27 without), and step 3 welds them.
  const std::size_t chunks = std::max<std::size_t>(1, (n + kChunk - 1) / kChunk);
  // Each corner's entry in its chunk; at the end, in place, its vertex (the one array of n).
  std::vector<std::int32_t> local(n);
  std::vector<std::vector<Key>> chunk_keys(chunks);
  std::vector<std::vector<std::uint64_t>> chunk_hashes(chunks);
  std::vector<std::vector<std::uint32_t>> chunk_first(chunks);
  std::vector<std::size_t> bad(chunks, n);
  ParallelForBlocks(static_cast<std::int64_t>(chunks), num_threads, [&](std::int64_t bb) {
    const auto b = static_cast<std::size_t>(bb);
    const std::size_t lo = b * kChunk, hi = std::min(n, lo + kChunk);
    if (kind == Positions::kVertices) {            // mostly distinct: every position an entry, welded in step 3
      std::vector<std::uint64_t> hashes(hi - lo);  // (its key and first corner: the position's own)
      for (std::size_t i = lo; i < hi; ++i) {
        const Key k = corner_at(i);
        if (!k.Finite()) {
          bad[b] = i;
          return;
        }
        hashes[i - lo] = Hash(k);
        local[i] = static_cast<std::int32_t>(i - lo);
      }
      chunk_hashes[b] = std::move(hashes);
      return;
    }
    WeldChunkCorners(corner_at, lo, hi, local.data(), chunk_keys[b], chunk_hashes[b], chunk_first[b], bad[b]);
  });
  g.first_non_finite = *std::min_element(bad.begin(), bad.end());
  if (g.first_non_finite < n) return g;
  if (chunks == 1 && kind == Positions::kCorners) {  // one chunk: its table saw every corner in order, and is the weld
    g.vertex_of = std::move(local);
    g.first_corner = std::move(chunk_first[0]);
    return g;
  }
  std::vector<std::size_t> entry_base(chunks + 1, 0);
  for (std::size_t b = 0; b < chunks; ++b) entry_base[b + 1] = entry_base[b] + chunk_hashes[b].size();
  const std::size_t entries = entry_base[chunks];

  // 2. Scatter the entries into partitions by their hash's top bits (each partition's table then
  // stays in cache): partition-major, chunk by chunk, so each partition lists its entries in the
  // order of their first corners.
  int bits = 0;  // partitions of about 2^14 entries
  while (bits < 10 && (entries >> (14 + bits)) > 0) ++bits;
  const std::size_t parts = std::size_t{1} << bits;
  auto part_of = [bits](std::uint64_t h) {
    return bits == 0 ? std::size_t{0} : static_cast<std::size_t>(h >> (64 - bits));
  };
  std::vector<std::size_t> cursor(chunks * parts, 0);
  for (std::size_t b = 0; b < chunks; ++b) {
    for (std::uint64_t h : chunk_hashes[b]) ++cursor[b * parts + part_of(h)];
  }
  std::vector<std::size_t> begin(parts + 1, 0);
  {
    std::size_t at = 0;
    for (std::size_t p = 0; p < parts; ++p) {
      begin[p] = at;
      for (std::size_t b = 0; b < chunks; ++b) {
        const std::size_t c = cursor[b * parts + p];
        cursor[b * parts + p] = at;
        at += c;
      }
    }
    begin[parts] = at;
  }
  // Entry numbers, positions and first corners, grouped by partition (copied so that each
  // partition reads its own entries in sequence).
  // Uninitialised: first touched by the threads that scatter into them.
  internal::LargeArray<std::uint32_t> bucket(entries);
  internal::LargeArray<Key> bucket_key(entries);
  internal::LargeArray<std::uint32_t> bucket_first(entries);
  ParallelForBlocks(static_cast<std::int64_t>(chunks), num_threads, [&](std::int64_t bb) {
    const auto b = static_cast<std::size_t>(bb);  // each chunk writes its own slots
    std::size_t* cur = cursor.data() + b * parts;
    for (std::size_t e = 0; e < chunk_hashes[b].size(); ++e) {
      const std::size_t at = cur[part_of(chunk_hashes[b][e])]++;
      bucket[at] = static_cast<std::uint32_t>(entry_base[b] + e);
      if (kind == Positions::kVertices) {  // the chunk's positions in order, read in order
        bucket_key[at] = corner_at(b * kChunk + e);
        bucket_first[at] = static_cast<std::uint32_t>(b * kChunk + e);
      } else {
        bucket_key[at] = chunk_keys[b][e];
        bucket_first[at] = chunk_first[b][e];
      }
    }
  });

  // 3. Weld each partition's entries: its vertices, each with its first corner.
  internal::LargeArray<std::uint32_t> entry_vertex(entries);  // partition-local for now
  std::vector<std::vector<std::uint32_t>> firsts(parts);
  ParallelForBlocks(static_cast<std::int64_t>(parts), num_threads, [&](std::int64_t pb) {
    const auto p = static_cast<std::size_t>(pb);
    const Key* keys = bucket_key.data() + begin[p];
    const std::uint32_t* entry = bucket.data() + begin[p];
    std::vector<std::uint32_t> first = detail::WeldThroughTable(
        begin[p + 1] - begin[p], [keys](std::size_t i) { return keys[i]; },
        [&](std::size_t i, std::uint32_t v) { entry_vertex[entry[i]] = v; });
    for (std::uint32_t& c : first) c = bucket_first[begin[p] + c];  // the entry's first corner
    firsts[p] = std::move(first);
  });

  // 4. Number the vertices by their first corners: a bitmap of first corners with prefix counts
  // gives each one's rank.
  const detail::FirstCornerRanks rank(n, firsts);
  g.first_corner.resize(rank.count());
  ParallelForBlocks(static_cast<std::int64_t>(parts), num_threads, [&](std::int64_t pb) {
    const auto p = static_cast<std::size_t>(pb);
    std::vector<std::uint32_t> global(firsts[p].size());
    for (std::size_t v = 0; v < global.size(); ++v) {
      global[v] = rank(firsts[p][v]);
      g.first_corner[global[v]] = firsts[p][v];
    }
    for (std::size_t i = begin[p]; i < begin[p + 1]; ++i) entry_vertex[bucket[i]] = global[entry_vertex[bucket[i]]];
  });

  // 5. Each corner's vertex, through its chunk's entry (in place of the entry).
  ParallelForBlocks(static_cast<std::int64_t>(chunks), num_threads, [&](std::int64_t bb) {
    const auto b = static_cast<std::size_t>(bb);
    const std::size_t lo = b * kChunk, hi = std::min(n, lo + kChunk);
    const std::uint32_t* ev = entry_vertex.data() + entry_base[b];
    for (std::size_t i = lo; i < hi; ++i) local[i] = static_cast<std::int32_t>(ev[local[i]]);
  });
  g.vertex_of = std::move(local);
  return g;
}

// The weld, over corners given by an accessor (so binary STL records are read in place, without
// an intermediate copy of every coordinate). `face_sizes` gives each face's corner count in order;
// null, every face is a triangle.
template <typename CornerAt>
LoadedMesh Weld(const std::string& path, std::size_t corners, const CornerAt& corner_at,
                const std::vector<int>* face_sizes, const char* format, int num_threads) {
  LoadedMesh out;
  out.format = format;
  Grouping g = GroupByPosition(corners, corner_at, num_threads);
  if (g.first_non_finite < corners) {
    const auto k = corner_at(g.first_non_finite);
    std::ostringstream msg;
    msg << "triangle " << g.first_non_finite / 3 << " has a non-finite coordinate (" << k.x << ", " << k.y << ", "
        << k.z << ")";
    Fail(path, msg.str());
  }
  out.welded = static_cast<std::int64_t>(corners - g.first_corner.size());
  const std::size_t vertices = g.first_corner.size();
  out.mesh.V.resize(static_cast<Eigen::Index>(vertices), 3);
  constexpr std::size_t kRows = std::size_t{1} << 15;  // first touched by the thread that fills them
  ParallelForBlocks(static_cast<std::int64_t>((vertices + kRows - 1) / kRows), num_threads, [&](std::int64_t b) {
    const std::size_t lo = static_cast<std::size_t>(b) * kRows, hi = std::min(vertices, lo + kRows);
    for (std::size_t v = lo; v < hi; ++v) {
      const auto k = corner_at(g.first_corner[v]);
      out.mesh.V.row(static_cast<Eigen::Index>(v)) << k.x, k.y, k.z;
    }
  });
  out.mesh.indices = std::move(g.vertex_of);
  std::vector<std::int64_t>& offsets = out.mesh.offsets;
  if (face_sizes == nullptr) {
    offsets.reserve(corners / 3 + 1);
    for (std::size_t c = 3; c <= corners; c += 3) offsets.push_back(static_cast<std::int64_t>(c));
  } else {
    offsets.reserve(face_sizes->size() + 1);
    for (int n : *face_sizes) offsets.push_back(offsets.back() + n);
  }
  return out;
}

}  // namespace massprops::weld
