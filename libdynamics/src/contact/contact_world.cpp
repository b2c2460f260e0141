// ContactWorld (contact.h): broad phase, contact points, the sequential-impulse solve with
// static and kinetic friction and restitution, and the step around it.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "../integrators/integrator.h"
#include "dynamics/contact.h"
#include "mesh_field.h"
#include "narrow_phase.h"
#include "polytope.h"

namespace dynamics {

const char* ShapeName(const Shape& s) {
  static const char* const kNames[] = {"sphere", "box", "capsule", "cylinder", "convex", "mesh"};
  return kNames[s.index()];
}

namespace {

// The polytope of a box or convex collider (null for the others).
std::shared_ptr<const contact::Polytope> PolytopeOf(const Shape& s) {
  if (const auto* box = std::get_if<shape::Box>(&s)) {
    return std::make_shared<contact::Polytope>(contact::BoxPolytope(box->half_extents));
  }
  if (const auto* convex = std::get_if<shape::Convex>(&s)) {
    return std::make_shared<contact::Polytope>(contact::MakePolytope(convex->vertices, convex->triangles));
  }
  if (const auto* cylinder = std::get_if<shape::Cylinder>(&s)) {
    // Against bodies, a cylinder is the 32-sided prism inscribed in it (its side at most
    // r (1 − cos(π/32)) = 0.0048 r inside the true one); against planes it stays exact.
    constexpr int kSides = 32;
    std::vector<Vector3> v;
    for (const double z : {cylinder->half_length, -cylinder->half_length}) {
      for (int i = 0; i < kSides; ++i) {
        const double phi = 2 * M_PI * i / kSides;
        v.emplace_back(cylinder->radius * std::cos(phi), cylinder->radius * std::sin(phi), z);
      }
    }
    std::vector<std::array<int, 3>> t;
    for (int i = 1; i + 1 < kSides; ++i) {
      t.push_back({0, i, i + 1});                         // top, counter-clockwise from +z
      t.push_back({kSides, kSides + i + 1, kSides + i});  // bottom, from −z
    }
    for (int i = 0; i < kSides; ++i) {
      const int j = (i + 1) % kSides;
      t.push_back({i, kSides + i, kSides + j});
      t.push_back({i, kSides + j, j});
    }
    return std::make_shared<contact::Polytope>(contact::MakePolytope(v, t));
  }
  return nullptr;
}

struct StaticBody {
  Collider collider;
  std::shared_ptr<const contact::Polytope> polytope;
  contact::Posed posed;  // in the world
  Vector3 lower, upper;  // bounds
};

// One contact point in the solve. Body b = -1: the ground or a static body.
struct Row {
  int a = -1, b = -1;
  Vector3 ra = Vector3::Zero(), rb = Vector3::Zero(), n = Vector3::UnitZ(), t1 = Vector3::UnitX(),
          t2 = Vector3::UnitY();
  Matrix3 Ka = Matrix3::Zero(), Kb = Matrix3::Zero();  // each body's share of K (below)
  int level = 0;                                       // of its lower body in the support graph
  double mass_n = 0;                                   // 1 / (n·K n)
  Eigen::Matrix2d mass_t = Eigen::Matrix2d::Zero();    // (T K Tᵀ)⁻¹
  double target = 0;                                   // the least normal velocity after the step
  double mu_s = 0, mu_k = 0;
  double mu = 0;         // the bound of this step: μs for a contact that holds, μk for one that slides
  bool sliding = false;  // slid last step, and slides now
  Eigen::Vector2d slip_direction = Eigen::Vector2d::Zero();  // unit, of the sliding at the start
  double lambda_n = 0;
  Eigen::Vector2d lambda_t = Eigen::Vector2d::Zero();
  std::tuple<int, int, std::uint32_t> key;  // (a, b or -1 - static index, feature): warm starting
  double separation = 0;
  // Mesh contacts only: overlap beyond this is pushed out after the step (< 0: never).
  double slop = -1;
  double push = 0;  // its accumulated pseudo-impulse
};

// The overlap a mesh contact may keep (a quarter of the finer field's cell), or -1: not a mesh
// contact.
double MeshSlop(const Shape& a, const Shape* b) {
  double cell = std::numeric_limits<double>::infinity();
  for (const Shape* s : {&a, b}) {
    if (const auto* m = s != nullptr ? std::get_if<shape::Mesh>(s) : nullptr) cell = std::min(cell, m->field->cell);
  }
  return std::isfinite(cell) ? 0.25 * cell : -1;
}

// The normal and tangential effective masses of a row for the response matrix K.
void SetEffectiveMasses(Row& r, const Matrix3& K) {
  r.mass_n = 1.0 / r.n.dot(K * r.n);
  Eigen::Matrix2d Kt;
  Kt << r.t1.dot(K * r.t1), r.t1.dot(K * r.t2), r.t2.dot(K * r.t1), r.t2.dot(K * r.t2);
  r.mass_t = Kt.inverse();
}

struct Velocities {
  Vector3 v, w;  // linear, angular (world)
};

}  // namespace

struct ContactWorld::Impl {
  std::vector<Collider> colliders;  // one per dynamic body
  std::vector<bool> collides;       // false: the body has no collider
  std::vector<bool> asleep;         // sleeping (ContactOptions::sleeping)
  std::vector<double> still_for;    // s the body has been slow
  std::vector<double> radii;        // each collider's bounding radius (a hull's: a pass over it)
  std::vector<std::shared_ptr<const contact::Polytope>> polytopes;
  std::vector<StaticBody> statics;
  std::vector<Ground> grounds;
  std::map<std::pair<int, int>, Material> pair_materials;
  // Impulses of the last step, by contact key: the warm start of the next.
  struct Cached {
    double lambda_n;
    Eigen::Vector2d lambda_t;
    bool stuck;  // its friction was inside the cone: it holds with μs next step
  };
  std::map<std::tuple<int, int, std::uint32_t>, Cached> cache;
  // Scratch.
  std::vector<Row> rows;
  std::vector<contact::ContactPoint> points;
  std::vector<Velocities> vel;
  std::vector<Velocities> before_kick;  // the velocities at the start of the step (for impacts)
  std::vector<Matrix3> inv_inertia;
};

ContactWorld::ContactWorld(World world, ContactOptions options)
    : world_(std::move(world)), options_(options), impl_(std::make_unique<Impl>()) {
  if (!world_.bodies().empty()) {
    throw std::invalid_argument("ContactWorld: start from a world without bodies (each body needs a collider)");
  }
}
ContactWorld::~ContactWorld() = default;
ContactWorld::ContactWorld(ContactWorld&&) noexcept = default;
ContactWorld& ContactWorld::operator=(ContactWorld&&) noexcept = default;

Material CombineMaterials(const Material& a, const Material& b) {
  return Material{std::sqrt(a.static_friction * b.static_friction), std::sqrt(a.kinetic_friction * b.kinetic_friction),
                  std::max(a.restitution, b.restitution)};
}

shape::Convex ConvexOf(const massprops::PolygonMesh& hull) {
  shape::Convex out;
  for (Eigen::Index v = 0; v < hull.V.rows(); ++v) out.vertices.push_back(hull.V.row(v).transpose());
  for (std::int64_t f = 0; f < hull.num_faces(); ++f) {
    const std::int32_t* idx = hull.indices.data() + hull.offsets[static_cast<std::size_t>(f)];
    for (int k = 1; k + 1 < hull.face_size(f); ++k) out.triangles.push_back({idx[0], idx[k], idx[k + 1]});
  }
  return out;
}

shape::Mesh MeshOf(const massprops::TriangleMesh& mesh, double cell) {
  shape::Mesh out;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) out.vertices.push_back(mesh.V.row(v).transpose());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) out.triangles.push_back({mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)});
  out.cell = cell;
  return out;
}

