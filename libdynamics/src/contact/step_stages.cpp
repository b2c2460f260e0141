// The contact step's stages (step_stages.h), in the order ContactWorld::Step runs them, with the
// helpers they share: the kick, the rows of a pair's contact points (materials, restitution), the
// drift of free and of jointed bodies.

#include "step_stages.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include "mesh_field.h"
#include "position_correction.h"

namespace dynamics::contact {
namespace {

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

contact::Posed PoseOf(const Collider& c, const contact::Polytope* polytope, const RigidBody& b) {
  const Matrix3 R = b.Rotation();
  return {&c.shape, polytope, R * c.rotation, b.position + R * c.translation, c.filter};
}

// The bodies' velocities after the step's forces, before contact (the kick), into `vel`: each
// body kicked by its wrench `w`, or (an articulated world) as the joints' kick left it, `kicked`
// (v, ω); the velocities at the start of the step into `before_kick`; each body's world inverse
// inertia into `response` (a jointed body's own, for its kinetic energy: impulses act on it
// through the coupling). Returns the largest speed the forces give in one step.
double KickBodies(const std::vector<RigidBody>& bodies, const std::vector<Wrench>* w,
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
                const PairMaterials& materials, double slop, bool points_kept, std::vector<contact::Row>& rows,
                ContactStats& stats) {
  Material scratch;
  for (const contact::ContactPoint& p : points) {
    const Material& mat = materials.At(p, scratch);
    contact::Row r;
    r.slop = slop;
    r.kept = points_kept;
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
StepStatus DriftJointed(internal::Articulation& jointed, Scratch& s, const std::vector<double>& radius, double h,
                        std::vector<RigidBody>& bodies, ContactStats& stats) {
  const std::vector<contact::Row>& rows = s.rows;
  const std::vector<contact::Patch>& patches = s.patches;
  const std::vector<contact::Velocities>& pseudo = s.pseudo;
  std::vector<Wrench>& impulses = s.impulses;
  std::vector<Wrench>& pushes = s.pushes;
  impulses.assign(bodies.size(), Wrench{});
  pushes.assign(bodies.size(), Wrench{});
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

bool Kick(const StepInput& in, Scratch& s) {
  double kick_speed = 0;
  if (in.jointed != nullptr) {
    if (!in.jointed->ContactKick(in.forces, in.time, in.h, s.kicked)) return false;
    in.jointed->Classify(s.coupling);
    kick_speed = KickBodies(in.bodies, nullptr, &s.kicked, in.h, s.vel, s.before_kick, s.response);
    s.response.coupling = &s.coupling;
  } else {
    internal::StepContext context(in.bodies, in.forces, s.step_scratch, in.threads);
    context.ComputeWrenches(in.time);
    kick_speed = KickBodies(in.bodies, &context.wrenches(), nullptr, in.h, s.vel, s.before_kick, s.response);
    s.response.coupling = nullptr;
  }
  s.bounce_threshold = in.options.restitution_threshold > 0 ? in.options.restitution_threshold : 2 * kick_speed + 1e-12;
  return true;
}

namespace {

// Each body's collider in the world and its reach in this step.
void PoseBodies(const StepInput& in, const Model& model, Scratch& s) {
  const std::size_t nb = in.bodies.size();
  s.posed.assign(nb, Posed{});
  s.placed.resize(nb);  // (their arrays kept from step to step; placed in PairRows, when in a pair)
  s.broad.assign(nb, BroadBody{});
  for (std::size_t k = 0; k < nb; ++k) {
    const RigidBody& b = in.bodies[k];
    s.posed[k] = PoseOf(model.colliders[k], model.polytopes[k].get(), b);
    const Vector3 c = s.posed[k].t - b.position;
    const double r = model.radii[k];
    const double reach = in.h * (s.vel[k].v.norm() + s.vel[k].w.norm() * (r + c.norm())) + 1e-9 * r;
    s.broad[k] = {&s.posed[k], r, reach, model.collides[k]};
  }
}

// The materials of contacts between bodies a and b (-1: a ground or static body).
PairMaterials MaterialsOf(const Model& model, int a, int b, const Material& ma, const Material& mb) {
  PairMaterials out;
  const auto it = model.pair_materials.find({std::min(a, b), std::max(a, b)});
  if (it != model.pair_materials.end()) out.pair = &it->second;
  out.a = &ma;
  out.b = &mb;
  if (out.pair == nullptr) out.combined = CombineMaterials(ma, mb);
  return out;
}

// Each body's rows against the grounds (a body welded to the world has none).
void GroundRows(const StepInput& in, const Model& model, State& state, Scratch& s, ContactStats& stats) {
  const RowContext row_context{in.bodies, s.vel, s.before_kick, in.h, s.bounce_threshold};
  std::vector<ContactPoint>& points = s.points;
  const std::size_t grounds = model.grounds.size();
  if (s.ground_scans.size() < s.posed.size() * grounds) s.ground_scans.resize(s.posed.size() * grounds);
  const std::vector<bool>& asleep = state.sleep.asleep;
  state.asleep_ground_rows.resize(s.posed.size());
  state.asleep_ground_known.resize(s.posed.size(), 0);
  for (std::size_t k = 0; k < s.posed.size(); ++k) {
    if (!model.collides[k]) continue;
    if (in.jointed != nullptr && !s.coupling.movable[k]) continue;  // welded to the world
    const bool sleeps = k < asleep.size() && asleep[k];
    std::vector<Row>& known = state.asleep_ground_rows[k];
    if (sleeps && state.asleep_ground_known[k]) {  // as found in its first step asleep
      s.rows.insert(s.rows.end(), known.begin(), known.end());
      continue;
    }
    const std::size_t first_row = s.rows.size();
    for (const Ground& g : model.grounds) {
      if (g.normal.dot(s.posed[k].t) - g.offset - model.radii[k] >= s.broad[k].reach) continue;
      points.clear();
      const auto gi = static_cast<std::size_t>(&g - model.grounds.data());
      CollideGround(s.posed[k], g.normal, g.offset, g.filter, s.broad[k].reach, points,
                    &s.ground_scans[k * grounds + gi]);
      const int i = static_cast<int>(k);
      AppendRows(row_context, points, i, -1, KeyOfGround(static_cast<int>(gi)),
                 MaterialsOf(model, i, -1, model.colliders[k].material, g.material),
                 Slop(model.colliders[k].shape, model.radii[k], nullptr, -1), false, s.rows, stats);
    }
    state.asleep_ground_known[k] = sleeps;
    known.assign(sleeps ? s.rows.begin() + static_cast<std::ptrdiff_t>(first_row) : s.rows.end(), s.rows.end());
  }
}

// The pairs whose bounds meet within their reach, less the excluded pairs and, in an articulated
// world, the pairs its joints rule out (links of one tree, unless self-collision is asked for,
// and never a joint's parent and child; bodies welded to the world).
const std::vector<Candidate>& CandidatePairs(const StepInput& in, const Model& model, Scratch& s) {
  std::vector<Candidate>& candidates = s.candidates;
  FindCandidates(s.broad, model.static_broad, candidates, s.intervals);
  if (!model.excluded.empty()) {
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [&](const Candidate& p) {
                                      return p.b >= 0 && model.excluded.count({std::min(p.a, p.b), std::max(p.a, p.b)});
                                    }),
                     candidates.end());
  }
  if (in.jointed != nullptr) {
    const Coupling& c = s.coupling;
    const bool self_collision = in.options.self_collision;
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [&](const Candidate& p) {
                                      const auto a = static_cast<std::size_t>(p.a);
                                      if (p.b < 0) return !c.movable[a];
                                      const auto b = static_cast<std::size_t>(p.b);
                                      if (!c.movable[a] && !c.movable[b]) return true;
                                      if (c.joint_tree[a] != c.joint_tree[b]) return false;
                                      return !self_collision || c.parent[a] == p.b || c.parent[b] == p.a;
                                    }),
                     candidates.end());
  }
  return candidates;
}

// Whether a shape's contacts may be kept from step to step: not a mesh's (nor a compound's with a
// mesh part): their points are samples of a distance field, whose choice among many nearly equal
// candidates moves with the pose; kept, they changed a settling pour's energy (measured: steps
// of 1.2·10⁻⁶ of it, against at most 4·10⁻⁷ fresh).
bool MayKeepPoints(const Shape& shape) {
  if (std::holds_alternative<shape::Mesh>(shape)) return false;
  if (const auto* c = std::get_if<shape::Compound>(&shape)) {
    for (const Collider& part : c->parts) {
      if (!MayKeepPoints(part.shape)) return false;
    }
  }
  return true;
}

// The narrow phase: each pair on its own, then the rows in the pairs' order, so the step does not
// depend on the thread count. A pair that has barely moved since its points were found takes
// them again (ManifoldCache; ContactOptions::reuse_distance); the others run the narrow phase
// with a margin wide enough for their points to serve the next steps, and keep them.
StepStatus PairRows(const StepInput& in, const Model& model, const std::vector<Candidate>& candidates, State& state,
                    Scratch& s, ContactStats& stats) {
  const std::vector<BroadStatic>& statics = model.static_broad;
  const double reuse = in.options.exact ? 0.0 : in.options.reuse_distance;
  ManifoldCache& kept = state.manifolds;
  auto radius = [&](int k) {
    return k >= 0 ? model.radii[static_cast<std::size_t>(k)] : statics[static_cast<std::size_t>(-1 - k)].radius;
  };
  auto posed = [&](int k) -> const Posed& {
    return k >= 0 ? s.posed[static_cast<std::size_t>(k)] : statics[static_cast<std::size_t>(-1 - k)].posed;
  };
  // A pair's points are kept only while it moved, over the last step, by at most a hundred gates
  // (the velocities before this step's kick: gravity's kick alone is 10 µm a step): a faster pair
  // would pass the gate in a step or two, and keeping its points would only cost (a falling pile:
  // 5 %).
  constexpr double kKeptMotion = 100;
  auto motion = [&](int a, int b) {
    const Velocities& va = s.before_kick[static_cast<std::size_t>(a)];
    const Velocities none{Vector3::Zero(), Vector3::Zero()};
    const Velocities& vb = b >= 0 ? s.before_kick[static_cast<std::size_t>(b)] : none;
    return in.h * ((va.v - vb.v).norm() + (va.w.norm() + vb.w.norm()) * (radius(a) + radius(b)));
  };
  // (found and fresh indexed by candidate, as the pairs are: their points' arrays keep their sizes.)
  s.found.resize(candidates.size());
  s.keep.assign(candidates.size(), 0);
  std::vector<PairQuery>& queries = s.queries;
  queries.clear();
  state.sample_bounds.Begin(candidates.size());
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const int a = candidates[c].a, b = candidates[c].b;
    const double margin = candidates[c].margin, gate = reuse * (radius(a) + radius(b));
    s.keep[c] = gate > 0 && motion(a, b) <= kKeptMotion * gate && MayKeepPoints(*posed(a).shape) &&
                MayKeepPoints(*posed(b).shape);
    s.found[c].clear();
    if (s.keep[c] && kept.Reuse(a, b, posed(a), posed(b), radius(b), margin, gate, s.found[c])) {
      ++stats.reused;
      queries.push_back({});  // (none: CollidePairs passes it by)
      continue;
    }
    // The polytope of each body in a pair placed once for the step (not of a body alone on the
    // ground: it needs none, and a hull of hundreds of faces costs a drop several µs a step).
    for (const int k : {a, b}) {
      if (k < 0) continue;
      Posed& p = s.posed[static_cast<std::size_t>(k)];
      if (p.polytope == nullptr || p.placed != nullptr) continue;
      PlacePolytope(*p.polytope, p, s.placed[static_cast<std::size_t>(k)]);
      p.placed = &s.placed[static_cast<std::size_t>(k)];
    }
    const bool meshes =
        std::holds_alternative<shape::Mesh>(*posed(a).shape) && std::holds_alternative<shape::Mesh>(*posed(b).shape);
    queries.push_back({&posed(a), &posed(b), s.keep[c] ? ManifoldCache::WideMargin(margin, gate) : margin,
                       meshes ? state.sample_bounds.Slot(a, b) : nullptr});
  }
  CollidePairs(queries, s.WorkersFor(in.threads), s.fresh);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (queries[c].a == nullptr) continue;
    if (s.keep[c]) {
      kept.Keep(candidates[c].a, candidates[c].b, *queries[c].a, *queries[c].b, queries[c].margin, s.fresh[c]);
    }
    for (const ContactPoint& p : s.fresh[c]) {
      if (p.separation < candidates[c].margin) s.found[c].push_back(p);
    }
  }
  kept.Flip();
  state.sample_bounds.Flip();
  const RowContext row_context{in.bodies, s.vel, s.before_kick, in.h, s.bounce_threshold};
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const int a = candidates[c].a, b = candidates[c].b;
    const auto ka = static_cast<std::size_t>(a);
    const Material& mb = b >= 0 ? model.colliders[static_cast<std::size_t>(b)].material
                                : model.statics[static_cast<std::size_t>(-1 - b)].collider.material;
    AppendRows(row_context, s.found[c], a, b >= 0 ? b : -1, b >= 0 ? b : KeyOfStatic(-1 - b),
               MaterialsOf(model, a, b >= 0 ? b : -1, model.colliders[ka].material, mb),
               Slop(*s.posed[ka].shape, model.radii[ka], posed(b).shape, radius(b)), queries[c].a == nullptr, s.rows,
               stats);
  }
  return {};
}

