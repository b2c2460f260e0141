// The definitions of scene/simulation.h: an rbsim run.

#include "scene/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "bodies/bodies.h"
#include "bodies/robot.h"
#include "dynamics/forces.h"
#include "json_fields.h"
#include "massprops/implicit.h"
#include "massprops/io/load.h"
#include "massprops/primitive.h"
#include "massprops/report/words.h"
#include "massprops/text.h"

namespace scene {
namespace {

using dynamics::BuiltShape;
using massprops::MassProperties;
using massprops::TriangleMesh;

std::string Num(double v, const char* fmt = "%.6g") { return massprops::FormatDouble(v, fmt); }

// A distinct, readable colour per body (a few hues of a qualitative palette).
Vector3 DefaultColor(std::size_t i) {
  static const double kPalette[][3] = {{0.90, 0.62, 0.00}, {0.34, 0.71, 0.91}, {0.00, 0.62, 0.45},
                                       {0.80, 0.47, 0.65}, {0.94, 0.89, 0.26}, {0.84, 0.37, 0.00}};
  const auto& c = kPalette[i % 6];
  return Vector3(c[0], c[1], c[2]);
}

// Loads a body's shape, its findings and faults named by the scene file and field ("where" and
// the part of the shape: ".mesh", ".implicit", ".solid").
BuiltShape LoadShape(dynamics::BodyBuilder& builder, const ShapeSpec& shape, const std::string& where,
                     std::vector<std::string>& warnings, bool solid_errors_name_field) {
  std::vector<dynamics::BodyWarning> found;
  const auto report = [&] {
    for (const auto& w : found) warnings.push_back(where + "." + w.field + ": " + w.text);
  };
  try {
    BuiltShape built = builder.Load(shape, found);
    report();
    return built;
  } catch (const dynamics::BodyError& e) {
    report();  // what was found before the fault
    const bool named = !e.field().empty() && (e.field() != "solid" || solid_errors_name_field);
    throw SceneError(where + (named ? "." + e.field() : std::string()) + ": " + e.what());
  }
}

// A mesh's vertices turned by R, then moved by t (when given).
void Place(TriangleMesh& m, const Matrix3& R, const std::optional<Vector3>& t = std::nullopt) {
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const Vector3 turned = R * m.V.row(v).transpose();
    m.V.row(v) = (t ? Vector3(turned + *t) : turned).transpose();
  }
}

// The scene's gravity: the sum of its gravity forces (m/s², world).
Vector3 SceneGravity(const Scene& scene) {
  Vector3 g = Vector3::Zero();
  for (const ForceSpec& f : scene.forces) {
    if (f.kind == ForceKind::kGravity) g += f.vector;
  }
  return g;
}

// MJCF gravcomp: each such link held up by that fraction of its weight under the scene's gravity,
// a force at its center of mass (MuJoCo 3's gravity compensation).
void CompensateGravity(Simulation& sim, const massprops::RobotModel& model, const dynamics::RobotInWorld& added) {
  const Vector3 g = SceneGravity(sim.scene);
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const massprops::RobotLink& link = model.links[l];
    if (link.gravity_compensation == 0 || !link.inertial || g.isZero(0)) continue;
    const Vector3 at =
        added.link_in_body[l].rotation * link.inertial->center_of_mass + added.link_in_body[l].translation;
    sim.physics.AddForce(
        dynamics::PointForce(added.body_of_link[l], at, -link.gravity_compensation * link.inertial->mass * g, false));
  }
}

