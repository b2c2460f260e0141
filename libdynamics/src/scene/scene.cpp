// The definitions of scene/scene.h: scenes (target massprops::scene).

#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "json_fields.h"
#include "massprops/io/load_schema.h"
#include "massprops/io/mesh_io.h"

namespace scene {
namespace {

using nlohmann::json;

using json_fields::Fields;
using json_fields::Join;
using json_fields::Num;
using json_fields::Suggest;
using json_fields::TypeName;

// The load options an entry gives under the schema's keys (massprops/io/load_schema.h), checked
// by the schema as the command line and Python check them.
massprops::LoadOptions ReadLoadKeys(Fields& f, std::initializer_list<const char*> keys) {
  massprops::LoadOptions o;
  for (const char* key : keys) {
    const json* v = f.Get(key);
    if (!v) continue;
    massprops::OptionValue value;
    if (v->is_boolean()) {
      value = v->get<bool>();
    } else if (v->is_number_integer()) {
      value = v->get<std::int64_t>();
    } else if (v->is_number()) {
      value = v->get<double>();
    } else if (v->is_string()) {
      value = v->get<std::string>();
    } else {
      f.Fail(key, "must be a boolean, a number or a string, not " + TypeName(*v));
    }
    if (const auto problem = massprops::SetLoadOption(o, *massprops::FindLoadOption(key), value)) f.Fail(key, *problem);
  }
  return o;
}

// A closed-form solid: {"type": NAME, sizes...}, the names and sizes of massprops::Primitive as
// scenes spell them (massprops::SizeKeys).
massprops::Primitive ReadPrimitive(Fields& o) {
  const std::vector<std::string> names(std::begin(massprops::kPrimitiveNames), std::end(massprops::kPrimitiveNames));
  const std::string t = o.String("type", "", names);
  if (t.empty()) o.Fail("type", "is required");
  std::vector<double> sizes;
  for (const massprops::SizeKey& k : massprops::SizeKeys(t, massprops::SizeSyntax::kScene)) {
    if (k.components == 3) {
      if (!o.Has(k.key)) o.Fail(k.key, std::string("is required: ") + k.what);
      const Vector3 v = o.Vec3(k.key, Vector3::Zero(), "positive");
      sizes.insert(sizes.end(), {v.x(), v.y(), v.z()});
    } else {
      sizes.push_back(o.RequiredNumber(k.key, "positive"));
    }
  }
  if (t == "torus" && !(sizes[1] < sizes[0])) {
    o.Fail("minor_radius", "must be smaller than major_radius (a self-intersecting torus is not a solid)");
  }
  o.Done();
  return massprops::MakePrimitive(t, sizes);
}

ShapeSpec ReadShape(Fields& f, const std::string& base_dir) {
  ShapeSpec s;
  const bool has_mesh = f.Has("mesh"), has_solid = f.Has("solid"), has_implicit = f.Has("implicit");
  const int kinds = int{has_mesh} + int{has_solid} + int{has_implicit};
  if (kinds != 1) {
    f.Get("mesh");
    f.Get("solid");
    f.Get("implicit");
    f.Fail(kinds > 1 ? "give one of 'mesh', 'solid' and 'implicit', not several"
                     : "needs a 'mesh' (file), a 'solid' or an 'implicit' shape");
  }
  if (f.Has("density") && f.Has("mass")) f.Fail("give 'density' or 'mass', not both");
  s.mass = ReadLoadKeys(f, {"density", "mass"}).mass;
  const auto read_unit = [&] {  // a closed-form solid is in metres: no unit key
    const massprops::LoadOptions load = ReadLoadKeys(f, {"unit"});
    s.unit = load.unit;
    s.unit_stated = load.unit_stated;
  };
  if (has_implicit) {
    dynamics::ImplicitSource implicit;
    implicit.text = f.String("implicit", "");
    try {
      implicit.shape = massprops::implicit::ParseShape(implicit.text, massprops::ReadSdfGridFile);
    } catch (const std::exception& e) {
      f.Fail("implicit", e.what());
    }
    s.source = std::move(implicit);
    read_unit();
  } else if (has_mesh) {
    const std::string file = f.String("mesh", "");
    if (file.empty()) f.Fail("mesh", "is empty");
    namespace fs = std::filesystem;
    fs::path p(file);
    if (p.is_relative()) p = fs::path(base_dir) / p;
    if (const std::string problem = MeshFileProblem(p); !problem.empty()) {
      f.Fail("mesh", "'" + file + "' " + problem + (file == p.string() ? "" : " (looked for " + p.string() + ")"));
    }
    dynamics::MeshSource mesh;
    mesh.path = p.lexically_normal().string();
    read_unit();
    const massprops::LoadOptions checks = ReadLoadKeys(f, {"repair", "allow_open", "parts"});
    mesh.repair = checks.repair;
    mesh.allow_open = checks.allow_open;
    mesh.parts = checks.parts;
    if (const json* part = f.Get("part")) {  // one part of the file, where the file places it
      if (!part->is_number_integer() || part->get<long long>() < 0 || part->get<long long>() > 1000000) {
        f.Fail("part", "must be a part's index, a whole number from 0, not " + part->dump());
      }
      mesh.part = static_cast<int>(part->get<long long>());
    }
    s.source = std::move(mesh);
  } else {
    Fields o(*f.Get("solid"), f.Path("solid"), f.file());
    s.source = ReadPrimitive(o);
  }
  return s;
}

// "collision": "none" | "hull" | "mesh" | a primitive {"type": "box", ...}; absent: the solid
// itself when it is a box, sphere, capsule or cylinder.
CollisionSpec ReadCollision(Fields& f) {
  CollisionSpec c;
  c.material = ReadMaterial(f);
  const json* v = f.Get("collision");
  if (!v) return c;
  if (v->is_string()) {
    const std::string s = v->get<std::string>();
    if (s == "none") {
      c.kind = CollisionKind::kNone;
    } else if (s == "hull") {
      c.kind = CollisionKind::kHull;
    } else if (s == "mesh") {
      c.kind = CollisionKind::kMesh;
    } else if (s == "itself") {
      c.kind = CollisionKind::kItself;
    } else {
      f.Fail("collision", "'" + s + "' is not \"none\", \"hull\", \"mesh\", \"itself\" or a primitive {\"type\": ...}" +
                              Suggest(s, {"none", "hull", "mesh", "itself"}));
    }
    return c;
  }
  if (!v->is_object()) f.Fail("collision", "must be \"none\", \"hull\", \"mesh\" or a primitive {\"type\": ...}");
  Fields o(*v, f.Path("collision"), f.file());
  c.primitive = ReadPrimitive(o);
  if (!CollidesAsItself(*c.primitive)) {
    f.Fail("collision", "collides as a box, sphere, capsule or cylinder (or \"hull\"), not a " +
                            std::string(massprops::PrimitiveName(*c.primitive)));
  }
  c.kind = CollisionKind::kPrimitive;
  return c;
}

GroundSpec ReadGround(const json& j, const std::string& path, const std::string& file) {
  Fields f(j, path, file);
  GroundSpec g;
  g.normal = f.Vec3("normal", Vector3::UnitZ());
  if (!(g.normal.norm() > 0)) f.Fail("normal", "must not be the zero vector");
  g.normal.normalize();
  g.offset = f.Number("offset", 0.0);
  g.material = ReadMaterial(f);
  f.Done();
  return g;
}

}  // namespace

Quaternion ReadOrientation(Fields& f, const std::string& key, std::vector<std::string>& warnings) {
  const json* v = f.Get(key);
  if (!v) return Quaternion::Identity();
  if (v->is_array()) {
    if (v->size() != 4) f.Fail(key, "a quaternion is 4 numbers [w, x, y, z], not " + std::to_string(v->size()));
    double c[4];
    for (std::size_t i = 0; i < 4; ++i) c[i] = f.CheckNumber(key + "[" + std::to_string(i) + "]", (*v)[i], nullptr);
    // Its norm without overflow or underflow: scaled by its largest component first (the norm of
    // [1e300, 1e300, 0, 0] overflowed, and was called zero).
    const double largest = std::max({std::abs(c[0]), std::abs(c[1]), std::abs(c[2]), std::abs(c[3])});
    if (!(largest > 0)) f.Fail(key, "the quaternion is zero: it names no rotation");
    const Quaternion scaled(c[0] / largest, c[1] / largest, c[2] / largest, c[3] / largest);
    const double n = largest * scaled.norm();  // may be infinite: only reported
    if (!(n > 1e-12)) f.Fail(key, "the quaternion is zero: it names no rotation");
    if (std::abs(n - 1.0) > 1e-12) {
      warnings.push_back(f.file() + ": " + f.Path(key) + ": the quaternion has norm " + Num(n) +
                         "; normalized to unit length");
    }
    return scaled.normalized();
  }
  if (v->is_object()) {
    Fields o(*v, f.Path(key), f.file());
    const Vector3 axis = o.Vec3("axis", Vector3::Zero());
    if (!o.Has("axis")) o.Fail("axis", "is required (with angle_deg or angle)");
    if (!(axis.norm() > 0)) o.Fail("axis", "must not be the zero vector");
    if (o.Has("angle_deg") == o.Has("angle")) o.Fail("give exactly one of angle_deg and angle (radians)");
    // An angle so large that its own rounding exceeds a microdegree names no rotation: refused.
    // Smaller ones lose their whole turns first (exactly: fmod rounds nothing).
    const bool radians = o.Has("angle");
    const char* name = radians ? "angle" : "angle_deg";
    const double given = o.Number(name, 0);
    const double microdegree = radians ? 1e-6 * massprops::kPi / 180.0 : 1e-6;
    const double rounding = std::nextafter(std::abs(given), HUGE_VAL) - std::abs(given);
    if (rounding > microdegree) {
      o.Fail(name, Num(given) + " is too large to name an angle: its own rounding is " + Num(rounding) +
                       (radians ? " rad" : " degrees") + ", more than a microdegree; give it modulo " +
                       (radians ? "2 pi" : "360"));
    }
    const double angle =
        radians ? std::fmod(given, 2 * massprops::kPi) : std::fmod(given, 360.0) * massprops::kPi / 180.0;
    o.Get(radians ? "angle_deg" : "angle");  // both are known keys
    o.Done();
    return Quaternion(Eigen::AngleAxisd(angle, axis.normalized()));
  }
  f.Fail(key, "must be a quaternion [w, x, y, z] or {\"axis\": [x, y, z], \"angle_deg\": a}, not " + TypeName(*v));
}

dynamics::Material ReadMaterial(Fields& f) {
  dynamics::Material m;
  const json* v = f.Get("material");
  if (!v) return m;
  Fields o(*v, f.Path("material"), f.file());
  if (o.Has("friction") && (o.Has("static_friction") || o.Has("kinetic_friction"))) {
    o.Fail("give 'friction' (both coefficients) or 'static_friction' and 'kinetic_friction', not both");
  }
  const double mu = o.Number("friction", -1, "non-negative");
  m.static_friction = o.Number("static_friction", mu >= 0 ? mu : m.static_friction, "non-negative");
  m.kinetic_friction =
      o.Number("kinetic_friction", mu >= 0 ? mu : std::min(m.kinetic_friction, m.static_friction), "non-negative");
  m.restitution = o.Number("restitution", 0.0, "non-negative");
  if (const auto fault = dynamics::CheckMaterial(m)) o.Fail(fault->field, fault->problem);
  o.Done();
  return m;
}

int BodyIndex(Fields& f, const std::string& key, const json& v, const std::vector<BodySpec>& bodies) {
  if (v.is_number_unsigned()) {  // read as unsigned: 2^64 - 1 is not -1
    const auto i = v.get<unsigned long long>();
    if (i >= bodies.size()) {
      f.Fail(key, "body index " + std::to_string(i) + " is out of range (the scene has " +
                      std::to_string(bodies.size()) + " bodies)");
    }
    return static_cast<int>(i);
  }
  if (v.is_number_integer()) {
    const auto i = v.get<long long>();
    if (i < 0 || i >= static_cast<long long>(bodies.size())) {
      f.Fail(key, "body index " + std::to_string(i) + " is out of range (the scene has " +
                      std::to_string(bodies.size()) + " bodies)");
    }
    return static_cast<int>(i);
  }
  if (v.is_string()) {
    const std::string name = v.get<std::string>();
    std::vector<std::string> names;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (bodies[i].name == name) return static_cast<int>(i);
      names.push_back(bodies[i].name);
    }
    f.Fail(key, "no body is named '" + name + "'" + Suggest(name, names) + "; bodies: " + Join(names));
  }
  f.Fail(key, "must name a body (its name or index), not " + TypeName(v));
}

