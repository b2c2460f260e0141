// The only translation unit that includes CGAL (heavy headers: keep them here).

#include "massprops/repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/box_intersection_d.h>
#include "from_surface_mesh.h"

namespace massprops {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Polygon = std::vector<std::size_t>;

double SignedVolume(const VertexMatrix& V, const std::vector<std::array<std::int32_t, 3>>& tris) {
  if (V.rows() == 0) return 0;
  const Vector3 ref = 0.5 * (V.colwise().minCoeff() + V.colwise().maxCoeff()).transpose();
  double v = 0;
  for (const auto& t : tris) {
    const Vector3 a = V.row(t[0]).transpose() - ref, b = V.row(t[1]).transpose() - ref,
                  c = V.row(t[2]).transpose() - ref;
    v += a.dot(b.cross(c));
  }
  return v / 6.0;
}

std::vector<std::array<std::int32_t, 3>> Fans(const PolygonMesh& m) {
  std::vector<std::array<std::int32_t, 3>> t;
  for (std::int64_t f = 0; f < m.num_faces(); ++f) {
    const std::int32_t* idx = m.indices.data() + m.offsets[f];
    SplitPolygon(idx, m.face_size(f), t);
  }
  return t;
}

// Merges vertices within `tol` (absolute) of an earlier one, through a hash grid of cell `tol`.
std::vector<std::int32_t> WeldWithin(const VertexMatrix& V, double tol, std::int64_t& merged) {
  std::vector<std::int32_t> rep(static_cast<std::size_t>(V.rows()));
  merged = 0;
  if (tol <= 0) {
    for (std::size_t i = 0; i < rep.size(); ++i) rep[i] = static_cast<std::int32_t>(i);
    return rep;
  }
  struct KeyHash {
    std::size_t operator()(const std::array<std::int64_t, 3>& k) const {
      return static_cast<std::size_t>(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
    }
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::int32_t>, KeyHash> grid;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const std::array<std::int64_t, 3> cell = {static_cast<std::int64_t>(std::floor(V(i, 0) / tol)),
                                              static_cast<std::int64_t>(std::floor(V(i, 1) / tol)),
                                              static_cast<std::int64_t>(std::floor(V(i, 2) / tol))};
    std::int32_t found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx) {
      for (int dy = -1; dy <= 1 && found < 0; ++dy) {
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
          if (it == grid.end()) continue;
          for (std::int32_t j : it->second) {
            if ((V.row(i) - V.row(j)).norm() <= tol) {
              found = j;
              break;
            }
          }
        }
      }
    }
    if (found >= 0) {
      rep[static_cast<std::size_t>(i)] = found;
      ++merged;
    } else {
      rep[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(i);
      grid[cell].push_back(static_cast<std::int32_t>(i));
    }
  }
  return rep;
}

Mesh ToCgal(const PolygonMesh& mesh) {
  std::vector<Point> points;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) points.emplace_back(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2));
  std::vector<Polygon> polys;
  for (const auto& t : Fans(mesh)) polys.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  Mesh out;
  PMP::polygon_soup_to_polygon_mesh(points, polys, out);
  return out;
}

PolygonMesh FromCgal(Mesh& mesh) { return cgal_internal::FromSurfaceMesh(mesh); }

}  // namespace

