// The scene's "loops", "tendons" and "couplings" (docs/scenes.md): read, each error naming its
// field, and added to the world with their frames placed from the bodies as the scene puts them.

#include <cmath>
#include <set>

#include <nlohmann/json.hpp>

#include "dynamics/contact.h"
#include "json_fields.h"
#include "scene/scene.h"

namespace scene {

using json_fields::Fields;
using nlohmann::json;

int BodyIndex(Fields& f, const std::string& key, const json& v, const std::vector<BodySpec>& bodies);

namespace {

template <typename Named>
int IndexNamed(Fields& f, const std::string& key, const std::vector<Named>& items, const char* kind,
               const std::function<std::string(const Named&)>& name_of) {
  const std::string name = f.String(key, "");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (name_of(items[i]) == name) return static_cast<int>(i);
    names.push_back(name_of(items[i]));
  }
  f.Fail(key, std::string("no ") + kind + " is named '" + name + "'" + json_fields::Suggest(name, names) +
                  (names.empty() ? std::string("; the scene has none")
                                 : "; " + std::string(kind) + "s: " + json_fields::Join(names)));
}

int JointNamed(Fields& f, const std::string& key, const Scene& scene) {
  const int j = IndexNamed<JointSpec>(f, key, scene.joints, "joint", [](const JointSpec& s) { return s.joint.name; });
  if (!dynamics::HasOneCoordinate(scene.joints[static_cast<std::size_t>(j)].joint.type))
    f.Fail(key, "'" + scene.joints[static_cast<std::size_t>(j)].joint.name + "' is not a revolute or prismatic joint");
  return j;
}

LoopSpec ReadLoop(const json& j, const std::string& path, const Scene& scene) {
  Fields f(j, path, scene.file);
  LoopSpec s;
  s.field = path;
  const std::string type = f.String("type", "", {"ball", "weld", "hinge", "slider"});
  if (type.empty()) f.Fail("type", "is required (ball, weld, hinge, slider)");
  s.loop.type = type == "ball"    ? dynamics::LoopType::kBall
                : type == "weld"  ? dynamics::LoopType::kWeld
                : type == "hinge" ? dynamics::LoopType::kHinge
                                  : dynamics::LoopType::kSlider;
  s.loop.name = f.String("name", path);
  for (const char* key : {"a", "b"}) {
    const json* v = f.Get(key);
    if (!v) f.Fail(key, "is required: a body, or \"world\"");
    (key[0] == 'a' ? s.loop.a : s.loop.b).body = BodyOrWorld(f, key, *v, scene.bodies);
  }
  if (s.loop.a.body == s.loop.b.body) f.Fail("b", "a loop joins two bodies, not one with itself");
  if (!f.Has("anchor")) f.Fail("anchor", "is required: the world point where the two bodies are held together");
  s.anchor = f.Vec3("anchor", Vector3::Zero());
  const bool axial = s.loop.type == dynamics::LoopType::kHinge || s.loop.type == dynamics::LoopType::kSlider;
  if (axial && !f.Has("axis")) f.Fail("axis", "is required for a " + type + " loop: a world direction");
  if (!axial && f.Has("axis")) f.Fail("axis", "has no meaning for a " + type + " loop");
  s.axis = f.Vec3("axis", Vector3::UnitZ());
  if (!(s.axis.norm() > 0)) f.Fail("axis", "must not be zero");
  s.loop.tolerance = f.Number("tolerance", 1e-6, "non-negative");
  f.Done();
  return s;
}

TendonSpec ReadTendon(const json& j, const std::string& path, const Scene& scene) {
  Fields f(j, path, scene.file);
  TendonSpec s;
  s.field = path;
  s.tendon.name = f.String("name", path);
  const bool fixed = f.Has("joints"), spatial = f.Has("path");
  if (fixed == spatial) f.Fail("give 'joints' (a fixed tendon) or 'path' (a spatial one), one of the two");
  if (const json* joints = f.Get("joints")) {
    if (!joints->is_array() || joints->empty()) f.Fail("joints", "must be an array of {\"joint\", \"coef\"}");
    for (std::size_t i = 0; i < joints->size(); ++i) {
      Fields o((*joints)[i], f.Path("joints[" + std::to_string(i) + "]"), scene.file);
      const int joint = JointNamed(o, "joint", scene);
      s.tendon.joints.emplace_back(joint, o.Number("coef", 1.0));
      o.Done();
    }
  }
  if (const json* points = f.Get("path")) {
    if (!points->is_array() || points->size() < 2) f.Fail("path", "must be an array of two points or more");
    for (std::size_t i = 0; i < points->size(); ++i) {
      Fields o((*points)[i], f.Path("path[" + std::to_string(i) + "]"), scene.file);
      const json* body = o.Get("body");
      if (!body) o.Fail("body", "is required: a body, or \"world\"");
      dynamics::BodyFrame frame;
      frame.body = BodyOrWorld(o, "body", *body, scene.bodies);
      s.tendon.path.push_back(frame);
      if (!o.Has("point")) o.Fail("point", "is required: the world point at the scene's placement");
      s.points.push_back(o.Vec3("point", Vector3::Zero()));
      o.Done();
    }
  }
  if (const json* range = f.Get("range")) {
    if (!range->is_array() || range->size() != 2) f.Fail("range", "must be [lower, upper]");
    s.tendon.limits.lower = f.CheckNumber("range[0]", (*range)[0], nullptr);
    s.tendon.limits.upper = f.CheckNumber("range[1]", (*range)[1], nullptr);
    if (!(s.tendon.limits.lower <= s.tendon.limits.upper)) f.Fail("range", "its lower end is above its upper");
  }
  s.tendon.stiffness = f.Number("stiffness", 0.0, "non-negative");
  s.tendon.damping = f.Number("damping", 0.0, "non-negative");
  s.rest_given = f.Has("rest_length");
  s.tendon.rest_length = f.Number("rest_length", 0.0);
  if (const json* m = f.Get("motor")) {
    Fields o(*m, f.Path("motor"), scene.file);
    s.tendon.motor = ReadMotor(o, false);
    if (s.tendon.motor.mode == dynamics::JointMotor::Mode::kVelocity)
      o.Fail("mode", "a tendon takes a position motor (kp = 0: a damper toward a rate)");
  }
  f.Done();
  return s;
}

CouplingSpec ReadCoupling(const json& j, const std::string& path, const Scene& scene,
                          const std::vector<TendonSpec>& tendons) {
  Fields f(j, path, scene.file);
  CouplingSpec s;
  s.field = path;
  dynamics::Coupling& c = s.coupling;
  c.name = f.String("name", path);
  auto coordinate = [&](const std::string& role, bool required) {
    const std::string tendon_key = role + "_tendon";
    if (f.Has(role) && f.Has(tendon_key)) f.Fail(role, "give '" + role + "' or '" + tendon_key + "', not both");
    dynamics::Coordinate x;
    if (f.Has(tendon_key)) {
      x.kind = dynamics::Coordinate::Kind::kTendon;
      x.index =
          IndexNamed<TendonSpec>(f, tendon_key, tendons, "tendon", [](const TendonSpec& t) { return t.tendon.name; });
    } else if (f.Has(role)) {
      x.index = JointNamed(f, role, scene);
    } else if (required) {
      f.Fail(role, "is required: the joint (or '" + tendon_key + "') that follows");
    }
    f.Get(role);
    f.Get(tendon_key);
    return x;
  };
  c.follower = coordinate("follower", true);
  c.leader = coordinate("leader", false);
  const bool linear = f.Has("multiplier") || f.Has("offset");
  if (linear && f.Has("polynomial")) f.Fail("polynomial", "give 'multiplier' and 'offset', or 'polynomial', not both");
  c.polynomial = {f.Number("offset", 0.0), f.Number("multiplier", 1.0), 0, 0, 0};
  if (const json* p = f.Get("polynomial")) {
    if (!p->is_array() || p->empty() || p->size() > 5) f.Fail("polynomial", "must be an array of one to five numbers");
    c.polynomial = {0, 0, 0, 0, 0};
    for (std::size_t i = 0; i < p->size(); ++i)
      c.polynomial[i] = f.CheckNumber("polynomial[" + std::to_string(i) + "]", (*p)[i], nullptr);
  }
  f.Done();
  return s;
}

template <typename Spec, typename Read>
std::vector<Spec> ReadArray(Fields& f, const char* key, const Read& read) {
  std::vector<Spec> out;
  const json* list = f.Get(key);
  if (!list) return out;
  if (!list->is_array()) f.Fail(key, "must be an array");
  for (std::size_t i = 0; i < list->size(); ++i)
    out.push_back(read((*list)[i], std::string(key) + "[" + std::to_string(i) + "]"));
  return out;
}

// Runs `add`, a SceneError naming `field` for what the world refuses.
template <typename Add>
void Named(const Scene& scene, const std::string& field, const Add& add) {
  try {
    add();
  } catch (const std::invalid_argument& e) {
    std::string what = e.what();
    if (const auto colon = what.find("': "); what.rfind("World::", 0) == 0 && colon != std::string::npos)
      what = what.substr(colon + 3);
    throw SceneError(scene.file + ": " + field + ": " + what);
  }
}

}  // namespace

