// The definitions of tolerance_weld.h: the repair's tolerance weld (internal).

#include "repair/tolerance_weld.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace massprops::internal {
namespace {

struct Cell {
  std::int64_t x, y, z;
  bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
};

std::uint64_t Mix(const Cell& c) {
  std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
  h ^= static_cast<std::uint64_t>(c.y) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
  h ^= static_cast<std::uint64_t>(c.z) + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
  h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
  return h ^ (h >> 31);
}

// Cells -> the first kept vertex in the cell (the others follow through `next`). Open addressing,
// linear probing, at most half full.
class CellTable {
 public:
  explicit CellTable(std::size_t expected) {
    while (slots_ < 2 * expected) slots_ *= 2;
    cells_.resize(slots_);
    head_.assign(slots_, -1);
  }
  std::int32_t Head(const Cell& c) const {
    for (std::size_t s = Mix(c) & (slots_ - 1);; s = (s + 1) & (slots_ - 1)) {
      if (head_[s] < 0 || cells_[s] == c) return head_[s];
    }
  }
  // Makes v the cell's head; returns the previous head (or -1).
  std::int32_t Push(const Cell& c, std::int32_t v) {
    std::size_t s = Mix(c) & (slots_ - 1);
    while (head_[s] >= 0 && !(cells_[s] == c)) s = (s + 1) & (slots_ - 1);
    const std::int32_t previous = head_[s];
    cells_[s] = c;
    head_[s] = v;
    return previous;
  }

 private:
  std::size_t slots_ = 64;
  std::vector<Cell> cells_;
  std::vector<std::int32_t> head_;
};

}  // namespace

std::vector<std::int32_t> WeldWithinTolerance(const VertexMatrix& V, double tol, std::int64_t& merged) {
  const auto n = static_cast<std::size_t>(V.rows());
  std::vector<std::int32_t> rep(n);
  for (std::size_t i = 0; i < n; ++i) rep[i] = static_cast<std::int32_t>(i);
  merged = 0;
  if (!(tol > 0) || n == 0) return rep;
  const Vector3 lo = V.colwise().minCoeff().transpose();
  const double cell = 2 * tol;
  // Cell coordinates relative to the lowest corner stay within int64 unless the mesh spans more
  // than 2^62 cells, where welding within tol means nothing in double precision anyway.
  if (!((V.colwise().maxCoeff().transpose() - lo).maxCoeff() / cell < 0x1p62)) return rep;
  CellTable table(n);
  std::vector<std::int32_t> next(n, -1);  // the next kept vertex in the same cell
  const double tol2 = tol * tol;
  for (std::size_t i = 0; i < n; ++i) {
    const Vector3 p = V.row(static_cast<Eigen::Index>(i)).transpose();
    const Vector3 rel = p - lo;
    std::int64_t from[3], to[3];
    for (int k = 0; k < 3; ++k) {
      from[k] = static_cast<std::int64_t>(std::floor((rel[k] - tol) / cell));
      to[k] = static_cast<std::int64_t>(std::floor((rel[k] + tol) / cell));
    }
    std::int32_t best = std::numeric_limits<std::int32_t>::max();
    for (std::int64_t x = from[0]; x <= to[0]; ++x) {
      for (std::int64_t y = from[1]; y <= to[1]; ++y) {
        for (std::int64_t z = from[2]; z <= to[2]; ++z) {
          for (std::int32_t j = table.Head({x, y, z}); j >= 0; j = next[static_cast<std::size_t>(j)]) {
            if (j < best && (V.row(j).transpose() - p).squaredNorm() <= tol2) best = j;
          }
        }
      }
    }
    if (best != std::numeric_limits<std::int32_t>::max()) {
      rep[i] = best;
      ++merged;
      continue;
    }
    const Cell own{static_cast<std::int64_t>(std::floor(rel[0] / cell)),
                   static_cast<std::int64_t>(std::floor(rel[1] / cell)),
                   static_cast<std::int64_t>(std::floor(rel[2] / cell))};
    next[i] = table.Push(own, static_cast<std::int32_t>(i));
  }
  return rep;
}

}  // namespace massprops::internal
