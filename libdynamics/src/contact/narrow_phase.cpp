// Contact generation for the primitive pairs (narrow_phase.h): closed-form closest points for
// spheres and capsules, corners for boxes and convex polytopes against planes and spheres,
// separating axes with face clipping for box pairs.

#include "narrow_phase.h"

#include "mesh_field.h"
#include "polytope.h"
#include "workers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dynamics::contact {
namespace {

bool PositiveFinite(double v) { return std::isfinite(v) && v > 0; }

// The closest points of segments [p0, p1] and [q0, q1]: parameters s, t in [0, 1].
void ClosestSegmentPoints(const Vector3& p0, const Vector3& p1, const Vector3& q0, const Vector3& q1, double& s,
                          double& t) {
  const Vector3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  if (a <= 1e-300 && e <= 1e-300) {
    s = t = 0;
    return;
  }
  if (a <= 1e-300) {
    s = 0;
    t = std::clamp(f / e, 0.0, 1.0);
    return;
  }
  const double c = d1.dot(r);
  if (e <= 1e-300) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
    return;
  }
  const double b = d1.dot(d2), denom = a * e - b * b;
  s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
}

// Two spheres (centres, radii): one point.
void SphereSphere(const Vector3& ca, double ra, const Vector3& cb, double rb, double margin, std::uint32_t feature,
                  std::vector<ContactPoint>& out) {
  const Vector3 d = ca - cb;
  const double dist = d.norm();
  const double sep = dist - ra - rb;
  if (sep >= margin) return;
  const Vector3 n = dist > 1e-300 ? Vector3(d / dist) : Vector3::UnitZ();
  out.push_back({cb + n * (rb + 0.5 * sep), n, sep, feature});
}

// Sphere (centre, radius) against a box: the box's closest point.
void SphereBox(const Vector3& c, double r, const Posed& box, double margin, bool sphere_first,
               std::vector<ContactPoint>& out) {
  const Vector3& h = std::get<shape::Box>(*box.shape).half_extents;
  const Vector3 local = box.R.transpose() * (c - box.t);
  const Vector3 q = local.cwiseMax(-h).cwiseMin(h);
  Vector3 n_local;
  double sep;
  if ((local - q).squaredNorm() > 0) {
    const double dist = (local - q).norm();
    n_local = (local - q) / dist;
    sep = dist - r;
  } else {  // the centre is inside: out through the nearest face
    int axis = 0;
    double best = h[0] - std::abs(local[0]);
    for (int i = 1; i < 3; ++i) {
      if (h[i] - std::abs(local[i]) < best) {
        best = h[i] - std::abs(local[i]);
        axis = i;
      }
    }
    n_local = Vector3::Zero();
    n_local[axis] = local[axis] >= 0 ? 1 : -1;
    sep = -best - r;
  }
  if (sep >= margin) return;
  const Vector3 n = box.R * n_local;  // from the box into the sphere
  const Vector3 on_box = box.R * q + box.t;
  const Vector3 p = on_box + n * (0.5 * sep);
  out.push_back({p, sphere_first ? n : Vector3(-n), sep, 0});
}

// The box's corners in the world.
std::array<Vector3, 8> Corners(const Posed& box) {
  const Vector3& h = std::get<shape::Box>(*box.shape).half_extents;
  std::array<Vector3, 8> c;
  for (int i = 0; i < 8; ++i) {
    const Vector3 local((i & 1) ? h[0] : -h[0], (i & 2) ? h[1] : -h[1], (i & 4) ? h[2] : -h[2]);
    c[static_cast<std::size_t>(i)] = box.R * local + box.t;
  }
  return c;
}

// Whether world point x lies on face f of a posed polytope (within `slack` of its outline).
bool OnFace(const Polytope& p, const Posed& posed, std::size_t f, const Vector3& x, double slack) {
  const Vector3 n = posed.R * p.normals[f];
  const std::vector<int>& face = p.faces[f];
  for (std::size_t k = 0; k < face.size(); ++k) {
    const Vector3 u = posed.R * p.vertices[static_cast<std::size_t>(face[k])] + posed.t;
    const Vector3 v = posed.R * p.vertices[static_cast<std::size_t>(face[(k + 1) % face.size()])] + posed.t;
    const Vector3 inward = n.cross(v - u).normalized();  // counter-clockwise from outside: inward
    if (inward.dot(x - u) < -slack) return false;
  }
  return true;
}

