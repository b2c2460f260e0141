// Contact with mesh colliders (narrow_phase.h): each shape's surface samples against the other's
// signed distance, both ways (Guendelman, Bridson & Fedkiw, "Nonconvex rigid bodies with
// stacking", 2003). A mesh's distance comes from its field (mesh_field.h); the primitives' are in
// closed form, a convex polytope's is its largest face-plane distance (exact inside and over the
// faces, a bound from below near edges and corners outside).

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh_field.h"
#include "narrow_phase.h"
#include "polytope.h"
#include "sample_bounds.h"

namespace dynamics::contact {
namespace {

constexpr std::uint32_t kSecond = 1u << 31;  // feature bit: a sample of the second shape
constexpr std::uint32_t kCentre = 1u << 30;  // feature bit: a sphere's or capsule's axis point
// A field's trilinear value exceeds the true distance by at most the largest distance to the cell's
// corners (the weights of a 1-Lipschitz function): √3 cells.
constexpr double kDiagonal = 1.7320508075688772;

// φ of a shape in its own frame at q, and its outward gradient (unit; a field's only when
// `want_normal`: most samples are only compared with the margin).
double LocalDistance(const Posed& s, const Vector3& q, Vector3& n, bool want_normal) {
  return std::visit(
      [&](const auto& x) -> double {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, shape::Sphere>) {
          const double len = q.norm();
          n = len > 1e-300 ? Vector3(q / len) : Vector3::UnitZ();
          return len - x.radius;
        } else if constexpr (std::is_same_v<T, shape::Box>) {
          const Vector3 e = q.cwiseAbs() - x.half_extents;
          const Vector3 out = e.cwiseMax(0.0);
          if (out.squaredNorm() > 0) {
            const double len = out.norm();
            n = Vector3(out[0] * (q[0] < 0 ? -1 : 1), out[1] * (q[1] < 0 ? -1 : 1), out[2] * (q[2] < 0 ? -1 : 1)) / len;
            return len;
          }
          int axis;
          const double d = e.maxCoeff(&axis);
          n = Vector3::Zero();
          n[axis] = q[axis] < 0 ? -1 : 1;
          return d;
        } else if constexpr (std::is_same_v<T, shape::Capsule>) {
          const Vector3 axis_point(0, 0, std::clamp(q.z(), -x.half_length, x.half_length));
          const Vector3 d = q - axis_point;
          const double len = d.norm();
          n = len > 1e-300 ? Vector3(d / len) : Vector3::UnitX();
          return len - x.radius;
        } else if constexpr (std::is_same_v<T, shape::Cylinder>) {
          const double rq = std::hypot(q.x(), q.y());
          const Vector3 radial = rq > 1e-300 ? Vector3(q.x() / rq, q.y() / rq, 0) : Vector3::UnitX();
          const double dr = rq - x.radius, dz = std::abs(q.z()) - x.half_length;
          const Vector3 up(0, 0, q.z() < 0 ? -1 : 1);
          if (dr > 0 && dz > 0) {
            const double len = std::hypot(dr, dz);
            n = (radial * dr + up * dz) / len;
            return len;
          }
          n = dr > dz ? radial : up;
          return std::max(dr, dz);
        } else if constexpr (std::is_same_v<T, shape::Convex>) {
          const Polytope& p = *s.polytope;
          double best = -std::numeric_limits<double>::infinity();
          for (std::size_t f = 0; f < p.faces.size(); ++f) {
            const double d = p.normals[f].dot(q - p.vertices[static_cast<std::size_t>(p.faces[f][0])]);
            if (d > best) {
              best = d;
              n = p.normals[f];
            }
          }
          return best;
        } else if constexpr (std::is_same_v<T, shape::Compound>) {
          // (never reached: Collide takes compounds part by part)
          n = Vector3::UnitZ();
          return std::numeric_limits<double>::infinity();
        } else {  // shape::Mesh
          if (!want_normal) return x.field->Distance(q, nullptr);
          Vector3 g;
          const double d = x.field->Distance(q, &g);
          const double len = g.norm();
          n = len > 1e-300 ? Vector3(g / len) : Vector3::UnitZ();
          return d;
        }
      },
      *s.shape);
}

// φ of a posed shape at a world point, and its outward normal in the world.
double Distance(const Posed& s, const Vector3& x, Vector3& n) {
  Vector3 local_n = Vector3::UnitZ();
  const double d = LocalDistance(s, s.R.transpose() * (x - s.t), local_n, true);
  n = s.R * local_n;
  return d;
}

// φ alone.
double DistanceOnly(const Posed& s, const Vector3& x) {
  Vector3 unused = Vector3::UnitZ();
  return LocalDistance(s, s.R.transpose() * (x - s.t), unused, false);
}

// φ alone where it matters only whether it is above `threshold`: +∞ when a mesh field's blocks
// show it is (MeshField::SurelyAbove), without reading the field's nodes; else φ as DistanceOnly.
// `bound` (optional): a bound from below of φ (less its rounding).
double DistanceOnlyUnless(const Posed& s, const Vector3& x, double threshold, double* bound = nullptr) {
  const Vector3 q = s.R.transpose() * (x - s.t);
  if (const auto* m = std::get_if<shape::Mesh>(s.shape); m != nullptr && m->field->SurelyAbove(q, threshold, bound)) {
    return std::numeric_limits<double>::infinity();
  }
  Vector3 unused = Vector3::UnitZ();
  const double d = LocalDistance(s, q, unused, false);
  if (bound != nullptr) *bound = d - 1e-12 * (1 + std::abs(d));
  return d;
}

// Surface points of a shape for testing against a mesh's field (world), spaced about `spacing`;
// spheres and capsules give axis points with their radius instead.
struct Sample {
  Vector3 p;
  double radius = 0;
};

void EdgePoints(const Vector3& a, const Vector3& b, double spacing, std::vector<Sample>& out) {
  const int k = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing)));
  for (int i = 1; i < k; ++i) out.push_back({a + (b - a) * (static_cast<double>(i) / k), 0});
}