// A robot of the scene: its file read (filled on request), its bodies and joints added, each
// body drawn as its collision geometry. Without a position it starts where its file places it, or
// raised so that its lowest point is 1 cm above the highest ground under it (PlaceAboveGround).
void AddRobot(Simulation& sim, const RobotSpec& spec, std::vector<std::string>& warnings) {
  // A robot given on the command line is its own scene: its messages name the file once.
  const bool alone = sim.scene.file == spec.path;
  const std::string where = alone ? std::string() : sim.scene.file + ": " + spec.field + ": ";
  const massprops::Vocabulary& words = massprops::report::WordsFor(alone ? massprops::report::FrontEnd::kCommandLine
                                                                         : massprops::report::FrontEnd::kScene);
  massprops::RobotModelOptions read;
  read.fill = spec.fill;
  read.fill_options = spec.fill_options;
  read.words = &words;
  massprops::RobotModel model;
  try {
    model = massprops::ReadRobotModel(spec.path, read);
  } catch (const std::exception& e) {
    throw SceneError(where + e.what());
  }
  if (!model.grounds.empty()) {  // the file's own floors, in place of the default one
    if (sim.scene.default_ground) {
      sim.scene.grounds.clear();
      sim.scene.default_ground = false;
    }
    for (const massprops::RobotGround& g : model.grounds) sim.scene.grounds.push_back(dynamics::GroundOf(g));
  }
  for (const massprops::RobotTerrain& t : model.terrains) {  // the file's height fields, static
    try {
      sim.physics.AddStatic(dynamics::TerrainCollider(t), t.pose.rotation, t.pose.translation);
    } catch (const std::exception& e) {
      throw SceneError(where + (alone ? spec.path + ": " : std::string()) + e.what());
    }
    SimStatic drawn{spec.name + "/" + (t.name.empty() ? std::string("terrain") : t.name), t.mesh};
    Place(drawn.display, t.pose.rotation, t.pose.translation);
    sim.statics.push_back(std::move(drawn));
    sim.contact = true;
  }
  dynamics::RobotOptions options = spec.options;
  if (spec.material_given && model.format == massprops::RobotFormat::kMjcf) {
    warnings.push_back(sim.scene.file + ": " + spec.field +
                       ".material: an MJCF file's geoms bring their own friction (MuJoCo's, the larger of a "
                       "pair's); the scene's material gives only their restitution");
  }
  try {
    if (!spec.position_given) {  // where the file places it, else 1 cm above the ground
      options.pose = dynamics::PlaceAboveGround(model, options, sim.scene.grounds, dynamics::kSetDownClearance);
    }
    const dynamics::RobotInWorld added = dynamics::AddRobot(sim.physics, model, options);
    std::vector<std::string> notes = added.notes;
    // What the pictures draw: the links' visual geometry (read only when a picture is asked for).
    const bool drawn = std::any_of(sim.scene.outputs.begin(), sim.scene.outputs.end(),
                                   [](OutputKind k) { return k == OutputKind::kGlb || k == OutputKind::kHtml; });
    const std::vector<TriangleMesh> visuals =
        drawn ? dynamics::VisualShapes(model, added, options.load, notes) : std::vector<TriangleMesh>();
    CompensateGravity(sim, model, added);
    for (const std::string& note : notes) warnings.push_back((alone ? spec.path + ": " : where) + note);
    for (std::size_t k = 0; k < added.bodies.size(); ++k) {
      const dynamics::RigidBody& rb = sim.world().bodies()[static_cast<std::size_t>(added.bodies[k])];
      SimBody body;
      body.name = spec.name + "/" + added.body_names[k];
      body.color = DefaultColor(sim.bodies.size());
      // In its link's frame (the outputs' orientation is the link's): the body's principal
      // axes R and center of mass t there; the drawn geometry about the center, in link axes.
      const massprops::Placement& in_link = added.body_in_link[k];
      body.mp.mass = rb.mass;
      body.mp.center_of_mass = in_link.translation;
      body.mp.inertia_com = in_link.rotation * rb.inertia.asDiagonal() * in_link.rotation.transpose();
      body.principal.axes = in_link.rotation;
      body.principal.moments = rb.inertia;
      body.source = spec.path + " (" + massprops::RobotFormatName(model.format) + (spec.fill ? ", filled" : "") + ")";
      body.display = added.shapes[k];
      body.collides = added.shapes[k].F.rows() > 0;
      if (k < visuals.size()) body.visual = visuals[k];
      for (TriangleMesh* m : {&body.display, &body.visual}) Place(*m, in_link.rotation);
      sim.bodies.push_back(std::move(body));
    }
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    // The file named once: AddRobot's messages start with it already.
    const std::string own = spec.path + ": ";
    std::string what = e.what();
    if (what.rfind(own, 0) == 0) what = what.substr(own.size());
    throw SceneError((alone ? own : where + own) + what);
  }
}

}  // namespace