namespace {

ForceSpec ReadForce(const json& j, const std::string& path, const std::string& file,
                    const std::vector<BodySpec>& bodies) {
  Fields f(j, path, file);
  ForceSpec s;
  s.field = path;
  const std::string type =
      f.String("type", "", {"gravity", "linear_damping", "angular_damping", "force", "torque", "spring", "fluid"});
  if (type.empty()) {
    f.Fail("type", "is required (gravity, linear_damping, angular_damping, force, torque, spring, fluid)");
  }
  for (const ForceKind k : {ForceKind::kGravity, ForceKind::kLinearDamping, ForceKind::kAngularDamping,
                            ForceKind::kForce, ForceKind::kTorque, ForceKind::kSpring, ForceKind::kFluid}) {
    if (type == ForceName(k)) s.kind = k;
  }
  auto one_body = [&](bool required) {
    const json* b = f.Get("body");
    if (!b) {
      if (required) f.Fail("body", "is required");
      return;
    }
    s.bodies.push_back(BodyIndex(f, "body", *b, bodies));
  };
  if (s.kind == ForceKind::kGravity) {
    s.vector = f.Vec3("g", Vector3(0, 0, -9.80665));
  } else if (s.kind == ForceKind::kLinearDamping || s.kind == ForceKind::kAngularDamping) {
    one_body(false);
    s.coefficient = f.RequiredNumber("c", "non-negative");
  } else if (s.kind == ForceKind::kForce || s.kind == ForceKind::kTorque) {
    one_body(true);
    const std::string key = type;
    if (!f.Has(key)) f.Fail(key, "is required: a vector [x, y, z]");
    s.vector = f.Vec3(key, Vector3::Zero());
    s.body_frame = f.String("frame", "world", {"world", "body"}) == "body";
    if (s.kind == ForceKind::kForce && f.Has("point")) s.point = f.Vec3("point", Vector3::Zero());
    if (s.kind == ForceKind::kForce) f.Get("point");
  } else if (s.kind == ForceKind::kFluid) {  // MuJoCo's inertia-box model; buoyancy on request
    one_body(false);
    s.medium.density = f.Number("density", 0.0, "non-negative");
    s.medium.viscosity = f.Number("viscosity", 0.0, "non-negative");
    s.medium.wind = f.Vec3("wind", Vector3::Zero());
    s.buoyancy = f.Bool("buoyancy", false);
    if (s.medium.density == 0 && s.medium.viscosity == 0) f.Fail("a fluid needs a density or a viscosity");
  } else {  // spring
    s.coefficient = f.RequiredNumber("k", "non-negative");
    s.rest_length = f.Number("rest_length", 0.0, "non-negative");
    s.damping = f.Number("damping", 0.0, "non-negative");
    if (f.Has("bodies")) {
      const json* b = f.Get("bodies");
      if (!b->is_array() || b->size() != 2) f.Fail("bodies", "must name two bodies");
      s.bodies = {BodyIndex(f, "bodies[0]", (*b)[0], bodies), BodyIndex(f, "bodies[1]", (*b)[1], bodies)};
      if (s.bodies[0] == s.bodies[1]) f.Fail("bodies", "a spring between a body and itself does nothing");
      const json* p = f.Get("points");
      if (p) {  // absent: the centers of mass
        if (!p->is_array() || p->size() != 2) f.Fail("points", "must be two points [[x, y, z], [x, y, z]]");
        s.points = {f.CheckVec3("points[0]", (*p)[0], nullptr), f.CheckVec3("points[1]", (*p)[1], nullptr)};
      }
      if (f.Has("body") || f.Has("anchor"))
        f.Fail("a spring between bodies takes 'bodies' and 'points', not 'body'/'anchor'");
    } else {
      one_body(true);
      if (!f.Has("anchor")) f.Fail("anchor", "is required: the world point the spring is tied to");
      s.anchor = f.Vec3("anchor", Vector3::Zero());
      if (f.Has("point")) s.point = f.Vec3("point", Vector3::Zero());  // absent: the center of mass
      f.Get("point");
      f.Get("bodies");
      f.Get("points");
    }
  }
  f.Done();
  return s;
}

}  // namespace

