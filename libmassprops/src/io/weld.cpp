#include "weld.h"

namespace massprops {

// Welds corners given one by one (xyz per corner) into shared vertices by bit-identical position,
// with faces given by their corner counts. Used by the STL readers and the assimp path.
LoadedMesh WeldCorners(const std::string& path, const std::vector<double>& xyz, const std::vector<int>& face_sizes,
                       const char* format) {
  return weld::Weld(
      path, xyz.size() / 3,
      [&xyz](std::size_t c) {
        return weld::PositionKey{xyz[3 * c], xyz[3 * c + 1], xyz[3 * c + 2]};
      },
      face_sizes, format);
}

std::int64_t MergeCoincidentVertices(PolygonMesh& mesh) {
  const auto nv = static_cast<std::size_t>(mesh.V.rows());
  if (nv < 2) return 0;
  // Open addressing over the vertices: each position maps to its first vertex.
  std::size_t slots = 16;
  while (slots < 2 * nv) slots *= 2;
  std::vector<std::int32_t> table(slots, -1);
  std::vector<std::int32_t> first(nv);
  const weld::PositionHash hash;
  std::int64_t merged = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const weld::PositionKey k{mesh.V(static_cast<Eigen::Index>(v), 0), mesh.V(static_cast<Eigen::Index>(v), 1),
                              mesh.V(static_cast<Eigen::Index>(v), 2)};
    std::size_t slot = hash(k) & (slots - 1);
    while (true) {
      const std::int32_t id = table[slot];
      if (id < 0) {
        table[slot] = static_cast<std::int32_t>(v);
        first[v] = static_cast<std::int32_t>(v);
        break;
      }
      const auto row = mesh.V.row(id);
      if (row(0) == k.x && row(1) == k.y && row(2) == k.z) {
        first[v] = id;
        ++merged;
        break;
      }
      slot = (slot + 1) & (slots - 1);
    }
  }
  if (merged == 0) return 0;  // the common case: nothing changes, not even the index array
  for (std::int32_t& i : mesh.indices) i = first[static_cast<std::size_t>(i)];
  return merged;
}

}  // namespace massprops
