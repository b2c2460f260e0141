// The self-intersection check (CGAL's box intersection and exact predicates; one of the few
// translation units that include CGAL).
//
// Candidate pairs come from bounding boxes. A large polygon split into triangles has a triangle
// spanning it at every scale, and each face along its rim overlaps the boxes of log2 n of them:
// 4·10^7 candidate pairs for a prism over a 10^6-gon. So a polygon of more than 32 corners that
// lies in one plane (exactly, or within rounding when the plane is tilted) is one box, tested as a whole against each
// triangle that meets its box: a triangle whose other corners lie strictly on one side of the plane, and which touches
// it only at one corner of the polygon or along one of its edges, meets it only there. Anything else (a triangle
// crossing the plane, or lying in it) is decided against the polygon's triangles.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include "massprops/repair/repair.h"

#include "mesh/certain_predicates.h"

namespace massprops {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Box =
    CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::int32_t, CGAL::Box_intersection_d::ID_FROM_BOX_ADDRESS>;
using Triangle = std::array<std::int32_t, 3>;

// The sign of orient3d(a, b, c, d) when double arithmetic certifies it, else 0.
int CertainOrientation(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double pa[3] = {a.x(), a.y(), a.z()}, pb[3] = {b.x(), b.y(), b.z()}, pc[3] = {c.x(), c.y(), c.z()},
               pd[3] = {d.x(), d.y(), d.z()};
  return internal::CertainOrient3d(pa, pb, pc, pd);
}

// Whether an axis certainly separates two triangles: among the separating-axis candidates (the two
// normals and the nine cross products of edges), one along which their corners' projections,
// computed in double relative to one corner with a bound on the rounding, do not overlap. Any
// axis proves it, so the axes themselves need no exactness. Decides most pairs of near neighbours
// without exact arithmetic (those whose corners lie within rounding of each other's planes).
bool CertainlySeparated(const std::array<const Point*, 3>& s, const std::array<const Point*, 3>& t) {
  const Point& o = *s[0];
  std::array<Vector3, 3> ps, pt;
  for (int k = 0; k < 3; ++k) {
    ps[static_cast<std::size_t>(k)] = Vector3(s[k]->x() - o.x(), s[k]->y() - o.y(), s[k]->z() - o.z());
    pt[static_cast<std::size_t>(k)] = Vector3(t[k]->x() - o.x(), t[k]->y() - o.y(), t[k]->z() - o.z());
  }
  double scale = 0;
  for (std::size_t k = 0; k < 3; ++k)
    scale = std::max({scale, ps[k].cwiseAbs().maxCoeff(), pt[k].cwiseAbs().maxCoeff()});
  if (!(scale > 1e-80 && scale < 1e80)) return false;  // the products would leave normal doubles
  std::array<Vector3, 3> es, et;
  for (std::size_t k = 0; k < 3; ++k) {
    es[k] = ps[(k + 1) % 3] - ps[k];
    et[k] = pt[(k + 1) % 3] - pt[k];
  }
  auto separates = [&](const Vector3& d) {
    // |fl(d·fl(p − o)) − d·(p − o)| ≤ 6e-16 Σ|d_k||fl(p − o)_k| (the subtraction and the dot).
    auto range = [&](const std::array<Vector3, 3>& pts, double& lo, double& hi) {
      lo = std::numeric_limits<double>::infinity();
      hi = -lo;
      for (const Vector3& p : pts) {
        const double v = d.dot(p), e = 6e-16 * d.cwiseAbs().dot(p.cwiseAbs());
        lo = std::min(lo, v - e);
        hi = std::max(hi, v + e);
      }
    };
    double slo, shi, tlo, thi;
    range(ps, slo, shi);
    range(pt, tlo, thi);
    return shi < tlo || thi < slo;
  };
  if (separates(es[0].cross(es[1])) || separates(et[0].cross(et[1]))) return true;
  for (const Vector3& a : es) {
    for (const Vector3& b : et) {
      if (separates(a.cross(b))) return true;
    }
  }
  return false;
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
    return CertainOrientation(pa, pb, ps, pt) == 0 && CGAL::orientation(pa, pb, ps, pt) == CGAL::COPLANAR &&
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
  if (shared == 0 && CertainlySeparated({&P(s[0]), &P(s[1]), &P(s[2])}, {&P(t[0]), &P(t[1]), &P(t[2])})) return false;
  const Kernel::Triangle_3 ts(P(s[0]), P(s[1]), P(s[2])), tt(P(t[0]), P(t[1]), P(t[2]));
  if (shared == 0) return CGAL::do_intersect(ts, tt);
  int cs = 0;
  while (s_at[cs] < 0) ++cs;
  const int ct = s_at[cs];
  const Kernel::Segment_3 opposite_s(P(s[(cs + 1) % 3]), P(s[(cs + 2) % 3]));
  const Kernel::Segment_3 opposite_t(P(t[(ct + 1) % 3]), P(t[(ct + 2) % 3]));
  return CGAL::do_intersect(opposite_s, tt) || CGAL::do_intersect(opposite_t, ts);
}

// The orientation of d against the plane through a, b, c, as CertainOrientation's sign (which is
// the opposite of CGAL::orientation's): certified in double when possible, else exact.
int Orientation(const Point& a, const Point& b, const Point& c, const Point& d) {
  const int o = CertainOrientation(a, b, c, d);
  if (o != 0) return o;
  const CGAL::Orientation exact = CGAL::orientation(a, b, c, d);
  return exact == CGAL::POSITIVE ? -1 : exact == CGAL::NEGATIVE ? 1 : 0;
}

// A polygon tested as a whole: its corners lie in the plane through three of them, exactly or
// within `off_plane` (rounding: a polygon in a tilted plane cannot hold its corners exactly in it).
struct FlatPolygon {
  std::int64_t face = 0;
  std::array<std::int32_t, 3> plane{};  // three corners, not collinear
  double off_plane = 0;                 // largest distance of a corner from that plane
  Kernel::Vector_3 unit_normal;         // of that plane, when off_plane > 0
  std::vector<Triangle> triangles;      // its split, for the pairs decided on triangles
};

// Where each vertex sits in the flat polygons: its first (polygon, position), and the rest in a
// sorted list (a vertex is in one or two large polygons, almost always).
class CornerIndex {
 public:
  explicit CornerIndex(std::size_t vertices) : polygon_(vertices, -1), position_(vertices, -1) {}
  void Add(std::int32_t v, std::int32_t polygon, std::int32_t position) {
    if (polygon_[static_cast<std::size_t>(v)] < 0) {
      polygon_[static_cast<std::size_t>(v)] = polygon;
      position_[static_cast<std::size_t>(v)] = position;
    } else {
      more_.push_back({v, polygon, position});
    }
  }
  void Finish() { std::sort(more_.begin(), more_.end()); }
  // v's position among the corners of `polygon`, or -1.
  std::int32_t Position(std::int32_t v, std::int32_t polygon) const {
    if (polygon_[static_cast<std::size_t>(v)] == polygon) return position_[static_cast<std::size_t>(v)];
    const auto it = std::lower_bound(more_.begin(), more_.end(), std::array<std::int32_t, 3>{v, polygon, -1});
    return it != more_.end() && (*it)[0] == v && (*it)[1] == polygon ? (*it)[2] : -1;
  }

