// Convex polytopes: construction, the separating-axis test and face clipping (polytope.h).

#include "polytope.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "massprops/simd_clones.h"

namespace dynamics::contact {
namespace {

// The working arrays of a pair's test, kept per thread so that a step's thousands of pairs do
// not allocate: the two placed polytopes, the clipped outline (and the one being made) with each
// corner's key, and the points found.
struct Scratch {
  PlacedPolytope a, b;
  std::vector<Vector3> poly, clipped;
  std::vector<std::uint32_t> ids, clipped_ids;
  std::vector<ContactPoint> found;
};
Scratch& ThreadScratch() {
  thread_local Scratch scratch;
  return scratch;
}

}  // namespace

void PlacePolytope(const Polytope& p, const Posed& posed, PlacedPolytope& w) {
  // (Sized, then written in place: an append a value cost a pile's step a few per cent.)
  const std::size_t nv = p.vertices.size(), nf = p.faces.size(), ne = p.edges.size();
  w.v.resize(nv);
  w.n.resize(nf);
  w.d.resize(nf);
  w.e.resize(ne);
  w.arc.resize(ne);
  for (std::size_t i = 0; i < nv; ++i) w.v[i] = posed.R * p.vertices[i] + posed.t;
  for (std::size_t f = 0; f < nf; ++f) {
    w.n[f] = posed.R * p.normals[f];
    w.d[f] = w.n[f].dot(w.v[static_cast<std::size_t>(p.faces[f][0])]);
  }
  for (std::size_t i = 0; i < ne; ++i) {
    w.e[i] = w.v[static_cast<std::size_t>(p.edges[i].second)] - w.v[static_cast<std::size_t>(p.edges[i].first)];
    const Vector3& first = w.n[static_cast<std::size_t>(p.edge_faces[i].first)];
    const Vector3& second = w.n[static_cast<std::size_t>(p.edge_faces[i].second)];
    w.arc[i] = second.cross(first);
  }
}

namespace {

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

// Each face's outline (Polytope::faces): its boundary edges chained, counter-clockwise seen from
// outside, starting at its lowest corner in the face's (u, w) basis, corners where it does not
// turn dropped. owner: each directed edge's triangle.
void FaceOutlines(const std::vector<Vector3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                  const std::vector<int>& face_of, const std::map<std::pair<int, int>, std::size_t>& owner,
                  Polytope& p) {
  const std::size_t nt = triangles.size();
  auto twin = [&](std::size_t t, int k) { return owner.at({triangles[t][(k + 1) % 3], triangles[t][k]}); };
  std::vector<std::map<int, int>> next(p.normals.size());
  for (std::size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      if (face_of[twin(t, k)] != face_of[t])
        next[static_cast<std::size_t>(face_of[t])][triangles[t][k]] = triangles[t][(k + 1) % 3];
    }
  }
  p.faces.resize(p.normals.size());
  for (std::size_t f = 0; f < p.normals.size(); ++f) {
    const Vector3& n = p.normals[f];
    const Vector3 u = (std::abs(n.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY()).cross(n).normalized();
    const Vector3 w = n.cross(u);  // (u, w, n) right-handed
    auto at = [&](int i) {
      const Vector3& x = vertices[static_cast<std::size_t>(i)];
      return Eigen::Vector2d(u.dot(x), w.dot(x));
    };
    std::vector<int> loop;
    int start = next[f].begin()->first;
    for (const auto& [a, b] : next[f]) {
      (void)b;
      const Eigen::Vector2d pa = at(a), ps = at(start);
      if (pa.x() < ps.x() || (pa.x() == ps.x() && pa.y() < ps.y())) start = a;
    }
    for (int v = start;;) {
      loop.push_back(v);
      v = next[f].at(v);
      if (v == start) break;
      if (loop.size() > next[f].size()) throw std::invalid_argument("the convex shape's hull is not closed");
    }
    if (loop.size() != next[f].size()) throw std::invalid_argument("the convex shape's hull is not closed");
    std::vector<int> corners;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Eigen::Vector2d a = at(corners.empty() ? loop[(k + loop.size() - 1) % loop.size()] : corners.back());
      const Eigen::Vector2d b = at(loop[k]), c = at(loop[(k + 1) % loop.size()]);
      if ((b - a).x() * (c - b).y() - (b - a).y() * (c - b).x() > 0 || k == 0) corners.push_back(loop[k]);
    }
    p.faces[f] = corners.size() >= 3 ? corners : loop;
  }
}

}  // namespace