// A cylinder against a polytope (normals from the polytope into the cylinder): the manifold of
// the cylinder's inscribed 32-sided prism, except where that contact is with one of the
// polytope's faces (the cylinder lies, rolls or stands on it: the manifold's normal within 8° of
// the face's, more than the prism's 5.6° facets tilt it): then the cylinder's own points against
// the face's plane, as against a ground plane, where they fall on the face. A cylinder so rolls
// on boxes and hulls as on the ground.
void CylinderPolytope(const Posed& cylinder, const Polytope& p, const Posed& posed, double margin,
                      std::vector<ContactPoint>& out) {
  const std::size_t first = out.size();
  PolytopePolytope(*cylinder.polytope, cylinder, p, posed, margin, out);
  if (out.size() == first) return;
  const Vector3 n = out[first].normal;
  std::size_t face = 0;
  double best = -2;
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    const double d = (posed.R * p.normals[f]).dot(n);
    if (d > best) {
      best = d;
      face = f;
    }
  }
  if (best < std::cos(8 * massprops::kPi / 180)) return;
  const Vector3 nf = posed.R * p.normals[face];
  const double offset = nf.dot(posed.R * p.vertices[static_cast<std::size_t>(p.faces[face][0])] + posed.t);
  thread_local std::vector<ContactPoint> exact;  // kept per thread
  exact.clear();
  CollideGround(cylinder, nf, offset, CollisionFilter{~0u, ~0u}, margin, exact);
  const double slack = 1e-9 * BoundingRadius(*cylinder.shape);
  exact.erase(std::remove_if(exact.begin(), exact.end(),
                             [&](const ContactPoint& c) { return !OnFace(p, posed, face, c.point, slack); }),
              exact.end());
  if (exact.empty()) return;  // over the face's edge: the prism's manifold
  out.resize(first);
  for (ContactPoint& c : exact) {
    c.feature |= 1u << 30;  // not the prism's features
    out.push_back(c);
  }
}

}  // namespace

Posed PartOf(const Posed& compound, const shape::Compound& c, std::size_t k) {
  const Collider& part = c.parts[k];
  Posed p;
  p.shape = &part.shape;
  p.polytope = k < c.polytopes.size() ? c.polytopes[k].get() : nullptr;
  p.R = compound.R * part.rotation;
  p.t = compound.R * part.translation + compound.t;
  p.filter = {compound.filter.contype & part.filter.contype, compound.filter.conaffinity & part.filter.conaffinity};
  return p;
}

namespace {

// The features of part k's points (out[first ...]) made distinct from the other parts' (side 0:
// the first shape's parts, 1: the second's), so that warm starting keys each part's own points.
// Each point also gets the part's material when the compound's parts touch with their own.
void MarkPart(std::vector<ContactPoint>& out, std::size_t first, const shape::Compound& c, std::size_t k, int side) {
  const std::uint32_t mark = static_cast<std::uint32_t>(k + 1) * (side == 0 ? 0x9E3779B1u : 0x85EBCA77u);
  const Material* own = c.part_materials ? &c.parts[k].material : nullptr;
  for (std::size_t i = first; i < out.size(); ++i) {
    out[i].feature ^= mark;
    if (own != nullptr) (side == 0 ? out[i].material_a : out[i].material_b) = own;
  }
}

}  // namespace

double BoundingRadius(const Shape& s) {
  return std::visit(
      [](const auto& x) -> double {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, shape::Compound>) {
          double r = 0;
          for (const Collider& part : x.parts) r = std::max(r, part.translation.norm() + BoundingRadius(part.shape));
          return r;
        }
        if constexpr (std::is_same_v<T, shape::Sphere>) return x.radius;
        if constexpr (std::is_same_v<T, shape::Box>) return x.half_extents.norm();
        if constexpr (std::is_same_v<T, shape::Capsule>) return x.radius + x.half_length;
        if constexpr (std::is_same_v<T, shape::Cylinder>) return std::hypot(x.radius, x.half_length);
        if constexpr (std::is_same_v<T, shape::Mesh>) {
          if (x.field != nullptr) return x.field->radius;
        }
        if constexpr (std::is_same_v<T, shape::Convex> || std::is_same_v<T, shape::Mesh>) {
          double r = 0;
          for (const Vector3& v : x.vertices) r = std::max(r, v.norm());
          return r;
        }
      },
      s);
}