 private:
  std::vector<std::int32_t> polygon_, position_;
  std::vector<std::array<std::int32_t, 3>> more_;
};

// Three corners of the polygon spanning its plane (the first, the farthest from it, the farthest
// from their line), when every corner lies in that plane: exactly, or within rounding of it (1e-12
// of the polygon's size; `off_plane` says how far).
bool FindPlane(const std::vector<Point>& p, const std::int32_t* corners, int n, std::array<std::int32_t, 3>& plane,
               double& off_plane, Kernel::Vector_3& unit_normal) {
  off_plane = 0;
  auto P = [&](int k) -> const Point& { return p[static_cast<std::size_t>(corners[k])]; };
  int far = 0;
  double best = 0;
  for (int k = 1; k < n; ++k) {
    const double d = CGAL::squared_distance(P(0), P(k));
    if (d > best) best = d, far = k;
  }
  if (far == 0) return false;
  const double size = std::sqrt(best);
  const Kernel::Vector_3 axis = P(far) - P(0);
  int third = 0;
  best = 0;
  for (int k = 1; k < n; ++k) {
    const double d = CGAL::cross_product(axis, P(k) - P(0)).squared_length();
    if (d > best) best = d, third = k;
  }
  if (third == 0 || CGAL::collinear(P(0), P(far), P(third))) return false;
  plane = {corners[0], corners[far], corners[third]};
  for (int axis_k = 0; axis_k < 3; ++axis_k) {  // a plane of constant x, y or z: nothing to decide
    bool constant = true;
    for (int k = 1; k < n && constant; ++k) constant = P(k)[axis_k] == P(0)[axis_k];
    if (constant) return true;
  }
  const Point &a = p[static_cast<std::size_t>(plane[0])], &b = p[static_cast<std::size_t>(plane[1])],
              &c = p[static_cast<std::size_t>(plane[2])];
  bool exact = true;
  for (int k = 0; k < n && exact; ++k) exact = CGAL::orientation(a, b, c, P(k)) == CGAL::COPLANAR;
  if (exact) return true;
  const Kernel::Vector_3 normal = CGAL::cross_product(b - a, c - a);
  const double length = std::sqrt(normal.squared_length());
  if (!(length > 0) || !std::isfinite(length)) return false;
  unit_normal = normal / length;
  for (int k = 0; k < n; ++k) off_plane = std::max(off_plane, std::abs(unit_normal * (P(k) - a)));
  return off_plane <= 1e-12 * size;
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
  std::vector<Triangle> tris;
  std::vector<std::int64_t> owner;  // the polygon each triangle comes from
  std::vector<FlatPolygon> flat;
  CornerIndex corner_index(points.size());
  std::vector<std::int64_t> seen_in(points.size(), -1);  // the last large polygon a vertex was seen in
  for (std::int64_t f = 0; f < polygons.num_faces(); ++f) {
    const std::int32_t* corners = polygons.indices.data() + polygons.offsets[f];
    const int n = polygons.face_size(f);
    FlatPolygon unit;
    if (n > 32 && FindPlane(points, corners, n, unit.plane, unit.off_plane, unit.unit_normal)) {
      bool repeated = false;  // a corner twice: the polygon touches itself, decided on triangles
      for (int k = 0; k < n && !repeated; ++k) {
        repeated = seen_in[static_cast<std::size_t>(corners[k])] == f;
        seen_in[static_cast<std::size_t>(corners[k])] = f;
      }
      if (!repeated) {
        const auto id = static_cast<std::int32_t>(flat.size());
        for (int k = 0; k < n; ++k) corner_index.Add(corners[k], id, k);
        unit.face = f;
        SplitPolygon(corners, n, unit.triangles);
        flat.push_back(std::move(unit));
        continue;
      }
    }
    SplitPolygon(corners, n, tris);
    owner.resize(tris.size(), f);
  }
  corner_index.Finish();
  auto box_of = [&](const Triangle& t) {
    return points[std::size_t(t[0])].bbox() + points[std::size_t(t[1])].bbox() + points[std::size_t(t[2])].bbox();
  };
  // The boxes of the triangles with an area (nothing to intersect otherwise), by their index.
  auto add_boxes = [&](const std::vector<Triangle>& ts, std::vector<Box>& out) {
    for (std::size_t i = 0; i < ts.size(); ++i) {
      const Triangle& t = ts[i];
      if (!CGAL::collinear(points[std::size_t(t[0])], points[std::size_t(t[1])], points[std::size_t(t[2])])) {
        out.emplace_back(box_of(t), static_cast<std::int32_t>(i));
      }
    }
  };

  // Boxes: triangles by index, flat polygons as -1 - their index.
  std::vector<Box> boxes;
  boxes.reserve(tris.size() + flat.size());
  add_boxes(tris, boxes);
  for (std::size_t u = 0; u < flat.size(); ++u) {
    CGAL::Bbox_3 box = points[std::size_t(flat[u].triangles[0][0])].bbox();
    for (const Triangle& t : flat[u].triangles) box += box_of(t);
    boxes.emplace_back(box, -1 - static_cast<std::int32_t>(u));
  }
  std::vector<const Box*> handles;
  handles.reserve(boxes.size());
  for (const Box& b : boxes) handles.push_back(&b);

  // Whether a triangle meets a flat polygon only where they share a corner or an edge.
  auto meets_only_at_shared = [&](const Triangle& t, std::int32_t u) {
    const FlatPolygon& poly = flat[static_cast<std::size_t>(u)];
    const Point &a = points[std::size_t(poly.plane[0])], &b = points[std::size_t(poly.plane[1])],
                &c = points[std::size_t(poly.plane[2])];
    std::int32_t at[3];
    int on = 0, side = 0;
    for (int k = 0; k < 3; ++k) {
      at[on] = corner_index.Position(t[k], u);
      if (at[on] >= 0) {
        ++on;
        continue;
      }
      const int o = Orientation(a, b, c, points[std::size_t(t[k])]);
      if (o == 0 || (side != 0 && o != side)) return false;
      // A polygon within rounding of its plane: the corner must clear the polygon's own spread.
      if (poly.off_plane > 0 && !(std::abs(poly.unit_normal * (points[std::size_t(t[k])] - a)) > 4 * poly.off_plane)) {
        return false;
      }
      side = o;
    }
    if (on <= 1) return side != 0;
    if (on == 3) return false;
    const auto n = static_cast<std::int32_t>(polygons.face_size(poly.face));
    const std::int32_t d = std::abs(at[0] - at[1]);
    return d == 1 || d == n - 1;
  };

  std::int64_t count = 0;
  // Candidate pairs are counted: past the budget the check stops undecided (a high-valence corner).
  struct OverBudget {};
  const std::int64_t budget = kSelfIntersectionWork + 50 * static_cast<std::int64_t>(tris.size());
  std::int64_t pairs = 0;
  auto spend = [&] {
    if (++pairs > budget) throw OverBudget{};
  };
  std::vector<std::pair<std::int32_t, std::int32_t>> triangle_vs_polygon;  // decided on its triangles
  std::vector<std::pair<std::int32_t, std::int32_t>> polygon_vs_polygon;
  auto test = [&](const Box* x, const Box* y) {
    if (count >= limit) return;
    spend();
    std::int32_t i = x->info(), j = y->info();
    if (i < 0 && j < 0) {
      polygon_vs_polygon.emplace_back(-1 - i, -1 - j);
      return;
    }
    if (i < 0 || j < 0) {
      if (i < 0) std::swap(i, j);
      const std::int32_t u = -1 - j;  // (a flat polygon's own triangles are not among tris)
      if (!meets_only_at_shared(tris[static_cast<std::size_t>(i)], u)) triangle_vs_polygon.emplace_back(i, u);
      return;
    }
    if (owner[static_cast<std::size_t>(i)] == owner[static_cast<std::size_t>(j)]) return;
    if (TrianglesIntersect(points, tris[static_cast<std::size_t>(i)], tris[static_cast<std::size_t>(j)])) ++count;
  };
  try {
    CGAL::box_self_intersection_d(handles.begin(), handles.end(), test);

    // What the whole-polygon test left open, triangle against triangle (in a fixed order).
    auto decide = [&](const std::vector<Triangle>& left, const std::vector<Triangle>& right) {
      std::vector<Box> lb, rb;
      add_boxes(left, lb);
      add_boxes(right, rb);
      CGAL::box_intersection_d(lb.begin(), lb.end(), rb.begin(), rb.end(), [&](const Box& x, const Box& y) {
        spend();
        if (count < limit && TrianglesIntersect(points, left[std::size_t(x.info())], right[std::size_t(y.info())])) {
          ++count;
        }
      });
    };
    std::sort(triangle_vs_polygon.begin(), triangle_vs_polygon.end(), [](const auto& p, const auto& q) {
      return p.second < q.second || (p.second == q.second && p.first < q.first);
    });
    for (std::size_t k = 0; k < triangle_vs_polygon.size() && count < limit;) {
      const std::int32_t u = triangle_vs_polygon[k].second;
      std::vector<Triangle> group;
      for (; k < triangle_vs_polygon.size() && triangle_vs_polygon[k].second == u; ++k) {
        group.push_back(tris[static_cast<std::size_t>(triangle_vs_polygon[k].first)]);
      }
      decide(group, flat[static_cast<std::size_t>(u)].triangles);
    }
    std::sort(polygon_vs_polygon.begin(), polygon_vs_polygon.end());
    for (const auto& [u, w] : polygon_vs_polygon) {
      if (count < limit)
        decide(flat[static_cast<std::size_t>(u)].triangles, flat[static_cast<std::size_t>(w)].triangles);
    }
  } catch (const OverBudget&) {
    return -1;
  }
  return count;
}

}  // namespace massprops