namespace {

// The scene's bodies, each with its collider when the scene has contact; whether each collides.
std::vector<bool> AddBodies(const Scene& scene, dynamics::BodyBuilder& builder, bool wants_contact, Simulation& sim,
                            std::vector<std::string>& warnings) {
  std::vector<bool> collides;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& spec = scene.bodies[i];
    const std::string where = scene.file + ": " + spec.field;
    SimBody body;
    body.name = spec.name;
    body.color = spec.color.value_or(DefaultColor(i));
    BuiltShape built = LoadShape(builder, spec.shape, where, warnings, true);
    body.mp = built.mp;
    body.principal = built.principal;
    body.source = built.source;
    dynamics::RigidBody rb;
    try {
      rb = dynamics::BodyFromMassProperties(body.mp, body.principal).body;
    } catch (const std::exception& e) {
      throw SceneError(where + ": " + e.what());
    }
    rb.orientation = (spec.orientation * rb.orientation).normalized();
    rb.position = spec.position.value_or(body.mp.center_of_mass);
    rb.velocity = spec.velocity;
    Vector3 omega = spec.angular_velocity;
    if (spec.angular_velocity_frame == VectorFrame::kBody) omega = spec.orientation * omega;
    if (spec.angular_velocity_frame == VectorFrame::kPrincipal) omega = rb.orientation * omega;
    rb.SetAngularVelocity(omega);
    try {
      const auto collider = wants_contact ? builder.ColliderOf(spec.collision, spec.shape, built) : std::nullopt;
      collides.push_back(collider.has_value());
      if (collider) {
        sim.physics.AddBody(rb, *collider);
      } else {
        sim.physics.AddBody(rb);
      }
    } catch (const std::exception& e) {
      throw SceneError(where + ": " + e.what());
    }
    body.collides = collides.back();
    body.display = std::move(built.display);  // the collider is made: the outputs keep the mesh
    sim.bodies.push_back(std::move(body));
  }
  return collides;
}

// The scene's joints: placed at the bodies as the scene puts them (PlaceJoint: as added, whatever
// joints added before have moved), then moved to their initial positions.
void AddJoints(const Scene& scene, Simulation& sim) {
  for (const JointSpec& spec : scene.joints) {
    dynamics::Joint joint = spec.joint;
    const Vector3 anchor = spec.anchor.value_or(sim.world().body_as_added(joint.child).position);
    sim.world().PlaceJoint(joint, anchor, spec.axis);  // the axis is checked non-zero
    const std::string prefix = "World::AddJoint: joint '" + joint.name + "': ";
    try {
      sim.physics.AddJoint(joint);
    } catch (const std::exception& e) {
      std::string what = e.what();
      if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
      throw SceneError(scene.file + ": " + spec.field + ": " + what);
    }
  }
}