void ValidateShape(const Shape& s) {
  std::visit(
      [](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        bool ok = true;
        if constexpr (std::is_same_v<T, shape::Sphere>) ok = PositiveFinite(x.radius);
        if constexpr (std::is_same_v<T, shape::Box>) {
          ok = PositiveFinite(x.half_extents[0]) && PositiveFinite(x.half_extents[1]) &&
               PositiveFinite(x.half_extents[2]);
        }
        if constexpr (std::is_same_v<T, shape::Capsule> || std::is_same_v<T, shape::Cylinder>) {
          ok = PositiveFinite(x.radius) && PositiveFinite(x.half_length);
        }
        if constexpr (std::is_same_v<T, shape::Convex>) {
          ok = x.vertices.size() >= 4 && x.triangles.size() >= 4;
          for (const Vector3& v : x.vertices) ok = ok && v.allFinite();
        }
        if constexpr (std::is_same_v<T, shape::Mesh>) {
          if (x.field == nullptr) throw std::invalid_argument("a mesh collider needs its field (MakeMesh builds it)");
        }
        if constexpr (std::is_same_v<T, shape::Compound>) {
          if (x.parts.empty()) throw std::invalid_argument("a compound collider needs at least one part");
          for (const Collider& part : x.parts) {
            if (std::holds_alternative<shape::Compound>(part.shape)) {
              throw std::invalid_argument("a compound collider's parts cannot be compounds");
            }
            if (!part.rotation.allFinite() || !part.translation.allFinite()) {
              throw std::invalid_argument("a compound collider's part is placed by non-finite numbers");
            }
            ValidateShape(part.shape);
          }
        }
        if (!ok) {
          throw std::invalid_argument(
              "a collision shape needs finite, positive sizes (a convex shape at least 4 finite vertices)");
        }
      },
      s);
}

// Greedy farthest-point selection from the deepest (narrow_phase.h).
void ReduceContacts(std::vector<ContactPoint>& out, std::size_t first) {
  const std::size_t n = out.size() - first;
  if (n <= kMaxContactPoints) return;
  // Working arrays kept per thread (a mesh pair reduces its points every step).
  thread_local std::vector<ContactPoint> all;
  thread_local std::vector<double> gap;
  thread_local std::vector<char> kept;
  all.assign(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
  out.resize(first);
  std::size_t deepest = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (all[i].separation < all[deepest].separation) deepest = i;
  }
  const double floor = all[deepest].separation;
  gap.assign(n, std::numeric_limits<double>::infinity());
  kept.assign(n, 0);
  std::size_t pick = deepest;
  for (std::size_t count = 0; count < kMaxContactPoints; ++count) {
    out.push_back(all[pick]);
    kept[pick] = 1;
    std::size_t next = n;
    double best = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      gap[i] = std::min(gap[i], (all[i].point - all[pick].point).norm());
      const double score = gap[i] - 4 * (all[i].separation - floor);
      if (!kept[i] && score > best) {
        best = score;
        next = i;
      }
    }
    if (next == n) break;
    pick = next;
  }
}

