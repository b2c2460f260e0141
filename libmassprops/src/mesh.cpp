#include "massprops/mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

PlanarityReport CheckPlanarity(const PolygonMesh& mesh, double tolerance) {
  PlanarityReport r;
  for (std::int64_t f = 0; f < mesh.num_faces(); ++f) {
    const int n = mesh.face_size(f);
    if (n <= 3) continue;
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    Vector3 normal = Vector3::Zero(), centroid = Vector3::Zero();
    Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int k = 0; k < n; ++k) {
      const Vector3 a = mesh.V.row(idx[k]).transpose();
      const Vector3 b = mesh.V.row(idx[(k + 1) % n]).transpose();
      normal += a.cross(b);  // Newell
      centroid += a;
      lo = lo.cwiseMin(a);
      hi = hi.cwiseMax(a);
    }
    centroid /= n;
    const double size = (hi - lo).norm();
    const double len = normal.norm();
    if (!(len > 0) || !(size > 0)) continue;  // degenerate: the topology reports it
    normal /= len;
    double deviation = 0;
    for (int k = 0; k < n; ++k) {
      deviation = std::max(deviation, std::abs(normal.dot(mesh.V.row(idx[k]).transpose() - centroid)));
    }
    deviation /= size;
    if (deviation > tolerance) ++r.non_planar_faces;
    if (deviation > r.worst_deviation) {
      r.worst_deviation = deviation;
      r.worst_face = f;
    }
  }
  return r;
}

}  // namespace massprops
