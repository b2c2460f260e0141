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

// A group of triangles tested as one box against the rest: a flat polygon's split, or the fan
// around one corner certified free of intersections within itself (a star).
struct Group {
  std::vector<Triangle> triangles;
  std::vector<std::int32_t> cycle;  // its boundary in order: the polygon's corners, or the star's link
  std::int32_t center = -1;         // a star's center, at position cycle.size() in the corner index
  // The plane its boundary lies in (exactly, or within `off_plane`: rounding in a tilted plane).
  bool has_plane = false;
  std::array<std::int32_t, 3> plane{};
  double off_plane = 0;
  Kernel::Vector_3 unit_normal;  // of that plane, when off_plane > 0
  int side = 0;                  // 0: the whole group lies in the plane; ±1: a star whose center is on that side
  CGAL::Bbox_3 box;
};

constexpr int kWholeLimit = 32;  // polygons and fans of more are tested as wholes

// Where each vertex sits in the groups: its first (group, position), and the rest in a
// sorted list (a vertex is in one or two groups, almost always).
class CornerIndex {
 public:
  explicit CornerIndex(std::size_t vertices) : group_(vertices, -1), position_(vertices, -1) {}
  void Add(std::int32_t v, std::int32_t group, std::int32_t position) {
    if (group_[static_cast<std::size_t>(v)] < 0) {
      group_[static_cast<std::size_t>(v)] = group;
      position_[static_cast<std::size_t>(v)] = position;
    } else {
      more_.push_back({v, group, position});
    }
  }
  void Finish() { std::sort(more_.begin(), more_.end()); }
  // v's position among the corners of `group`, or -1.
  std::int32_t Position(std::int32_t v, std::int32_t group) const {
    if (group_[static_cast<std::size_t>(v)] == group) return position_[static_cast<std::size_t>(v)];
    const auto it = std::lower_bound(more_.begin(), more_.end(), std::array<std::int32_t, 3>{v, group, -1});
    return it != more_.end() && (*it)[0] == v && (*it)[1] == group ? (*it)[2] : -1;
  }

 private:
  std::vector<std::int32_t> group_, position_;
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

// Whether the triangle's three corners are three different vertices.
bool Distinct(const Triangle& t) { return t[0] != t[1] && t[1] != t[2] && t[0] != t[2]; }

// The link of v's fan as one cycle: for each triangle (v, a, b) in its own turning, a is followed
// by b. False unless every link corner starts exactly one triangle and they close into one cycle.
bool LinkCycle(const std::vector<Triangle>& tris, std::int32_t v, const std::int32_t* fan, int k,
               std::vector<std::pair<std::int32_t, std::int32_t>>& next, std::vector<std::int32_t>& cycle) {
  next.clear();
  for (int i = 0; i < k; ++i) {
    const Triangle& t = tris[static_cast<std::size_t>(fan[i])];
    const int at = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    next.emplace_back(t[static_cast<std::size_t>((at + 1) % 3)], t[static_cast<std::size_t>((at + 2) % 3)]);
  }
  std::sort(next.begin(), next.end());
  for (std::size_t i = 1; i < next.size(); ++i) {
    if (next[i].first == next[i - 1].first) return false;
  }
  cycle.clear();
  std::int32_t a = next[0].first;
  for (int i = 0; i < k; ++i) {
    if (i > 0 && a == cycle[0]) return false;  // a shorter cycle: more than one around v
    cycle.push_back(a);
    const auto it = std::lower_bound(next.begin(), next.end(), std::pair<std::int32_t, std::int32_t>{a, INT32_MIN});
    if (it == next.end() || it->first != a) return false;  // an open fan
    a = it->second;
  }
  return a == cycle[0];
}

// Whether v's fan, whose link is `cycle`, meets itself only at v and along its spokes. Seen around
// the line L through v and a point q off every triangle's plane, each triangle (v, a_i, a_i+1)
// sweeps an angle in (0, π) from a_i to a_i+1, in the direction the sign of orient(v, a_i, a_i+1, q)
// gives. When all sweep the same way and wind around L exactly once, the sweeps of two triangles
// share only a spoke's angle, and only when they are neighbours: two triangles then meet only at
// v or along their shared spoke (a triangle meets L at v alone, and the points of one at its
// spoke's angle are on that spoke). The winding is the number of times the link passes from one
// side of a plane through L to the other in one sense (each sweep is under π, so it crosses that
// plane at most once, and always on the same half of it in that sense). Exact predicates
// throughout; q and the plane are any points in double that make no sign zero.
bool WindsOnce(const std::vector<Point>& p, std::int32_t v, const std::vector<std::int32_t>& cycle) {
  const Point& c = p[static_cast<std::size_t>(v)];
  const std::size_t k = cycle.size();
  auto a = [&](std::size_t i) -> const Point& { return p[static_cast<std::size_t>(cycle[i % k])]; };
  Kernel::Vector_3 normal(0, 0, 0);
  double size = 0;
  for (std::size_t i = 0; i < k; ++i) {
    normal = normal + CGAL::cross_product(a(i) - c, a(i + 1) - c);
    size = std::max(size, std::sqrt((a(i) - c).squared_length()));
  }
  const double length = std::sqrt(normal.squared_length());
  if (!(length > 0 && std::isfinite(length) && size > 0 && std::isfinite(size))) return false;
  const Kernel::Vector_3 n = normal / length;
  const Point q = c + n * size;
  int turn = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const int o = Orientation(c, a(i), a(i + 1), q);
    if (o == 0 || (turn != 0 && o != turn)) return false;
    turn = o;
  }
  // Planes through L: across the axis least aligned with n, then a quarter and an eighth turn on.
  const int least = std::abs(n.x()) <= std::abs(n.y()) && std::abs(n.x()) <= std::abs(n.z()) ? 0
                    : std::abs(n.y()) <= std::abs(n.z())                                     ? 1
                                                                                             : 2;
  const Kernel::Vector_3 axis(least == 0, least == 1, least == 2);
  Kernel::Vector_3 u = CGAL::cross_product(n, axis);
  u = u / std::sqrt(u.squared_length());
  const Kernel::Vector_3 w = CGAL::cross_product(n, u);
  for (const Kernel::Vector_3& d : {u, w, (u + w) / std::sqrt(2.0)}) {
    const Point r = c + d * size;
    int previous = Orientation(q, c, r, a(k - 1)), crossings = 0;
    bool decided = previous != 0;
    for (std::size_t i = 0; i < k && decided; ++i) {
      const int s = Orientation(q, c, r, a(i));
      decided = s != 0;
      crossings += previous < 0 && s > 0;
      previous = s;
    }
    if (decided) return crossings == 1;
  }
  return false;
}