namespace {

// A hull's corners against the plane: each corner's height along n in the shape's frame
// ((Rᵀn)·v) decides, and only corners within reach are placed (`add`). Most lie far above: a
// vectorized scan rules them out, or — with `scan` kept from an earlier step whose corners near
// the plane are still the only ones that can be within reach — only those are tested; the exact
// test then runs on the rest, so the points and their order are the same either way.
template <typename Add>
void ConvexGround(const Posed& a, const shape::Convex& x, const Vector3& n, double offset, double margin,
                  const Add& add, std::vector<ContactPoint>& out, GroundScan* scan) {
  const std::size_t first = out.size();
  const Vector3 u = a.R.transpose() * n;
  const double limit = margin + offset - n.dot(a.t);
  const double scale = a.t.cwiseAbs().sum() + std::abs(offset) + std::abs(margin);
  auto test = [&](std::size_t i) {
    const Vector3& v = x.vertices[i];
    if (u.dot(v) - limit > 1e-12 * (scale + v.cwiseAbs().sum())) return;
    add(a.R * v + a.t, static_cast<std::uint32_t>(i), 0);
  };
  const std::size_t nv = x.vertices.size();
  if (a.polytope == nullptr || a.polytope->xs.size() != nv) {
    for (std::size_t i = 0; i < nv; ++i) test(i);
    ReduceContacts(out, first);
    return;
  }
  const Polytope& poly = *a.polytope;
  // A corner the last scan left out lay above limit + band by more than its tolerance; since then
  // its height u·v has fallen by at most |Δu| |v|, the limit risen by its change, the tolerance
  // grown by 10⁻¹² of the scale's: while all that stays below the band, the corners kept are the
  // only ones that can be within reach.
  if (scan != nullptr && scan->polytope == &poly) {
    const double moved = (u - scan->u).norm() * poly.max_norm * (1 + 1e-12) + std::abs(limit - scan->limit) +
                         1e-12 * std::max(0.0, scale - scan->scale) + 1e-14 * (poly.max_norm + std::abs(limit) + scale);
    if (moved < scan->band) {
      for (const int i : scan->near) test(static_cast<std::size_t>(i));
      ReduceContacts(out, first);
      return;
    }
  }
  const double band = scan != nullptr ? 0.02 * poly.max_norm : 0.0;
  if (scan != nullptr) {
    scan->polytope = &poly;
    scan->u = u;
    scan->limit = limit;
    scan->scale = scale;
    scan->band = band;
    scan->near.clear();
  }
  std::uint8_t maybe[kScan];
  for (std::size_t at = 0; at < nv; at += kScan) {
    const int count = static_cast<int>(std::min<std::size_t>(kScan, nv - at));
    MayLieBelow(poly, at, count, u, limit + band, scale, maybe);
    for (int j = 0; j < count; ++j) {
      if (maybe[j] == 0) continue;
      if (scan != nullptr) scan->near.push_back(static_cast<int>(at) + j);
      test(at + static_cast<std::size_t>(j));
    }
  }
  ReduceContacts(out, first);  // a finely tessellated hull lying flat: thousands of corners
}

}  // namespace

void CollideGround(const Posed& a, const Vector3& n, double offset, const CollisionFilter& ground, double margin,
                   std::vector<ContactPoint>& out, GroundScan* scan) {
  if (const auto* c = std::get_if<shape::Compound>(a.shape)) {
    for (std::size_t k = 0; k < c->parts.size(); ++k) {
      const std::size_t first = out.size();
      CollideGround(PartOf(a, *c, k), n, offset, ground, margin, out);
      MarkPart(out, first, *c, k, 0);
    }
    return;
  }
  if (!a.filter.Touches(ground)) return;
  auto add = [&](const Vector3& p, std::uint32_t feature, double radius) {
    const double sep = n.dot(p) - offset - radius;
    if (sep < margin) out.push_back({p - n * (radius + 0.5 * sep), n, sep, feature});
  };
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, shape::Sphere>) {
          add(a.t, 0, x.radius);
        } else if constexpr (std::is_same_v<T, shape::Box>) {
          const std::array<Vector3, 8> c = Corners(a);
          for (std::uint32_t i = 0; i < 8; ++i) add(c[i], i, 0);
        } else if constexpr (std::is_same_v<T, shape::Capsule>) {
          add(a.t + a.R.col(2) * x.half_length, 0, x.radius);
          add(a.t - a.R.col(2) * x.half_length, 1, x.radius);
        } else if constexpr (std::is_same_v<T, shape::Cylinder>) {
          const Vector3 axis = a.R.col(2);
          const Vector3 across = n - axis * n.dot(axis);  // n's part in the caps' plane
          for (std::uint32_t cap = 0; cap < 2; ++cap) {
            const Vector3 centre = a.t + axis * (cap == 0 ? x.half_length : -x.half_length);
            if (across.norm() < 1e-3) {
              // A cap (nearly) flat on the plane: four rim points keep it from rocking.
              for (std::uint32_t k = 0; k < 4; ++k) {
                const double phi = k * massprops::kPi / 2;
                add(centre + x.radius * (std::cos(phi) * a.R.col(0) + std::sin(phi) * a.R.col(1)), 2 + cap * 4 + k, 0);
              }
            } else {
              add(centre - x.radius * across.normalized(), cap, 0);  // the rim point deepest in the plane
            }
          }
        } else if constexpr (std::is_same_v<T, shape::Convex>) {
          ConvexGround(a, x, n, offset, margin, add, out, scan);
        } else if constexpr (std::is_same_v<T, shape::Mesh>) {
          CollideMeshGround(a, n, offset, margin, out);
        }
      },
      *a.shape);
}