VectorFrame ParseVectorFrame(const std::string& name) {
  return name == "world" ? VectorFrame::kWorld : name == "body" ? VectorFrame::kBody : VectorFrame::kPrincipal;
}

const char* ForceName(ForceKind kind) {
  switch (kind) {
    case ForceKind::kGravity: return "gravity";
    case ForceKind::kLinearDamping: return "linear_damping";
    case ForceKind::kAngularDamping: return "angular_damping";
    case ForceKind::kForce: return "force";
    case ForceKind::kTorque: return "torque";
    case ForceKind::kSpring: return "spring";
    case ForceKind::kFluid: return "fluid";
  }
  return "?";
}

const char* OutputName(OutputKind kind) {
  switch (kind) {
    case OutputKind::kCsv: return "csv";
    case OutputKind::kJsonl: return "jsonl";
    case OutputKind::kDiagnostics: return "diagnostics";
    case OutputKind::kPlotSvg: return "svg";
    case OutputKind::kPlotPng: return "png";
    case OutputKind::kGlb: return "glb";
    case OutputKind::kContacts: return "contacts";
    case OutputKind::kHtml: return "html";
  }
  return "?";
}

OutputKind ParseOutputName(const std::string& name) {
  for (OutputKind k : {OutputKind::kCsv, OutputKind::kJsonl, OutputKind::kDiagnostics, OutputKind::kPlotSvg,
                       OutputKind::kPlotPng, OutputKind::kGlb, OutputKind::kContacts, OutputKind::kHtml}) {
    if (name == OutputName(k)) return k;
  }
  throw std::invalid_argument("unknown output '" + name + "' (csv, jsonl, diagnostics, svg, png, glb, contacts, html)");
}