namespace {

void ValidateMaterial(const Material& m) {
  if (!(std::isfinite(m.static_friction) && m.static_friction >= 0 && std::isfinite(m.kinetic_friction) &&
        m.kinetic_friction >= 0 && m.kinetic_friction <= m.static_friction)) {
    throw std::invalid_argument("friction coefficients must be finite, non-negative, and kinetic <= static");
  }
  if (!(m.restitution >= 0 && m.restitution <= 1)) throw std::invalid_argument("restitution must lie in [0, 1]");
}

contact::Posed PoseOf(const Collider& c, const contact::Polytope* polytope, const RigidBody& b) {
  const Matrix3 R = b.Rotation();
  return {&c.shape, polytope, R * c.rotation, b.position + R * c.translation};
}

}  // namespace

namespace {
// A mesh collider's field, built here when the shape came without it.
void BuildFieldIfMissing(Collider& c) {
  if (auto* mesh = std::get_if<shape::Mesh>(&c.shape); mesh != nullptr && mesh->field == nullptr) {
    mesh->field = contact::BuildMeshField(*mesh);
  }
}
}  // namespace

int ContactWorld::AddBody(const RigidBody& body, Collider collider) {
  BuildFieldIfMissing(collider);
  contact::ValidateShape(collider.shape);
  ValidateMaterial(collider.material);
  auto polytope = PolytopeOf(collider.shape);
  const int index = world_.AddBody(body);
  impl_->radii.push_back(contact::BoundingRadius(collider.shape));
  impl_->colliders.push_back(std::move(collider));
  impl_->polytopes.push_back(std::move(polytope));
  impl_->collides.push_back(true);
  impl_->asleep.push_back(false);
  impl_->still_for.push_back(0.0);
  return index;
}