namespace {

// The pair routines, one for each pair of kinds the table below names. Each appends a's points
// against b with normals from b into a.

// A capsule's axis in the world, end to end.
std::pair<Vector3, Vector3> Axis(const Posed& p, double half) {
  return {p.t - p.R.col(2) * half, p.t + p.R.col(2) * half};
}

void SphereSpherePair(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  SphereSphere(a.t, std::get<shape::Sphere>(*a.shape).radius, b.t, std::get<shape::Sphere>(*b.shape).radius, margin, 0,
               out);
}

void SphereBoxPair(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  SphereBox(a.t, std::get<shape::Sphere>(*a.shape).radius, b, margin, true, out);
}

void SpherePolytopePair(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  SpherePolytope(a.t, std::get<shape::Sphere>(*a.shape).radius, *b.polytope, b, margin, true, 0, out);
}

void SphereCapsulePair(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  const auto& y = std::get<shape::Capsule>(*b.shape);
  const auto [q0, q1] = Axis(b, y.half_length);
  double s, t;
  ClosestSegmentPoints(a.t, a.t, q0, q1, s, t);
  SphereSphere(a.t, std::get<shape::Sphere>(*a.shape).radius, q0 + (q1 - q0) * t, y.radius, margin, 0, out);
}

// Two points when the segments lie side by side (a capsule resting along another).
void CapsuleCapsulePair(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  const auto& x = std::get<shape::Capsule>(*a.shape);
  const auto& y = std::get<shape::Capsule>(*b.shape);
  const auto [p0, p1] = Axis(a, x.half_length);
  const auto [q0, q1] = Axis(b, y.half_length);
  double s, t;
  ClosestSegmentPoints(p0, p1, q0, q1, s, t);
  SphereSphere(p0 + (p1 - p0) * s, x.radius, q0 + (q1 - q0) * t, y.radius, margin, 0, out);
}

// The two end spheres against the polytope, and a sphere wherever the axis passes closest to one
// of the polytope's edges between its ends (a capsule lying across an edge).
void CapsulePolytopePair(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  const auto& x = std::get<shape::Capsule>(*a.shape);
  const auto [p0, p1] = Axis(a, x.half_length);
  SpherePolytope(p0, x.radius, *b.polytope, b, margin, true, 0, out);
  SpherePolytope(p1, x.radius, *b.polytope, b, margin, true, 1, out);
  const Polytope& poly = *b.polytope;
  std::vector<double> taken = {0.0, 1.0};
  for (std::size_t e = 0; e < poly.edges.size(); ++e) {
    const Vector3 q0 = b.R * poly.vertices[static_cast<std::size_t>(poly.edges[e].first)] + b.t;
    const Vector3 q1 = b.R * poly.vertices[static_cast<std::size_t>(poly.edges[e].second)] + b.t;
    double s, t;
    ClosestSegmentPoints(p0, p1, q0, q1, s, t);
    const Vector3 on_axis = p0 + (p1 - p0) * s;
    if ((on_axis - (q0 + (q1 - q0) * t)).norm() - x.radius >= margin) continue;
    // Points within a hundredth of the length of one taken already add nothing.
    if (std::any_of(taken.begin(), taken.end(), [&](double u) { return std::abs(u - s) < 1e-2; })) continue;
    taken.push_back(s);
    SpherePolytope(on_axis, x.radius, poly, b, margin, true, 2 + static_cast<std::uint32_t>(e), out);
  }
}

void CylinderPolytopePair(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  CylinderPolytope(a, *b.polytope, b, margin, out);
}

void PolytopePair(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  PolytopePolytope(*a.polytope, a, *b.polytope, b, margin, out);
}

using PairRoutine = void (*)(const Posed&, const Posed&, double, std::vector<ContactPoint>&);

// A routine made for (b, a), run on (a, b): its points' normals turned.
template <PairRoutine routine>
void Swapped(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  const std::size_t before = out.size();
  routine(b, a, margin, out);
  for (std::size_t i = before; i < out.size(); ++i) out[i].normal = -out[i].normal;
}

// The pair table, by the kinds' indices in Shape (sphere, box, capsule, cylinder, convex, mesh);
// a cylinder is its inscribed prism where no routine of its own applies. Compounds go part by
// part (Collide); null: no routine (ContactWorld refuses such a pair when the body is added).
constexpr std::size_t kKinds = std::variant_size_v<Shape> - 1;  // the compound is not a kind here
constexpr PairRoutine kMesh = CollideWithMesh;
constexpr PairRoutine kPairTable[kKinds][kKinds] = {
    // sphere                       box                            capsule
    // cylinder                      convex                         mesh
    {SphereSpherePair, SphereBoxPair, SphereCapsulePair,  //
     SpherePolytopePair, SpherePolytopePair, kMesh},
    {Swapped<SphereBoxPair>, PolytopePair, Swapped<CapsulePolytopePair>,  //
     Swapped<CylinderPolytopePair>, PolytopePair, kMesh},
    {Swapped<SphereCapsulePair>, CapsulePolytopePair, CapsuleCapsulePair,  //
     CapsulePolytopePair, CapsulePolytopePair, kMesh},
    {Swapped<SpherePolytopePair>, CylinderPolytopePair, Swapped<CapsulePolytopePair>,  //
     PolytopePair, CylinderPolytopePair, kMesh},
    {Swapped<SpherePolytopePair>, PolytopePair, Swapped<CapsulePolytopePair>,  //
     Swapped<CylinderPolytopePair>, PolytopePair, kMesh},
    {kMesh, kMesh, kMesh, kMesh, kMesh, kMesh},
};

// The shape's kinds: its own, or its parts' for a compound.
template <typename F>
void ForEachKind(const Shape& s, F&& f) {
  if (const auto* c = std::get_if<shape::Compound>(&s)) {
    for (const auto& part : c->parts) ForEachKind(part.shape, f);
    return;
  }
  f(s.index());
}

}  // namespace