RepairedMesh RepairMesh(const PolygonMesh& input, const RepairOptions& options) {
  RepairedMesh out;
  RepairReport& rep = out.report;
  const auto input_tris = Fans(input);
  rep.volume_before = SignedVolume(input.V, input_tris);

  // 1. Tolerance weld.
  const double diag = input.V.rows() > 0 ? (input.V.colwise().maxCoeff() - input.V.colwise().minCoeff()).norm() : 0.0;
  const std::vector<std::int32_t> map = WeldWithin(input.V, options.weld_tolerance * diag, rep.welded_vertices);

  // 2. Soup repair and orientation (CGAL).
  std::vector<Point> points;
  for (Eigen::Index i = 0; i < input.V.rows(); ++i) {
    points.emplace_back(input.V(i, 0), input.V(i, 1), input.V(i, 2));
  }
  // Polygons with the corners of an earlier one (in either orientation) are dropped before they
  // are split into fans: a quad and its reverse make different fans, which CGAL would not see as
  // duplicates.
  std::vector<Polygon> polys;
  std::set<std::vector<std::int32_t>> seen;
  std::int64_t duplicate_polygons = 0;
  for (std::int64_t f = 0; f < input.num_faces(); ++f) {
    const std::int32_t* idx = input.indices.data() + input.offsets[f];
    const int n = input.face_size(f);
    std::vector<std::int32_t> mapped(static_cast<std::size_t>(n));  // corners after the weld
    for (int k = 0; k < n; ++k) mapped[static_cast<std::size_t>(k)] = map[static_cast<std::size_t>(idx[k])];
    std::vector<std::int32_t> key = mapped;
    std::sort(key.begin(), key.end());
    if (n > 3 && !seen.insert(std::move(key)).second) {
      ++duplicate_polygons;
      continue;
    }
    std::vector<std::array<std::int32_t, 3>> split;
    SplitPolygon(mapped.data(), n, split);
    for (const auto& t : split) polys.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  }
  const std::size_t faces_before = polys.size();
  PMP::repair_polygon_soup(points, polys);
  rep.removed_faces = duplicate_polygons + static_cast<std::int64_t>(faces_before - polys.size());
  const std::size_t points_before = points.size();
  // orient_polygon_soup returns false when it had to duplicate points (non-manifold vertices).
  std::vector<Polygon> before_orient = polys;
  PMP::orient_polygon_soup(points, polys);
  rep.split_vertices = static_cast<std::int64_t>(points.size() - points_before);
  rep.reoriented = before_orient != polys;

  // 3. Mesh, stitching, and orientation of closed shells.
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polys, mesh);
  rep.stitched_edges = static_cast<std::int64_t>(PMP::stitch_borders(mesh));
  if (CGAL::is_closed(mesh) && !mesh.is_empty()) {
    PMP::orient_to_bound_a_volume(mesh);
    rep.oriented_to_bound_volume = true;
  }

  // 4. Back to our mesh.
  out.mesh = FromCgal(mesh);
  rep.volume_after = SignedVolume(out.mesh.V, Fans(out.mesh));
  return out;
}

PolygonMesh UnionOfShells(const PolygonMesh& input, std::int64_t& merged) {
  Mesh all = ToCgal(input);
  std::vector<Mesh> parts;
  PMP::split_connected_components(all, parts);
  std::vector<Mesh> outward, inward;
  for (Mesh& part : parts) {
    if (!CGAL::is_closed(part)) throw std::runtime_error("the union of overlapping shells needs closed shells");
    (PMP::volume(part) > 0 ? outward : inward).push_back(std::move(part));
  }
  if (outward.empty()) throw std::runtime_error("no shell faces outward: nothing to unite");
  Mesh result = outward[0];
  for (std::size_t i = 1; i < outward.size(); ++i) {
    Mesh united;
    if (!PMP::corefine_and_compute_union(result, outward[i], united)) {
      throw std::runtime_error(
          "CGAL could not compute the union of the overlapping shells (a shell intersects "
          "itself, or does not bound a volume)");
    }
    result = std::move(united);
  }
  for (const Mesh& cavity : inward) result += cavity;  // cavities facing inward stay as they are
  merged = static_cast<std::int64_t>(outward.size()) - 1;
  return FromCgal(result);
}

