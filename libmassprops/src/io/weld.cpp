// The definitions of weld.h: the weld (internal).

#include "io/weld.h"

namespace massprops {

// Welds corners given one by one (xyz per corner) into shared vertices by bit-identical position.
// Used by the ASCII STL reader and the assimp path.
LoadedMesh WeldCorners(const std::string& path, const std::vector<double>& xyz, const std::vector<int>* face_sizes,
                       const char* format, int num_threads) {
  return weld::Weld(
      path, xyz.size() / 3,
      [&xyz](std::size_t c) {
        return weld::PositionKey{xyz[3 * c], xyz[3 * c + 1], xyz[3 * c + 2]};
      },
      face_sizes, format, num_threads);
}

std::int64_t MergeCoincidentVertices(PolygonMesh& mesh, int num_threads) {
  const auto nv = static_cast<std::size_t>(mesh.V.rows());
  if (nv < 2) return 0;
  const weld::Grouping g = weld::GroupByPosition(
      nv,
      [&mesh](std::size_t v) {
        const auto i = static_cast<Eigen::Index>(v);
        return weld::PositionKey{mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2)};
      },
      num_threads, weld::Positions::kVertices);
  if (g.first_non_finite < nv) return 0;  // the readers refuse non-finite coordinates themselves
  const auto merged = static_cast<std::int64_t>(nv - g.first_corner.size());
  if (merged == 0) return 0;  // the common case: nothing changes, not even the index array
  for (std::int32_t& i : mesh.indices) {
    i = static_cast<std::int32_t>(g.first_corner[static_cast<std::size_t>(g.vertex_of[static_cast<std::size_t>(i)])]);
  }
  return merged;
}

}  // namespace massprops
