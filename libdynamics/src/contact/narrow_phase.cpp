// Contact generation for the primitive pairs (narrow_phase.h): closed-form closest points for
// spheres and capsules, corners for boxes and convex polytopes against planes and spheres,
// separating axes with face clipping for box pairs.

#include "narrow_phase.h"

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

// Box pairs: the axis of least overlap among the 15 (faces of each, edge cross products); a face
// axis gives the incident face clipped against the reference face's sides (up to 8 points,
// reduced to the deepest 4 spread out), an edge axis the closest points of the two edges.
void BoxBox(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  const Vector3& ha = std::get<shape::Box>(*a.shape).half_extents;
  const Vector3& hb = std::get<shape::Box>(*b.shape).half_extents;
  const Vector3 d = a.t - b.t;  // from b to a
  // Separation along a unit axis u (pointing from b to a): gap between the projections.
  auto separation = [&](const Vector3& u) {
    double ra = 0, rb = 0;
    for (int i = 0; i < 3; ++i) {
      ra += ha[i] * std::abs(u.dot(a.R.col(i)));
      rb += hb[i] * std::abs(u.dot(b.R.col(i)));
    }
    return std::abs(u.dot(d)) - ra - rb;
  };
  double best = -std::numeric_limits<double>::infinity();
  int best_axis = -1;
  Vector3 best_u = Vector3::UnitZ();
  for (int k = 0; k < 15; ++k) {
    Vector3 u;
    if (k < 3) {
      u = a.R.col(k);
    } else if (k < 6) {
      u = b.R.col(k - 3);
    } else {
      u = a.R.col((k - 6) / 3).cross(b.R.col((k - 6) % 3));
      const double len = u.norm();
      if (len < 1e-9) continue;  // parallel edges: a face axis covers it
      u /= len;
    }
    const double s = separation(u);
    if (s >= margin) return;  // separated (beyond the margin) along this axis
    // Prefer face axes: an edge axis must be clearly better (avoids flicker between them).
    const double bias = k < 6 ? 0.0 : 1e-9 * (ha.norm() + hb.norm());
    if (s > best + bias) {
      best = s;
      best_axis = k;
      best_u = u.dot(d) >= 0 ? u : Vector3(-u);
    }
  }
  const Vector3 n = best_u;  // from b into a
  if (best_axis >= 6) {
    // Edge against edge: the closest points of the two edges that meet along n.
    const int ia = (best_axis - 6) / 3, ib = (best_axis - 6) % 3;
    Vector3 pa = a.t, pb = b.t;
    for (int i = 0; i < 3; ++i) {
      if (i != ia) pa += a.R.col(i) * (a.R.col(i).dot(n) > 0 ? -ha[i] : ha[i]);
      if (i != ib) pb += b.R.col(i) * (b.R.col(i).dot(n) > 0 ? hb[i] : -hb[i]);
    }
    double s, t;
    ClosestSegmentPoints(pa - a.R.col(ia) * ha[ia], pa + a.R.col(ia) * ha[ia], pb - b.R.col(ib) * hb[ib],
                         pb + b.R.col(ib) * hb[ib], s, t);
    const Vector3 qa = pa + a.R.col(ia) * ha[ia] * (2 * s - 1), qb = pb + b.R.col(ib) * hb[ib] * (2 * t - 1);
    out.push_back({0.5 * (qa + qb), n, best, 100u + static_cast<std::uint32_t>(best_axis)});
    return;
  }
  // Face contact: the reference box owns the axis; the incident box's face most anti-parallel.
  const bool ref_is_a = best_axis < 3;
  const Posed& ref = ref_is_a ? a : b;
  const Posed& inc = ref_is_a ? b : a;
  const Vector3& hr = ref_is_a ? ha : hb;
  const Vector3& hi = ref_is_a ? hb : ha;
  const Vector3 ref_n = ref_is_a ? Vector3(-n) : n;  // the reference face's outward normal
  const int ref_axis = ref_is_a ? best_axis : best_axis - 3;
  int inc_axis = 0;
  double most = -1;
  for (int i = 0; i < 3; ++i) {
    const double c = std::abs(inc.R.col(i).dot(ref_n));
    if (c > most) {
      most = c;
      inc_axis = i;
    }
  }
  const double inc_sign = inc.R.col(inc_axis).dot(ref_n) > 0 ? -1.0 : 1.0;
  const Vector3 inc_center = inc.t + inc.R.col(inc_axis) * (inc_sign * hi[inc_axis]);
  const int u1 = (inc_axis + 1) % 3, u2 = (inc_axis + 2) % 3;
  std::vector<Vector3> poly = {
      inc_center + inc.R.col(u1) * hi[u1] + inc.R.col(u2) * hi[u2],
      inc_center - inc.R.col(u1) * hi[u1] + inc.R.col(u2) * hi[u2],
      inc_center - inc.R.col(u1) * hi[u1] - inc.R.col(u2) * hi[u2],
      inc_center + inc.R.col(u1) * hi[u1] - inc.R.col(u2) * hi[u2],
  };
  // Clip against the four side planes of the reference face.
  for (int side = 0; side < 2; ++side) {
    const int axis = (ref_axis + 1 + side) % 3;
    for (double sign : {1.0, -1.0}) {
      const Vector3 pn = ref.R.col(axis) * sign;
      const double po = pn.dot(ref.t) + hr[axis];
      std::vector<Vector3> clipped;
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vector3& p = poly[i];
        const Vector3& q = poly[(i + 1) % poly.size()];
        const double dp = pn.dot(p) - po, dq = pn.dot(q) - po;
        if (dp <= 0) clipped.push_back(p);
        if ((dp < 0) != (dq < 0) && dp != dq) clipped.push_back(p + (q - p) * (dp / (dp - dq)));
      }
      poly = std::move(clipped);
      if (poly.empty()) return;
    }
  }
  const double face_offset = ref_n.dot(ref.t) + hr[ref_axis];
  std::vector<ContactPoint> found;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const double sep = ref_n.dot(poly[i]) - face_offset;
    if (sep >= margin) continue;
    const Vector3 p = poly[i] - ref_n * (0.5 * sep);  // between the surfaces
    found.push_back({p, n, sep, static_cast<std::uint32_t>(best_axis * 16 + static_cast<int>(i))});
  }
  if (found.size() > 4) {  // the deepest, then the ones farthest from the points kept
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

}  // namespace