bool SupportsPair(const Shape& a, const Shape& b) {
  bool ok = true;
  ForEachKind(
      a, [&](std::size_t ka) { ForEachKind(b, [&](std::size_t kb) { ok = ok && kPairTable[ka][kb] != nullptr; }); });
  return ok;
}

void Collide(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out, PairSampleBounds* bounds) {
  for (int side = 0; side < 2; ++side) {
    const Posed& whole = side == 0 ? a : b;
    const auto* c = std::get_if<shape::Compound>(whole.shape);
    if (c == nullptr) continue;
    for (std::size_t k = 0; k < c->parts.size(); ++k) {
      const std::size_t first = out.size();
      const Posed part = PartOf(whole, *c, k);
      if (side == 0) {
        Collide(part, b, margin, out);
      } else {
        Collide(a, part, margin, out);
      }
      MarkPart(out, first, *c, k, side);
    }
    return;
  }
  if (!a.filter.Touches(b.filter)) return;
  const PairRoutine routine = kPairTable[a.shape->index()][b.shape->index()];
  if (routine == nullptr) {
    throw std::logic_error(std::string("contact between a ") + ShapeName(*a.shape) + " and a " + ShapeName(*b.shape) +
                           " has no routine (ContactWorld refuses it when the body is added)");
  }
  if (routine == kMesh && bounds != nullptr) {
    CollideMeshes(a, b, margin, out, bounds);
    return;
  }
  routine(a, b, margin, out);
}

void CollidePairs(const std::vector<PairQuery>& pairs, Workers* workers,
                  std::vector<std::vector<ContactPoint>>& found) {
  found.resize(pairs.size());
  for (auto& f : found) f.clear();
  constexpr std::size_t kGroup = 16;
  const std::size_t groups = (pairs.size() + kGroup - 1) / kGroup;
  auto collide = [&](std::size_t g) {
    for (std::size_t c = g * kGroup; c < std::min(pairs.size(), (g + 1) * kGroup); ++c) {
      if (pairs[c].a != nullptr) Collide(*pairs[c].a, *pairs[c].b, pairs[c].margin, found[c], pairs[c].bounds);
    }
  };
  if (workers != nullptr && groups > 1) {
    workers->ForEach(groups, collide);
  } else {
    for (std::size_t g = 0; g < groups; ++g) collide(g);
  }
}

}  // namespace dynamics::contact
