// Marching tetrahedra over a regular grid: each cube is cut into the six tetrahedra around its
// main diagonal (the same cut in every cube, so neighbouring cubes share faces and the surface
// has no cracks), and each tetrahedron contributes zero, one or two triangles.

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "massprops/implicit.h"

namespace massprops::implicit {

TriangleMesh Polygonize(const ImplicitSolid& solid, int resolution) {
  if (resolution < 2 || resolution > 1024) throw std::invalid_argument("Polygonize: resolution must be 2..1024");
  const AlignedBox3 box = solid.Bounds();
  const double cell = box.sizes().maxCoeff() / resolution;
  if (!(cell > 0) || !std::isfinite(cell)) throw std::invalid_argument("Polygonize: empty or infinite bounds");
  // One cell of margin so that the surface closes inside the grid.
  const Vector3 lo = box.min() - Vector3::Constant(cell);
  Eigen::Vector3i n;
  for (int k = 0; k < 3; ++k) n[k] = static_cast<int>(std::ceil(box.sizes()[k] / cell)) + 2;
  auto at = [&](int i, int j, int k) { return Vector3(lo + cell * Vector3(i, j, k)); };
  std::vector<double> phi(static_cast<std::size_t>((n.x() + 1) * (n.y() + 1) * (n.z() + 1)));
  auto idx = [&](int i, int j, int k) { return static_cast<std::size_t>(i + (n.x() + 1) * (j + (n.y() + 1) * k)); };
  for (int k = 0; k <= n.z(); ++k)
    for (int j = 0; j <= n.y(); ++j)
      for (int i = 0; i <= n.x(); ++i) phi[idx(i, j, k)] = solid.Value(at(i, j, k));

  // Cube corners c = (dx, dy, dz) as bit masks; the six tetrahedra share the diagonal 0–7.
  static const int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  std::vector<Vector3> out;
  auto emit = [&](Vector3 a, Vector3 b, Vector3 c, const Vector3& outward) {
    if ((b - a).cross(c - a).dot(outward) < 0) std::swap(b, c);
    out.push_back(a);
    out.push_back(b);
    out.push_back(c);
  };
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        std::array<Vector3, 8> p;
        std::array<double, 8> v;
        int inside_corners = 0;
        for (int c = 0; c < 8; ++c) {
          const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
          p[static_cast<std::size_t>(c)] = at(i + di, j + dj, k + dk);
          v[static_cast<std::size_t>(c)] = phi[idx(i + di, j + dj, k + dk)];
          inside_corners += v[static_cast<std::size_t>(c)] <= 0;
        }
        if (inside_corners == 0 || inside_corners == 8) continue;
        for (const auto& t : kTets) {
          std::vector<int> in, outv;
          for (int q = 0; q < 4; ++q) (v[static_cast<std::size_t>(t[q])] <= 0 ? in : outv).push_back(t[q]);
          if (in.empty() || outv.empty()) continue;
          auto cut = [&](int a, int b) {
            const double fa = v[static_cast<std::size_t>(a)], fb = v[static_cast<std::size_t>(b)];
            const double s = fa / (fa - fb);
            return Vector3(p[static_cast<std::size_t>(a)] +
                           s * (p[static_cast<std::size_t>(b)] - p[static_cast<std::size_t>(a)]));
          };
          Vector3 cin = Vector3::Zero(), cout = Vector3::Zero();
          for (int q : in) cin += p[static_cast<std::size_t>(q)] / static_cast<double>(in.size());
          for (int q : outv) cout += p[static_cast<std::size_t>(q)] / static_cast<double>(outv.size());
          const Vector3 outward = cout - cin;
          if (in.size() == 1 || outv.size() == 1) {
            const auto& lone = in.size() == 1 ? in : outv;
            const auto& rest = in.size() == 1 ? outv : in;
            emit(cut(lone[0], rest[0]), cut(lone[0], rest[1]), cut(lone[0], rest[2]), outward);
          } else {  // two and two: a quad
            const Vector3 a = cut(in[0], outv[0]), b = cut(in[0], outv[1]), c = cut(in[1], outv[1]),
                          d = cut(in[1], outv[0]);
            emit(a, b, c, outward);
            emit(a, c, d, outward);
          }
        }
      }
  TriangleMesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(out.size()), 3);
  mesh.F.resize(static_cast<Eigen::Index>(out.size() / 3), 3);
  for (std::size_t q = 0; q < out.size(); ++q) mesh.V.row(static_cast<Eigen::Index>(q)) = out[q].transpose();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    mesh.F.row(f) << static_cast<std::int32_t>(3 * f), static_cast<std::int32_t>(3 * f + 1),
        static_cast<std::int32_t>(3 * f + 2);
  }
  return mesh;
}

}  // namespace massprops::implicit