// The ground planes (the scene's, or a robot file's own), each drawn as a checkerboard four times
// as wide as the bodies' spread, under their centre.
void AddGrounds(Simulation& sim) {
  Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < sim.bodies.size(); ++i) {
    const dynamics::RigidBody& rb = sim.world().bodies()[i];
    const double r = Reach(sim.bodies[i]);
    lo = lo.cwiseMin(rb.position - Vector3::Constant(r));
    hi = hi.cwiseMax(rb.position + Vector3::Constant(r));
  }
  for (std::size_t k = 0; k < sim.scene.grounds.size(); ++k) {  // (robot files may have brought their own)
    const GroundSpec& g = sim.scene.grounds[k];
    sim.physics.AddGround(g);
    const Vector3 centre = 0.5 * (lo + hi);
    const Vector3 foot = centre - g.normal * (g.normal.dot(centre) - g.offset);
    const double half = 2 * std::max((hi - lo).maxCoeff(), 0.1);
    const Vector3 u = g.normal.cross(std::abs(g.normal.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY()).normalized();
    const Vector3 w = g.normal.cross(u);
    // A checkerboard of 12 × 12 tiles in two shades (a sense of scale and motion in the .glb).
    constexpr int kTiles = 12;
    SimStatic shade[2] = {{"ground" + std::to_string(k) + "_light", {}, Vector3(0.80, 0.78, 0.72)},
                          {"ground" + std::to_string(k) + "_dark", {}, Vector3(0.62, 0.60, 0.55)}};
    for (SimStatic& sh : shade) {
      sh.display.V.resize(4 * kTiles * kTiles / 2, 3);
      sh.display.F.resize(kTiles * kTiles, 3);
    }
    int count[2] = {0, 0};
    const double tile = 2 * half / kTiles;
    for (int i = 0; i < kTiles; ++i) {
      for (int j = 0; j < kTiles; ++j) {
        SimStatic& sh = shade[(i + j) % 2];
        const int n = count[(i + j) % 2]++;
        const Vector3 corner = foot + (-half + i * tile) * u + (-half + j * tile) * w;
        const Vector3 c[4] = {corner, corner + tile * u, corner + tile * u + tile * w, corner + tile * w};
        for (int q = 0; q < 4; ++q) sh.display.V.row(4 * n + q) = c[q].transpose();
        // Counter-clockwise seen from above the ground (u × w = n).
        sh.display.F.row(2 * n) << 4 * n, 4 * n + 1, 4 * n + 2;
        sh.display.F.row(2 * n + 1) << 4 * n, 4 * n + 2, 4 * n + 3;
      }
    }
    for (SimStatic& sh : shade) sim.statics.push_back(std::move(sh));
  }
}

// The static bodies, each drawn where it is.
void AddStatics(const Scene& scene, dynamics::BodyBuilder& builder, Simulation& sim,
                std::vector<std::string>& warnings) {
  for (const StaticSpec& st : scene.statics) {
    const std::string where = scene.file + ": " + st.field;
    try {
      // Its mass properties only place the solid; statics do not move.
      BuiltShape shape = LoadShape(builder, st.shape, where, warnings, false);
      // In the static's own frame (its mesh or solid frame): the collider sits at the center of
      // mass with the mesh's axes.
      shape.principal.axes = Matrix3::Identity();
      auto collider = builder.ColliderOf(st.collision, st.shape, shape);
      if (!collider) throw SceneError(where + ": collides as nothing (give \"collision\": \"hull\" or a primitive)");
      const Matrix3 R = st.orientation.toRotationMatrix();
      const Vector3 at = st.position + R * shape.mp.center_of_mass;
      sim.physics.AddStatic(*collider, R, at);
      SimStatic drawn{st.name, shape.display};
      Place(drawn.display, R, at);
      sim.statics.push_back(std::move(drawn));
    } catch (const SceneError&) {
      throw;
    } catch (const std::exception& e) {
      throw SceneError(where + ": " + e.what());
    }
  }
}

// Fields that the scene's own content makes inert are errors, not silently ignored; pair
// materials are set.
void ApplyContactFields(const Scene& scene, const std::vector<bool>& collides, Simulation& sim) {
  // (A robot's links collide with the ground at least.)
  const bool anything_collides =
      std::find(collides.begin(), collides.end(), true) != collides.end() || !scene.robots.empty();
  if (scene.contact_given && !anything_collides) {
    throw SceneError(scene.file +
                     ": contact: no body collides with anything (give bodies \"collision\"), so these "
                     "options would never apply");
  }
  for (std::size_t i = 0; i < scene.pairs.size(); ++i) {
    const Scene::PairMaterial& p = scene.pairs[i];
    const std::string where = scene.file + ": pairs[" + std::to_string(i) + "]: ";
    for (const int end : {p.a, p.b}) {
      if (end >= 0 && !collides[static_cast<std::size_t>(end)]) {
        throw SceneError(where + "body '" + scene.bodies[static_cast<std::size_t>(end)].name +
                         "' collides with nothing (give it \"collision\"), so this pair's material would never apply");
      }
      if (end < 0 && scene.grounds.empty() && scene.statics.empty()) {
        throw SceneError(where + "the scene has no ground or static body, so this pair's material would never apply");
      }
    }
  }
  for (const Scene::PairMaterial& p : scene.pairs) sim.physics.SetPairMaterial(p.a, p.b, p.material);
  if (!scene.pairs.empty()) sim.contact = true;
}