// The plane a star's boundary lies in: the whole fan's, when it is flat (a cap's fan: side 0), or
// its link's with the center strictly to one side, clear of the link's rounding (a cone's apex, a
// sphere's pole). Without one, the star is tested triangle by triangle against the rest.
void FindStarPlane(const std::vector<Point>& p, Group& star) {
  std::vector<std::int32_t> corners = star.cycle;
  corners.push_back(star.center);
  const int k = static_cast<int>(star.cycle.size());
  if (FindPlane(p, corners.data(), k + 1, star.plane, star.off_plane, star.unit_normal)) {
    star.has_plane = true;
    return;
  }
  if (!FindPlane(p, star.cycle.data(), k, star.plane, star.off_plane, star.unit_normal)) return;
  const Point &a = p[std::size_t(star.plane[0])], &b = p[std::size_t(star.plane[1])],
              &c = p[std::size_t(star.plane[2])], &v = p[std::size_t(star.center)];
  const int o = Orientation(a, b, c, v);
  const bool clear = star.off_plane == 0 || std::abs(star.unit_normal * (v - a)) > 4 * star.off_plane;
  if (o != 0 && clear) {
    star.has_plane = true;
    star.side = o;
  }
}

// The bounding box of a triangle.
CGAL::Bbox_3 BoxOf(const std::vector<Point>& p, const Triangle& t) {
  return p[std::size_t(t[0])].bbox() + p[std::size_t(t[1])].bbox() + p[std::size_t(t[2])].bbox();
}

// Pairs of triangles from one polygon are not tested: they meet only if the polygon is folded in
// its own plane, and testing them made a large polygon's split (all coplanar, all near each other)
// the whole cost — and a non-convex polygon's split overlaps itself where the polygon does not.
class SelfIntersectionCheck {
 public:
  SelfIntersectionCheck(const PolygonMesh& polygons, const SelfIntersectionOptions& options)
      : polygons_(polygons), options_(options), corner_index_(static_cast<std::size_t>(polygons.V.rows())) {
    points_.reserve(static_cast<std::size_t>(polygons.V.rows()));
    for (Eigen::Index i = 0; i < polygons.V.rows(); ++i) {
      points_.emplace_back(polygons.V(i, 0), polygons.V(i, 1), polygons.V(i, 2));
    }
  }

