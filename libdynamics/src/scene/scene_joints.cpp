// The scene's "joints": type, parent and child, anchor and axis, limits, damping, friction,
// spring, motor and initial state, each error naming the joint's field (docs/scenes.md).

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "json_fields.h"
#include "scene/scene.h"

namespace scene {

using json_fields::Fields;
using nlohmann::json;

int BodyIndex(Fields& f, const std::string& key, const json& v, const std::vector<BodySpec>& bodies);

namespace {

constexpr double kDegree = massprops::kPi / 180.0;

/// A number given as `key` (SI) or `key_deg` (degrees, revolute joints only).
std::optional<double> Angle(Fields& f, const std::string& key, bool revolute) {
  const bool has = f.Has(key), has_deg = f.Has(key + "_deg");
  if (has && has_deg) f.Fail(key, "give '" + key + "' or '" + key + "_deg', not both");
  if (has_deg && !revolute) f.Fail(key + "_deg", "degrees are for revolute joints");
  f.Get(key);
  f.Get(key + "_deg");
  if (has) return f.Number(key, 0.0);
  if (has_deg) return f.Number(key + "_deg", 0.0) * kDegree;
  return std::nullopt;
}

/// A joint's position or velocity: one number for revolute and prismatic joints, else an array.
std::vector<double> State(Fields& f, const std::string& key, std::size_t size, bool revolute) {
  if (size == 1) {
    const std::optional<double> x = Angle(f, key, revolute);
    return x ? std::vector<double>{*x} : std::vector<double>{};
  }
  const json* v = f.Get(key);
  if (!v) return {};
  if (!v->is_array() || v->size() != size) f.Fail(key, "must be an array of " + std::to_string(size) + " numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < size; ++i)
    out.push_back(f.CheckNumber(key + "[" + std::to_string(i) + "]", (*v)[i], nullptr));
  return out;
}

JointSpec ReadJoint(const json& j, const std::string& path, const std::string& file,
                    const std::vector<BodySpec>& bodies, std::set<std::string>& names, std::vector<int>& parent_joint,
                    int index) {
  Fields f(j, path, file);
  JointSpec s;
  s.field = path;
  dynamics::Joint& jt = s.joint;
  const std::string type = f.String("type", "", {"fixed", "revolute", "prismatic", "spherical", "free"});
  if (type.empty()) f.Fail("type", "is required (fixed, revolute, prismatic, spherical, free)");
  jt.type = dynamics::ParseJointType(type);  // one of the names String checked
  const bool one_dof = dynamics::HasOneCoordinate(jt.type);
  const bool revolute = jt.type == dynamics::JointType::kRevolute;
  const json* child = f.Get("child");
  if (!child) f.Fail("child", "is required: the body the joint moves");
  jt.child = BodyIndex(f, "child", *child, bodies);
  int& slot = parent_joint[static_cast<std::size_t>(jt.child)];
  if (slot >= 0) {
    f.Fail("child", "'" + bodies[static_cast<std::size_t>(jt.child)].name + "' already hangs from joints[" +
                        std::to_string(slot) + "] (each body is the child of one joint)");
  }
  slot = index;
  jt.name = f.String("name", bodies[static_cast<std::size_t>(jt.child)].name + "_joint");
  if (jt.name.empty()) f.Fail("name", "must not be empty");
  if (!names.insert(jt.name).second) f.Fail("name", "'" + jt.name + "' is used by another joint");
  const json* parent = f.Get("parent");
  if (!parent) f.Fail("parent", "is required: a body, or \"world\"");
  jt.parent = BodyOrWorld(f, "parent", *parent, bodies);
  if (jt.parent == jt.child) f.Fail("parent", "a body cannot be jointed to itself");
  if (f.Has("anchor")) s.anchor = f.Vec3("anchor", Vector3::Zero());
  f.Get("anchor");
  if (!s.anchor && jt.type != dynamics::JointType::kFree)
    f.Fail("anchor", "is required: the joint's world point at the scene's placement");
  const bool needs_axis = one_dof;
  if (needs_axis && !f.Has("axis")) f.Fail("axis", "is required for a " + type + " joint: a world direction");
  s.axis = f.Vec3("axis", Vector3::UnitZ());
  if (!(s.axis.norm() > 0)) f.Fail("axis", "must not be zero");
  auto only_one_dof = [&](const char* key) {
    if (f.Has(key) && !one_dof) f.Fail(key, "acts on revolute and prismatic joints, not on a " + type + " joint");
  };
  only_one_dof("limits");
  only_one_dof("friction");
  only_one_dof("spring");
  only_one_dof("motor");
  only_one_dof("armature");
  if (const json* l = f.Get("limits")) {
    Fields o(*l, f.Path("limits"), file);
    if (auto x = Angle(o, "lower", revolute)) jt.limits.lower = *x;
    if (auto x = Angle(o, "upper", revolute)) jt.limits.upper = *x;
    jt.limits.restitution = o.Number("restitution", 0.0, "non-negative");
    if (jt.limits.restitution > 1)
      o.Fail("restitution", "must be between 0 and 1 (got " + json_fields::Num(jt.limits.restitution) + ")");
    if (!(jt.limits.lower <= jt.limits.upper)) o.Fail("lower must not exceed upper");
    o.Done();
  }
  if (f.Has("damping") && !(one_dof || jt.type == dynamics::JointType::kSpherical)) {
    f.Fail("damping", "acts on revolute, prismatic and spherical joints, not on a " + type + " joint");
  }
  jt.damping = f.Number("damping", 0.0, "non-negative");
  jt.friction = f.Number("friction", 0.0, "non-negative");
  jt.armature = f.Number("armature", 0.0, "non-negative");  // kg·m² or kg, on the mass matrix's diagonal
  if (const json* sp = f.Get("spring")) {
    Fields o(*sp, f.Path("spring"), file);
    jt.stiffness = o.RequiredNumber("stiffness", "non-negative");
    if (auto x = Angle(o, "rest", revolute)) jt.rest_position = *x;
    o.Done();
  }
  if (const json* m = f.Get("motor")) {
    Fields o(*m, f.Path("motor"), file);
    jt.motor = ReadMotor(o, revolute);
  }
  const auto nq = static_cast<std::size_t>(dynamics::JointPositionSize(jt.type));
  const auto nv = static_cast<std::size_t>(dynamics::JointVelocitySize(jt.type));
  jt.position = State(f, "position", nq, revolute);
  jt.velocity = State(f, "velocity", nv, revolute);
  if (one_dof && !jt.position.empty() && (jt.position[0] < jt.limits.lower || jt.position[0] > jt.limits.upper)) {
    f.Fail("position", "is outside the joint's limits");
  }
  f.Done();
  return s;
}

}  // namespace

int BodyOrWorld(Fields& f, const std::string& key, const json& v, const std::vector<BodySpec>& bodies) {
  const bool world = v.is_string() && v.get<std::string>() == "world" &&
                     std::none_of(bodies.begin(), bodies.end(), [](const BodySpec& b) { return b.name == "world"; });
  return world ? -1 : BodyIndex(f, key, v, bodies);
}

dynamics::JointMotor ReadMotor(Fields& o, bool degrees_allowed) {
  dynamics::JointMotor motor;
  const std::string mode = o.String("mode", "", {"velocity", "position"});
  if (mode.empty()) o.Fail("mode", "is required (velocity, position)");
  motor.mode = mode == "velocity" ? dynamics::JointMotor::Mode::kVelocity : dynamics::JointMotor::Mode::kPosition;
  const std::optional<double> target = Angle(o, "target", degrees_allowed);
  if (!target) o.Fail("target", "is required");
  motor.target = *target;
  if (o.Has("max_effort")) motor.max_effort = o.Number("max_effort", 1.0, "positive");
  o.Get("max_effort");
  if (motor.mode == dynamics::JointMotor::Mode::kPosition) {
    motor.kp = o.RequiredNumber("kp", "non-negative");
    motor.kd = o.Number("kd", 0.0, "non-negative");
  }
  o.Done();
  return motor;
}

std::vector<JointSpec> ReadJoints(const json& joints, const std::string& file, const std::vector<BodySpec>& bodies) {
  if (!joints.is_array()) throw SceneError(file + ": joints: must be an array of joints");
  std::vector<JointSpec> out;
  std::set<std::string> names;
  std::vector<int> parent_joint(bodies.size(), -1);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::string path = "joints[" + std::to_string(i) + "]";
    out.push_back(ReadJoint(joints[i], path, file, bodies, names, parent_joint, static_cast<int>(i)));
  }
  return out;
}

}  // namespace scene