// A fluid (MuJoCo's inertia-box model) on one body or every body; with buoyancy, the weight of the
// medium each body with a volume displaces, under the scene's gravity.
void AddFluid(const Scene& scene, const ForceSpec& f, Simulation& sim) {
  sim.physics.AddForce(dynamics::Fluid(f.medium, f.bodies));
  if (!f.buoyancy) return;
  const Vector3 g = SceneGravity(scene);
  for (std::size_t b = 0; b < sim.bodies.size(); ++b) {
    if (!f.bodies.empty() && f.bodies[0] != static_cast<int>(b)) continue;
    const double volume = sim.bodies[b].mp.volume;
    if (volume > 0) sim.physics.AddForce(dynamics::Buoyancy(f.medium.density, g, static_cast<int>(b), volume));
  }
}

// The scene's forces, their points and vectors in the bodies' principal frames.
void AddForces(const Scene& scene, Simulation& sim) {
  // Mesh coordinates → body (principal) coordinates, x_B = R_MBᵀ (x_M − com).
  auto to_body = [&](int b, const Vector3& p_mesh) {
    const SimBody& sb = sim.bodies[static_cast<std::size_t>(b)];
    return Vector3(sb.principal.axes.transpose() * (p_mesh - sb.mp.center_of_mass));
  };
  for (const ForceSpec& f : scene.forces) {
    const int body = f.bodies.empty() ? -1 : f.bodies[0];
    const auto principal_axes = [&](int b) { return sim.bodies[static_cast<std::size_t>(b)].principal.axes; };
    switch (f.kind) {
      case ForceKind::kGravity: sim.physics.AddForce(dynamics::Gravity(f.vector)); break;
      case ForceKind::kLinearDamping: sim.physics.AddForce(dynamics::LinearDamping(f.coefficient, body)); break;
      case ForceKind::kAngularDamping: sim.physics.AddForce(dynamics::AngularDamping(f.coefficient, body)); break;
      case ForceKind::kForce: {
        const Vector3 point = f.point ? to_body(body, *f.point) : Vector3::Zero();
        const Vector3 vec = f.body_frame ? Vector3(principal_axes(body).transpose() * f.vector) : f.vector;
        sim.physics.AddForce(dynamics::PointForce(body, point, vec, f.body_frame));
        break;
      }
      case ForceKind::kTorque:
        if (f.body_frame) {
          sim.physics.AddForce(dynamics::BodyFrameTorque(body, principal_axes(body).transpose() * f.vector));
        } else {
          sim.physics.AddForce(dynamics::ConstantTorque(body, f.vector));
        }
        break;
      case ForceKind::kFluid: AddFluid(scene, f, sim); break;
      case ForceKind::kSpring:
        // Unless the scene names points, springs hold the centers of mass (body point 0).
        if (f.bodies.size() == 2) {
          const Vector3 pa = f.points.empty() ? Vector3::Zero() : to_body(f.bodies[0], f.points[0]);
          const Vector3 pb = f.points.empty() ? Vector3::Zero() : to_body(f.bodies[1], f.points[1]);
          sim.physics.AddForce(
              dynamics::SpringBetween(f.bodies[0], pa, f.bodies[1], pb, f.coefficient, f.rest_length, f.damping));
        } else {
          const Vector3 p = f.point ? to_body(body, *f.point) : Vector3::Zero();
          sim.physics.AddForce(dynamics::SpringToWorld(body, p, f.anchor, f.coefficient, f.rest_length, f.damping));
        }
        break;
    }
  }
}

