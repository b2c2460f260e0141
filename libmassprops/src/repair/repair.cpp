// Mesh repair with CGAL's Polygon Mesh Processing (heavy headers: one of the few translation units
// that include CGAL).

#include "massprops/repair/repair.h"

#include "massprops/mesh_topology.h"

#include <algorithm>
#include <array>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <Eigen/Eigenvalues>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/intersection.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include "repair/from_surface_mesh.h"
#include "repair/tolerance_weld.h"

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

// How polygon g's corners run against f's, both of n corners and the same corner set: +1 as the
// same cycle, -1 reversed, 0 neither (a polygon that repeats a corner).
int Direction(const std::int32_t* f, const std::int32_t* g, int n) {
  for (int k = 0; k < n; ++k) {
    if (g[k] != f[0]) continue;
    bool same = true, reversed = true;
    for (int i = 0; i < n; ++i) {
      same = same && f[i] == g[(k + i) % n];
      reversed = reversed && f[i] == g[(k - i + n) % n];
    }
    if (same) return 1;
    if (reversed) return -1;
  }
  return 0;
}

// What became of repeated polygons.
struct Repeats {
  std::int64_t repeated = 0;  // copies of a kept polygon, dropped
  std::int64_t walls = 0;     // polygons of internal walls (repeated in both directions), all dropped
};

// The mesh with its corners renumbered through `map` (the weld) and its repeated polygons (the
// same corners after the weld) resolved: copies in the same direction keep the first; when a
// polygon comes in both directions, all its copies go (the internal wall where two bodies, each
// exported closed, touch: without it their shells are one, their union) — unless every polygon is
// in such a pair, a double-sided surface, which keeps one side. The vertices no face uses are
// removed (the others keep their order).
PolygonMesh WeldedWithoutRepeats(const PolygonMesh& input, const std::vector<std::int32_t>& map, Repeats& repeats) {
  const std::int64_t nf = input.num_faces();
  // Each corner after the weld; and each polygon's sorted corners, hashed (equal hashes are
  // compared in full).
  std::vector<std::int32_t> mapped(input.indices.size());
  for (std::size_t c = 0; c < mapped.size(); ++c) mapped[c] = map[static_cast<std::size_t>(input.indices[c])];
  std::vector<std::int32_t> sorted = mapped;
  std::vector<std::pair<std::uint64_t, std::int64_t>> keys;
  keys.reserve(static_cast<std::size_t>(nf));
  for (std::int64_t f = 0; f < nf; ++f) {
    std::int32_t* b = sorted.data() + input.offsets[f];
    std::int32_t* e = sorted.data() + input.offsets[f + 1];
    std::sort(b, e);
    std::uint64_t h = static_cast<std::uint64_t>(e - b) * 0x9E3779B97F4A7C15ull;
    for (const std::int32_t* c = b; c != e; ++c) h = (h ^ static_cast<std::uint64_t>(*c)) * 0x100000001B3ull;
    keys.emplace_back(h ^ (h >> 29), f);
  }
  std::sort(keys.begin(), keys.end());
  enum : char { kKeep = 0, kRepeated = 1, kWall = 2 };
  std::vector<char> drop(static_cast<std::size_t>(nf), kKeep);
  std::vector<std::int64_t> wall_firsts;  // the first polygon of each wall (kept if all are walls)
  const auto same_corners = [&](std::int64_t f, std::int64_t g) {
    return input.face_size(f) == input.face_size(g) &&
           std::equal(sorted.begin() + input.offsets[f], sorted.begin() + input.offsets[f + 1],
                      sorted.begin() + input.offsets[g]);
  };
  std::vector<char> seen(static_cast<std::size_t>(nf), 0);
  std::vector<std::int64_t> group;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j].first == keys[i].first) ++j;
    for (std::size_t a = i; a < j; ++a) {  // faces in increasing order: the earliest is kept
      const std::int64_t f = keys[a].second;
      if (seen[static_cast<std::size_t>(f)]) continue;
      group.assign(1, f);
      for (std::size_t b = a + 1; b < j; ++b) {
        const std::int64_t g = keys[b].second;
        if (!seen[static_cast<std::size_t>(g)] && same_corners(f, g))
          group.push_back(g), seen[static_cast<std::size_t>(g)] = 1;
      }
      if (group.size() == 1) continue;
      bool reversed = false;
      for (std::size_t k = 1; k < group.size(); ++k) {
        reversed = reversed || Direction(mapped.data() + input.offsets[f], mapped.data() + input.offsets[group[k]],
                                         input.face_size(f)) < 0;
      }
      if (reversed) wall_firsts.push_back(f);
      for (std::size_t k = reversed ? 0 : 1; k < group.size(); ++k) {
        drop[static_cast<std::size_t>(group[k])] = reversed ? kWall : kRepeated;
      }
    }
    i = j;
  }
  if (std::count(drop.begin(), drop.end(), kWall) == nf) {
    for (std::int64_t f : wall_firsts) drop[static_cast<std::size_t>(f)] = kKeep;  // a double-sided surface
    for (char& d : drop) d = d == kWall ? char{kRepeated} : d;
  }
  repeats.walls = static_cast<std::int64_t>(std::count(drop.begin(), drop.end(), kWall));
  repeats.repeated = static_cast<std::int64_t>(std::count(drop.begin(), drop.end(), kRepeated));
  std::vector<std::int32_t> renumber(static_cast<std::size_t>(input.V.rows()), -1);
  for (std::int64_t f = 0; f < nf; ++f) {
    if (drop[static_cast<std::size_t>(f)]) continue;
    for (std::int64_t c = input.offsets[f]; c < input.offsets[f + 1]; ++c) {
      renumber[static_cast<std::size_t>(mapped[static_cast<std::size_t>(c)])] = 0;
    }
  }
  std::int32_t kept = 0;
  for (auto& r : renumber) r = r < 0 ? -1 : kept++;
  PolygonMesh out;
  out.V.resize(kept, 3);
  for (std::size_t v = 0; v < renumber.size(); ++v) {
    if (renumber[v] >= 0) out.V.row(renumber[v]) = input.V.row(static_cast<Eigen::Index>(v));
  }
  out.indices.reserve(input.indices.size());
  out.offsets.reserve(static_cast<std::size_t>(nf) + 1);
  for (std::int64_t f = 0; f < nf; ++f) {
    if (drop[static_cast<std::size_t>(f)]) continue;
    for (std::int64_t c = input.offsets[f]; c < input.offsets[f + 1]; ++c) {
      out.indices.push_back(renumber[static_cast<std::size_t>(mapped[static_cast<std::size_t>(c)])]);
    }
    out.offsets.push_back(static_cast<std::int64_t>(out.indices.size()));
  }
  return out;
}