int ContactWorld::AddBody(const RigidBody& body) {
  const int index = world_.AddBody(body);
  impl_->colliders.push_back(Collider{shape::Sphere{1}, Matrix3::Identity(), Vector3::Zero(), Material{}});
  impl_->radii.push_back(1.0);
  impl_->polytopes.push_back(nullptr);
  impl_->collides.push_back(false);
  impl_->asleep.push_back(false);
  impl_->still_for.push_back(0.0);
  return index;
}

void ContactWorld::AddStatic(Collider collider, const Matrix3& rotation, const Vector3& translation) {
  BuildFieldIfMissing(collider);
  contact::ValidateShape(collider.shape);
  ValidateMaterial(collider.material);
  if (!rotation.allFinite() || std::abs(rotation.determinant() - 1) > 1e-9 ||
      !(rotation.transpose() * rotation).isApprox(Matrix3::Identity(), 1e-9) || !translation.allFinite()) {
    throw std::invalid_argument("a static body's placement needs a rotation and a finite translation");
  }
  StaticBody s;
  s.collider = std::move(collider);
  s.polytope = PolytopeOf(s.collider.shape);
  s.posed = {nullptr, s.polytope.get(), rotation * s.collider.rotation,
             translation + rotation * s.collider.translation};
  const double r = contact::BoundingRadius(s.collider.shape);
  s.lower = s.posed.t - Vector3::Constant(r);
  s.upper = s.posed.t + Vector3::Constant(r);
  impl_->statics.push_back(std::move(s));
}

void ContactWorld::AddGround(Ground ground) {
  const double len = ground.normal.norm();
  if (!(std::isfinite(len) && len > 0) || !std::isfinite(ground.offset)) {
    throw std::invalid_argument("a ground plane needs a finite, non-zero normal and a finite offset");
  }
  ValidateMaterial(ground.material);
  ground.offset /= len;
  ground.normal /= len;
  impl_->grounds.push_back(ground);
}

void ContactWorld::SetPairMaterial(int a, int b, const Material& material) {
  ValidateMaterial(material);
  impl_->pair_materials[{std::min(a, b), std::max(a, b)}] = material;
}