void SamplesOf(const Posed& s, double spacing, std::vector<Sample>& out) {
  auto world = [&](const Vector3& v) -> Vector3 { return s.R * v + s.t; };
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, shape::Sphere>) {
          out.push_back({s.t, x.radius});
        } else if constexpr (std::is_same_v<T, shape::Capsule>) {
          const int k = std::max(1, static_cast<int>(std::ceil(2 * x.half_length / spacing)));
          for (int i = 0; i <= k; ++i) {
            out.push_back({world(Vector3(0, 0, -x.half_length + 2 * x.half_length * i / k)), x.radius});
          }
        } else if constexpr (std::is_same_v<T, shape::Mesh>) {
          for (const Vector3& v : x.field->samples) out.push_back({world(v), 0});
        } else {  // boxes and convex shapes (cylinders: rings, in SamplesAgainst): corners and edges
          const Polytope& p = *s.polytope;
          for (const Vector3& v : p.vertices) out.push_back({world(v), 0});
          for (const auto& [i, j] : p.edges) {
            EdgePoints(world(p.vertices[static_cast<std::size_t>(i)]), world(p.vertices[static_cast<std::size_t>(j)]),
                       spacing, out);
          }
        }
      },
      *s.shape);
}

double Spacing(const Posed& s) {
  if (const auto* m = std::get_if<shape::Mesh>(s.shape)) return m->field->cell;
  return std::numeric_limits<double>::infinity();
}

using Box3 = Eigen::AlignedBox<double, 3>;

// A box that holds the posed shape (world): a mesh's grid box turned, else its own box turned.
Box3 WorldBox(const Posed& s) {
  Box3 box;
  if (const auto* m = std::get_if<shape::Mesh>(s.shape)) {
    const MeshField& f = *m->field;
    const Box3 local(f.origin, f.origin + f.cell * Vector3(f.nodes[0] - 1, f.nodes[1] - 1, f.nodes[2] - 1));
    for (int k = 0; k < 8; ++k) box.extend(s.R * local.corner(static_cast<Box3::CornerType>(k)) + s.t);
    return box;
  }
  // The shape's half extents in its frame, turned: |R| h holds the turned box.
  const Vector3 half = std::visit(
      [](const auto& x) -> Vector3 {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, shape::Sphere>) return Vector3::Constant(x.radius);
        if constexpr (std::is_same_v<T, shape::Box>) return x.half_extents;
        if constexpr (std::is_same_v<T, shape::Capsule>) return Vector3(x.radius, x.radius, x.half_length + x.radius);
        if constexpr (std::is_same_v<T, shape::Cylinder>) return Vector3(x.radius, x.radius, x.half_length);
        if constexpr (std::is_same_v<T, shape::Convex> || std::is_same_v<T, shape::Mesh>) {
          Vector3 h = Vector3::Zero();
          for (const Vector3& v : x.vertices) h = h.cwiseMax(v.cwiseAbs());
          return h;
        }
        if constexpr (std::is_same_v<T, shape::Compound>) return Vector3::Constant(BoundingRadius(Shape(x)));
      },
      *s.shape);
  const Vector3 extent = s.R.cwiseAbs() * half;
  return Box3(s.t - extent, s.t + extent);
}