// What the scene's physics conserves: the forces' report, less what contact breaks.
void NoteConservation(const Scene& scene, Simulation& sim) {
  sim.conservation = sim.world().Conserves();
  if (sim.contact) {
    // Contact steps are dissipative (friction, restitution below 1, and the semi-implicit step
    // itself); the ground and static bodies push: momentum is theirs to change.
    auto note = [](std::string& list, const char* what) { list += (list.empty() ? "" : ", ") + std::string(what); };
    sim.conservation.energy = false;
    note(sim.conservation.energy_broken_by, "contact");
    if (!sim.scene.grounds.empty() || !scene.statics.empty()) {
      sim.conservation.momentum = false;
      note(sim.conservation.momentum_broken_by, "ground and static bodies");
    }
  }
}

}  // namespace

Simulation BuildSimulation(const Scene& scene, std::vector<std::string>& warnings, int threads) {
  Simulation sim;
  sim.scene = scene;
  sim.physics = dynamics::ContactWorld(dynamics::World(scene.integrator), scene.contact);
  sim.physics.set_num_threads(threads);
  dynamics::BodyBuilder builder(
      scene.words ? *scene.words : massprops::report::WordsFor(massprops::report::FrontEnd::kScene), threads);
  // Contact is on when the scene asks for it: a ground, a static body, or a body's "collision".
  // Then box, sphere, capsule and cylinder solids collide as themselves unless they say "none";
  // scenes without any of these run as before, bodies passing through each other.
  bool wants_contact = !scene.grounds.empty() || !scene.statics.empty() || !scene.robots.empty();
  for (const BodySpec& b : scene.bodies) wants_contact = wants_contact || b.collision.kind != CollisionKind::kAuto;
  sim.contact = wants_contact;
  const std::vector<bool> collides = AddBodies(scene, builder, wants_contact, sim, warnings);
  AddJoints(scene, sim);
  AddSceneConstraints(scene, sim.physics);
  for (const RobotSpec& spec : scene.robots) AddRobot(sim, spec, warnings);
  AddGrounds(sim);
  AddStatics(scene, builder, sim, warnings);
  ApplyContactFields(scene, collides, sim);
  AddForces(scene, sim);
  NoteConservation(scene, sim);
  return sim;
}

BodyState StateOf(const SimBody& body, const dynamics::RigidBody& rb) {
  BodyState s;
  s.position = rb.position;
  // q_mesh = q_B · R_MBᵀ: maps mesh axes to world.
  s.orientation = (rb.orientation * Quaternion(body.principal.axes.transpose())).normalized();
  s.velocity = rb.velocity;
  s.omega_world = rb.AngularVelocity();
  s.omega_principal = rb.BodyAngularVelocity();
  return s;
}

double Reach(const SimBody& body) {
  return body.display.V.rows() > 0 ? body.display.V.rowwise().norm().maxCoeff() : 0.0;
}

double FastestPointSpeed(const dynamics::RigidBody& rb, double reach) {
  return rb.velocity.norm() + rb.AngularVelocity().norm() * reach;
}

std::int64_t StepCount(const Scene& scene) {
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(scene.duration / scene.dt - 1e-9)));
}

std::int64_t SampleEvery(const Scene& scene) {
  // A rate so low that the steps between samples overflow an integer (output_rate 1e-30): the
  // first and the last state only, not every step (llround would overflow).
  const double every = 1.0 / (scene.output_rate * scene.dt);
  if (!(every < 4e18)) return std::numeric_limits<std::int64_t>::max();
  return std::max<std::int64_t>(1, std::llround(every));
}