// An articulated world's rows: the touched links' responses through their trees; a contact whose
// normal no motion of the trees changes (a hinged link pressed along its axis) takes no impulse,
// and its row is left out (its response would be singular).
void JointedRows(const StepInput& in, Scratch& s) {
  if (!s.rows.empty()) {
    std::vector<char>& touched = s.touched;
    touched.assign(in.bodies.size(), 0);
    for (const Row& r : s.rows) {
      touched[static_cast<std::size_t>(r.a)] = 1;
      if (r.b >= 0) touched[static_cast<std::size_t>(r.b)] = 1;
    }
    in.jointed->Respond(s.coupling, touched);
  }
  s.rows.erase(std::remove_if(s.rows.begin(), s.rows.end(),
                              [&](const Row& r) {
                                const double own = s.response.inv_mass[static_cast<std::size_t>(r.a)] +
                                                   (r.b >= 0 ? s.response.inv_mass[static_cast<std::size_t>(r.b)] : 0);
                                return !(s.coupling.NormalResponse(r) > 1e-9 * own);
                              }),
               s.rows.end());
}

}  // namespace

StepStatus Detect(const StepInput& in, const Model& model, State& state, Scratch& s, ContactStats& stats) {
  PoseBodies(in, model, s);
  s.rows.clear();
  s.patches.clear();
  GroundRows(in, model, state, s, stats);
  const StepStatus status = PairRows(in, model, CandidatePairs(in, model, s), state, s, stats);
  if (!status.ok) return status;
  if (in.jointed != nullptr) JointedRows(in, s);
  stats.contacts = static_cast<int>(s.rows.size());
  return status;
}