Polytope MakePolytope(const std::vector<Vector3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  Polytope p;
  p.vertices = vertices;
  if (vertices.size() < 4 || triangles.size() < 4) throw std::invalid_argument("a convex shape needs a closed hull");
  for (const auto& t : triangles) {
    for (int i : t) {
      if (i < 0 || static_cast<std::size_t>(i) >= vertices.size())
        throw std::invalid_argument("a hull index out of range");
    }
  }
  for (const Vector3& v : vertices) {
    p.centroid += v;
    p.xs.push_back(v.x());
    p.ys.push_back(v.y());
    p.zs.push_back(v.z());
    p.l1.push_back(v.cwiseAbs().sum());
    p.max_norm = std::max(p.max_norm, v.norm());
  }
  p.centroid /= static_cast<double>(vertices.size());
  double size = 0;
  for (const Vector3& v : vertices) size = std::max(size, (v - p.centroid).norm());
  const double eps = 1e-9 * size;
  const std::size_t nt = triangles.size();
  auto corner = [&](std::size_t t, int k) { return vertices[static_cast<std::size_t>(triangles[t][k])]; };

  // Each directed edge once, its twin present: a closed, consistently oriented surface.
  std::map<std::pair<int, int>, std::size_t> owner;  // directed edge → its triangle
  for (std::size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      if (!owner.emplace(std::pair{triangles[t][k], triangles[t][(k + 1) % 3]}, t).second)
        throw std::invalid_argument("the convex shape's hull is not closed");
    }
  }
  for (const auto& [e, t] : owner) {
    if (owner.count({e.second, e.first}) == 0) throw std::invalid_argument("the convex shape's hull is not closed");
  }

  // Faces: triangles joined across edges while they share a plane (a face of a convex solid is
  // one connected region); a sliver (no plane of its own) joins a neighbour.
  std::vector<Vector3> normal(nt, Vector3::Zero());
  std::vector<double> offset(nt, 0.0);
  std::vector<bool> sliver(nt, false);
  for (std::size_t t = 0; t < nt; ++t) {
    const Vector3 cr = (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
    sliver[t] = cr.norm() <= eps * size;
    if (!sliver[t]) {
      normal[t] = cr.normalized();
      offset[t] = normal[t].dot(corner(t, 0));
    }
  }
  std::vector<std::size_t> parent(nt);
  for (std::size_t t = 0; t < nt; ++t) parent[t] = t;
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  auto join = [&](std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the first triangle names the face
  };
  auto twin = [&](std::size_t t, int k) { return owner.at({triangles[t][(k + 1) % 3], triangles[t][k]}); };
  for (std::size_t t = 0; t < nt; ++t) {
    if (sliver[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const std::size_t u = twin(t, k);
      if (!sliver[u] && (normal[u] - normal[t]).norm() < 1e-9 && std::abs(offset[u] - offset[t]) < eps) join(t, u);
    }
  }
  std::vector<bool> placed(nt);
  for (std::size_t t = 0; t < nt; ++t) placed[t] = !sliver[t];
  for (bool changed = true; changed;) {  // a sliver takes the face of the neighbour whose plane holds it
    changed = false;
    for (std::size_t t = 0; t < nt; ++t) {
      if (placed[t]) continue;
      std::size_t best = nt;
      double best_off = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) {
        const std::size_t u = twin(t, k);
        if (!placed[u]) continue;
        double off = 0;
        for (int m = 0; m < 3; ++m) off = std::max(off, std::abs(normal[u].dot(corner(t, m)) - offset[u]));
        if (off < best_off) best_off = off, best = u;
      }
      if (best == nt) continue;
      join(t, best);
      normal[t] = normal[best];
      offset[t] = offset[best];
      placed[t] = changed = true;
    }
  }
  // Faces numbered, and their planes taken, in the order of their first triangle with a plane.
  std::vector<int> face_of(nt, -1), id(nt, -1);
  for (std::size_t t = 0; t < nt; ++t) {
    if (sliver[t] || id[find(t)] >= 0) continue;
    id[find(t)] = static_cast<int>(p.normals.size());
    p.normals.push_back(normal[t]);
  }
  for (std::size_t t = 0; t < nt; ++t) {
    face_of[t] = id[find(t)];
    if (face_of[t] < 0) throw std::invalid_argument("the convex shape's triangles do not bound a convex solid");
  }

  // Convex: across every edge between faces, the neighbour's far corner lies under this plane.
  for (std::size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3 && !sliver[t]; ++k) {
      const std::size_t u = twin(t, k);
      if (face_of[u] == face_of[t]) continue;
      for (int m = 0; m < 3; ++m) {
        if (normal[t].dot(corner(u, m)) - offset[t] > 1e3 * eps)
          throw std::invalid_argument("the convex shape's triangles do not bound a convex solid");
      }
    }
  }

  FaceOutlines(vertices, triangles, face_of, owner, p);

  // Edges: the triangle edges between two faces (a long edge of a tessellated hull may come as
  // several collinear pieces: each is an edge, which the separating-axis test takes alike).
  std::map<std::pair<int, int>, std::pair<int, int>> edges;
  for (std::size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3], fa = face_of[t], fb = face_of[twin(t, k)];
      if (fa != fb) edges[{std::min(a, b), std::max(a, b)}] = {std::min(fa, fb), std::max(fa, fb)};
    }
  }
  for (const auto& [e, faces] : edges) {
    p.edges.push_back(e);
    p.edge_faces.push_back(faces);
  }
  p.triangle_faces = face_of;
  p.vertex_faces.resize(vertices.size());
  for (std::size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      auto& list = p.vertex_faces[static_cast<std::size_t>(triangles[t][k])];
      if (std::find(list.begin(), list.end(), face_of[t]) == list.end()) list.push_back(face_of[t]);
    }
  }
  return p;
}