// The bounds' reference for this step: kept while the sampled mesh has moved, in the field's
// frame, by less than kReferMotion cells of the field; past that, moved to the pose of now, every
// bound lowered by what the move may have changed it (so that bounds found from then on are not
// lowered by the motion before). A first step starts with no bound. Returns the motion since the
// reference (none when it was just moved).
constexpr double kReferMotion = 0.25;
SampleBounds::Moved Refer(SampleBounds& bounds, const Posed& from, const Posed& to, const MeshField& sampled) {
  const Matrix3 R = to.R.transpose() * from.R;
  const Vector3 t = to.R.transpose() * (from.t - to.t);
  const double cell = std::get<shape::Mesh>(*to.shape).field->cell;
  const std::vector<MeshField::Cluster>& clusters = sampled.clusters;
  if (!bounds.valid || bounds.cluster.size() != clusters.size()) {
    bounds.valid = true;
    bounds.R = R, bounds.t = t;
    bounds.cluster.assign(clusters.size(), -std::numeric_limits<double>::infinity());
    bounds.first.assign(clusters.size(), SampleBounds::kNone);
    bounds.sample.clear();
    return {};
  }
  const SampleBounds::Moved moved = bounds.Since(R, t);
  if (moved.turned * sampled.radius + moved.shifted < kReferMotion * cell) return moved;
  for (std::size_t ci = 0; ci < clusters.size(); ++ci) {
    const MeshField::Cluster& c = clusters[ci];
    const double change = SampleBounds::Change(moved, c.centre, c.radius);
    bounds.cluster[ci] -= change;
    if (bounds.first[ci] == SampleBounds::kNone) continue;
    double* b = bounds.sample.data() + bounds.first[ci];
    for (int i = 0; i < c.count; ++i) b[i] -= change;
  }
  bounds.R = R, bounds.t = t;
  return {};
}

// Cluster `ci`'s samples' bounds (room for `count`, without bounds, the first time it is asked).
double* KeptSamples(SampleBounds& bounds, std::size_t ci, int count) {
  if (bounds.first[ci] == SampleBounds::kNone) {
    bounds.first[ci] = static_cast<std::uint32_t>(bounds.sample.size());
    bounds.sample.resize(bounds.sample.size() + static_cast<std::size_t>(count),
                         -std::numeric_limits<double>::infinity());
  }
  return bounds.sample.data() + bounds.first[ci];
}