namespace {

// Bodies with a collider below every ground by more than their size at the end of the run.
std::vector<std::string> FellThrough(const Simulation& sim) {
  std::vector<std::string> out;
  if (sim.scene.grounds.empty()) return out;
  for (std::size_t k = 0; k < sim.bodies.size(); ++k) {
    const SimBody& body = sim.bodies[k];
    if (!body.collides) continue;
    const Vector3 p = sim.world().bodies()[k].position;
    const double size = 2 * Reach(body);
    double least = std::numeric_limits<double>::infinity();  // how far below the nearest ground
    for (const GroundSpec& g : sim.scene.grounds) least = std::min(least, g.offset - g.normal.dot(p));
    if (least > size) {
      out.push_back("body '" + body.name + "' ended the run " + Num(least, "%.3g") + " m below the ground (it is " +
                    Num(size, "%.3g") +
                    " m across): it passed through; a collider that touches nothing of the ground's (MJCF "
                    "contype/conaffinity), or a step too long for its speed");
    }
  }
  return out;
}

// Each body's reach, once for the run (Reach).
std::vector<double> Reaches(const Simulation& sim) {
  std::vector<double> out;
  for (std::size_t k = 0; k < std::min(sim.bodies.size(), sim.world().bodies().size()); ++k) {
    out.push_back(Reach(sim.bodies[k]));
  }
  return out;
}

// The fastest point of any body, m/s.
double FastestPoint(const Simulation& sim, const std::vector<double>& reaches) {
  double fastest = 0;
  for (std::size_t k = 0; k < reaches.size(); ++k) {
    fastest = std::max(fastest, FastestPointSpeed(sim.world().bodies()[k], reaches[k]));
  }
  return fastest;
}

}  // namespace

RunStats Run(Simulation& sim,
             const std::function<void(const dynamics::World&, const dynamics::Diagnostics&)>& on_sample,
             const std::function<void(double)>& on_progress, const std::atomic<bool>* stop,
             const std::function<void(std::int64_t)>& on_step) {
  RunStats stats;
  const auto t0 = std::chrono::steady_clock::now();
  const std::int64_t n = StepCount(sim.scene);
  const std::int64_t every = SampleEvery(sim.scene);
  auto sample = [&] {
    const dynamics::Diagnostics d = sim.world().Diagnose();
    if (!std::isfinite(d.total_energy) || !d.linear_momentum.allFinite() || !d.angular_momentum.allFinite()) {
      const char* what = !std::isfinite(d.total_energy) ? "energy" : "momentum";
      throw std::runtime_error(stats.samples == 0
                                   ? std::string("the initial state's ") + what +
                                         " is not finite (velocities, masses or forces beyond double precision)"
                                   : "diverged at t = " + Num(d.time, "%.9g") + " s (the world's " + what +
                                         " is no longer finite); reduce dt, or use a stable integrator");
    }
    if (stats.samples == 0) stats.start = d;
    const dynamics::Drift drift = dynamics::DriftSince(stats.start, d);
    stats.max_drift.energy = std::max(stats.max_drift.energy, std::abs(drift.energy));
    stats.max_drift.linear_momentum = std::max(stats.max_drift.linear_momentum, std::abs(drift.linear_momentum));
    stats.max_drift.angular_momentum = std::max(stats.max_drift.angular_momentum, std::abs(drift.angular_momentum));
    stats.end = d;
    ++stats.samples;
    on_sample(sim.world(), d);
  };
  sample();
  const std::int64_t progress_every = std::max<std::int64_t>(1, n / 1000);
  const std::optional<RestRule>& rest = sim.scene.until_rest;
  double quiet_since = -1;  // the time the bodies last came under the rest speed, or -1
  const std::vector<double> reaches = rest ? Reaches(sim) : std::vector<double>();
  for (std::int64_t i = 1; i <= n; ++i) {
    const dynamics::StepStatus status = sim.physics.Step(sim.scene.dt);
    const dynamics::ContactStats& cs = sim.physics.stats();
    stats.max_contacts = std::max(stats.max_contacts, cs.contacts);
    stats.max_penetration = std::max(stats.max_penetration, cs.max_penetration);
    stats.dissipated_by_contact += cs.dissipated;
    if (status.diverged) {
      const auto [body, quantity] = sim.world().FirstNonFinite();
      throw std::runtime_error("diverged at t = " + Num(sim.world().time(), "%.9g") + " s (body '" +
                               sim.bodies[static_cast<std::size_t>(body)].name + "': " + quantity +
                               " no longer finite); reduce dt, or use a stable integrator");
    }
    if (!status.ok)
      throw std::runtime_error("the run failed at t = " + Num(sim.world().time(), "%.9g") + " s: " + status.message);
    stats.max_substeps = std::max(stats.max_substeps, status.substeps);
    stats.steps = i;
    if (on_step) on_step(i);
    bool rested = false;
    if (rest) {
      const double t = sim.world().time();
      if (FastestPoint(sim, reaches) >= rest->speed) {
        quiet_since = -1;
      } else if (quiet_since < 0) {
        quiet_since = t;
      } else if (t - quiet_since >= rest->hold - 1e-9 * sim.scene.dt) {
        stats.rest_time = quiet_since;
        rested = true;
      }
    }
    if (i % every == 0 || i == n || rested) sample();
    if (rested) break;
    if (i % progress_every == 0) {
      if (on_progress) on_progress(static_cast<double>(i) / static_cast<double>(n));
      if (stop && stop->load(std::memory_order_relaxed)) {
        stats.interrupted = true;
        break;
      }
    }
  }
  stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  stats.fell_through = FellThrough(sim);
  return stats;
}