  // The count, or -1 past the budget of candidate pairs.
  std::int64_t Run() {
    SplitFaces();
    if (options_.whole_groups) CollectStars();
    std::size_t all = tris_.size();
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      Group& group = groups_[g];
      all += group.triangles.size();
      group.box = BoxOf(points_, group.triangles[0]);
      for (const Triangle& t : group.triangles) group.box += BoxOf(points_, t);
      for (std::size_t k = 0; k < group.cycle.size(); ++k) {
        corner_index_.Add(group.cycle[k], static_cast<std::int32_t>(g), static_cast<std::int32_t>(k));
      }
      if (group.center >= 0) {
        corner_index_.Add(group.center, static_cast<std::int32_t>(g), static_cast<std::int32_t>(group.cycle.size()));
      }
    }
    corner_index_.Finish();
    budget_ = kSelfIntersectionWork + 50 * static_cast<std::int64_t>(all);
    try {
      EnumerateBoxes();
      DecideTrianglesAgainstGroups();
      DecideGroupPairs();
    } catch (const OverBudget&) {
      return -1;
    }
    return count_;
  }

 private:
  struct OverBudget {};

  // Faces into triangles (tris_, with the face each comes from) or, for flat polygons of more than
  // kWholeLimit corners, into groups.
  void SplitFaces() {
    std::vector<std::int64_t> seen_in(points_.size(), -1);  // the last large polygon a vertex was seen in
    for (std::int64_t f = 0; f < polygons_.num_faces(); ++f) {
      const std::int32_t* corners = polygons_.indices.data() + polygons_.offsets[f];
      const int n = polygons_.face_size(f);
      Group unit;
      if (options_.whole_groups && n > kWholeLimit &&
          FindPlane(points_, corners, n, unit.plane, unit.off_plane, unit.unit_normal)) {
        bool repeated = false;  // a corner twice: the polygon touches itself, decided on triangles
        for (int k = 0; k < n && !repeated; ++k) {
          repeated = seen_in[static_cast<std::size_t>(corners[k])] == f;
          seen_in[static_cast<std::size_t>(corners[k])] = f;
        }
        if (!repeated) {
          unit.has_plane = true;
          unit.cycle.assign(corners, corners + n);
          SplitPolygon(corners, n, unit.triangles);
          groups_.push_back(std::move(unit));
          continue;
        }
      }
      SplitPolygon(corners, n, tris_);
      owner_.resize(tris_.size(), f);
    }
  }

  // The fans of corners of more than kWholeLimit triangles (each a triangle face of its own), the
  // corners of most triangles first, as groups when WindsOnce certifies them; a triangle joins one
  // fan at most. The rest stay in tris_.
  void CollectStars() {
    const std::size_t nt = tris_.size();
    auto alone = [&](std::size_t t) {
      return (t == 0 || owner_[t - 1] != owner_[t]) && (t + 1 == nt || owner_[t + 1] != owner_[t]);
    };
    std::vector<std::int32_t> valence(points_.size(), 0);
    for (std::size_t t = 0; t < nt; ++t) {
      if (!alone(t) || !Distinct(tris_[t])) continue;
      for (const std::int32_t c : tris_[t]) ++valence[static_cast<std::size_t>(c)];
    }
    std::vector<std::int32_t> centers;
    for (std::size_t v = 0; v < points_.size(); ++v) {
      if (valence[v] > kWholeLimit) centers.push_back(static_cast<std::int32_t>(v));
    }
    if (centers.empty()) return;
    std::sort(centers.begin(), centers.end(), [&](std::int32_t x, std::int32_t y) {
      return valence[std::size_t(x)] > valence[std::size_t(y)] ||
             (valence[std::size_t(x)] == valence[std::size_t(y)] && x < y);
    });
    // Each center's triangles, in one array.
    std::vector<std::int32_t> slot(points_.size(), -1);
    std::vector<std::int64_t> start(centers.size() + 1, 0);
    for (std::size_t i = 0; i < centers.size(); ++i) {
      slot[std::size_t(centers[i])] = static_cast<std::int32_t>(i);
      start[i + 1] = start[i] + valence[std::size_t(centers[i])];
    }
    std::vector<std::int32_t> fans(static_cast<std::size_t>(start.back()));
    std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < nt; ++t) {
      if (!alone(t) || !Distinct(tris_[t])) continue;
      for (const std::int32_t c : tris_[t]) {
        const std::int32_t s = slot[static_cast<std::size_t>(c)];
        if (s >= 0) fans[static_cast<std::size_t>(fill[std::size_t(s)]++)] = static_cast<std::int32_t>(t);
      }
    }
    std::vector<char> taken(nt, 0);
    std::vector<std::pair<std::int32_t, std::int32_t>> next;
    for (std::size_t i = 0; i < centers.size(); ++i) {
      const std::int32_t* fan = fans.data() + start[i];
      const int k = static_cast<int>(start[i + 1] - start[i]);
      bool free = true;
      for (int j = 0; j < k && free; ++j) free = !taken[static_cast<std::size_t>(fan[j])];
      Group star;
      star.center = centers[i];
      if (!free || !LinkCycle(tris_, star.center, fan, k, next, star.cycle) ||
          !WindsOnce(points_, star.center, star.cycle)) {
        continue;
      }
      for (int j = 0; j < k; ++j) {
        taken[static_cast<std::size_t>(fan[j])] = 1;
        star.triangles.push_back(tris_[static_cast<std::size_t>(fan[j])]);
      }
      FindStarPlane(points_, star);
      groups_.push_back(std::move(star));
    }
    std::size_t kept = 0;
    for (std::size_t t = 0; t < nt; ++t) {
      if (taken[t]) continue;
      tris_[kept] = tris_[t];
      owner_[kept++] = owner_[t];
    }
    tris_.resize(kept);
    owner_.resize(kept);
  }

  void Spend() {
    if (++pairs_ > budget_) throw OverBudget{};
  }

  // Whether a triangle meets group g only where they share a corner or an edge: its other corners
  // strictly on one side of the group's plane (for a star with its center off the plane, the far
  // side), and what it shares a corner, a boundary edge, or a flat fan's spoke.
  bool MeetsOnlyAtShared(const Triangle& t, std::int32_t g) const {
    const Group& group = groups_[static_cast<std::size_t>(g)];
    if (!group.has_plane) return false;
    const Point &a = points_[std::size_t(group.plane[0])], &b = points_[std::size_t(group.plane[1])],
                &c = points_[std::size_t(group.plane[2])];
    std::int32_t at[3];
    int on = 0, side = 0;
    for (int k = 0; k < 3; ++k) {
      at[on] = corner_index_.Position(t[k], g);
      if (at[on] >= 0) {
        ++on;
        continue;
      }
      const Point& x = points_[std::size_t(t[k])];
      const int o = Orientation(a, b, c, x);
      if (o == 0 || (side != 0 && o != side) || (group.side != 0 && o != -group.side)) return false;
      // A group within rounding of its plane: the corner must clear the group's own spread.
      if (group.off_plane > 0 && !(std::abs(group.unit_normal * (x - a)) > 4 * group.off_plane)) return false;
      side = o;
    }
    if (side == 0) return false;  // every corner shared: the same triangle, or a chord's
    const auto n = static_cast<std::int32_t>(group.cycle.size());  // a star's center is at n
    if (on == 0) return true;
    if (on == 1) return at[0] < n || group.side == 0;
    if (at[0] == n || at[1] == n) return group.side == 0;  // a flat fan's spoke: an edge of its own
    const std::int32_t d = std::abs(at[0] - at[1]);
    return d == 1 || d == n - 1;
  }

  void Test(const Triangle& s, const Triangle& t) {
    if (count_ < options_.limit && TrianglesIntersect(points_, s, t)) ++count_;
  }

  // Every candidate pair of boxes: triangle pairs decided at once, a triangle against a group by
  // the whole-group test (or remembered for its triangles), group pairs remembered.
  void EnumerateBoxes() {
    std::vector<Box> boxes;
    boxes.reserve(tris_.size() + groups_.size());
    AddBoxes(tris_, boxes);
    for (std::size_t g = 0; g < groups_.size(); ++g)
      boxes.emplace_back(groups_[g].box, -1 - static_cast<std::int32_t>(g));
    std::vector<const Box*> handles;
    handles.reserve(boxes.size());
    for (const Box& b : boxes) handles.push_back(&b);
    CGAL::box_self_intersection_d(handles.begin(), handles.end(), [&](const Box* x, const Box* y) {
      if (count_ >= options_.limit) return;
      Spend();
      std::int32_t i = x->info(), j = y->info();
      if (i < 0 && j < 0) {
        group_pairs_.emplace_back(std::min(-1 - i, -1 - j), std::max(-1 - i, -1 - j));
      } else if (i < 0 || j < 0) {
        if (i < 0) std::swap(i, j);
        const std::int32_t g = -1 - j;
        if (!MeetsOnlyAtShared(tris_[static_cast<std::size_t>(i)], g)) triangle_vs_group_.emplace_back(i, g);
      } else if (owner_[static_cast<std::size_t>(i)] != owner_[static_cast<std::size_t>(j)]) {
        Test(tris_[static_cast<std::size_t>(i)], tris_[static_cast<std::size_t>(j)]);
      }
    });
  }

  // The boxes of the triangles with an area (nothing to intersect otherwise), by their index.
  void AddBoxes(const std::vector<Triangle>& ts, std::vector<Box>& out) const {
    for (std::size_t i = 0; i < ts.size(); ++i) {
      const Triangle& t = ts[i];
      if (!CGAL::collinear(points_[std::size_t(t[0])], points_[std::size_t(t[1])], points_[std::size_t(t[2])])) {
        out.emplace_back(BoxOf(points_, t), static_cast<std::int32_t>(i));
      }
    }
  }

  // Every pair of a triangle from `left` and one from `right` whose boxes overlap.
  void Decide(const std::vector<Triangle>& left, const std::vector<Triangle>& right) {
    std::vector<Box> lb, rb;
    AddBoxes(left, lb);
    AddBoxes(right, rb);
    CGAL::box_intersection_d(lb.begin(), lb.end(), rb.begin(), rb.end(), [&](const Box& x, const Box& y) {
      Spend();
      Test(left[std::size_t(x.info())], right[std::size_t(y.info())]);
    });
  }

  // What the whole-group test left open, triangle against the group's triangles (by group).
  void DecideTrianglesAgainstGroups() {
    std::sort(triangle_vs_group_.begin(), triangle_vs_group_.end(), [](const auto& p, const auto& q) {
      return p.second < q.second || (p.second == q.second && p.first < q.first);
    });
    std::vector<Triangle> group;
    for (std::size_t k = 0; k < triangle_vs_group_.size() && count_ < options_.limit;) {
      const std::int32_t g = triangle_vs_group_[k].second;
      group.clear();
      for (; k < triangle_vs_group_.size() && triangle_vs_group_[k].second == g; ++k) {
        group.push_back(tris_[static_cast<std::size_t>(triangle_vs_group_[k].first)]);
      }
      Decide(group, groups_[static_cast<std::size_t>(g)].triangles);
    }
  }

  // Two groups: the triangles of each that the whole-group test cannot clear against the other;
  // only pairs of those are left (a triangle cleared against a whole group meets none of its own).
  void DecideGroupPairs() {
    std::sort(group_pairs_.begin(), group_pairs_.end());
    std::vector<Triangle> left, right;
    auto open_against = [&](std::int32_t from, std::int32_t other, std::vector<Triangle>& out) {
      out.clear();
      const CGAL::Bbox_3& box = groups_[static_cast<std::size_t>(other)].box;
      for (const Triangle& t : groups_[static_cast<std::size_t>(from)].triangles) {
        if (!CGAL::do_overlap(BoxOf(points_, t), box)) continue;
        Spend();
        if (!MeetsOnlyAtShared(t, other)) out.push_back(t);
      }
    };
    for (const auto& [g, h] : group_pairs_) {
      if (count_ >= options_.limit) break;
      open_against(g, h, left);
      if (left.empty()) continue;
      open_against(h, g, right);
      if (!right.empty()) Decide(left, right);
    }
  }

  const PolygonMesh& polygons_;
  SelfIntersectionOptions options_;
  std::vector<Point> points_;
  std::vector<Triangle> tris_;
  std::vector<std::int64_t> owner_;  // the polygon each triangle comes from
  std::vector<Group> groups_;
  CornerIndex corner_index_;
  std::vector<std::pair<std::int32_t, std::int32_t>> triangle_vs_group_;  // decided on its triangles
  std::vector<std::pair<std::int32_t, std::int32_t>> group_pairs_;
  std::int64_t count_ = 0, pairs_ = 0, budget_ = 0;
};

}  // namespace

std::int64_t CountSelfIntersections(const PolygonMesh& polygons, const SelfIntersectionOptions& options) {
  return SelfIntersectionCheck(polygons, options).Run();
}

}  // namespace massprops
