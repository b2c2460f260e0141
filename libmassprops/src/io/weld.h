#pragma once
// The weld (internal): corners with bit-identical positions (-0.0 == 0.0) become one vertex,
// numbered in order of first appearance. A template over a corner accessor, so that binary STL
// records are welded in place, without a copy of every coordinate.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "io_internal.h"

namespace massprops::weld {

// Welds corners by bit-identical position (with -0.0 == 0.0).
struct PositionKey {
  double x, y, z;
  bool operator==(const PositionKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    auto bits = [](double d) {
      std::uint64_t u;
      d = d == 0.0 ? 0.0 : d;
      std::memcpy(&u, &d, sizeof u);
      return u;
    };
    std::uint64_t h = bits(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= bits(k.y) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
    h ^= bits(k.z) + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

// The weld, over corners given by an accessor (so binary STL records are read in place, without
// an intermediate copy of every coordinate).
template <typename CornerAt>
LoadedMesh Weld(const std::string& path, std::size_t corners, const CornerAt& corner_at,
                const std::vector<int>& face_sizes, const char* format) {
  LoadedMesh out;
  out.format = format;
  // Open addressing with linear probing over a power-of-two table of vertex ids (−1: empty),
  // at most half full: no allocation per vertex, unlike a node-based map. Vertices are numbered
  // in order of first appearance.
  // A closed triangle mesh has about corners/6 distinct vertices: start there and double the
  // table whenever it gets half full.
  std::size_t slots = 16;
  int shift = 60;  // slot = top log2(slots) bits of the mixed hash
  while (slots < corners / 3) slots *= 2, --shift;
  std::vector<std::int32_t> table(slots, -1);
  auto mix = [](std::uint64_t h) {
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
    return h ^ (h >> 31);
  };
  const PositionHash hash;
  std::vector<double> verts;
  verts.reserve(corners / 2 + 3);
  out.mesh.indices.reserve(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    const PositionKey k = corner_at(c);
    if (!std::isfinite(k.x) || !std::isfinite(k.y) || !std::isfinite(k.z)) {
      std::ostringstream msg;
      msg << "triangle " << c / 3 << " has a non-finite coordinate (" << k.x << ", " << k.y << ", " << k.z << ")";
      Fail(path, msg.str());
    }
    // Float-derived doubles have many zero low bits: mix (Stafford's variant 13) and take the top bits.
    std::size_t slot = static_cast<std::size_t>(mix(hash(k)) >> shift);
    while (true) {
      const std::int32_t id = table[slot];
      if (id < 0) {
        table[slot] = static_cast<std::int32_t>(verts.size() / 3);
        out.mesh.indices.push_back(table[slot]);
        verts.insert(verts.end(), {k.x, k.y, k.z});
        if (2 * (verts.size() / 3) > slots) {  // grow: reinsert every vertex id
          slots *= 2;
          --shift;
          table.assign(slots, -1);
          for (std::size_t v = 0; v < verts.size() / 3; ++v) {
            const PositionKey kv{verts[3 * v], verts[3 * v + 1], verts[3 * v + 2]};
            std::size_t sl = static_cast<std::size_t>(mix(hash(kv)) >> shift);
            while (table[sl] >= 0) sl = (sl + 1) & (slots - 1);
            table[sl] = static_cast<std::int32_t>(v);
          }
        }
        break;
      }
      const double* v = verts.data() + 3 * static_cast<std::size_t>(id);
      if (v[0] == k.x && v[1] == k.y && v[2] == k.z) {
        out.mesh.indices.push_back(id);
        ++out.welded;
        break;
      }
      slot = (slot + 1) & (slots - 1);
    }
  }
  out.mesh.offsets.reserve(face_sizes.size() + 1);
  for (int n : face_sizes) out.mesh.offsets.push_back(out.mesh.offsets.back() + n);
  out.mesh.V = Eigen::Map<const VertexMatrix>(verts.data(), static_cast<Eigen::Index>(verts.size() / 3), 3);
  return out;
}

}  // namespace massprops::weld
