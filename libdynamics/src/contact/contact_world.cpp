// ContactWorld (contact.h): its bodies, statics and grounds, and the step that runs the stages —
// kick, broad phase (broad_phase.h), narrow phase (narrow_phase.h), rows, islands and sleeping
// (islands.h), the impulses (solver.h), position correction (position_correction.h), drift.

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "../articulated/articulation.h"
#include "../integrators/integrator.h"
#include "broad_phase.h"
#include "dynamics/contact.h"
#include "islands.h"
#include "mesh_field.h"
#include "narrow_phase.h"
#include "polytope.h"
#include "position_correction.h"
#include "solver.h"
#include "workers.h"

namespace dynamics {

const char* ShapeName(const Shape& s) {
  static const char* const kNames[] = {"sphere", "box", "capsule", "cylinder", "convex", "mesh", "compound"};
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
        const double phi = 2 * massprops::kPi * i / kSides;
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
};

// The overlap a contact may keep before the position correction pushes it out: a quarter of the
// finer mesh field's cell for a mesh contact, else half a percent of the smaller shape's bounding
// radius (ra, rb; rb < 0: a ground plane). Speculative contacts keep overlaps from forming; the
// ones that do form (bodies turning into each other within a step) are pushed out.
// The finest mesh field cell of a shape (a compound's parts too); infinite without a mesh.
double FinestCell(const Shape* s) {
  double cell = std::numeric_limits<double>::infinity();
  if (const auto* m = s != nullptr ? std::get_if<shape::Mesh>(s) : nullptr) cell = m->field->cell;
  if (const auto* c = s != nullptr ? std::get_if<shape::Compound>(s) : nullptr) {
    for (const Collider& part : c->parts) cell = std::min(cell, FinestCell(&part.shape));
  }
  return cell;
}

double Slop(const Shape& a, double ra, const Shape* b, double rb) {
  const double cell = std::min(FinestCell(&a), FinestCell(b));
  if (std::isfinite(cell)) return 0.25 * cell;
  return 0.005 * (rb > 0 ? std::min(ra, rb) : ra);
}

}  // namespace

struct ContactWorld::Impl {
  std::vector<Collider> colliders;  // one per dynamic body
  std::vector<bool> collides;       // false: the body has no collider
  contact::SleepState sleep;        // ContactOptions::sleeping
  std::vector<double> radii;        // each collider's bounding radius (a hull's: a pass over it)
  std::vector<std::shared_ptr<const contact::Polytope>> polytopes;
  std::vector<StaticBody> statics;
  std::vector<contact::BroadStatic> static_broad;  // each static body posed in the world, with its bounds
  std::vector<Ground> grounds;
  std::map<std::pair<int, int>, Material> pair_materials;
  std::set<std::pair<int, int>> excluded;  // body pairs that never touch (ExcludePair), (min, max)
  contact::ContactCache cache;             // the last step's impulses: the warm start of the next
  // Scratch.
  std::vector<contact::Row> rows;
  std::vector<contact::Patch> patches;  // the last step's, with its rows (Contacts())
  std::vector<contact::Velocities> vel;
  std::vector<contact::Velocities> before_kick;  // the velocities at the start of the step (for impacts)
  contact::BodyResponse response;
  std::unique_ptr<contact::Workers> workers;              // kept between steps; null: one thread
  internal::StepScratch scratch;                          // the forces' wrenches
  std::vector<std::vector<contact::ContactPoint>> found;  // each candidate pair's points
  std::vector<char> supported;                            // each candidate pair's kinds have a routine
  contact::Coupling coupling;                             // an articulated world's bodies (a step's)
  std::vector<internal::Vector6> kicked;                  // their (v, ω) after the kick

  // The worker pool for `threads` (null for one thread).
  contact::Workers* WorkersFor(int threads) {
    const int n = contact::ThreadCount(threads);
    if (n <= 1) return nullptr;
    if (!workers || workers->threads() != n) workers = std::make_unique<contact::Workers>(n);
    return workers.get();
  }
};

