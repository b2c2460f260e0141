// Convex polytopes: construction, the separating-axis test and face clipping (polytope.h).

#include "polytope.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace dynamics::contact {
namespace {

// The 2D convex hull (Andrew's monotone chain) of points given in a plane basis, as indices in
// counter-clockwise order.
std::vector<int> Hull2D(const std::vector<Eigen::Vector2d>& p, const std::vector<int>& ids) {
  std::vector<int> order(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(),
            [&](int x, int y) { return p[x].x() < p[y].x() || (p[x].x() == p[y].x() && p[x].y() < p[y].y()); });
  auto cross = [&](int o, int a, int b) {
    return (p[a] - p[o]).x() * (p[b] - p[o]).y() - (p[a] - p[o]).y() * (p[b] - p[o]).x();
  };
  std::vector<int> h(2 * order.size());
  std::size_t k = 0;
  for (int i : order) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], i) <= 0) --k;
    h[k++] = i;
  }
  for (std::size_t i = order.size() - 1, t = k + 1; i-- > 0;) {
    const int j = order[i];
    while (k >= t && cross(h[k - 2], h[k - 1], j) <= 0) --k;
    h[k++] = j;
  }
  h.resize(k > 1 ? k - 1 : k);
  std::vector<int> out;
  for (int i : h) out.push_back(ids[static_cast<std::size_t>(i)]);
  return out;
}

// A posed polytope's vertices and face planes in the world.
struct World {
  std::vector<Vector3> v;
  std::vector<Vector3> n;
  std::vector<double> d;  // n·x = d on the face
};

World Place(const Polytope& p, const Posed& posed) {
  World w;
  w.v.reserve(p.vertices.size());
  for (const Vector3& x : p.vertices) w.v.push_back(posed.R * x + posed.t);
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    w.n.push_back(posed.R * p.normals[f]);
    w.d.push_back(w.n.back().dot(w.v[static_cast<std::size_t>(p.faces[f][0])]));
  }
  return w;
}

double MinAlong(const std::vector<Vector3>& v, const Vector3& u) {
  double m = std::numeric_limits<double>::infinity();
  for (const Vector3& x : v) m = std::min(m, u.dot(x));
  return m;
}
double MaxAlong(const std::vector<Vector3>& v, const Vector3& u) {
  double m = -std::numeric_limits<double>::infinity();
  for (const Vector3& x : v) m = std::max(m, u.dot(x));
  return m;
}

}  // namespace

Polytope MakePolytope(const std::vector<Vector3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  Polytope p;
  p.vertices = vertices;
  if (vertices.size() < 4 || triangles.size() < 4) throw std::invalid_argument("a convex shape needs a closed hull");
  for (const Vector3& v : vertices) p.centroid += v;
  p.centroid /= static_cast<double>(vertices.size());
  double size = 0;
  for (const Vector3& v : vertices) size = std::max(size, (v - p.centroid).norm());
  const double eps = 1e-9 * size;
  // One face per distinct plane of the triangles: the hull of the vertices on it.
  std::vector<std::pair<Vector3, double>> planes;
  for (const auto& t : triangles) {
    for (int i : t) {
      if (i < 0 || static_cast<std::size_t>(i) >= vertices.size())
        throw std::invalid_argument("a hull index out of range");
    }
    const Vector3 a = vertices[static_cast<std::size_t>(t[0])], b = vertices[static_cast<std::size_t>(t[1])],
                  c = vertices[static_cast<std::size_t>(t[2])];
    const Vector3 cr = (b - a).cross(c - a);
    if (cr.norm() <= eps * size) continue;  // a sliver: its plane comes from the others
    const Vector3 n = cr.normalized();
    const double d = n.dot(a);
    bool seen = false;
    for (const auto& [m, e] : planes) seen = seen || ((m - n).norm() < 1e-9 && std::abs(e - d) < eps);
    if (!seen) planes.emplace_back(n, d);
  }
  for (const auto& [n, d] : planes) {
    std::vector<int> on;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      const double s = n.dot(vertices[i]) - d;
      if (s > 1e3 * eps) throw std::invalid_argument("the convex shape's triangles do not bound a convex solid");
      if (std::abs(s) <= 1e3 * eps) on.push_back(static_cast<int>(i));
    }
    const Vector3 u = (std::abs(n.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY()).cross(n).normalized();
    const Vector3 w = n.cross(u);  // (u, w, n) right-handed: counter-clockwise seen from outside
    std::vector<Eigen::Vector2d> pts;
    for (int i : on)
      pts.emplace_back(u.dot(vertices[static_cast<std::size_t>(i)]), w.dot(vertices[static_cast<std::size_t>(i)]));
    std::vector<int> face = Hull2D(pts, on);
    if (face.size() < 3) continue;
    p.faces.push_back(face);
    p.normals.push_back(n);
  }
  std::map<std::pair<int, int>, std::vector<int>> edges;  // edge → the faces it bounds
  for (std::size_t fi = 0; fi < p.faces.size(); ++fi) {
    const auto& f = p.faces[fi];
    for (std::size_t i = 0; i < f.size(); ++i) {
      const int a = f[i], b = f[(i + 1) % f.size()];
      edges[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(fi));
    }
  }
  for (const auto& [e, faces] : edges) {
    if (faces.size() != 2) throw std::invalid_argument("the convex shape's hull is not closed");
    p.edges.push_back(e);
    p.edge_faces.emplace_back(faces[0], faces[1]);
  }
  return p;
}