void ReadConstraints(Fields& f, Scene& scene) {
  scene.loops =
      ReadArray<LoopSpec>(f, "loops", [&](const json& j, const std::string& p) { return ReadLoop(j, p, scene); });
  scene.tendons =
      ReadArray<TendonSpec>(f, "tendons", [&](const json& j, const std::string& p) { return ReadTendon(j, p, scene); });
  scene.couplings = ReadArray<CouplingSpec>(
      f, "couplings", [&](const json& j, const std::string& p) { return ReadCoupling(j, p, scene, scene.tendons); });
}

void AddSceneConstraints(const Scene& scene, dynamics::ContactWorld& physics) {
  const dynamics::World& world = physics.world();
  for (const TendonSpec& spec : scene.tendons) {
    dynamics::Tendon t = spec.tendon;
    double length = 0;
    for (std::size_t k = 0; k < t.path.size(); ++k) {
      t.path[k].frame = world.FrameAsAdded(t.path[k].body, spec.points[k]);
      if (k > 0) length += (spec.points[k] - spec.points[k - 1]).norm();
    }
    if (!spec.rest_given) t.rest_length = length;
    Named(scene, spec.field, [&] { physics.AddTendon(t); });
  }
  for (const LoopSpec& spec : scene.loops) {
    dynamics::Loop loop = spec.loop;
    loop.a.frame = world.FrameAsAdded(loop.a.body, spec.anchor, spec.axis);
    loop.b.frame = world.FrameAsAdded(loop.b.body, spec.anchor, spec.axis);
    Named(scene, spec.field, [&] { physics.AddLoop(loop); });
  }
  for (const CouplingSpec& spec : scene.couplings)
    Named(scene, spec.field, [&] { physics.AddCoupling(spec.coupling); });
}

}  // namespace scene