// Whether the mesh (of signed volume `volume`) bounds a volume as it is, the way
// orient_to_bound_a_volume leaves a mesh: closed, every edge used by two faces in opposite
// directions, no repeated corner or face, and its shells outward with cavities inward (the nesting
// test is per shell: up to 64 shells).
bool BoundsVolumeAsItIs(const PolygonMesh& mesh, double volume) {
  if (mesh.num_faces() == 0) return false;
  const MeshTopology t = AnalyzeTopology(mesh);
  if (!t.BoundsVolume() || t.non_manifold_edges > 0 || t.degenerate_faces > 0 || t.duplicate_faces > 0 ||
      t.reversed_duplicate_faces > 0 || t.components > 64) {
    return false;
  }
  if (t.components == 1) return volume > 0;
  return AnalyzeShells(mesh).problem.empty();
}

// Closes each border cycle with triangles on its own corners (CGAL's triangulate_hole: a 2D
// constrained Delaunay triangulation in the fitted plane when the corners lie near one, else the
// minimal-area one). A planar hole (its corners within `flat` of one plane) is filled exactly; a
// non-planar one adds its ambiguity, the thickness of the slab that holds its corners times the
// patch's area, to the report's bound.
void FillHoles(Mesh& mesh, double flat, RepairReport& rep) {
  std::vector<Mesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  for (const Mesh::Halfedge_index h : cycles) {
    std::vector<Vector3> ring;
    for (const Mesh::Halfedge_index e : CGAL::halfedges_around_face(h, mesh)) {
      const Point& p = mesh.point(mesh.target(e));
      ring.emplace_back(p.x(), p.y(), p.z());
    }
    if (ring.size() < 3) continue;
    Vector3 center = Vector3::Zero();
    for (const Vector3& p : ring) center += p;
    center /= static_cast<double>(ring.size());
    Matrix3 scatter = Matrix3::Zero();
    for (const Vector3& p : ring) scatter += (p - center) * (p - center).transpose();
    const Vector3 normal = Eigen::SelfAdjointEigenSolver<Matrix3>(scatter).eigenvectors().col(0);
    double low = 0, high = 0;
    for (const Vector3& p : ring)
      low = std::min(low, normal.dot(p - center)), high = std::max(high, normal.dot(p - center));
    const bool planar = high - low <= flat;
    std::vector<Mesh::Face_index> patch;
    // The cubic search space is for small holes only (time grows as the cube of the edges).
    PMP::triangulate_hole(mesh, h, std::back_inserter(patch),
                          PMP::parameters::do_not_use_cubic_algorithm(ring.size() > 100));
    if (patch.empty()) {
      ++rep.unfilled_holes;
      continue;
    }
    double area = 0;
    for (const Mesh::Face_index f : patch) area += PMP::face_area(f, mesh);
    ++rep.filled_holes;
    rep.largest_hole = std::max(rep.largest_hole, static_cast<std::int64_t>(ring.size()));
    if (planar) {
      ++rep.planar_holes;
    } else {
      rep.fill_volume_bound += (high - low) * area;
    }
  }
}