Polytope BoxPolytope(const Vector3& h) {
  std::vector<Vector3> v;
  for (int i = 0; i < 8; ++i) v.emplace_back((i & 1) ? h[0] : -h[0], (i & 2) ? h[1] : -h[1], (i & 4) ? h[2] : -h[2]);
  const std::vector<std::array<int, 3>> t = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                             {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return MakePolytope(v, t);
}

void PolytopePolytope(const Polytope& pa, const Posed& a, const Polytope& pb, const Posed& b, double margin,
                      std::vector<ContactPoint>& out) {
  const World wa = Place(pa, a), wb = Place(pb, b);
  // Face axes: the separation of the other polytope from each face's plane.
  double best = -std::numeric_limits<double>::infinity();
  int best_kind = -1, best_index = -1;  // 0: a face of a, 1: a face of b, 2: an edge pair
  for (std::size_t f = 0; f < wa.n.size(); ++f) {
    const double s = MinAlong(wb.v, wa.n[f]) - wa.d[f];
    if (s >= margin) return;
    if (s > best) {
      best = s;
      best_kind = 0;
      best_index = static_cast<int>(f);
    }
  }
  for (std::size_t f = 0; f < wb.n.size(); ++f) {
    const double s = MinAlong(wa.v, wb.n[f]) - wb.d[f];
    if (s >= margin) return;
    if (s > best) {
      best = s;
      best_kind = 1;
      best_index = static_cast<int>(f);
    }
  }
  // Edge axes: cross products of an edge of each; clearly better than the faces to count.
  const Vector3 ca = a.R * pa.centroid + a.t;
  const double face_best = best;
  const double tie = 1e-6 * (wa.v.empty() ? 1.0 : (wa.v[0] - ca).norm());
  Vector3 edge_axis = Vector3::Zero();
  std::pair<int, int> edge_pair{-1, -1};
  for (std::size_t i = 0; i < pa.edges.size(); ++i) {
    const Vector3 ea =
        wa.v[static_cast<std::size_t>(pa.edges[i].second)] - wa.v[static_cast<std::size_t>(pa.edges[i].first)];
    for (std::size_t j = 0; j < pb.edges.size(); ++j) {
      const Vector3 eb =
          wb.v[static_cast<std::size_t>(pb.edges[j].second)] - wb.v[static_cast<std::size_t>(pb.edges[j].first)];
      // Only pairs whose arcs on the Gauss map cross (Gregorius, GDC 2013) can be the axis:
      // the others are never closer than a face axis, and skipping them makes hulls cheap.
      {
        const Vector3& na = wa.n[static_cast<std::size_t>(pa.edge_faces[i].first)];
        const Vector3& nb = wa.n[static_cast<std::size_t>(pa.edge_faces[i].second)];
        const Vector3 nc = -wb.n[static_cast<std::size_t>(pb.edge_faces[j].first)];
        const Vector3 nd = -wb.n[static_cast<std::size_t>(pb.edge_faces[j].second)];
        const Vector3 bxa = nb.cross(na), dxc = nd.cross(nc);
        const double cba = nc.dot(bxa), dba = nd.dot(bxa), adc = na.dot(dxc), bdc = nb.dot(dxc);
        if (!(cba * dba < 0 && adc * bdc < 0 && cba * bdc > 0)) continue;
      }
      Vector3 u = ea.cross(eb);
      const double len = u.norm();
      if (len < 1e-9 * ea.norm() * eb.norm()) continue;
      u /= len;
      if (u.dot(wa.v[static_cast<std::size_t>(pa.edges[i].first)] - ca) < 0) u = -u;  // out of a
      const double s = MinAlong(wb.v, u) - MaxAlong(wa.v, u);
      if (s >= margin) return;
      if (s > best && s > face_best + tie) {
        best = s;
        best_kind = 2;
        edge_axis = u;
        edge_pair = {static_cast<int>(i), static_cast<int>(j)};
      }
    }
  }
  if (best_kind == 2) {
    // Edge against edge: the closest points of the two edges, normal from b into a.
    const Vector3 p0 = wa.v[static_cast<std::size_t>(pa.edges[static_cast<std::size_t>(edge_pair.first)].first)];
    const Vector3 p1 = wa.v[static_cast<std::size_t>(pa.edges[static_cast<std::size_t>(edge_pair.first)].second)];
    const Vector3 q0 = wb.v[static_cast<std::size_t>(pb.edges[static_cast<std::size_t>(edge_pair.second)].first)];
    const Vector3 q1 = wb.v[static_cast<std::size_t>(pb.edges[static_cast<std::size_t>(edge_pair.second)].second)];
    const Vector3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double aa = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r), c = d1.dot(r), bb = d1.dot(d2);
    const double denom = aa * e - bb * bb;
    double s = denom > 0 ? std::clamp((bb * f - c * e) / denom, 0.0, 1.0) : 0.0;
    double t = std::clamp((bb * s + f) / e, 0.0, 1.0);
    s = std::clamp((bb * t - c) / aa, 0.0, 1.0);
    const Vector3 qa = p0 + d1 * s, qb = q0 + d2 * t;
    out.push_back({0.5 * (qa + qb), -edge_axis, best,
                   1000u + static_cast<std::uint32_t>(edge_pair.first * 131 + edge_pair.second)});
    return;
  }
  // Face contact: the reference face's polytope, and the other's face most against its normal.
  const bool ref_a = best_kind == 0;
  const Polytope& pr = ref_a ? pa : pb;
  const Polytope& pi = ref_a ? pb : pa;
  const World& wr = ref_a ? wa : wb;
  const World& wi = ref_a ? wb : wa;
  const Vector3 rn = wr.n[static_cast<std::size_t>(best_index)];
  std::size_t inc = 0;
  double most = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < wi.n.size(); ++f) {
    const double c = wi.n[f].dot(rn);
    if (c < most) {
      most = c;
      inc = f;
    }
  }
  std::vector<Vector3> poly;
  for (int i : pi.faces[inc]) poly.push_back(wi.v[static_cast<std::size_t>(i)]);
  const std::vector<int>& ref_face = pr.faces[static_cast<std::size_t>(best_index)];
  for (std::size_t k = 0; k < ref_face.size() && !poly.empty(); ++k) {
    const Vector3& p = wr.v[static_cast<std::size_t>(ref_face[k])];
    const Vector3& q = wr.v[static_cast<std::size_t>(ref_face[(k + 1) % ref_face.size()])];
    const Vector3 side = (q - p).cross(rn).normalized();  // out of the face, in its plane
    const double offset = side.dot(p);
    std::vector<Vector3> clipped;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vector3& x = poly[i];
      const Vector3& y = poly[(i + 1) % poly.size()];
      const double dx = side.dot(x) - offset, dy = side.dot(y) - offset;
      if (dx <= 0) clipped.push_back(x);
      if ((dx < 0) != (dy < 0) && dx != dy) clipped.push_back(x + (y - x) * (dx / (dx - dy)));
    }
    poly = std::move(clipped);
  }
  const double rd = wr.d[static_cast<std::size_t>(best_index)];
  std::vector<ContactPoint> found;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const double sep = rn.dot(poly[i]) - rd;
    if (sep >= margin) continue;
    found.push_back({poly[i] - rn * (0.5 * sep), ref_a ? Vector3(-rn) : rn, sep,
                     static_cast<std::uint32_t>((ref_a ? 0 : 1) * 65536 + best_index * 64 + static_cast<int>(i))});
  }
  if (found.size() > 4) {  // the deepest, then those farthest from the points kept
    std::vector<ContactPoint> kept;
    auto deepest = std::min_element(found.begin(), found.end(), [](const ContactPoint& x, const ContactPoint& y) {
      return x.separation < y.separation;
    });
    kept.push_back(*deepest);
    found.erase(deepest);
    while (kept.size() < 4 && !found.empty()) {
      auto far = std::max_element(found.begin(), found.end(), [&](const ContactPoint& x, const ContactPoint& y) {
        double dx = 1e300, dy = 1e300;
        for (const ContactPoint& k : kept) {
          dx = std::min(dx, (x.point - k.point).squaredNorm());
          dy = std::min(dy, (y.point - k.point).squaredNorm());
        }
        return dx < dy;
      });
      kept.push_back(*far);
      found.erase(far);
    }
    found = std::move(kept);
  }
  out.insert(out.end(), found.begin(), found.end());
}