void Forget(State& state) {
  state.cache.Clear();
  state.asleep_ground_rows.clear();
  state.asleep_ground_known.clear();
  std::fill(state.sleep.asleep.begin(), state.sleep.asleep.end(), false);
  std::fill(state.sleep.still_for.begin(), state.sleep.still_for.end(), 0.0);
}

Islands& HoldSleeping(const StepInput& in, State& state, Scratch& s) {
  ContactCache& kept = s.kept;
  kept.Clear();
  const int nb = static_cast<int>(in.bodies.size());
  Islands& islands = s.islands;
  islands.Reset(nb, s.rows);
  if (in.jointed != nullptr) {
    for (const std::vector<int>& tree : s.coupling.members) {
      for (const int k : tree) islands.Join(k, tree.front());
    }
  }
  islands.WakeTouched(state.sleep);
  for (std::size_t k = 0; k < in.bodies.size(); ++k) {
    if (state.sleep.asleep[k]) {
      s.vel[k] = {Vector3::Zero(), Vector3::Zero()};
      s.response.inv_inertia[k] = Matrix3::Zero();
      s.response.inv_mass[k] = 0;
    }
  }
  s.rows.erase(std::remove_if(s.rows.begin(), s.rows.end(),
                              [&](const Row& r) {
                                const bool still = state.sleep.asleep[static_cast<std::size_t>(r.a)] &&
                                                   (r.b < 0 || state.sleep.asleep[static_cast<std::size_t>(r.b)]);
                                if (still) {
                                  if (const CachedRow* row = state.cache.FindRow(r.key)) kept.SetRow(r.key, *row);
                                  kept.KeepPatches(state.cache.FindPatches({std::get<0>(r.key), std::get<1>(r.key)}));
                                }
                                return still;
                              }),
               s.rows.end());
  return islands;
}