std::vector<OutputKind> DefaultOutputs() {
  return {OutputKind::kCsv, OutputKind::kDiagnostics, OutputKind::kPlotSvg, OutputKind::kPlotPng, OutputKind::kGlb};
}

namespace {

// "outputs": the names given, or the defaults.
void ReadOutputs(Fields& f, Scene& scene) {
  if (const json* o = f.Get("outputs")) {
    if (!o->is_array()) f.Fail("outputs", "must be an array of names (csv, jsonl, diagnostics, svg, png, glb)");
    for (std::size_t i = 0; i < o->size(); ++i) {
      const std::string key = "outputs[" + std::to_string(i) + "]";
      if (!(*o)[i].is_string()) f.Fail(key, "must be a string");
      try {
        scene.outputs.push_back(ParseOutputName((*o)[i].get<std::string>()));
      } catch (const std::invalid_argument& e) {
        f.Fail(key, e.what());
      }
    }
  } else {
    scene.outputs = DefaultOutputs();
  }
}

// "bodies": each body's shape, placement, motion, colour and collision (none needed with robots).
void ReadBodies(Fields& f, const std::string& file, const std::string& base_dir, Scene& scene,
                std::vector<std::string>& warnings) {
  static const json kNoBodies = json::array();
  const json* bodies = f.Get("bodies");
  if (!bodies && !scene.robots.empty()) bodies = &kNoBodies;
  if (!bodies || !bodies->is_array() || (bodies->empty() && scene.robots.empty())) {
    f.Fail("bodies", "must be a non-empty array of bodies (or give \"robots\")" +
                         (bodies ? std::string() : f.MisspelledAs("bodies")));
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < bodies->size(); ++i) {
    const std::string path = "bodies[" + std::to_string(i) + "]";
    Fields b((*bodies)[i], path, file);
    BodySpec body;
    body.field = path;
    body.name = b.String("name", "body" + std::to_string(i));
    if (body.name.empty()) b.Fail("name", "must not be empty");
    if (!names.insert(body.name).second) b.Fail("name", "'" + body.name + "' is used by another body");
    body.shape = ReadShape(b, base_dir);
    if (b.Has("position")) body.position = b.Vec3("position", Vector3::Zero());
    b.Get("position");
    body.orientation = ReadOrientation(b, "orientation", warnings);
    body.velocity = b.Vec3("velocity", Vector3::Zero());
    body.angular_velocity = b.Vec3("angular_velocity", Vector3::Zero());
    const std::string frame = b.String("angular_velocity_frame", "world", {"world", "body", "principal"});
    body.angular_velocity_frame = ParseVectorFrame(frame);
    if (b.Has("color")) {
      body.color = b.Vec3("color", Vector3::Zero(), "non-negative");
      if (body.color->maxCoeff() > 1) b.Fail("color", "components are between 0 and 1");
    }
    b.Get("color");
    body.collision = ReadCollision(b);
    b.Done();
    scene.bodies.push_back(std::move(body));
  }
}

// "ground": one plane or several.
void ReadGrounds(Fields& f, const std::string& file, Scene& scene) {
  if (const json* g = f.Get("ground")) {
    if (g->is_array()) {
      for (std::size_t i = 0; i < g->size(); ++i) {
        scene.grounds.push_back(ReadGround((*g)[i], "ground[" + std::to_string(i) + "]", file));
      }
    } else {
      scene.grounds.push_back(ReadGround(*g, "ground", file));
    }
  }
}

// "static": fixed bodies that collide.
void ReadStatics(Fields& f, const std::string& file, const std::string& base_dir, Scene& scene,
                 std::vector<std::string>& warnings) {
  if (const json* st = f.Get("static")) {
    if (!st->is_array()) f.Fail("static", "must be an array of fixed bodies");
    for (std::size_t i = 0; i < st->size(); ++i) {
      const std::string path = "static[" + std::to_string(i) + "]";
      Fields b((*st)[i], path, file);
      StaticSpec s;
      s.field = path;
      s.name = b.String("name", "static" + std::to_string(i));
      s.shape = ReadShape(b, base_dir);
      s.position = b.Vec3("position", Vector3::Zero());
      s.orientation = ReadOrientation(b, "orientation", warnings);
      s.collision = ReadCollision(b);
      if (s.collision.kind == CollisionKind::kNone)
        b.Fail("collision", "a static body that collides with nothing does nothing");
      b.Get("color");
      b.Done();
      scene.statics.push_back(std::move(s));
    }
  }
}

// "contact": the solver's options.
void ReadContact(Fields& f, const std::string& file, Scene& scene) {
  if (const json* c = f.Get("contact")) {
    scene.contact_given = true;
    Fields o(*c, "contact", file);
    if (o.Get("max_iterations") != nullptr) {
      const double sweeps = o.Number("max_iterations", 16, "positive");
      if (sweeps != std::floor(sweeps) || sweeps > 1e6) o.Fail("max_iterations", "must be a whole number up to 10^6");
      scene.contact.max_iterations = static_cast<int>(sweeps);
    }
    scene.contact.speed_tolerance = o.Number("speed_tolerance", scene.contact.speed_tolerance, "positive");
    scene.contact.exact = o.Bool("exact", false);
    scene.contact.restitution_threshold = o.Number("restitution_threshold", 0.0, "non-negative");
    scene.contact.sleeping = o.Bool("sleeping", false);
    scene.contact.sleep_speed = o.Number("sleep_speed", scene.contact.sleep_speed, "positive");
    scene.contact.sleep_time = o.Number("sleep_time", scene.contact.sleep_time, "positive");
    scene.contact.self_collision = o.Bool("self_collision", false);
    scene.contact.reuse_distance = o.Number("reuse_distance", scene.contact.reuse_distance, "non-negative");
    if (scene.contact.reuse_distance > 1e-3) o.Fail("reuse_distance", "must be at most 10^-3 (0: off)");
    o.Done();
  }
}

// "pairs": a pair of bodies' (or a body's and the ground's) own material.
void ReadPairs(Fields& f, const std::string& file, Scene& scene) {
  if (const json* pairs = f.Get("pairs")) {
    if (!pairs->is_array()) f.Fail("pairs", "must be an array of {\"bodies\": [a, b], \"material\": {...}}");
    for (std::size_t i = 0; i < pairs->size(); ++i) {
      const std::string path = "pairs[" + std::to_string(i) + "]";
      Fields p((*pairs)[i], path, file);
      const json* b = p.Get("bodies");
      if (!b || !b->is_array() || b->size() != 2) {
        p.Fail("bodies", "must name two bodies (a name, an index, or \"ground\" for the ground and static bodies)");
      }
      Scene::PairMaterial pm;
      int ends[2];
      for (int k = 0; k < 2; ++k) {
        const json& e = (*b)[static_cast<std::size_t>(k)];
        const bool named_body =
            e.is_string() && std::any_of(scene.bodies.begin(), scene.bodies.end(),
                                         [&](const BodySpec& x) { return x.name == e.get<std::string>(); });
        ends[k] = e.is_string() && e.get<std::string>() == "ground" && !named_body
                      ? -1
                      : BodyIndex(p, "bodies[" + std::to_string(k) + "]", e, scene.bodies);
      }
      if (ends[0] == ends[1]) p.Fail("bodies", "a pair needs two different bodies");
      pm.a = ends[0];
      pm.b = ends[1];
      if (!p.Has("material")) p.Fail("material", "is required");
      pm.material = ReadMaterial(p);
      p.Done();
      scene.pairs.push_back(pm);
    }
  }
}

}  // namespace

