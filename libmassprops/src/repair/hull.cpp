// The convex hull (CGAL's convex_hull_3, exact predicates): a translation unit of its own, so
// that the hull's headers do not weigh on the repair's.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "massprops/repair/repair.h"
#include "repair/from_surface_mesh.h"

namespace massprops {
namespace {

// The hull in one order whatever the run: CGAL's output order follows its memory addresses (it
// differed between two calls in one process), and contact built on the hull must not. Vertices
// sorted by position, each face starting at its smallest index, faces sorted.
PolygonMesh Canonical(const PolygonMesh& h) {
  const auto n = static_cast<std::size_t>(h.V.rows());
  std::vector<std::int32_t> order(n), rank(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return std::tie(h.V(a, 0), h.V(a, 1), h.V(a, 2)) < std::tie(h.V(b, 0), h.V(b, 1), h.V(b, 2));
  });
  PolygonMesh out;
  out.V.resize(h.V.rows(), 3);
  for (std::size_t k = 0; k < n; ++k) {
    out.V.row(static_cast<Eigen::Index>(k)) = h.V.row(order[k]);
    rank[static_cast<std::size_t>(order[k])] = static_cast<std::int32_t>(k);
  }
  std::vector<std::vector<std::int32_t>> faces;
  for (std::int64_t f = 0; f < h.num_faces(); ++f) {
    std::vector<std::int32_t> face;
    for (std::int64_t c = h.offsets[f]; c < h.offsets[f + 1]; ++c)
      face.push_back(rank[static_cast<std::size_t>(h.indices[c])]);
    std::rotate(face.begin(), std::min_element(face.begin(), face.end()), face.end());
    faces.push_back(std::move(face));
  }
  std::sort(faces.begin(), faces.end());
  for (const auto& face : faces) {  // out.offsets starts with its 0
    out.indices.insert(out.indices.end(), face.begin(), face.end());
    out.offsets.push_back(static_cast<std::int64_t>(out.indices.size()));
  }
  return out;
}

}  // namespace

PolygonMesh ConvexHull(const PolygonMesh& mesh) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = Kernel::Point_3;
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(mesh.V.rows()));
  std::vector<char> used(static_cast<std::size_t>(mesh.V.rows()), 0);
  for (std::int32_t i : mesh.indices) used[static_cast<std::size_t>(i)] = 1;  // only corners of faces
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    if (used[static_cast<std::size_t>(i)]) points.emplace_back(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2));
  }
  auto flat = [] {
    return std::invalid_argument("the convex hull is flat (every corner in one plane or line): it bounds no volume");
  };
  if (points.size() < 4) throw flat();
  CGAL::Surface_mesh<Point> hull;
  CGAL::convex_hull_3(points.begin(), points.end(), hull);
  if (hull.number_of_faces() < 4 || !CGAL::is_closed(hull)) throw flat();  // coplanar input: a polygon
  return Canonical(cgal_internal::FromSurfaceMesh(hull));
}

}  // namespace massprops