// The samples of `from` against the distance of `to`; normals from `to` into `from`, flipped
// when `from` is the second shape of the pair. Only samples in the overlap of the two shapes'
// boxes (grown by the margin and the samples' radii) are tested: a mesh's are culled in its own
// frame before they are moved.
// `bounds` (a mesh against a mesh, optional): the bounds kept from the steps before
// (sample_bounds.h), which answer the tests they can and take what the others find.
void SamplesAgainst(const Posed& from, const Posed& to, double spacing, double margin, bool from_is_second,
                    std::vector<ContactPoint>& out, SampleBounds* bounds) {
  double grow = margin;
  if (const auto* c = std::get_if<shape::Capsule>(from.shape)) grow += c->radius;
  if (const auto* c = std::get_if<shape::Sphere>(from.shape)) grow += c->radius;
  Box3 reach = WorldBox(to);  // where a sample may touch `to` within the margin
  reach.min() -= Vector3::Constant(grow);
  reach.max() += Vector3::Constant(grow);
  const Box3 overlap = WorldBox(from).intersection(reach);
  if (overlap.isEmpty()) return;
  const MeshField* from_field = nullptr;
  if (const auto* m = std::get_if<shape::Mesh>(from.shape)) from_field = m->field.get();
  // Each sample's test: a contact point appended, or the sample rejected; returns a bound from
  // below of φ where the field rejected it (−∞ otherwise).
  constexpr double kNoBound = -std::numeric_limits<double>::infinity();
  auto test = [&](const Vector3& p, double radius, std::size_t index) {
    if (!overlap.contains(p)) return kNoBound;
    double bound = kNoBound;
    if (!(DistanceOnlyUnless(to, p, margin + radius, &bound) - radius < margin)) return bound;
    Vector3 n = Vector3::UnitZ();
    const double sep = Distance(to, p, n) - radius;
    if (from_field != nullptr) {
      // A sample on an inactive feature (a flat seam or a crease) pushes along the face normal
      // nearest the other shape's: the face, not the seam (mesh_field.h).
      const MeshField::SampleFaces& faces = from_field->sample_faces[index];
      double best = -std::numeric_limits<double>::infinity();
      for (std::uint32_t k = faces.first; k < faces.first + faces.count; ++k) {
        const Vector3 face = from.R * from_field->normals[k];
        if (-face.dot(n) > best) {
          best = -face.dot(n);
          n = -face;
        }
      }
    }
    const Vector3 surface = p - n * radius;  // the sample's own surface point
    std::uint32_t feature = static_cast<std::uint32_t>(index) & (kCentre - 1);
    if (radius > 0) feature |= kCentre;
    if (from_is_second) feature |= kSecond;
    out.push_back({surface - n * (0.5 * sep), from_is_second ? Vector3(-n) : n, sep, feature});
    return kNoBound;
  };
  if (const auto* m = std::get_if<shape::Mesh>(from.shape)) {
    Box3 local;  // the overlap in the mesh's frame
    for (int k = 0; k < 8; ++k)
      local.extend(from.R.transpose() * (overlap.corner(static_cast<Box3::CornerType>(k)) - from.t));
    // The other's distance is a bound from below (a convex shape's plane distance) or at most a
    // cell's diagonal above the truth (a field: trilinear weights of a 1-Lipschitz function): a
    // cluster farther than its radius plus that is skipped whole.
    const auto* other_mesh = std::get_if<shape::Mesh>(to.shape);
    const double slack = margin + (other_mesh != nullptr ? kDiagonal * other_mesh->field->cell : 0.0);
    const std::vector<Vector3>& samples = m->field->samples;
    // Against a sphere, capsule or cylinder, whose own samples (centres and rings) meet a face
    // exactly, the samples of inactive features are left out: on a seam they could only push
    // along the face, and a curved surface approaching the face would seem, along the face's
    // normal, to close the gap twice as fast as it does.
    const bool smooth = std::holds_alternative<shape::Sphere>(*to.shape) ||
                        std::holds_alternative<shape::Capsule>(*to.shape) ||
                        std::holds_alternative<shape::Cylinder>(*to.shape);
    const std::vector<MeshField::Cluster>& clusters = m->field->clusters;
    const SampleBounds::Moved moved = bounds != nullptr ? Refer(*bounds, from, to, *m->field) : SampleBounds::Moved{};
    for (std::size_t ci = 0; ci < clusters.size(); ++ci) {
      const MeshField::Cluster& c = clusters[ci];
      if (local.exteriorDistance(c.centre) > c.radius) continue;
      const double within = c.radius + slack;
      const double change = SampleBounds::Change(moved, c.centre, c.radius);  // since the reference
      if (bounds != nullptr && bounds->cluster[ci] - change > within * (1 + 1e-12)) {
        ++bounds->skipped;
        continue;
      }
      double bound = kNoBound;
      const bool far =
          DistanceOnlyUnless(to, from.R * c.centre + from.t, within, bounds != nullptr ? &bound : nullptr) > within;
      double* kept = nullptr;  // the cluster's samples' bounds
      if (bounds != nullptr) {
        ++bounds->evaluated;
        bounds->cluster[ci] = std::max(bounds->cluster[ci], bound - change);
        if (!far) kept = KeptSamples(*bounds, ci, c.count);
      }
      if (far) continue;
      for (int i = c.first; i < c.first + c.count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (smooth && m->field->sample_faces[k].count > 0) continue;
        if (!local.contains(samples[k])) continue;
        double* b = kept != nullptr ? kept + (i - c.first) : nullptr;
        if (b != nullptr && *b - change > margin * (1 + 1e-12)) {
          ++bounds->skipped;
          continue;
        }
        const double found = test(from.R * samples[k] + from.t, 0, k);
        if (b != nullptr) {
          ++bounds->evaluated;
          *b = std::max(*b, found - change);
        }
      }
    }
    return;
  }
  if (const auto* c = std::get_if<shape::Cylinder>(from.shape)) {
    // Rings across the axis about a cell apart, the caps' rims included: each meets the other
    // shape first at its point farthest along −∇φ at its centre (exact against a flat face: a
    // cylinder rolls on a mesh as on a plane), a cap's rim at four points when ∇φ lies along the
    // axis (it stands on its cap). φ is 1-Lipschitz: a ring whose centre is farther than its
    // radius plus the margin is skipped.
    const Vector3 axis = from.R.col(2);
    const int k = std::max(1, static_cast<int>(std::ceil(2 * c->half_length / spacing)));
    for (int i = 0; i <= k; ++i) {
      const Vector3 centre = from.t + axis * (-c->half_length + 2 * c->half_length * i / k);
      if (!overlap.contains(centre) && overlap.exteriorDistance(centre) > c->radius) continue;
      if (!(DistanceOnly(to, centre) - c->radius < margin)) continue;
      Vector3 g = Vector3::UnitZ();
      Distance(to, centre, g);
      const Vector3 radial = -g - axis * axis.dot(-g);
      const std::size_t id = static_cast<std::size_t>(i) * 4;
      if (radial.norm() > 1e-3) {
        test(centre + c->radius * radial.normalized(), 0, id);
      } else if (i == 0 || i == k) {
        for (int q = 0; q < 4; ++q) {
          test(centre + c->radius * (std::cos(q * massprops::kPi / 2) * from.R.col(0) +
                                     std::sin(q * massprops::kPi / 2) * from.R.col(1)),
               0, id + static_cast<std::size_t>(q));
        }
      }
    }
    return;
  }
  thread_local std::vector<Sample> samples;  // kept per thread: a mesh pair samples every step
  samples.clear();
  SamplesOf(from, spacing, samples);
  for (std::size_t i = 0; i < samples.size(); ++i) test(samples[i].p, samples[i].radius, i);
}

}  // namespace