ContactWorld::ContactWorld(World world, ContactOptions options)
    : world_(std::move(world)), options_(options), impl_(std::make_unique<Impl>()) {
  if (!world_.bodies().empty()) {
    throw std::invalid_argument("ContactWorld: start from a world without bodies (each body needs a collider)");
  }
  const ContactOptions& o = options_;
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("contact options: ") + what);
  };
  require(o.max_iterations >= 0 && o.max_iterations <= 1000000, "max_iterations must be 0 (automatic) or 1 to 10^6");
  require(o.speed_tolerance > 0 && std::isfinite(o.speed_tolerance), "speed_tolerance must be positive and finite");
  require(o.tolerance >= 0 && std::isfinite(o.tolerance), "tolerance must be non-negative and finite");
  require(o.restitution_threshold >= 0 && std::isfinite(o.restitution_threshold),
          "restitution_threshold must be non-negative and finite");
  require(o.sleep_speed > 0 && std::isfinite(o.sleep_speed), "sleep_speed must be positive and finite");
  require(o.sleep_time > 0 && std::isfinite(o.sleep_time), "sleep_time must be positive and finite");
}
ContactWorld::~ContactWorld() = default;
ContactWorld::ContactWorld(ContactWorld&&) noexcept = default;
ContactWorld& ContactWorld::operator=(ContactWorld&&) noexcept = default;

Material CombineMaterials(const Material& a, const Material& b) {
  if (a.mix_by_maximum && b.mix_by_maximum) {
    return Material{std::max(a.static_friction, b.static_friction), std::max(a.kinetic_friction, b.kinetic_friction),
                    std::max(a.restitution, b.restitution), true};
  }
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
// The collider's material and, when its parts touch with their own, theirs.
void ValidateMaterials(const Collider& c) {
  ValidateMaterial(c.material);
  if (const auto* compound = std::get_if<shape::Compound>(&c.shape); compound != nullptr && compound->part_materials) {
    for (const Collider& part : compound->parts) ValidateMaterial(part.material);
  }
}

contact::Posed PoseOf(const Collider& c, const contact::Polytope* polytope, const RigidBody& b) {
  const Matrix3 R = b.Rotation();
  return {&c.shape, polytope, R * c.rotation, b.position + R * c.translation, c.filter};
}

}  // namespace

namespace {
// What a shape needs before it collides: a mesh collider's field, built here when the shape came
// without it; a compound's parts' fields and polytopes.
void PrepareShape(Collider& c) {
  if (auto* mesh = std::get_if<shape::Mesh>(&c.shape); mesh != nullptr && mesh->field == nullptr) {
    mesh->field = contact::BuildMeshField(*mesh);
  }
  if (auto* compound = std::get_if<shape::Compound>(&c.shape)) {
    compound->polytopes.clear();
    for (Collider& part : compound->parts) {
      PrepareShape(part);
      compound->polytopes.push_back(PolytopeOf(part.shape));
    }
  }
}
}  // namespace

int ContactWorld::AddBody(const RigidBody& body, Collider collider) {
  PrepareShape(collider);
  contact::ValidateShape(collider.shape);
  ValidateMaterials(collider);
  auto polytope = PolytopeOf(collider.shape);
  const int index = world_.AddBody(body);
  impl_->radii.push_back(contact::BoundingRadius(collider.shape));
  impl_->colliders.push_back(std::move(collider));
  impl_->polytopes.push_back(std::move(polytope));
  impl_->collides.push_back(true);
  impl_->sleep.asleep.push_back(false);
  impl_->sleep.still_for.push_back(0.0);
  return index;
}

int ContactWorld::AddBody(const RigidBody& body) {
  const int index = world_.AddBody(body);
  impl_->colliders.push_back(Collider{shape::Sphere{1}});
  impl_->radii.push_back(1.0);
  impl_->polytopes.push_back(nullptr);
  impl_->collides.push_back(false);
  impl_->sleep.asleep.push_back(false);
  impl_->sleep.still_for.push_back(0.0);
  return index;
}