// A closed mesh's shells that CGAL's orientation turned inward though they cross another shell
// (a pin through a hub: CGAL takes it for a cavity) turned back outward, in place (Cavities'
// rule, below).
void OrientCrossingShellsOutward(Mesh& mesh);

}  // namespace

RepairedMesh RepairMesh(const PolygonMesh& input, const RepairOptions& options) {
  RepairedMesh out;
  RepairReport& rep = out.report;
  rep.volume_before = SignedVolume(input.V, Fans(input));

  // 1. Tolerance weld, and repeated polygons resolved while they are polygons (a quad and its
  // reverse make different fans) and before CGAL, whose soup repair keeps one of a reversed pair.
  const double diag = input.V.rows() > 0 ? (input.V.colwise().maxCoeff() - input.V.colwise().minCoeff()).norm() : 0.0;
  const std::vector<std::int32_t> map =
      internal::WeldWithinTolerance(input.V, options.weld_tolerance * diag, rep.welded_vertices);
  Repeats repeats;
  PolygonMesh welded = WeldedWithoutRepeats(input, map, repeats);
  rep.repeated_faces = repeats.repeated;
  rep.internal_walls = repeats.walls;
  const std::int64_t duplicate_polygons = repeats.repeated + repeats.walls;
  const double welded_volume = SignedVolume(welded.V, Fans(welded));

  // 2. When the welded mesh already bounds a volume — closed, manifold edges, consistent, every
  // shell outward and cavities inward — CGAL would change nothing, and its polygons stay as they
  // are (a polygon of a million corners split into triangles made CGAL's steps the whole cost).
  if (BoundsVolumeAsItIs(welded, welded_volume)) {
    rep.removed_faces = duplicate_polygons;
    rep.oriented_to_bound_volume = true;
    rep.volume_after = welded_volume;
    out.mesh = std::move(welded);
    return out;
  }

  // 3. Soup repair and orientation (CGAL), on the polygons as they are, except that polygons of
  // more than 32 corners are split (SplitPolygon): CGAL's soup orientation is quadratic in a
  // polygon's corners (140 s for one of 10^6).
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(welded.V.rows()));
  for (Eigen::Index i = 0; i < welded.V.rows(); ++i)
    points.emplace_back(welded.V(i, 0), welded.V(i, 1), welded.V(i, 2));
  std::vector<Polygon> polys;
  polys.reserve(static_cast<std::size_t>(welded.num_faces()));
  std::vector<std::array<std::int32_t, 3>> split;
  for (std::int64_t f = 0; f < welded.num_faces(); ++f) {
    const int n = welded.face_size(f);
    const std::int32_t* corners = welded.indices.data() + welded.offsets[f];
    if (n <= 32) {
      polys.emplace_back(corners, corners + n);
      continue;
    }
    split.clear();
    SplitPolygon(corners, n, split);
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

  // 4. Mesh, stitching, and — when the result is closed — orientation of its shells, which CGAL
  // does on triangles (SplitPolygon's).
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polys, mesh);
  rep.stitched_edges = static_cast<std::int64_t>(PMP::stitch_borders(mesh));
  if (!CGAL::is_closed(mesh) && !mesh.is_empty()) FillHoles(mesh, options.weld_tolerance * diag, rep);
  if (CGAL::is_closed(mesh) && !mesh.is_empty()) {
    mesh = ToCgal(FromCgal(mesh));
    PMP::orient_to_bound_a_volume(mesh);
    OrientCrossingShellsOutward(mesh);
    rep.oriented_to_bound_volume = true;
  }

  // 5. Back to our mesh.
  out.mesh = FromCgal(mesh);
  rep.volume_after = SignedVolume(out.mesh.V, Fans(out.mesh));
  return out;
}