MASSPROPS_CLONES_AVX2_AVX512
void MayLieBelow(const Polytope& p, std::size_t first, int n, const Vector3& u, double limit, double scale,
                 std::uint8_t* maybe) {
  const double* x = p.xs.data() + first;
  const double* y = p.ys.data() + first;
  const double* z = p.zs.data() + first;
  const double* l1 = p.l1.data() + first;
  const double u0 = u.x(), u1 = u.y(), u2 = u.z(), slack = 1e-14 * std::abs(limit);
  // The exact test sums u·v in Eigen's order; this one may differ from it by a few units in the
  // last place of Σ|uᵢ vᵢ| ≤ |v|₁ (|u| = 1), far below the slack.
  for (int j = 0; j < n; ++j) {
    const double h = u0 * x[j] + u1 * y[j] + u2 * z[j];
    maybe[j] = static_cast<std::uint8_t>(h - limit <= 1e-12 * (scale + l1[j]) + 1e-14 * l1[j] + slack);
  }
}

Polytope BoxPolytope(const Vector3& h) {
  std::vector<Vector3> v;
  for (int i = 0; i < 8; ++i) v.emplace_back((i & 1) ? h[0] : -h[0], (i & 2) ? h[1] : -h[1], (i & 4) ? h[2] : -h[2]);
  const std::vector<std::array<int, 3>> t = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                             {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return MakePolytope(v, t);
}

namespace {

// Of more than four points, four (appended to out): the deepest, then each time the one farthest
// from those kept. `found` is used up.
void KeepFour(std::vector<ContactPoint>& found, std::vector<ContactPoint>& out) {
  const std::size_t first = out.size();
  auto deepest = std::min_element(found.begin(), found.end(), [](const ContactPoint& x, const ContactPoint& y) {
    return x.separation < y.separation;
  });
  out.push_back(*deepest);
  found.erase(deepest);
  while (out.size() - first < 4 && !found.empty()) {
    auto far = std::max_element(found.begin(), found.end(), [&](const ContactPoint& x, const ContactPoint& y) {
      double dx = 1e300, dy = 1e300;
      for (std::size_t k = first; k < out.size(); ++k) {
        dx = std::min(dx, (x.point - out[k].point).squaredNorm());
        dy = std::min(dy, (y.point - out[k].point).squaredNorm());
      }
      return dx < dy;
    });
    out.push_back(*far);
    found.erase(far);
  }
}

// The contact of a face of pr (best_index, its normal rn out of pr) with the face of pi most against
// it: pi's face clipped by the reference face's sides, its corners within the margin. ref_a: pr is
// the pair's first polytope (the normal points out of the second into the first).
void FaceContact(const Polytope& pr, const PlacedPolytope& wr, const Polytope& pi, const PlacedPolytope& wi,
                 int best_index, bool ref_a, double margin, Scratch& scratch, std::vector<ContactPoint>& out) {
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
  // Each point's key: the incident corner's index, or for a point the clipping made, a mix of the
  // reference side and the two points of the segment it cut (stable while the faces overlap alike).
  std::vector<Vector3>& poly = scratch.poly;
  std::vector<std::uint32_t>& ids = scratch.ids;
  poly.clear();
  ids.clear();
  for (int i : pi.faces[inc]) {
    poly.push_back(wi.v[static_cast<std::size_t>(i)]);
    ids.push_back(static_cast<std::uint32_t>(i) & 0x3FFFFu);
  }
  const std::vector<int>& ref_face = pr.faces[static_cast<std::size_t>(best_index)];
  for (std::size_t k = 0; k < ref_face.size() && !poly.empty(); ++k) {
    const Vector3& p = wr.v[static_cast<std::size_t>(ref_face[k])];
    const Vector3& q = wr.v[static_cast<std::size_t>(ref_face[(k + 1) % ref_face.size()])];
    const Vector3 side = (q - p).cross(rn).normalized();  // out of the face, in its plane
    const double offset = side.dot(p);
    // A corner within rounding of the side (a box flush on an equal box) is kept as itself, not
    // replaced by a cut whose key would change with the rounding from step to step.
    const double on = 1e-9 * (q - p).norm();
    std::vector<Vector3>& clipped = scratch.clipped;
    std::vector<std::uint32_t>& clipped_ids = scratch.clipped_ids;
    clipped.clear();
    clipped_ids.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const std::size_t j = (i + 1) % poly.size();
      const Vector3& x = poly[i];
      const Vector3& y = poly[j];
      const double dx = side.dot(x) - offset, dy = side.dot(y) - offset;
      if (dx <= on) {
        clipped.push_back(x);
        clipped_ids.push_back(ids[i]);
      }
      if ((dx < -on && dy > on) || (dx > on && dy < -on)) {
        clipped.push_back(x + (y - x) * (dx / (dx - dy)));
        clipped_ids.push_back(0x40000u |
                              ((static_cast<std::uint32_t>(k) * 2654435761u + ids[i] * 40503u + ids[j]) & 0x3FFFFu));
      }
    }
    poly.swap(clipped);
    ids.swap(clipped_ids);
  }
  const double rd = wr.d[static_cast<std::size_t>(best_index)];
  std::vector<ContactPoint>& found = scratch.found;
  found.clear();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const double sep = rn.dot(poly[i]) - rd;
    if (sep >= margin) continue;
    found.push_back({poly[i] - rn * (0.5 * sep), ref_a ? Vector3(-rn) : rn, sep,
                     (ref_a ? 0u : 1u << 31) | (static_cast<std::uint32_t>(best_index) & 0x7FFu) << 19 | ids[i]});
  }
  if (found.size() > 4) {
    KeepFour(found, out);
  } else {
    out.insert(out.end(), found.begin(), found.end());
  }
}

}  // namespace