void CollideMeshGround(const Posed& a, const Vector3& n, double offset, double margin, std::vector<ContactPoint>& out) {
  const std::size_t first = out.size();
  const shape::Mesh& mesh = std::get<shape::Mesh>(*a.shape);
  const std::vector<Vector3>& vertices = mesh.vertices;  // a plane meets a body at vertices first
  const Vector3 local = a.R.transpose() * n;             // the plane's normal in the mesh's frame
  const double base = n.dot(a.t) - offset;
  const double pad = 1e-9 * (mesh.field->radius + a.t.norm() + std::abs(offset));
  thread_local std::vector<std::uint32_t> near;  // the vertices that may be within the margin
  near.clear();
  const std::vector<int>& order = mesh.field->vertex_order;
  for (const MeshField::Cluster& run : mesh.field->vertex_runs) {
    // Every vertex of the run is at least the ball's radius nearer than its centre (padded far
    // beyond the rounding): a run wholly beyond the margin adds nothing, so it is skipped.
    const Vector3 c = a.R * run.centre + a.t;
    const double slack = 1e-9 * (run.radius + c.norm() + std::abs(offset)) + run.radius;
    if (n.dot(c) - offset - slack >= margin) continue;
    for (int k = run.first; k < run.first + run.count; ++k) {
      const auto i = static_cast<std::uint32_t>(order[static_cast<std::size_t>(k)]);
      // The separation in the mesh's frame first (3 products, not 12), padded beyond its rounding.
      if (local.dot(vertices[i]) + base - pad < margin) near.push_back(i);
    }
  }
  // In the vertices' own order, each computed as always: the same points as a scan of them all.
  std::sort(near.begin(), near.end());
  for (const std::uint32_t i : near) {
    const Vector3 p = a.R * vertices[i] + a.t;
    const double sep = n.dot(p) - offset;
    if (sep < margin) out.push_back({p - n * (0.5 * sep), n, sep, i});
  }
  ReduceContacts(out, first);
}

// Whether the shape's bounding sphere lies beyond `reach` of the mesh (the field at its centre,
// less a cell's diagonal for the interpolation's error): then nothing of it can touch the mesh.
bool OutOfReach(const Posed& mesh, const Posed& other, double margin) {
  const auto* m = std::get_if<shape::Mesh>(mesh.shape);
  if (m == nullptr) return false;
  const double d = DistanceOnly(mesh, other.t);
  return d - kDiagonal * m->field->cell > BoundingRadius(*other.shape) + margin;
}

void CollideWithMesh(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out) {
  CollideMeshes(a, b, margin, out, nullptr);
}

void CollideMeshes(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out,
                   PairSampleBounds* bounds) {
  if (OutOfReach(a, b, margin) || OutOfReach(b, a, margin)) return;
  const std::size_t first = out.size();
  const double spacing = std::min(Spacing(a), Spacing(b));
  const bool both = std::holds_alternative<shape::Mesh>(*a.shape) && std::holds_alternative<shape::Mesh>(*b.shape);
  SamplesAgainst(a, b, spacing, margin, false, out, both && bounds != nullptr ? &bounds->of[0] : nullptr);
  SamplesAgainst(b, a, spacing, margin, true, out, both && bounds != nullptr ? &bounds->of[1] : nullptr);
  ReduceContacts(out, first);
}

}  // namespace dynamics::contact