void SpherePolytope(const Vector3& c, double r, const Polytope& p, const Posed& posed, double margin, bool sphere_first,
                    std::uint32_t feature, std::vector<ContactPoint>& out) {
  const World w = Place(p, posed);
  // Inside every face plane: out through the nearest face.
  double deepest = -std::numeric_limits<double>::infinity();
  std::size_t face = 0;
  for (std::size_t f = 0; f < w.n.size(); ++f) {
    const double s = w.n[f].dot(c) - w.d[f];
    if (s > deepest) {
      deepest = s;
      face = f;
    }
  }
  Vector3 closest = c, n = Vector3::UnitZ();
  double sep;
  if (deepest <= 0) {
    n = w.n[face];
    closest = c - n * deepest;
    sep = deepest - r;
  } else {
    // Outside: the closest point of the surface (on a face, an edge or a corner).
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < w.n.size(); ++f) {
      const std::vector<int>& ids = p.faces[f];
      const Vector3 onplane = c - w.n[f] * (w.n[f].dot(c) - w.d[f]);
      bool inside = true;
      for (std::size_t k = 0; k < ids.size() && inside; ++k) {
        const Vector3& a = w.v[static_cast<std::size_t>(ids[k])];
        const Vector3& b = w.v[static_cast<std::size_t>(ids[(k + 1) % ids.size()])];
        inside = (b - a).cross(onplane - a).dot(w.n[f]) >= 0;
      }
      if (inside) {
        const double d = (c - onplane).norm();
        if (d < best) {
          best = d;
          closest = onplane;
        }
        continue;
      }
      for (std::size_t k = 0; k < ids.size(); ++k) {
        const Vector3& a = w.v[static_cast<std::size_t>(ids[k])];
        const Vector3& b = w.v[static_cast<std::size_t>(ids[(k + 1) % ids.size()])];
        const double t = std::clamp((c - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        const Vector3 q = a + (b - a) * t;
        const double d = (c - q).norm();
        if (d < best) {
          best = d;
          closest = q;
        }
      }
    }
    n = (c - closest) / best;
    sep = best - r;
  }
  if (sep >= margin) return;
  out.push_back({closest + n * (0.5 * sep), sphere_first ? n : Vector3(-n), sep, feature});
}

}  // namespace dynamics::contact