void ContactWorld::AddStatic(Collider collider, const Matrix3& rotation, const Vector3& translation) {
  PrepareShape(collider);
  contact::ValidateShape(collider.shape);
  ValidateMaterials(collider);
  if (!rotation.allFinite() || std::abs(rotation.determinant() - 1) > 1e-9 ||
      !(rotation.transpose() * rotation).isApprox(Matrix3::Identity(), 1e-9) || !translation.allFinite()) {
    throw std::invalid_argument("a static body's placement needs a rotation and a finite translation");
  }
  StaticBody s;
  s.collider = std::move(collider);
  s.polytope = PolytopeOf(s.collider.shape);
  contact::BroadStatic broad;
  broad.posed = {nullptr, s.polytope.get(), rotation * s.collider.rotation,
                 translation + rotation * s.collider.translation, s.collider.filter};
  broad.radius = contact::BoundingRadius(s.collider.shape);
  broad.lower = broad.posed.t - Vector3::Constant(broad.radius);
  broad.upper = broad.posed.t + Vector3::Constant(broad.radius);
  impl_->statics.push_back(std::move(s));
  impl_->static_broad.push_back(broad);
  // The shapes may have moved with the vector: every posed shape points at its collider again.
  for (std::size_t k = 0; k < impl_->statics.size(); ++k) {
    impl_->static_broad[k].posed.shape = &impl_->statics[k].collider.shape;
  }
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

void ContactWorld::ExcludePair(int a, int b) {
  const int n = static_cast<int>(world_.bodies().size());
  if (a < 0 || b < 0 || a >= n || b >= n || a == b) {
    throw std::invalid_argument("ContactWorld::ExcludePair: bodies " + std::to_string(a) + " and " + std::to_string(b) +
                                " are not two of the world's " + std::to_string(n) + " bodies");
  }
  impl_->excluded.insert({std::min(a, b), std::max(a, b)});
}

const std::vector<Ground>& ContactWorld::grounds() const { return impl_->grounds; }

void ContactWorld::SetPairMaterial(int a, int b, const Material& material) {
  ValidateMaterial(material);
  impl_->pair_materials[{std::min(a, b), std::max(a, b)}] = material;
}

namespace {

// The bodies' velocities after the step's forces, before contact (the kick), into `vel`: each
// body kicked by its wrench `w`, or (an articulated world) as the joints' kick left it, `kicked`
// (v, ω); the velocities at the start of the step into `before_kick`; each body's world inverse
// inertia into `response` (a jointed body's own, for its kinetic energy: impulses act on it
// through the coupling). Returns the largest speed the forces give in one step.
double Kick(const std::vector<RigidBody>& bodies, const std::vector<Wrench>* w,
            const std::vector<internal::Vector6>* kicked, double h, std::vector<contact::Velocities>& vel,
            std::vector<contact::Velocities>& before_kick, contact::BodyResponse& response) {
  const std::size_t nb = bodies.size();
  vel.resize(nb);
  before_kick.resize(nb);
  response.inv_inertia.resize(nb);
  response.inv_mass.resize(nb);
  double kick_speed = 0;
  for (std::size_t i = 0; i < nb; ++i) {
    const RigidBody& b = bodies[i];
    const Matrix3 R = b.Rotation();
    response.inv_inertia[i] = R * b.inertia.cwiseInverse().asDiagonal() * R.transpose();
    response.inv_mass[i] = 1.0 / b.mass;
    before_kick[i] = {b.velocity, b.AngularVelocity()};
    if (kicked != nullptr) {
      vel[i] = {(*kicked)[i].head<3>(), (*kicked)[i].tail<3>()};
      kick_speed = std::max(kick_speed, (vel[i].v - b.velocity).norm());
      continue;
    }
    const Vector3 dv = h / b.mass * (*w)[i].force;
    kick_speed = std::max(kick_speed, dv.norm());
    const Vector3 L = b.angular_momentum + h * (*w)[i].torque;
    vel[i] = {b.velocity + dv, response.inv_inertia[i] * L};
  }
  return kick_speed;
}

int KeyOfStatic(int s) { return -2 - s; }
int KeyOfGround(int g) { return std::numeric_limits<int>::min() + g; }

// What the rows of a step are built from.
struct RowContext {
  const std::vector<RigidBody>& bodies;
  const std::vector<contact::Velocities>& vel;          // after the kick
  const std::vector<contact::Velocities>& before_kick;  // at the start of the step
  double h = 0, bounce_threshold = 0;
};

// A row for each contact point between body a and b (-1: a ground or static body); key_b names b
// in the rows' keys: b itself, KeyOfStatic or KeyOfGround (distinct, so that the warm start and
// the friction state of a body on a ground never pass to the same body on a static body).
// The materials of a pair's contacts: the pair's own (ContactWorld::SetPairMaterial), else its
// colliders' combined, else — at a point on a compound's part that touches with its own — that
// part's combined with the other side's.
struct PairMaterials {
  const Material* pair = nullptr;  ///< SetPairMaterial's, which wins
  const Material* a = nullptr;
  const Material* b = nullptr;
  Material combined;  ///< CombineMaterials(*a, *b)
  const Material& At(const contact::ContactPoint& p, Material& scratch) const {
    if (pair != nullptr) return *pair;
    if (p.material_a == nullptr && p.material_b == nullptr) return combined;
    scratch =
        CombineMaterials(p.material_a != nullptr ? *p.material_a : *a, p.material_b != nullptr ? *p.material_b : *b);
    return scratch;
  }
};

void AppendRows(const RowContext& c, const std::vector<contact::ContactPoint>& points, int a, int b, int key_b,
                const PairMaterials& materials, double slop, std::vector<contact::Row>& rows, ContactStats& stats) {
  Material scratch;
  for (const contact::ContactPoint& p : points) {
    const Material& mat = materials.At(p, scratch);
    contact::Row r;
    r.slop = slop;
    r.a = a;
    r.b = b;
    r.n = p.normal;
    r.ra = p.point - c.bodies[static_cast<std::size_t>(a)].position;
    r.rb = b >= 0 ? Vector3(p.point - c.bodies[static_cast<std::size_t>(b)].position) : Vector3::Zero();
    r.point = p.point;
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
    const double h = c.h;
    const double approach = -r.n.dot(contact::RelativeVelocity(c.vel, r));
    const double closing = -r.n.dot(contact::RelativeVelocity(c.before_kick, r));                   // b
    const double s = std::max(p.separation, 0.0), accel = std::max(0.0, (approach - closing) / h);  // a
    const double e = mat.restitution, impact_squared = closing * std::abs(closing) + 2 * accel * s;
    const double radicand = accel * accel * h * h + e * e * impact_squared - 2 * accel * s;
    const double leave = radicand > 0 ? std::sqrt(radicand) - accel * h : 0.0;
    if (e > 0 && impact_squared > c.bounce_threshold * c.bounce_threshold && p.separation < approach * h && leave > 0) {
      r.target = leave;
    } else {
      r.target = -s / h;
    }
    stats.max_penetration = std::max(stats.max_penetration, -p.separation);
    rows.push_back(r);
  }
  if (!points.empty()) ++stats.pairs;
}

// The drift: positions with the new velocities, the free rotation with the new L, and the
// position correction's pseudo-velocities (if any) on top. Bodies held still stay.
StepStatus DriftBodies(std::vector<RigidBody>& bodies, const std::vector<contact::Velocities>& vel,
                       const std::vector<contact::Velocities>& pseudo, const std::vector<bool>& asleep,
                       const std::vector<double>& radius, double h, ContactStats& stats) {
  StepStatus status;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    RigidBody& b = bodies[k];
    if (asleep[k]) {
      b.velocity.setZero();
      b.angular_momentum.setZero();
      continue;
    }
    const RigidBody before = b;
    b.velocity = vel[k].v;
    b.angular_momentum = b.WorldInertia() * vel[k].w;
    b.position += h * b.velocity;
    if (!internal::MidpointRotation(b, h)) {
      b = before;
      status.ok = false;
      status.body = static_cast<int>(k);
      status.message = "the free rotation of body " + std::to_string(k) +
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
      stats.pushed = std::max(stats.pushed, moved.norm() + angle * radius[k]);
    }
  }
  return status;
}

// The drift of an articulated world: the impulses the solve found (and the push-out's) as
// wrenches on the bodies, handed to the joints, which finish the step.
StepStatus DriftJointed(internal::Articulation& jointed, const std::vector<contact::Row>& rows,
                        const std::vector<contact::Patch>& patches, const std::vector<contact::Velocities>& pseudo,
                        const std::vector<double>& radius, double h, std::vector<RigidBody>& bodies,
                        ContactStats& stats) {
  std::vector<Wrench> impulses(bodies.size()), pushes(bodies.size());
  auto add = [](std::vector<Wrench>& w, int body, const Vector3& f, const Vector3& tau) {
    if (body < 0) return;
    w[static_cast<std::size_t>(body)].force += f;
    w[static_cast<std::size_t>(body)].torque += tau;
  };
  for (const contact::Row& r : rows) {
    add(impulses, r.a, r.lambda_n * r.n, r.lambda_n * r.ang_a);
    add(impulses, r.b, -r.lambda_n * r.n, -r.lambda_n * r.ang_b);
    if (r.push > 0) {
      add(pushes, r.a, r.push * r.n, r.push * r.ang_a);
      add(pushes, r.b, -r.push * r.n, -r.push * r.ang_b);
    }
  }
  for (const contact::Patch& p : patches) {
    const Vector3 f = p.t1 * p.lambda[0] + p.t2 * p.lambda[1];
    add(impulses, p.a, f, p.ang_a * p.lambda);
    add(impulses, p.b, -f, -(p.ang_b * p.lambda));
  }
  StepStatus status;
  if (!jointed.ContactFinish(impulses, pushes, h, bodies)) {
    status.ok = false;
    status.message =
        "the joints' step through contact failed (a configuration whose mass matrix is not positive "
        "definite, or a state no longer finite)";
    return status;
  }
  for (std::size_t k = 0; k < pseudo.size(); ++k) {
    stats.pushed = std::max(stats.pushed, h * (pseudo[k].v.norm() + pseudo[k].w.norm() * radius[k]));
  }
  return status;
}

double KineticEnergy(const std::vector<RigidBody>& bodies, const std::vector<contact::Velocities>& vel) {
  double e = 0;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const RigidBody& b = bodies[k];
    e += 0.5 * b.mass * vel[k].v.squaredNorm() + 0.5 * vel[k].w.dot(b.WorldInertia() * vel[k].w);
  }
  return e;
}

}  // namespace

