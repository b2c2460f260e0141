// The definitions of massprops/mesh.h: mesh containers.

#include "massprops/mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace massprops {

void SplitPolygon(const std::int32_t* corners, int n, std::vector<std::array<std::int32_t, 3>>& out) {
  constexpr int kFanLimit = 32;
  if (n <= kFanLimit) {
    for (int k = 1; k + 1 < n; ++k) out.push_back({corners[0], corners[k], corners[k + 1]});
    return;
  }
  // The chain corners[i..j] closed by the chord j → i: triangle (i, m, j), then (i..m) and (m..j).
  std::vector<std::pair<int, int>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const int m = i + (j - i) / 2;
    out.push_back({corners[i], corners[m], corners[j]});
    stack.emplace_back(m, j);
    stack.emplace_back(i, m);
  }
}

TriangleMesh Triangulate(const PolygonMesh& mesh) {
  std::int64_t count = 0;
  for (std::int64_t f = 0; f < mesh.num_faces(); ++f) count += std::max(mesh.face_size(f) - 2, 0);
  TriangleMesh out;
  out.V = mesh.V;
  out.F.resize(count, 3);
  std::int64_t t = 0;
  std::vector<std::array<std::int32_t, 3>> tris;
  for (std::int64_t f = 0; f < mesh.num_faces(); ++f) {
    const int n = mesh.face_size(f);
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    if (n <= 32) {  // the fan, written directly (the common case)
      for (int k = 1; k + 1 < n; ++k, ++t) out.F.row(t) << idx[0], idx[k], idx[k + 1];
      continue;
    }
    tris.clear();
    SplitPolygon(idx, n, tris);
    for (const auto& tri : tris) out.F.row(t++) << tri[0], tri[1], tri[2];
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
  // Every face of 3 corners: offsets[f] = 3 f throughout. Their differences or-ed together, which
  // vectorizes on any x86-64 (SSE2 has no 64-bit comparison).
  const std::int64_t* offsets = mesh.offsets.data();
  const auto n = static_cast<std::int64_t>(mesh.offsets.size());
  std::uint64_t differ = 0;
  for (std::int64_t f = 0; f < n; ++f) differ |= static_cast<std::uint64_t>(offsets[f] ^ (3 * f));
  return differ == 0;
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
