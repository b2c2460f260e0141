// ContactWorld (contact.h): its bodies, statics and grounds (the model), and the step, which runs
// the stages of step_stages.h in order — kick, detect, islands, solve, drift, sleep.

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "dynamics/contact.h"
#include "massprops/text.h"
#include "mesh_field.h"
#include "polytope.h"
#include "step_stages.h"

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
    if (convex->polytope != nullptr) return convex->polytope;
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

}  // namespace

// The world's model, the state kept between steps and the step's scratch (step_stages.h).
struct ContactWorld::Impl : contact::Model, contact::State, contact::Scratch {};

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
  require(o.reuse_distance >= 0 && o.reuse_distance <= 1e-3, "reuse_distance must be 0 (off) to 10^-3");
}
ContactWorld::~ContactWorld() = default;
ContactWorld::ContactWorld(ContactWorld&&) noexcept = default;
ContactWorld& ContactWorld::operator=(ContactWorld&&) noexcept = default;

std::optional<MaterialFault> CheckMaterial(const Material& m) {
  auto coefficient = [](double mu) { return std::isfinite(mu) && mu >= 0; };
  if (!coefficient(m.static_friction)) return MaterialFault{"static_friction", "must be finite and non-negative"};
  if (!coefficient(m.kinetic_friction)) return MaterialFault{"kinetic_friction", "must be finite and non-negative"};
  if (m.kinetic_friction > m.static_friction) {
    return MaterialFault{"kinetic_friction", "must not exceed static_friction (" +
                                                 massprops::FormatDouble(m.static_friction, "%.6g") + ")"};
  }
  if (!(m.restitution >= 0 && m.restitution <= 1)) return MaterialFault{"restitution", "lies between 0 and 1"};
  return std::nullopt;
}

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
  if (const auto fault = CheckMaterial(m))
    throw std::invalid_argument("material: " + fault->field + " " + fault->problem);
}
// The collider's material and, when its parts touch with their own, theirs.
void ValidateMaterials(const Collider& c) {
  ValidateMaterial(c.material);
  if (const auto* compound = std::get_if<shape::Compound>(&c.shape); compound != nullptr && compound->part_materials) {
    for (const Collider& part : compound->parts) ValidateMaterial(part.material);
  }
}

// What a shape needs before it collides: a mesh collider's field, built here when the shape came
// without it (on the world's threads); a compound's parts' fields and polytopes.
void PrepareShape(Collider& c, int threads) {
  if (auto* mesh = std::get_if<shape::Mesh>(&c.shape); mesh != nullptr && mesh->field == nullptr) {
    mesh->field = contact::BuildMeshField(*mesh, threads);
  }
  if (auto* compound = std::get_if<shape::Compound>(&c.shape)) {
    compound->polytopes.clear();
    for (Collider& part : compound->parts) {
      PrepareShape(part, threads);
      compound->polytopes.push_back(PolytopeOf(part.shape));
    }
  }
}

// Every pair the new shape could form has a contact routine (narrow_phase.cpp's table), or the
// shape is refused here rather than in the middle of a run.
void RefuseUnsupportedPairs(const contact::Model& m, const Shape& s) {
  auto check = [&](const Shape& other, const std::string& whose) {
    if (contact::SupportsPair(s, other)) return;
    throw std::invalid_argument(std::string("a ") + ShapeName(s) + " cannot touch the " + ShapeName(other) + " of " +
                                whose + ": that pair of shapes has no contact routine");
  };
  for (std::size_t k = 0; k < m.colliders.size(); ++k) {
    if (m.collides[k]) check(m.colliders[k].shape, "body " + std::to_string(k));
  }
  for (std::size_t k = 0; k < m.statics.size(); ++k)
    check(m.statics[k].collider.shape, "static body " + std::to_string(k));
}
}  // namespace

int ContactWorld::AddBody(const RigidBody& body, Collider collider) {
  impl_->manifolds.Clear();  // (kept points name the colliders' part materials, which may move)
  PrepareShape(collider, world_.num_threads());
  contact::ValidateShape(collider.shape);
  ValidateMaterials(collider);
  RefuseUnsupportedPairs(*impl_, collider.shape);
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
  impl_->manifolds.Clear();  // (kept points name the colliders' part materials, which may move)
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
  impl_->manifolds.Clear();  // (kept points name the colliders' part materials, which may move)
  PrepareShape(collider, world_.num_threads());
  contact::ValidateShape(collider.shape);
  ValidateMaterials(collider);
  RefuseUnsupportedPairs(*impl_, collider.shape);
  if (!rotation.allFinite() || std::abs(rotation.determinant() - 1) > 1e-9 ||
      !(rotation.transpose() * rotation).isApprox(Matrix3::Identity(), 1e-9) || !translation.allFinite()) {
    throw std::invalid_argument("a static body's placement needs a rotation and a finite translation");
  }
  contact::StaticBody s;
  s.collider = std::move(collider);
  s.polytope = PolytopeOf(s.collider.shape);
  contact::BroadStatic broad;
  broad.posed = {nullptr, s.polytope.get(), rotation * s.collider.rotation,
                 translation + rotation * s.collider.translation, s.collider.filter};
  broad.radius = contact::BoundingRadius(s.collider.shape);
  broad.lower = broad.posed.t - Vector3::Constant(broad.radius);
  broad.upper = broad.posed.t + Vector3::Constant(broad.radius);
  if (s.polytope != nullptr) {
    s.placed = std::make_unique<contact::PlacedPolytope>();
    contact::PlacePolytope(*s.polytope, broad.posed, *s.placed);
    broad.posed.placed = s.placed.get();
  }
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

StepStatus ContactWorld::Step(double h) {
  if (!(h > 0) || !std::isfinite(h)) return world_.Step(h);  // throws, naming the step
  Impl& m = *impl_;
  stats_ = {};
  if (m.grounds.empty() && m.statics.empty() &&
      std::find(m.collides.begin(), m.collides.end(), true) == m.collides.end()) {
    return world_.Step(h);  // nothing can touch: the world's integrator, at no extra cost
  }
  world_.Place();
  const contact::StepInput in{
      world_.bodies(), world_.forces(), world_.articulation_.get(), options_, world_.time(), h, world_.num_threads()};
  if (!contact::Kick(in, m)) {
    StepStatus failure;
    failure.ok = false;
    failure.message = "the joints' mass matrix is not positive definite at t = " + std::to_string(world_.time());
    return failure;
  }
  if (const StepStatus detected = contact::Detect(in, m, m, m, stats_); !detected.ok) return detected;
  if (m.rows.empty()) {  // free flight: the world's own integrator, bit for bit
    contact::Forget(m);
    return world_.Step(h);
  }
  contact::Islands& islands = contact::HoldSleeping(in, m, m);
  contact::Solve(in, islands, m, m, stats_);
  StepStatus status = contact::Drift(in, m, m, m, stats_);
  if (!status.ok) return status;
  world_.set_time(world_.time() + h);
  contact::Sleep(in, m, islands, m, m, stats_);
  const auto [bad, quantity] = world_.FirstNonFinite();
  if (bad >= 0) return internal::Diverged(world_.time(), bad, quantity);
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
