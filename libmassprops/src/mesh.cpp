#include "massprops/mesh.h"

namespace massprops {

TriangleMesh Triangulate(const PolygonMesh& mesh) {
  std::int64_t count = 0;
  for (std::int64_t f = 0; f < mesh.num_faces(); ++f) count += std::max(mesh.face_size(f) - 2, 0);
  TriangleMesh out;
  out.V = mesh.V;
  out.F.resize(count, 3);
  std::int64_t t = 0;
  for (std::int64_t f = 0; f < mesh.num_faces(); ++f) {
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    for (int k = 1; k + 1 < mesh.face_size(f); ++k, ++t) out.F.row(t) << idx[0], idx[k], idx[k + 1];
  }
  return out;
}

PolygonMesh ToPolygonMesh(const TriangleMesh& mesh) {
  PolygonMesh out;
  out.V = mesh.V;
  out.indices.assign(mesh.F.data(), mesh.F.data() + mesh.F.size());
  out.offsets.resize(static_cast<std::size_t>(mesh.F.rows()) + 1);
  for (std::size_t f = 0; f < out.offsets.size(); ++f) out.offsets[f] = 3 * static_cast<std::int64_t>(f);
  return out;
}

bool IsAllTriangles(const PolygonMesh& mesh) {
  for (std::int64_t f = 0; f < mesh.num_faces(); ++f) {
    if (mesh.face_size(f) != 3) return false;
  }
  return true;
}

}  // namespace massprops