void PolytopePolytope(const Polytope& pa, const Posed& a, const Polytope& pb, const Posed& b, double margin,
                      std::vector<ContactPoint>& out) {
  Scratch& scratch = ThreadScratch();
  // Each body's placed once a step, a static body once (Posed::placed); a compound's parts here.
  if (a.placed == nullptr) PlacePolytope(pa, a, scratch.a);
  if (b.placed == nullptr) PlacePolytope(pb, b, scratch.b);
  const PlacedPolytope& wa = a.placed != nullptr ? *a.placed : scratch.a;
  const PlacedPolytope& wb = b.placed != nullptr ? *b.placed : scratch.b;
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
  // A face of b is the reference only when clearly better than a's best: two faces flush (a
  // box on a box) would otherwise swap with rounding from step to step, and with them the
  // points' keys that warm-start the next step.
  const double face_tie = 1e-6 * (wa.v.empty() ? 1.0 : (wa.v[0] - a.R * pa.centroid - a.t).norm());
  const double best_of_a = best;
  for (std::size_t f = 0; f < wb.n.size(); ++f) {
    const double s = MinAlong(wa.v, wb.n[f]) - wb.d[f];
    if (s >= margin) return;
    if (s > best && s > best_of_a + face_tie) {
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
    const Vector3& ea = wa.e[i];
    const Vector3& na = wa.n[static_cast<std::size_t>(pa.edge_faces[i].first)];
    const Vector3& nb = wa.n[static_cast<std::size_t>(pa.edge_faces[i].second)];
    const Vector3& bxa = wa.arc[i];
    for (std::size_t j = 0; j < pb.edges.size(); ++j) {
      const Vector3& eb = wb.e[j];
      // Only pairs whose arcs on the Gauss map cross (Gregorius, GDC 2013) can be the axis:
      // the others are never closer than a face axis, and skipping them makes hulls cheap. (b's
      // arc is taken negated, −n_d × −n_c = n_d × n_c, its normals negated in the dot products.)
      {
        const Vector3& nc = wb.n[static_cast<std::size_t>(pb.edge_faces[j].first)];
        const Vector3& nd = wb.n[static_cast<std::size_t>(pb.edge_faces[j].second)];
        const Vector3& dxc = wb.arc[j];
        const double cba = -nc.dot(bxa), dba = -nd.dot(bxa), adc = na.dot(dxc), bdc = nb.dot(dxc);
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
  if (best_kind == 0) {
    FaceContact(pa, wa, pb, wb, best_index, true, margin, scratch, out);
  } else {
    FaceContact(pb, wb, pa, wa, best_index, false, margin, scratch, out);
  }
}

void SpherePolytope(const Vector3& c, double r, const Polytope& p, const Posed& posed, double margin, bool sphere_first,
                    std::uint32_t feature, std::vector<ContactPoint>& out) {
  if (posed.placed == nullptr) PlacePolytope(p, posed, ThreadScratch().a);
  const PlacedPolytope& w = posed.placed != nullptr ? *posed.placed : ThreadScratch().a;
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

namespace dynamics {

shape::Convex MakeConvex(std::vector<Vector3> vertices, std::vector<std::array<int, 3>> triangles) {
  shape::Convex convex{std::move(vertices), std::move(triangles)};
  convex.polytope = std::make_shared<contact::Polytope>(contact::MakePolytope(convex.vertices, convex.triangles));
  return convex;
}

}  // namespace dynamics