namespace {

// Which shells bound voids: a shell that lies wholly inside an odd number of the others (its
// surface meeting none of theirs) is a cavity; every other shell is solid, whichever way its faces
// point — the repair's orientation takes a shell partly inside another (a pin through a hub) for a
// cavity, and that shell is to be united, not subtracted.
std::vector<bool> Cavities(std::vector<Mesh>& parts) {
  const std::size_t n = parts.size();
  std::vector<CGAL::Bbox_3> box(n);
  for (std::size_t i = 0; i < n; ++i) {
    PMP::triangulate_faces(parts[i]);
    box[i] = PMP::bbox(parts[i]);
  }
  auto within = [](const CGAL::Bbox_3& a, const CGAL::Bbox_3& b) {
    return a.xmin() >= b.xmin() && a.ymin() >= b.ymin() && a.zmin() >= b.zmin() && a.xmax() <= b.xmax() &&
           a.ymax() <= b.ymax() && a.zmax() <= b.zmax();
  };
  std::vector<bool> cavity(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    int depth = 0;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || !within(box[i], box[j]) || PMP::do_intersect(parts[i], parts[j])) continue;
      const CGAL::Side_of_triangle_mesh<Mesh, Kernel> inside(parts[j]);
      if (inside(parts[i].point(*parts[i].vertices().begin())) == CGAL::ON_BOUNDED_SIDE) ++depth;
    }
    cavity[i] = depth % 2 == 1;
  }
  return cavity;
}

void OrientCrossingShellsOutward(Mesh& mesh) {
  std::vector<Mesh> parts;
  PMP::split_connected_components(mesh, parts);
  if (parts.size() < 2) return;
  const std::vector<bool> cavity = Cavities(parts);
  std::vector<bool> flip(parts.size());
  bool any = false;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    flip[i] = (PMP::volume(parts[i]) > 0) == cavity[i];
    any = any || flip[i];
  }
  if (!any) return;  // CGAL's orientation stands (the same mesh, face for face)
  auto component = mesh.add_property_map<Mesh::Face_index, std::size_t>("f:component", 0).first;
  PMP::connected_components(mesh, component);
  std::vector<Mesh::Face_index> faces;
  for (const Mesh::Face_index f : mesh.faces())
    if (flip[component[f]]) faces.push_back(f);
  PMP::reverse_face_orientations(faces, mesh);
  mesh.remove_property_map(component);
}

// The union of closed outward meshes, pairwise in a balanced tree (each mesh joins one about its
// own size, not the growing whole one after another). @throws std::runtime_error when CGAL cannot.
Mesh BalancedUnion(std::vector<Mesh> meshes) {
  while (meshes.size() > 1) {
    std::vector<Mesh> next;
    for (std::size_t i = 0; i + 1 < meshes.size(); i += 2) {
      Mesh united;
      if (!PMP::corefine_and_compute_union(meshes[i], meshes[i + 1], united)) {
        throw std::runtime_error(
            "CGAL could not compute the union of the overlapping shells (a shell intersects "
            "itself, or does not bound a volume)");
      }
      next.push_back(std::move(united));
    }
    if (meshes.size() % 2 == 1) next.push_back(std::move(meshes.back()));
    meshes = std::move(next);
  }
  return std::move(meshes.front());
}

}  // namespace

PolygonMesh UnionOfShells(const PolygonMesh& input, std::int64_t& merged) {
  Mesh all = ToCgal(input);
  std::vector<Mesh> parts;
  PMP::split_connected_components(all, parts);
  std::vector<Mesh> solids, voids;  // as RepairMesh oriented them: solids outward, cavities inward
  for (Mesh& part : parts) {
    if (!CGAL::is_closed(part)) throw std::runtime_error("the union of overlapping shells needs closed shells");
    (PMP::volume(part) > 0 ? solids : voids).push_back(std::move(part));
  }
  if (solids.empty()) throw std::runtime_error("no shell bounds a solid: nothing to unite");
  merged = static_cast<std::int64_t>(solids.size()) - 1;
  Mesh result = BalancedUnion(std::move(solids));
  for (const Mesh& v : voids) result += v;  // cavities stay as they are, facing inward
  return FromCgal(result);
}

}  // namespace massprops