namespace {
// The sign of orient3d(a, b, c, d) when double arithmetic certifies it (Shewchuk's first error
// bound, "Adaptive precision floating-point arithmetic", 1997), else 0: not known.
int CertainOrientation(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y(), adz = a.z() - d.z();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y(), bdz = b.z() - d.z();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y(), cdz = c.z() - d.z();
  const double det = adx * (bdy * cdz - bdz * cdy) + bdx * (cdy * adz - cdz * ady) + cdx * (ady * bdz - adz * bdy);
  const double permanent = std::abs(adx) * (std::abs(bdy * cdz) + std::abs(bdz * cdy)) +
                           std::abs(bdx) * (std::abs(cdy * adz) + std::abs(cdz * ady)) +
                           std::abs(cdx) * (std::abs(ady * bdz) + std::abs(adz * bdy));
  if (!(permanent > 1e-250 && permanent < 1e250)) return 0;  // underflow or overflow: no bound
  const double bound = 7.771561172376103e-16 * permanent;    // (7 + 56ε)ε, ε = 2^-53
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

// Whether two triangles meet other than along what they share. Triangles are index triples into
// `p`; shared corners are shared indices (the mesh is welded). A shared edge: they meet elsewhere
// only when folded onto each other (coplanar, opposite corners on the same side). A shared corner:
// the set they share beyond it is a segment from that corner, which ends on the edge opposite it
// in one of them — so it suffices to test each opposite edge against the other triangle.
bool TrianglesIntersect(const std::vector<Point>& p, const std::array<std::int32_t, 3>& s,
                        const std::array<std::int32_t, 3>& t) {
  int shared = 0;
  int s_at[3] = {-1, -1, -1};  // for each corner of s, its position in t (or -1)
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (s[i] == t[j]) {
        s_at[i] = j;
        ++shared;
      }
    }
  }
  auto P = [&](std::int32_t i) -> const Point& { return p[static_cast<std::size_t>(i)]; };
  if (shared == 3) return true;  // the same triangle twice
  if (shared == 2) {
    int lone_s = 0;
    while (s_at[lone_s] >= 0) ++lone_s;
    const int a = (lone_s + 1) % 3, b = (lone_s + 2) % 3;
    const int lone_t = 3 - s_at[a] - s_at[b];
    const Point &pa = P(s[a]), &pb = P(s[b]), &ps = P(s[lone_s]), &pt = P(t[lone_t]);
    return CGAL::orientation(pa, pb, ps, pt) == CGAL::COPLANAR &&
           CGAL::coplanar_orientation(pa, pb, ps, pt) == CGAL::POSITIVE;
  }
  // Cheap rejection first: the corners one triangle does not share all certainly on one side of
  // the other's plane. (Exact predicates decide corners that lie on a plane, at a high price; a big
  // polygon's split meets the side faces of its rim exactly so, in millions of pairs.)
  auto strictly_beside = [&](const std::array<std::int32_t, 3>& u, const std::array<std::int32_t, 3>& w) {
    int side = 0;
    for (int k = 0; k < 3; ++k) {
      if (w[k] == u[0] || w[k] == u[1] || w[k] == u[2]) continue;
      const int o = CertainOrientation(P(u[0]), P(u[1]), P(u[2]), P(w[k]));
      if (o == 0 || (side != 0 && o != side)) return false;
      side = o;
    }
    return true;
  };
  if (strictly_beside(s, t) || strictly_beside(t, s)) return false;
  const Kernel::Triangle_3 ts(P(s[0]), P(s[1]), P(s[2])), tt(P(t[0]), P(t[1]), P(t[2]));
  if (shared == 0) return CGAL::do_intersect(ts, tt);
  int cs = 0;
  while (s_at[cs] < 0) ++cs;
  const int ct = s_at[cs];
  const Kernel::Segment_3 opposite_s(P(s[(cs + 1) % 3]), P(s[(cs + 2) % 3]));
  const Kernel::Segment_3 opposite_t(P(t[(ct + 1) % 3]), P(t[(ct + 2) % 3]));
  return CGAL::do_intersect(opposite_s, tt) || CGAL::do_intersect(opposite_t, ts);
}
}  // namespace

// Pairs of triangles from one polygon are not tested: they meet only if the polygon is folded in
// its own plane, and testing them made a large polygon's split (all coplanar, all near each other)
// the whole cost — and a non-convex polygon's split overlaps itself where the polygon does not.
std::int64_t CountSelfIntersections(const PolygonMesh& polygons, std::int64_t limit) {
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(polygons.V.rows()));
  for (Eigen::Index i = 0; i < polygons.V.rows(); ++i) {
    points.emplace_back(polygons.V(i, 0), polygons.V(i, 1), polygons.V(i, 2));
  }
  std::vector<std::array<std::int32_t, 3>> tris;
  std::vector<std::int64_t> owner;  // the polygon each triangle comes from
  for (std::int64_t f = 0; f < polygons.num_faces(); ++f) {
    SplitPolygon(polygons.indices.data() + polygons.offsets[f], polygons.face_size(f), tris);
    owner.resize(tris.size(), f);
  }
  using Box =
      CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::int32_t, CGAL::Box_intersection_d::ID_FROM_BOX_ADDRESS>;
  std::vector<Box> boxes;
  boxes.reserve(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const auto& t = tris[i];
    const Point &a = points[std::size_t(t[0])], &b = points[std::size_t(t[1])], &c = points[std::size_t(t[2])];
    if (CGAL::collinear(a, b, c)) continue;  // no area: nothing to intersect
    boxes.emplace_back(a.bbox() + b.bbox() + c.bbox(), static_cast<std::int32_t>(i));
  }
  std::vector<const Box*> handles;
  handles.reserve(boxes.size());
  for (const Box& b : boxes) handles.push_back(&b);
  std::int64_t count = 0;
  auto test = [&](const Box* x, const Box* y) {
    if (count >= limit) return;
    const auto i = static_cast<std::size_t>(x->info()), j = static_cast<std::size_t>(y->info());
    if (owner[i] == owner[j]) return;
    if (TrianglesIntersect(points, tris[i], tris[j])) ++count;
  };
  CGAL::box_self_intersection_d(handles.begin(), handles.end(), test);
  return count;
}

}  // namespace massprops