std::string Summary(const Simulation& sim, const RunStats& stats) {
  std::ostringstream out;
  const auto& s = stats.start;
  const auto& e = stats.end;
  const dynamics::Drift end = dynamics::DriftSince(s, e);
  out << "rbsim: " << sim.scene.file << ": " << sim.bodies.size() << (sim.bodies.size() == 1 ? " body, " : " bodies, ")
      << dynamics::IntegratorName(sim.scene.integrator) << ", dt " << Num(sim.scene.dt) << " s, " << stats.steps
      << " steps to t = " << Num(e.time) << " s in " << Num(stats.wall_seconds, "%.3g") << " s ("
      << Num(static_cast<double>(stats.steps * static_cast<std::int64_t>(sim.bodies.size())) /
                 std::max(stats.wall_seconds, 1e-9),
             "%.3g")
      << " body-steps/s)\n";
  if (stats.max_substeps > 1) {
    out << "  note: the implicit solve needed up to " << stats.max_substeps
        << " sub-steps in some steps: dt is large for these spin rates\n";
  }
  auto vec = [](const Vector3& v) {
    return "[" + Num(v.x(), "%.9g") + ", " + Num(v.y(), "%.9g") + ", " + Num(v.z(), "%.9g") + "]";
  };
  const dynamics::Conservation& c = sim.conservation;
  const std::string energy_note =
      c.energy ? "conserved by this scene's physics" : "not conserved here: " + c.energy_broken_by;
  const std::string momentum_note =
      c.momentum ? "conserved by this scene's physics" : "not conserved here: " + c.momentum_broken_by;
  out << "                       start              end                drift (end)   drift (max)\n";
  char line[256];
  std::snprintf(line, sizeof line, "  energy, J            % .9e  % .9e  % .2e     %.2e   %s\n", s.total_energy,
                e.total_energy, end.energy, stats.max_drift.energy, energy_note.c_str());
  out << line;
  std::snprintf(line, sizeof line, "  |p|, kg m/s          % .9e  % .9e  % .2e     %.2e   %s\n",
                s.linear_momentum.norm(), e.linear_momentum.norm(), end.linear_momentum,
                stats.max_drift.linear_momentum, momentum_note.c_str());
  out << line;
  std::snprintf(line, sizeof line, "  |L|, kg m^2/s        % .9e  % .9e  % .2e     %.2e   %s\n",
                s.angular_momentum.norm(), e.angular_momentum.norm(), end.angular_momentum,
                stats.max_drift.angular_momentum, momentum_note.c_str());
  out << line;
  out << "  (start, end: E, |p| and |L| (L about the world origin); drift: (E - E0)/|E0|, |p - p0|/|p0|, |L - "
         "L0|/|L0|)\n";
  out << "  L end " << vec(e.angular_momentum) << "\n";
  for (const std::string& f : stats.fell_through) out << "  warning: " << f << "\n";
  if (sim.contact) {
    out << "  contact: up to " << stats.max_contacts << " points in a step, deepest overlap "
        << Num(stats.max_penetration, "%.3g") << " m, " << Num(stats.dissipated_by_contact, "%.6g")
        << " J of kinetic energy taken by the contact impulses\n";
  }
  return out.str();
}

}  // namespace scene