// "until_rest": true, or {"speed": m/s, "hold": s}: the run ends once every body is at rest.
void ReadUntilRest(Fields& f, Scene& scene) {
  const json* v = f.Get("until_rest");
  if (!v) return;
  if (v->is_boolean()) {
    if (v->get<bool>()) scene.until_rest = RestRule{};
    return;
  }
  if (!v->is_object())
    f.Fail("until_rest", "must be true, false or {\"speed\": m/s, \"hold\": s}, not " + TypeName(*v));
  Fields o(*v, f.Path("until_rest"), f.file());
  RestRule rule;
  rule.speed = o.Number("speed", rule.speed, "positive");
  rule.hold = o.Number("hold", rule.hold, "positive");
  o.Done();
  scene.until_rest = rule;
}

Scene ParseScene(const json& j, const std::string& file, const std::string& base_dir,
                 std::vector<std::string>& warnings) {
  Scene scene;
  scene.file = file;
  Fields f(j, "", file);
  f.Get("description");  // free text
  scene.dt = f.Number("dt", 1e-3, "positive");
  scene.duration = f.Number("duration", 1.0, "positive");
  const std::string integrator = f.String("integrator", "implicit-midpoint");
  try {
    scene.integrator = dynamics::ParseIntegrator(integrator);
  } catch (const std::invalid_argument&) {
    std::vector<std::string> names;
    for (auto i : dynamics::kAllIntegrators) names.emplace_back(dynamics::IntegratorName(i));  // for the suggestion
    f.Fail("integrator", "'" + integrator + "' is not one of " + Join(names) + Suggest(integrator, names));
  }
  scene.output_rate = f.Number("output_rate", 60.0, "positive");
  scene.up = f.String("up", "z", {"x", "y", "z"})[0];
  ReadUntilRest(f, scene);
  ReadOutputs(f, scene);

  if (const json* r = f.Get("robots")) scene.robots = ReadRobots(*r, file, base_dir, warnings);
  ReadBodies(f, file, base_dir, scene, warnings);
  ReadGrounds(f, file, scene);
  ReadStatics(f, file, base_dir, scene, warnings);
  ReadContact(f, file, scene);
  if (const json* forces = f.Get("forces")) {
    if (!forces->is_array()) f.Fail("forces", "must be an array");
    for (std::size_t i = 0; i < forces->size(); ++i) {
      scene.forces.push_back(ReadForce((*forces)[i], "forces[" + std::to_string(i) + "]", file, scene.bodies));
    }
  }
  if (const json* jt = f.Get("joints")) scene.joints = ReadJoints(*jt, file, scene.bodies);
  ReadConstraints(f, scene);
  if ((!scene.loops.empty() || !scene.couplings.empty()) && scene.integrator != dynamics::Integrator::kImplicitMidpoint)
    f.Fail("integrator", "'" + integrator + "': loops and couplings are held by implicit-midpoint only");
  if ((!scene.joints.empty() || !scene.robots.empty()) && scene.integrator != dynamics::Integrator::kImplicitMidpoint &&
      scene.integrator != dynamics::Integrator::kRK4) {
    f.Fail("integrator", "'" + integrator + "' has no meaning for joints and robots (it steps free bodies): use " +
                             "implicit-midpoint or rk4");
  }
  ReadPairs(f, file, scene);
  if (const json* pb = f.Get("plot_body")) {
    scene.plot_body = BodyIndex(f, "plot_body", *pb, scene.bodies);
  }
  f.Done();
  CheckTiming(scene, warnings);
  return scene;
}