StepStatus ContactWorld::Step(double h) {
  if (!(h > 0) || !std::isfinite(h)) return world_.Step(h);  // throws, naming the step
  Impl& m = *impl_;
  if (m.grounds.empty() && m.statics.empty() &&
      std::find(m.collides.begin(), m.collides.end(), true) == m.collides.end()) {
    stats_ = {};
    return world_.Step(h);  // nothing can touch: the world's integrator, at no extra cost
  }
  std::vector<RigidBody>& bodies = world_.bodies_;
  const int nb = static_cast<int>(bodies.size());
  stats_ = {};
  // 1. The kick: velocities after this step's forces, before contact.
  internal::StepContext context(bodies, world_.forces_, *world_.scratch_, world_.num_threads_);
  context.ComputeWrenches(world_.time_);
  const std::vector<Wrench>& w = context.wrenches();
  m.vel.resize(static_cast<std::size_t>(nb));
  m.before_kick.resize(static_cast<std::size_t>(nb));
  m.inv_inertia.resize(static_cast<std::size_t>(nb));
  double kick_speed = 0;  // the largest speed the forces give in one step
  for (int i = 0; i < nb; ++i) {
    const RigidBody& b = bodies[static_cast<std::size_t>(i)];
    const Matrix3 R = b.Rotation();
    m.inv_inertia[static_cast<std::size_t>(i)] = R * b.inertia.cwiseInverse().asDiagonal() * R.transpose();
    const Vector3 dv = h / b.mass * w[static_cast<std::size_t>(i)].force;
    kick_speed = std::max(kick_speed, dv.norm());
    const Vector3 L = b.angular_momentum + h * w[static_cast<std::size_t>(i)].torque;
    m.before_kick[static_cast<std::size_t>(i)] = {b.velocity, b.AngularVelocity()};
    m.vel[static_cast<std::size_t>(i)] = {b.velocity + dv, m.inv_inertia[static_cast<std::size_t>(i)] * L};
  }
  const double bounce_threshold =
      options_.restitution_threshold > 0 ? options_.restitution_threshold : 2 * kick_speed + 1e-12;
  // The velocity of a contact point on a relative to b (the ground: at rest), and the kinetic
  // energy, both of the velocities the solve works on.
  auto relative_in = [&](const std::vector<Velocities>& vel, const Row& r) {
    const Velocities& va = vel[static_cast<std::size_t>(r.a)];
    Vector3 v = va.v + va.w.cross(r.ra);
    if (r.b >= 0) {
      const Velocities& vb = vel[static_cast<std::size_t>(r.b)];
      v -= vb.v + vb.w.cross(r.rb);
    }
    return v;
  };
  auto relative = [&](const Row& r) { return relative_in(m.vel, r); };
  auto kinetic_energy = [&] {
    double e = 0;
    for (int i = 0; i < nb; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const RigidBody& b = bodies[k];
      e += 0.5 * b.mass * m.vel[k].v.squaredNorm() + 0.5 * m.vel[k].w.dot(b.WorldInertia() * m.vel[k].w);
    }
    return e;
  };
  // 2. Contacts at the start-of-step positions, within each body's reach in this step.
  std::vector<double> reach(static_cast<std::size_t>(nb));
  const std::vector<double>& radius = m.radii;
  std::vector<contact::Posed> posed(static_cast<std::size_t>(nb));
  for (int i = 0; i < nb; ++i) {
    const auto k = static_cast<std::size_t>(i);
    posed[k] = PoseOf(m.colliders[k], m.polytopes[k].get(), bodies[k]);
    const Vector3 c = posed[k].t - bodies[k].position;
    reach[k] = h * (m.vel[k].v.norm() + m.vel[k].w.norm() * (radius[k] + c.norm())) + 1e-9 * radius[k];
  }
  m.rows.clear();
  auto material_of = [&](int a, int b, const Material& ma, const Material& mb) {
    const auto it = m.pair_materials.find({std::min(a, b), std::max(a, b)});
    if (it != m.pair_materials.end()) return it->second;
    return CombineMaterials(ma, mb);
  };
  auto add_rows = [&](int a, int b, int key_b, const Material& mat, double slop) {
    for (const contact::ContactPoint& p : m.points) {
      Row r;
      r.slop = slop;
      r.a = a;
      r.b = b;
      r.n = p.normal;
      r.ra = p.point - bodies[static_cast<std::size_t>(a)].position;
      r.rb = b >= 0 ? Vector3(p.point - bodies[static_cast<std::size_t>(b)].position) : Vector3::Zero();
      r.mu_s = mat.static_friction;
      r.mu_k = mat.kinetic_friction;
      r.separation = p.separation;
      r.key = {a, key_b, p.feature};
      // Restitution at an impact faster than the resting threshold; else the gap may close. The
      // impact is where the point meets the surface: it approaches at b now (before the step's
      // kick), accelerated by a = kick / h over the gap s, so it hits at w = √(b² + 2as) and
      // leaves at e w. The bounce is taken now, at the gap, and the step then moves the point by
      // h u: u is the speed whose energy at the end of the step, ½u² + a (s + h u), is that of
      // the real bounce, ½e²w². A bounce so gains no energy from the gap it did not fall (a point
      // bouncing off a speculative contact would otherwise rise higher each time, or hover).
      const double approach = -r.n.dot(relative(r));
      const double closing = -r.n.dot(relative_in(m.before_kick, r));                                 // b
      const double s = std::max(p.separation, 0.0), accel = std::max(0.0, (approach - closing) / h);  // a
      const double e = mat.restitution, impact_squared = closing * std::abs(closing) + 2 * accel * s;
      const double radicand = accel * accel * h * h + e * e * impact_squared - 2 * accel * s;
      const double leave = radicand > 0 ? std::sqrt(radicand) - accel * h : 0.0;
      if (e > 0 && impact_squared > bounce_threshold * bounce_threshold && p.separation < approach * h && leave > 0) {
        r.target = leave;
      } else {
        r.target = -s / h;
      }
      stats_.max_penetration = std::max(stats_.max_penetration, -p.separation);
      m.rows.push_back(r);
    }
    if (!m.points.empty()) ++stats_.pairs;
  };
  for (int i = 0; i < nb; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!m.collides[k]) continue;
    for (const Ground& g : m.grounds) {
      const double reach_g = reach[k];
      if (g.normal.dot(posed[k].t) - g.offset - radius[k] >= reach_g) continue;
      m.points.clear();
      contact::CollideGround(posed[k], g.normal, g.offset, reach_g, m.points);
      add_rows(i, -1, -1, material_of(i, -1, m.colliders[k].material, g.material),
               MeshSlop(m.colliders[k].shape, nullptr));
    }
  }
  // Broad phase: sweep and prune along x over bounding spheres grown by the reach.
  struct Interval {
    double lo, hi;
    int id;  // >= 0: dynamic body; < 0: -1 - static index
  };
  std::vector<Interval> intervals;
  intervals.reserve(static_cast<std::size_t>(nb) + m.statics.size());
  for (int i = 0; i < nb; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!m.collides[k]) continue;
    intervals.push_back({posed[k].t.x() - radius[k] - reach[k], posed[k].t.x() + radius[k] + reach[k], i});
  }
  for (std::size_t s = 0; s < m.statics.size(); ++s) {
    intervals.push_back({m.statics[s].lower.x(), m.statics[s].upper.x(), -1 - static_cast<int>(s)});
  }
  std::sort(intervals.begin(), intervals.end(),
            [](const Interval& x, const Interval& y) { return x.lo < y.lo || (x.lo == y.lo && x.id < y.id); });
  StepStatus failure;
  struct Candidate {
    int a, b;  // b < 0: static body -1 - b
    contact::Posed pb;
    const Material* mb;
    double margin;
  };
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < intervals.size(); ++i) {
    for (std::size_t j = i + 1; j < intervals.size() && intervals[j].lo <= intervals[i].hi; ++j) {
      int a = intervals[i].id, b = intervals[j].id;
      if (a < 0 && b < 0) continue;                     // two static bodies
      if (a < 0 || (b >= 0 && b < a)) std::swap(a, b);  // a dynamic; the lower index first
      const auto ka = static_cast<std::size_t>(a);
      contact::Posed pb;
      double rb = 0, reach_b = 0;
      const Material* mb;
      if (b >= 0) {
        pb = posed[static_cast<std::size_t>(b)];
        rb = radius[static_cast<std::size_t>(b)];
        reach_b = reach[static_cast<std::size_t>(b)];
        mb = &m.colliders[static_cast<std::size_t>(b)].material;
      } else {
        const StaticBody& s = m.statics[static_cast<std::size_t>(-1 - b)];
        pb = s.posed;
        pb.shape = &s.collider.shape;
        rb = contact::BoundingRadius(s.collider.shape);
        mb = &s.collider.material;
      }
      const double margin = reach[ka] + reach_b;
      if ((posed[ka].t - pb.t).norm() - radius[ka] - rb >= margin) continue;
      candidates.push_back({a, b, pb, mb, margin});
    }
  }
  // The narrow phase: each pair on its own (on worker threads when there are many; mesh pairs
  // test thousands of samples), then the rows in the pairs' order, so the step does not depend on
  // the thread count.
  std::vector<std::vector<contact::ContactPoint>> found(candidates.size());
  std::vector<char> supported(candidates.size(), 1);
  {
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
      for (std::size_t c = next.fetch_add(1); c < candidates.size(); c = next.fetch_add(1)) {
        const Candidate& p = candidates[c];
        supported[c] = contact::Collide(posed[static_cast<std::size_t>(p.a)], p.pb, p.margin, found[c]);
      }
    };
    static const int kHardwareThreads = static_cast<int>(std::thread::hardware_concurrency());
    const int threads = std::min<int>(world_.num_threads_ > 0 ? world_.num_threads_ : kHardwareThreads,
                                      static_cast<int>(candidates.size() / 8));
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
  }
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const Candidate& p = candidates[c];
    const int a = p.a, b = p.b;
    const auto ka = static_cast<std::size_t>(a);
    if (!supported[c]) {
      failure.ok = false;
      std::ostringstream msg;
      msg << "contact between a " << ShapeName(*posed[ka].shape) << " (body " << a << ") and a "
          << ShapeName(*p.pb.shape) << (b >= 0 ? " (body " + std::to_string(b) + ")" : std::string(" (static)"))
          << " is not supported yet";
      failure.message = msg.str();
      return failure;
    }
    m.points.swap(found[c]);
    add_rows(a, b >= 0 ? b : -1, b, material_of(a, b >= 0 ? b : -1, m.colliders[ka].material, *p.mb),
             MeshSlop(*posed[ka].shape, p.pb.shape));
  }
  stats_.contacts = static_cast<int>(m.rows.size());
  if (m.rows.empty()) {  // free flight: the world's own integrator, bit for bit
    m.cache.clear();
    std::fill(m.asleep.begin(), m.asleep.end(), false);
    std::fill(m.still_for.begin(), m.still_for.end(), 0.0);
    return world_.Step(h);
  }
  // Islands: bodies joined by contacts (union-find). An island sleeps as a whole and wakes as a
  // whole: one awake body touching it wakes every body in it.
  std::vector<int> island(static_cast<std::size_t>(nb));
  for (int i = 0; i < nb; ++i) island[static_cast<std::size_t>(i)] = i;
  auto find = [&](int i) {
    while (island[static_cast<std::size_t>(i)] != i) {
      island[static_cast<std::size_t>(i)] = island[static_cast<std::size_t>(island[static_cast<std::size_t>(i)])];
      i = island[static_cast<std::size_t>(i)];
    }
    return i;
  };
  for (const Row& r : m.rows) {
    if (r.b >= 0) island[static_cast<std::size_t>(find(r.a))] = find(r.b);
  }
  std::vector<char> island_awake(static_cast<std::size_t>(nb), 0);
  for (int i = 0; i < nb; ++i) {
    if (!m.asleep[static_cast<std::size_t>(i)]) island_awake[static_cast<std::size_t>(find(i))] = 1;
  }
  for (int i = 0; i < nb; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (m.asleep[k] && island_awake[static_cast<std::size_t>(find(i))]) m.asleep[k] = false;  // woken
    if (m.asleep[k]) {  // held still: no kick, and as heavy as the ground for the others
      m.vel[k] = {Vector3::Zero(), Vector3::Zero()};
      m.inv_inertia[k] = Matrix3::Zero();
    }
  }
  // Contacts between bodies that are all held still have nothing to solve; their impulses are
  // kept for when the island wakes.
  std::vector<std::pair<std::tuple<int, int, std::uint32_t>, Impl::Cached>> kept;
  m.rows.erase(std::remove_if(m.rows.begin(), m.rows.end(),
                              [&](const Row& r) {
                                const bool still = m.asleep[static_cast<std::size_t>(r.a)] &&
                                                   (r.b < 0 || m.asleep[static_cast<std::size_t>(r.b)]);
                                if (still) {
                                  const auto it = m.cache.find(r.key);
                                  if (it != m.cache.end()) kept.emplace_back(*it);
                                }
                                return still;
                              }),
               m.rows.end());
  // 3. The impulses.
  auto inv_mass = [&](int i) {
    return i >= 0 && !m.asleep[static_cast<std::size_t>(i)] ? 1.0 / bodies[static_cast<std::size_t>(i)].mass : 0.0;
  };
  auto inv_I = [&](int i) { return i >= 0 ? m.inv_inertia[static_cast<std::size_t>(i)] : Matrix3::Zero().eval(); };
  for (Row& r : m.rows) {
    const Vector3 helper = std::abs(r.n.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY();
    r.t1 = r.n.cross(helper).normalized();
    r.t2 = r.n.cross(r.t1);
    // K = (1/ma + 1/mb) E − [ra]× Ia⁻¹ [ra]× − [rb]× Ib⁻¹ [rb]×: the point's response to an impulse.
    const Matrix3 Sa = internal::Skew(r.ra), Sb = internal::Skew(r.rb);
    r.Ka = inv_mass(r.a) * Matrix3::Identity() - Sa * inv_I(r.a) * Sa;
    r.Kb = inv_mass(r.b) * Matrix3::Identity() - Sb * inv_I(r.b) * Sb;
    SetEffectiveMasses(r, r.Ka + r.Kb);
    // Static or kinetic: a contact that held last step (or a new one whose points barely slide)
    // holds while its friction stays within μs; one that slid slides at μk until it stops.
    const auto it = m.cache.find(r.key);
    bool stuck;
    if (it != m.cache.end()) {
      r.lambda_n = it->second.lambda_n;
      r.lambda_t = it->second.lambda_t;
      stuck = it->second.stuck;
    } else {
      const Vector3 rel = relative(r);
      stuck = (rel - r.n * r.n.dot(rel)).norm() <= bounce_threshold;
    }
    r.mu = stuck ? r.mu_s : r.mu_k;
    if (!stuck) {
      // Friction opposes the sliding: its direction at the start of the step, kept through the
      // iterations (the direction of the impulse that would stop the point is tilted by the
      // body's rotation, and following the changing velocity would not converge).
      const Vector3 rel = relative(r);
      const Eigen::Vector2d vt(r.t1.dot(rel), r.t2.dot(rel));
      r.sliding = vt.norm() > 0;
      if (r.sliding) r.slip_direction = vt / vt.norm();
    }
  }
  int frozen = -1;  // shock propagation: the body held still (the lower one of a row)
  // An impulse at a row's point, on a (and its opposite on b), into the velocities `vel`.
  auto apply_to = [&](std::vector<Velocities>& vel, const Row& r, const Vector3& impulse) {
    if (r.a != frozen) {
      Velocities& va = vel[static_cast<std::size_t>(r.a)];
      va.v += inv_mass(r.a) * impulse;
      va.w += m.inv_inertia[static_cast<std::size_t>(r.a)] * r.ra.cross(impulse);
    }
    if (r.b >= 0 && r.b != frozen) {
      Velocities& vb = vel[static_cast<std::size_t>(r.b)];
      vb.v -= inv_mass(r.b) * impulse;
      vb.w -= m.inv_inertia[static_cast<std::size_t>(r.b)] * r.rb.cross(impulse);
    }
  };
  auto apply = [&](const Row& r, const Vector3& impulse) { apply_to(m.vel, r, impulse); };
  const double energy_before = kinetic_energy();
  // The support graph: level 0 touches the ground or a static body, level k + 1 rests on level
  // k; bodies touching none of them come last. Rows are solved from the ground up.
  std::vector<int> body_level(static_cast<std::size_t>(nb), std::numeric_limits<int>::max());
  {
    std::vector<int> frontier;
    for (const Row& r : m.rows) {
      if (r.b < 0 && body_level[static_cast<std::size_t>(r.a)] != 0) {
        body_level[static_cast<std::size_t>(r.a)] = 0;
        frontier.push_back(r.a);
      }
    }
    for (int level = 1; !frontier.empty(); ++level) {
      std::vector<int> next;
      for (const Row& r : m.rows) {
        if (r.b < 0) continue;
        for (const auto& [lower, upper] : {std::pair{r.a, r.b}, std::pair{r.b, r.a}}) {
          if (body_level[static_cast<std::size_t>(lower)] == level - 1 &&
              body_level[static_cast<std::size_t>(upper)] == std::numeric_limits<int>::max()) {
            body_level[static_cast<std::size_t>(upper)] = level;
            next.push_back(upper);
          }
        }
      }
      frontier = std::move(next);
    }
  }
  int max_level = -1;
  for (Row& r : m.rows) {
    const int la = body_level[static_cast<std::size_t>(r.a)];
    r.level = r.b < 0 ? la : std::min(la, body_level[static_cast<std::size_t>(r.b)]);
    if (r.level != std::numeric_limits<int>::max()) max_level = std::max(max_level, r.level);
  }
  std::stable_sort(m.rows.begin(), m.rows.end(), [](const Row& x, const Row& y) { return x.level < y.level; });
  // Warm start, then iterate until no impulse changes.
  for (const Row& r : m.rows) apply(r, r.n * r.lambda_n + r.t1 * r.lambda_t[0] + r.t2 * r.lambda_t[1]);
  // One Gauss-Seidel update of a row: the normal impulse, then the friction.
  auto update = [&](Row& r, double& change, double& scale) {
    // Normal: the least impulse that keeps the normal velocity at its target.
    const double vn = r.n.dot(relative(r));
    const double ln = std::max(r.lambda_n + r.mass_n * (r.target - vn), 0.0);
    const double dn = ln - r.lambda_n;
    r.lambda_n = ln;
    apply(r, r.n * dn);
    // Friction: the impulse that stops the point's sliding, within the cone μ λn. Within the
    // cone it holds (or comes to rest in this step); beyond it, a sliding contact takes μk λn
    // against its sliding, a holding one breaks away at the cone's edge.
    const Vector3 rel = relative(r);
    const Eigen::Vector2d vt(r.t1.dot(rel), r.t2.dot(rel));
    const Eigen::Vector2d stop = r.lambda_t - r.mass_t * vt;
    const double bound = r.mu * r.lambda_n;
    Eigen::Vector2d lt = stop;
    if (stop.norm() > bound) {
      lt = r.sliding ? Eigen::Vector2d(-bound * r.slip_direction) : Eigen::Vector2d(stop * (bound / stop.norm()));
    }
    const Eigen::Vector2d dt = lt - r.lambda_t;
    r.lambda_t = lt;
    apply(r, r.t1 * dt[0] + r.t2 * dt[1]);
    change = std::max({change, std::abs(dn), dt.norm()});
    scale = std::max({scale, r.lambda_n, lt.norm()});
  };
  // Sweeps from the ground up, then back down (symmetric Gauss-Seidel carries a load through a
  // stack in both directions), until no impulse changes.
  int iteration = 0;
  for (; iteration < options_.max_iterations; ++iteration) {
    double change = 0, scale = 0;
    if (iteration % 2 == 0) {
      for (Row& r : m.rows) update(r, change, scale);
    } else {
      for (auto it = m.rows.rbegin(); it != m.rows.rend(); ++it) update(*it, change, scale);
    }
    if (change <= options_.tolerance * scale) {
      ++iteration;
      break;
    }
  }
  // Shock propagation (Guendelman, Bridson & Fedkiw 2003): level by level from the ground up,
  // each body's contacts with the level below are solved with the lower body held still, so
  // what the iterations left of a resting stack's velocities does not survive the step.
  if (iteration >= options_.max_iterations) {
    for (int level = 0; level <= max_level; ++level) {
      for (int pass = 0; pass < options_.max_iterations; ++pass) {
        double change = 0, scale = 0;
        for (Row& r : m.rows) {
          if (r.level != level) continue;
          const int la = body_level[static_cast<std::size_t>(r.a)];
          const int lb = r.b >= 0 ? body_level[static_cast<std::size_t>(r.b)] : -1;
          if (la == lb) continue;
          frozen = la < lb ? r.a : r.b;
          const Row saved = r;
          SetEffectiveMasses(r, frozen == r.a ? r.Kb : r.Ka);
          update(r, change, scale);
          r.mass_n = saved.mass_n;
          r.mass_t = saved.mass_t;
          frozen = -1;
        }
        if (change <= options_.tolerance * scale) break;
      }
    }
  }
  stats_.iterations = iteration;
  m.cache.clear();
  for (const auto& [key, value] : kept) m.cache[key] = value;
  for (const Row& r : m.rows) {
    // On the cone's surface: it slides (or just broke away); inside: it holds.
    const bool stuck = r.lambda_t.norm() < r.mu * r.lambda_n * (1 - 1e-9) || r.lambda_n == 0;
    m.cache[r.key] = {r.lambda_n, r.lambda_t, stuck};
  }
  stats_.dissipated = energy_before - kinetic_energy();
  // 3b. Mesh contacts: overlap beyond the slop (which the velocity solve only stops from growing)
  // is pushed out by pseudo-velocities that move the bodies in this step's drift and are then
  // dropped (split impulses): the velocities, and so the kinetic energy, are not changed; the
  // potential energy may rise by the weight times the distance moved, reported in the stats.
  std::vector<Velocities> pseudo;
  bool pushes = false;
  for (const Row& r : m.rows) pushes = pushes || (r.slop >= 0 && -r.separation > r.slop);
  if (pushes) {
    pseudo.assign(static_cast<std::size_t>(nb), {Vector3::Zero(), Vector3::Zero()});
    constexpr double kPush = 0.5;  // of the excess overlap, per step
    for (int sweep = 0; sweep < options_.max_iterations; ++sweep) {
      double change = 0, scale = 0;
      for (Row& r : m.rows) {
        if (r.slop < 0) continue;
        const double target = kPush * std::max(-r.separation - r.slop, 0.0) / h;
        const double push = std::max(r.push + r.mass_n * (target - r.n.dot(relative_in(pseudo, r))), 0.0);
        const Vector3 impulse = r.n * (push - r.push);
        change = std::max(change, std::abs(push - r.push));
        scale = std::max(scale, push);
        r.push = push;
        apply_to(pseudo, r, impulse);
      }
      if (change <= options_.tolerance * scale) break;
    }
  }
  // 4. The drift: positions with the new velocities, the free rotation with the new L.
  StepStatus status;
  for (int i = 0; i < nb; ++i) {
    const auto k = static_cast<std::size_t>(i);
    RigidBody& b = bodies[k];
    if (m.asleep[k]) {
      b.velocity.setZero();
      b.angular_momentum.setZero();
      continue;
    }
    const RigidBody before = b;
    b.velocity = m.vel[k].v;
    b.angular_momentum = b.WorldInertia() * m.vel[k].w;
    b.position += h * b.velocity;
    if (!internal::MidpointRotation(b, h)) {
      b = before;
      status.ok = false;
      status.body = i;
      status.message = "the free rotation of body " + std::to_string(i) +
                       " did not converge in a contact step (angular velocity too large for this step)";
      return status;
    }
    if (!pseudo.empty() && (pseudo[k].v.squaredNorm() > 0 || pseudo[k].w.squaredNorm() > 0)) {
      const Vector3 moved = h * pseudo[k].v;
      b.position += moved;
      const Vector3 turn = h * pseudo[k].w;
      const double angle = turn.norm();
      if (angle > 0) {
        const Vector3 L_world = b.angular_momentum;  // the momentum stays; the body turns under it
        b.orientation = (Quaternion(Eigen::AngleAxisd(angle, turn / angle)) * b.orientation).normalized();
        b.angular_momentum = L_world;
      }
      stats_.pushed = std::max(stats_.pushed, moved.norm() + angle * radius[k]);
    }
  }
  world_.time_ += h;
  if (options_.sleeping) {
    // An island whose bodies have all been slow for sleep_time falls asleep.
    std::vector<char> slow(static_cast<std::size_t>(nb), 1);
    for (int i = 0; i < nb; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const RigidBody& b = bodies[k];
      const bool still = b.velocity.norm() + b.AngularVelocity().norm() * radius[k] < options_.sleep_speed;
      m.still_for[k] = still ? m.still_for[k] + h : 0.0;
      if (m.still_for[k] < options_.sleep_time) slow[static_cast<std::size_t>(find(i))] = 0;
    }
    std::vector<char> touches(static_cast<std::size_t>(nb), 0);  // islands resting on something
    for (const Row& r : m.rows) touches[static_cast<std::size_t>(find(r.a))] = 1;
    for (int i = 0; i < nb; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const int root = find(i);
      if (m.collides[k] && slow[static_cast<std::size_t>(root)] && touches[static_cast<std::size_t>(root)] &&
          !m.asleep[k]) {
        m.asleep[k] = true;
        bodies[k].velocity.setZero();
        bodies[k].angular_momentum.setZero();
      }
    }
    stats_.sleeping = static_cast<int>(std::count(m.asleep.begin(), m.asleep.end(), true));
  }
  const auto [bad, quantity] = world_.FirstNonFinite();
  if (bad >= 0) {
    status.ok = false;
    status.diverged = true;
    status.body = bad;
    status.message = "diverged at t = " + std::to_string(world_.time_) + " s: body " + std::to_string(bad) + "'s " +
                     quantity + " is no longer finite";
  }
  return status;
}

}  // namespace dynamics