double BoundingRadius(const Shape& s) {
  return std::visit(
      [](const auto& x) -> double {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, shape::Sphere>) return x.radius;
        if constexpr (std::is_same_v<T, shape::Box>) return x.half_extents.norm();
        if constexpr (std::is_same_v<T, shape::Capsule>) return x.radius + x.half_length;
        if constexpr (std::is_same_v<T, shape::Cylinder>) return std::hypot(x.radius, x.half_length);
        if constexpr (std::is_same_v<T, shape::Convex>) {
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
          ok = x.vertices.size() >= 4;
          for (const Vector3& v : x.vertices) ok = ok && v.allFinite();
        }
        if (!ok) {
          throw std::invalid_argument(
              "a collision shape needs finite, positive sizes (a convex shape at least 4 finite vertices)");
        }
      },
      s);
}

void CollideGround(const Posed& a, const Vector3& n, double offset, double margin, std::vector<ContactPoint>& out) {
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
                const double phi = k * M_PI / 2;
                add(centre + x.radius * (std::cos(phi) * a.R.col(0) + std::sin(phi) * a.R.col(1)), 2 + cap * 4 + k, 0);
              }
            } else {
              add(centre - x.radius * across.normalized(), cap, 0);  // the rim point deepest in the plane
            }
          }
        } else if constexpr (std::is_same_v<T, shape::Convex>) {
          for (std::size_t i = 0; i < x.vertices.size(); ++i)
            add(a.R * x.vertices[i] + a.t, static_cast<std::uint32_t>(i), 0);
        }
      },
      *a.shape);
}

bool Collide(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  const std::size_t before = out.size();
  auto flip = [&] {  // the points were made with b first: turn their normals
    for (std::size_t i = before; i < out.size(); ++i) out[i].normal = -out[i].normal;
  };
  const Shape& sa = *a.shape;
  const Shape& sb = *b.shape;
  auto segment = [](const Posed& p, double half) {
    return std::pair<Vector3, Vector3>{p.t - p.R.col(2) * half, p.t + p.R.col(2) * half};
  };
  if (const auto* x = std::get_if<shape::Sphere>(&sa)) {
    if (const auto* y = std::get_if<shape::Sphere>(&sb)) {
      SphereSphere(a.t, x->radius, b.t, y->radius, margin, 0, out);
      return true;
    }
    if (std::holds_alternative<shape::Box>(sb)) {
      SphereBox(a.t, x->radius, b, margin, true, out);
      return true;
    }
    if (const auto* y = std::get_if<shape::Capsule>(&sb)) {
      const auto [q0, q1] = segment(b, y->half_length);
      double s, t;
      ClosestSegmentPoints(a.t, a.t, q0, q1, s, t);
      SphereSphere(a.t, x->radius, q0 + (q1 - q0) * t, y->radius, margin, 0, out);
      return true;
    }
  }
  if (const auto* x = std::get_if<shape::Capsule>(&sa)) {
    if (const auto* y = std::get_if<shape::Capsule>(&sb)) {
      const auto [p0, p1] = segment(a, x->half_length);
      const auto [q0, q1] = segment(b, y->half_length);
      // Two points when the segments lie side by side (a capsule resting along another).
      double s, t;
      ClosestSegmentPoints(p0, p1, q0, q1, s, t);
      SphereSphere(p0 + (p1 - p0) * s, x->radius, q0 + (q1 - q0) * t, y->radius, margin, 0, out);
      return true;
    }
    if (std::holds_alternative<shape::Sphere>(sb)) {
      const bool ok = Collide(b, a, margin, out);
      flip();
      return ok;
    }
    if (std::holds_alternative<shape::Box>(sb)) {
      // The two end spheres and the closest point of the axis against the box.
      const auto [p0, p1] = segment(a, x->half_length);
      SphereBox(p0, x->radius, b, margin, true, out);
      SphereBox(p1, x->radius, b, margin, true, out);
      for (std::size_t i = before; i < out.size(); ++i) out[i].feature = static_cast<std::uint32_t>(i - before);
      return true;
    }
  }
  if (std::holds_alternative<shape::Box>(sa)) {
    if (std::holds_alternative<shape::Box>(sb)) {
      BoxBox(a, b, margin, out);
      return true;
    }
    if (std::holds_alternative<shape::Sphere>(sb) || std::holds_alternative<shape::Capsule>(sb)) {
      const bool ok = Collide(b, a, margin, out);
      flip();
      return ok;
    }
  }
  return false;
}

}  // namespace dynamics::contact