StepStatus ContactWorld::Step(double h) {
  if (!(h > 0) || !std::isfinite(h)) return world_.Step(h);  // throws, naming the step
  Impl& m = *impl_;
  if (m.grounds.empty() && m.statics.empty() &&
      std::find(m.collides.begin(), m.collides.end(), true) == m.collides.end()) {
    stats_ = {};
    return world_.Step(h);  // nothing can touch: the world's integrator, at no extra cost
  }
  std::vector<RigidBody>& bodies = world_.bodies();
  const int nb = static_cast<int>(bodies.size());
  stats_ = {};
  // 1. The kick: velocities after this step's forces, before contact.
  internal::Articulation* const jointed = world_.articulation_.get();
  double kick_speed = 0;
  if (jointed != nullptr) {
    if (!jointed->ContactKick(world_.forces(), world_.time(), h, m.kicked)) {
      StepStatus failure;
      failure.ok = false;
      failure.message = "the joints' mass matrix is not positive definite at t = " + std::to_string(world_.time());
      return failure;
    }
    jointed->Classify(m.coupling);
    kick_speed = Kick(bodies, nullptr, &m.kicked, h, m.vel, m.before_kick, m.response);
    m.response.coupling = &m.coupling;
  } else {
    internal::StepContext context(bodies, world_.forces(), m.scratch, world_.num_threads());
    context.ComputeWrenches(world_.time());
    kick_speed = Kick(bodies, &context.wrenches(), nullptr, h, m.vel, m.before_kick, m.response);
    m.response.coupling = nullptr;
  }
  const double bounce_threshold =
      options_.restitution_threshold > 0 ? options_.restitution_threshold : 2 * kick_speed + 1e-12;
  // 2. Contacts at the start-of-step positions, within each body's reach in this step.
  const std::vector<double>& radius = m.radii;
  std::vector<contact::Posed> posed(static_cast<std::size_t>(nb));
  std::vector<contact::BroadBody> broad(static_cast<std::size_t>(nb));
  for (std::size_t k = 0; k < posed.size(); ++k) {
    posed[k] = PoseOf(m.colliders[k], m.polytopes[k].get(), bodies[k]);
    const Vector3 c = posed[k].t - bodies[k].position;
    const double reach = h * (m.vel[k].v.norm() + m.vel[k].w.norm() * (radius[k] + c.norm())) + 1e-9 * radius[k];
    broad[k] = {&posed[k], radius[k], reach, m.collides[k]};
  }
  m.rows.clear();
  m.patches.clear();
  auto material_of = [&](int a, int b, const Material& ma, const Material& mb) {
    PairMaterials out;
    const auto it = m.pair_materials.find({std::min(a, b), std::max(a, b)});
    if (it != m.pair_materials.end()) out.pair = &it->second;
    out.a = &ma;
    out.b = &mb;
    if (out.pair == nullptr) out.combined = CombineMaterials(ma, mb);
    return out;
  };
  const RowContext row_context{bodies, m.vel, m.before_kick, h, bounce_threshold};
  std::vector<contact::ContactPoint> points;
  for (std::size_t k = 0; k < posed.size(); ++k) {
    if (!m.collides[k]) continue;
    if (jointed != nullptr && !m.coupling.movable[k]) continue;  // welded to the world
    for (const Ground& g : m.grounds) {
      if (g.normal.dot(posed[k].t) - g.offset - radius[k] >= broad[k].reach) continue;
      points.clear();
      contact::CollideGround(posed[k], g.normal, g.offset, g.filter, broad[k].reach, points);
      const int i = static_cast<int>(k);
      AppendRows(row_context, points, i, -1, KeyOfGround(static_cast<int>(&g - m.grounds.data())),
                 material_of(i, -1, m.colliders[k].material, g.material),
                 Slop(m.colliders[k].shape, radius[k], nullptr, -1), m.rows, stats_);
    }
  }
  const std::vector<contact::BroadStatic>& statics = m.static_broad;
  std::vector<contact::Candidate> candidates = contact::FindCandidates(broad, statics);
  if (!m.excluded.empty()) {
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [&](const contact::Candidate& p) {
                                      return p.b >= 0 && m.excluded.count({std::min(p.a, p.b), std::max(p.a, p.b)});
                                    }),
                     candidates.end());
  }
  if (jointed != nullptr) {
    const contact::Coupling& c = m.coupling;
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [&](const contact::Candidate& p) {
                                      const auto a = static_cast<std::size_t>(p.a);
                                      if (p.b < 0) return !c.movable[a];
                                      const auto b = static_cast<std::size_t>(p.b);
                                      if (!c.movable[a] && !c.movable[b]) return true;
                                      if (c.tree[a] != c.tree[b]) return false;
                                      return !options_.self_collision || c.parent[a] == p.b || c.parent[b] == p.a;
                                    }),
                     candidates.end());
  }
  std::vector<contact::PairQuery> queries;
  queries.reserve(candidates.size());
  for (const contact::Candidate& c : candidates) {
    queries.push_back(
        {&posed[static_cast<std::size_t>(c.a)],
         c.b >= 0 ? &posed[static_cast<std::size_t>(c.b)] : &statics[static_cast<std::size_t>(-1 - c.b)].posed,
         c.margin});
  }
  // The narrow phase: each pair on its own, then the rows in the pairs' order, so the step does
  // not depend on the thread count.
  std::vector<std::vector<contact::ContactPoint>>& found = m.found;
  std::vector<char>& supported = m.supported;
  contact::CollidePairs(queries, m.WorkersFor(world_.num_threads()), found, supported);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const int a = candidates[c].a, b = candidates[c].b;
    const auto ka = static_cast<std::size_t>(a);
    if (!supported[c]) {
      std::ostringstream msg;
      msg << "contact between a " << ShapeName(*posed[ka].shape) << " (body " << a << ") and a "
          << ShapeName(*queries[c].b->shape)
          << (b >= 0 ? " (body " + std::to_string(b) + ")" : std::string(" (static)")) << " is not supported yet";
      StepStatus failure;
      failure.ok = false;
      failure.message = msg.str();
      return failure;
    }
    const Material& mb = b >= 0 ? m.colliders[static_cast<std::size_t>(b)].material
                                : m.statics[static_cast<std::size_t>(-1 - b)].collider.material;
    AppendRows(row_context, found[c], a, b >= 0 ? b : -1, b >= 0 ? b : KeyOfStatic(-1 - b),
               material_of(a, b >= 0 ? b : -1, m.colliders[ka].material, mb),
               Slop(*posed[ka].shape, radius[ka], queries[c].b->shape,
                    b >= 0 ? radius[static_cast<std::size_t>(b)] : statics[static_cast<std::size_t>(-1 - b)].radius),
               m.rows, stats_);
  }
  if (jointed != nullptr && !m.rows.empty()) {  // the touched links' responses
    std::vector<char> touched(static_cast<std::size_t>(nb), 0);
    for (const contact::Row& r : m.rows) {
      touched[static_cast<std::size_t>(r.a)] = 1;
      if (r.b >= 0) touched[static_cast<std::size_t>(r.b)] = 1;
    }
    jointed->Respond(m.coupling, touched);
  }
  if (jointed != nullptr) {
    // A contact whose normal no motion of the trees changes (a hinged link pressed along its
    // axis) takes no impulse: its row is left out (its response would be singular).
    m.rows.erase(std::remove_if(m.rows.begin(), m.rows.end(),
                                [&](const contact::Row& r) {
                                  const double own =
                                      m.response.inv_mass[static_cast<std::size_t>(r.a)] +
                                      (r.b >= 0 ? m.response.inv_mass[static_cast<std::size_t>(r.b)] : 0);
                                  return !(m.coupling.NormalResponse(r) > 1e-9 * own);
                                }),
                 m.rows.end());
  }
  stats_.contacts = static_cast<int>(m.rows.size());
  if (m.rows.empty()) {  // free flight: the world's own integrator, bit for bit
    m.cache = {};
    std::fill(m.sleep.asleep.begin(), m.sleep.asleep.end(), false);
    std::fill(m.sleep.still_for.begin(), m.sleep.still_for.end(), 0.0);
    return world_.Step(h);
  }
  // 3. Islands: a sleeping island wakes as a whole when an awake body touches it; bodies still
  // asleep are held still (no kick, as heavy as the ground), and contacts among them alone are
  // not solved (their impulses are kept for when the island wakes).
  contact::Islands islands(nb, m.rows);
  if (jointed != nullptr) {
    for (const std::vector<int>& tree : m.coupling.members) {
      for (const int k : tree) islands.Join(k, tree.front());
    }
  }
  contact::WakeTouched(islands, m.sleep);
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    if (m.sleep.asleep[k]) {
      m.vel[k] = {Vector3::Zero(), Vector3::Zero()};
      m.response.inv_inertia[k] = Matrix3::Zero();
      m.response.inv_mass[k] = 0;
    }
  }
  contact::ContactCache kept;
  m.rows.erase(std::remove_if(m.rows.begin(), m.rows.end(),
                              [&](const contact::Row& r) {
                                const bool still = m.sleep.asleep[static_cast<std::size_t>(r.a)] &&
                                                   (r.b < 0 || m.sleep.asleep[static_cast<std::size_t>(r.b)]);
                                if (still) {
                                  const auto it = m.cache.rows.find(r.key);
                                  if (it != m.cache.rows.end()) kept.rows.insert(*it);
                                  const std::pair<int, int> pair{std::get<0>(r.key), std::get<1>(r.key)};
                                  const auto patches = m.cache.patches.find(pair);
                                  if (patches != m.cache.patches.end()) kept.patches.insert(*patches);
                                }
                                return still;
                              }),
               m.rows.end());
  // 4. The impulses.
  std::vector<contact::Patch>& patches = m.patches;
  patches = contact::PreparePatches(m.rows, m.cache, m.vel, m.response, bounce_threshold);
  const double energy_before = KineticEnergy(bodies, m.vel);
  std::vector<int> island(bodies.size());
  for (int k = 0; k < nb; ++k) island[static_cast<std::size_t>(k)] = islands.Find(k);
  const int sweeps = options_.max_iterations > 0 ? options_.max_iterations : (options_.exact ? 64 : 32);
  const contact::SolveSettings settings{sweeps, options_.speed_tolerance, options_.exact, options_.tolerance};
  stats_.iterations = contact::SolveImpulses(m.rows, patches, m.vel, m.response, contact::SupportLevels(nb, m.rows),
                                             island, settings, m.WorkersFor(world_.num_threads()));
  m.cache = std::move(kept);
  contact::StoreImpulses(m.rows, patches, m.cache);
  stats_.dissipated = energy_before - KineticEnergy(bodies, m.vel);
  // 5. Position correction of overlap beyond each contact's slop, then 6. the drift.
  const std::vector<contact::Velocities> pseudo = contact::PushOutVelocities(m.rows, nb, h, settings);
  StepStatus status = jointed != nullptr ? DriftJointed(*jointed, m.rows, patches, pseudo, radius, h, bodies, stats_)
                                         : DriftBodies(bodies, m.vel, pseudo, m.sleep.asleep, radius, h, stats_);
  if (!status.ok) return status;
  world_.set_time(world_.time() + h);
  if (options_.sleeping && jointed == nullptr) {
    contact::FallAsleep(islands, m.rows, m.collides, radius, options_.sleep_speed, options_.sleep_time, h, bodies,
                        m.sleep);
    stats_.sleeping = static_cast<int>(std::count(m.sleep.asleep.begin(), m.sleep.asleep.end(), true));
  }
  const auto [bad, quantity] = world_.FirstNonFinite();
  if (bad >= 0) {
    status.ok = false;
    status.diverged = true;
    status.body = bad;
    status.message = "diverged at t = " + std::to_string(world_.time()) + " s: body " + std::to_string(bad) + "'s " +
                     quantity + " is no longer finite";
  }
  return status;
}

