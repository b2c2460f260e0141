// The convex hull (CGAL's convex_hull_3, exact predicates): a translation unit of its own, so
// that the hull's headers do not weigh on the repair's.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <stdexcept>
#include <vector>

#include "from_surface_mesh.h"
#include "massprops/repair.h"

namespace massprops {

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
  return cgal_internal::FromSurfaceMesh(hull);
}

}  // namespace massprops