void CheckTiming(const Scene& scene, std::vector<std::string>& warnings) {
  if (scene.dt > scene.duration) {
    throw SceneError(scene.file + ": dt: the step (" + Num(scene.dt) + " s) is longer than the duration (" +
                     Num(scene.duration) + " s)");
  }
  if (scene.duration / scene.dt > 1e9) {
    throw SceneError(scene.file + ": dt: duration / dt = " + Num(scene.duration / scene.dt) +
                     " steps; more than 10^9 is refused");
  }
  if (scene.output_rate * scene.dt > 1.0 + 1e-9) {
    warnings.push_back(scene.file + ": output_rate " + Num(scene.output_rate) +
                       " Hz is above 1/dt; every step is written");
  }
}

std::string MeshFileProblem(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return "";
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::directory) return "is a directory, not a mesh file";
  if (fs::exists(st)) return "is not a regular file (a device, FIFO or socket): meshes are read from files";
  return "not found";
}

Scene ParseSceneText(const std::string& text, const std::string& file, const std::string& base_dir,
                     std::vector<std::string>& warnings) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte is the 1-based offset of the fault; turn it into a line number.
    const std::size_t upto = std::min<std::size_t>(e.byte, text.size());
    const long line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(upto), '\n');
    throw SceneError(file + ": line " + std::to_string(line) + ": not valid JSON (" + e.what() + ")");
  } catch (const json::out_of_range& e) {  // a number beyond double precision (1e400)
    throw SceneError(file + ": a number is beyond double precision: " +
                     std::string(e.what()).substr(std::string(e.what()).find(']') + 2));
  }
  return ParseScene(j, file, base_dir, warnings);
}

Scene LoadScene(const std::string& path, std::vector<std::string>& warnings) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    throw SceneError(path + ": not a regular file (a FIFO, device or directory); scenes are read from regular files");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::stringstream text;
  text << in.rdbuf();
  const std::string base = std::filesystem::path(path).parent_path().string();
  return ParseSceneText(text.str(), path, base.empty() ? "." : base, warnings);
}

}  // namespace scene