std::vector<ContactReport> ContactWorld::Contacts() const {
  const Impl& m = *impl_;
  std::vector<ContactReport> out;
  out.reserve(m.rows.size());
  for (const contact::Row& r : m.rows) out.push_back({r.a, r.b, r.point, r.n, r.lambda_n * r.n, Vector3::Zero()});
  for (const contact::Patch& p : m.patches) {  // the friction, shared by the patch's points
    double sum = 0;
    for (int i = p.first; i < p.first + p.count; ++i) sum += m.rows[static_cast<std::size_t>(i)].lambda_n;
    // The solver's friction: a force at the anchor and a turn about the normal (Jacobian columns
    // t1, t2 at the anchor and ρ n).
    const Vector3 friction = p.lambda.x() * p.t1 + p.lambda.y() * p.t2, twist = p.rho * p.lambda.z() * p.n;
    for (int i = p.first; i < p.first + p.count; ++i) {
      ContactReport& c = out[static_cast<std::size_t>(i)];
      const double share = sum > 0 ? m.rows[static_cast<std::size_t>(i)].lambda_n / sum : 1.0 / p.count;
      c.impulse += share * friction;
      c.torque = share * (twist + (p.anchor - c.point).cross(friction));
    }
  }
  return out;
}

bool ContactWorld::asleep(int k) const {
  const std::vector<bool>& a = impl_->sleep.asleep;
  return k >= 0 && static_cast<std::size_t>(k) < a.size() && a[static_cast<std::size_t>(k)];
}

}  // namespace dynamics