namespace {

// When the sweeps stop: the options, with the automatic sweep count resolved.
SolveSettings SettingsOf(const ContactOptions& o) {
  const int sweeps = o.max_iterations > 0 ? o.max_iterations : (o.exact ? 64 : 32);
  return {sweeps, o.speed_tolerance, o.exact, o.tolerance};
}

}  // namespace

void Solve(const StepInput& in, Islands& islands, State& state, Scratch& s, ContactStats& stats) {
  const int nb = static_cast<int>(in.bodies.size());
  PreparePatches(s.rows, state.cache, s.vel, s.response, s.bounce_threshold, s.patches, s.solve);
  const double energy_before = KineticEnergy(in.bodies, s.vel);
  s.island.resize(in.bodies.size());
  for (int k = 0; k < nb; ++k) s.island[static_cast<std::size_t>(k)] = islands.Find(k);
  SupportLevels(nb, s.rows, s.levels);
  stats.iterations = SolveImpulses(s.rows, s.patches, s.vel, s.response, s.levels, s.island, SettingsOf(in.options),
                                   s.WorkersFor(in.threads), s.solve);
  stats.lanes = s.solve.lanes_used;
  s.kept.Finish();
  std::swap(state.cache, s.kept);  // s.kept keeps the old arrays for the next step
  StoreImpulses(s.rows, s.patches, state.cache, s.solve);
  stats.dissipated = energy_before - KineticEnergy(in.bodies, s.vel);
}

StepStatus Drift(const StepInput& in, const Model& model, const State& state, Scratch& s, ContactStats& stats) {
  const int nb = static_cast<int>(in.bodies.size());
  PushOutVelocities(s.rows, nb, in.h, SettingsOf(in.options), s.pseudo);
  return in.jointed != nullptr ? DriftJointed(*in.jointed, s, model.radii, in.h, in.bodies, stats)
                               : DriftBodies(in.bodies, s.vel, s.pseudo, state.sleep.asleep, model.radii, in.h, stats);
}

void Sleep(const StepInput& in, const Model& model, Islands& islands, State& state, const Scratch& s,
           ContactStats& stats) {
  if (!in.options.sleeping || in.jointed != nullptr) return;
  islands.FallAsleep(s.rows, model.collides, model.radii, in.options.sleep_speed, in.options.sleep_time, in.h,
                     in.bodies, state.sleep);
  stats.sleeping = static_cast<int>(std::count(state.sleep.asleep.begin(), state.sleep.asleep.end(), true));
}

}  // namespace dynamics::contact
