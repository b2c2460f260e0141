// Joint names and sizes, PlaceJointAt, and the checks World::AddJoint runs.

#include "dynamics/joints.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dynamics {

const char* JointTypeName(JointType type) {
  switch (type) {
    case JointType::kFixed: return "fixed";
    case JointType::kRevolute: return "revolute";
    case JointType::kPrismatic: return "prismatic";
    case JointType::kSpherical: return "spherical";
    case JointType::kFree: return "free";
  }
  return "?";
}

JointType ParseJointType(const std::string& name) {
  for (JointType t : kAllJointTypes) {
    if (name == JointTypeName(t)) return t;
  }
  throw std::invalid_argument("'" + name + "' is not one of fixed, revolute, prismatic, spherical, free");
}

int JointPositionSize(JointType type) {
  switch (type) {
    case JointType::kFixed: return 0;
    case JointType::kRevolute:
    case JointType::kPrismatic: return 1;
    case JointType::kSpherical: return 4;
    case JointType::kFree: return 7;
  }
  return 0;
}

int JointVelocitySize(JointType type) {
  switch (type) {
    case JointType::kFixed: return 0;
    case JointType::kRevolute:
    case JointType::kPrismatic: return 1;
    case JointType::kSpherical: return 3;
    case JointType::kFree: return 6;
  }
  return 0;
}

Frame FrameAt(const std::vector<RigidBody>& bodies, int body, const Vector3& anchor, const Vector3& axis) {
  if (!(axis.norm() > 0) || !axis.allFinite() || !anchor.allFinite())
    throw std::invalid_argument("the axis must be finite and non-zero (and the anchor finite)");
  if (body < -1 || body >= static_cast<int>(bodies.size()))
    throw std::invalid_argument("body " + std::to_string(body) + " does not exist");
  // Origin at the anchor, z along the axis (world).
  const Quaternion world_frame = Quaternion::FromTwoVectors(Vector3::UnitZ(), axis.normalized());
  Frame frame;
  if (body < 0) {
    frame.origin = anchor;
    frame.orientation = world_frame;
    return frame;
  }
  const RigidBody& b = bodies[static_cast<std::size_t>(body)];
  frame.origin = b.orientation.conjugate() * (anchor - b.position);
  frame.orientation = (b.orientation.conjugate() * world_frame).normalized();
  return frame;
}

void PlaceJointAt(Joint& joint, const std::vector<RigidBody>& bodies, const Vector3& anchor, const Vector3& axis) {
  try {
    joint.parent_frame = FrameAt(bodies, joint.parent, anchor, axis);
    joint.child_frame = FrameAt(bodies, joint.child, anchor, axis);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("PlaceJointAt: joint '" + joint.name + "': " + e.what());
  }
  joint.axis = Vector3::UnitZ();
}

}  // namespace dynamics

namespace dynamics::internal {

void CheckJoint(const Joint& j, int num_bodies, const std::vector<Joint>& existing) {
  std::ostringstream msg;
  msg << "World::AddJoint: joint '" << j.name << "': ";
  auto fail = [&](const std::string& what) { throw std::invalid_argument(msg.str() + what); };
  auto number = [](double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  };
  if (j.child < 0 || j.child >= num_bodies) fail("child body " + std::to_string(j.child) + " does not exist");
  if (j.parent < -1 || j.parent >= num_bodies) fail("parent body " + std::to_string(j.parent) + " does not exist");
  if (j.parent == j.child) fail("a body cannot be jointed to itself");
  for (const Joint& other : existing) {
    if (other.child == j.child) {
      fail("body " + std::to_string(j.child) + " already hangs from joint '" + other.name +
           "' (each body is the child of one joint)");
    }
  }
  const bool one_dof = HasOneCoordinate(j.type);
  if (one_dof && (!j.axis.allFinite() || !(j.axis.norm() > 1e-12))) fail("the axis must be finite and non-zero");
  for (const Frame* f : {&j.parent_frame, &j.child_frame}) {
    if (!f->origin.allFinite() || !f->orientation.coeffs().allFinite() || !(f->orientation.norm() > 1e-12)) {
      fail("its frames must be finite, with non-zero quaternions");
    }
  }
  auto non_negative = [&](double x, const char* what) {
    if (!(x >= 0) || !std::isfinite(x)) fail(std::string(what) + " must be finite and >= 0 (got " + number(x) + ")");
  };
  non_negative(j.damping, "damping");
  non_negative(j.friction, "friction");
  non_negative(j.stiffness, "stiffness");
  non_negative(j.armature, "armature");
  non_negative(j.motor.kp, "motor kp");
  non_negative(j.motor.kd, "motor kd");
  if (!std::isfinite(j.rest_position)) fail("the spring's rest position must be finite");
  if (!std::isfinite(j.motor.target)) fail("the motor's target must be finite");
  if (!std::isfinite(j.motor.target_velocity)) fail("the motor's target velocity must be finite");
  if (!(j.motor.max_effort > 0)) fail("the motor's max effort must be > 0 (got " + number(j.motor.max_effort) + ")");
  if (std::isnan(j.limits.lower) || std::isnan(j.limits.upper) || !(j.limits.lower <= j.limits.upper)) {
    fail("limits must have lower <= upper (got " + number(j.limits.lower) + ", " + number(j.limits.upper) + ")");
  }
  if (!(j.limits.restitution >= 0 && j.limits.restitution <= 1)) {
    fail("restitution must be in [0, 1] (got " + number(j.limits.restitution) + ")");
  }
  const bool has_limits = std::isfinite(j.limits.lower) || std::isfinite(j.limits.upper);
  if (!one_dof &&
      (has_limits || j.friction > 0 || j.stiffness > 0 || j.armature > 0 || j.motor.mode != JointMotor::Mode::kOff)) {
    fail(std::string("limits, friction, springs, armature and motors act on revolute and prismatic joints, not on a ") +
         JointTypeName(j.type) + " joint");
  }
  if (j.damping > 0 && !(one_dof || j.type == JointType::kSpherical)) {
    fail(std::string("damping acts on revolute, prismatic and spherical joints, not on a ") + JointTypeName(j.type) +
         " joint");
  }
  const auto nq = static_cast<std::size_t>(JointPositionSize(j.type));
  const auto nv = static_cast<std::size_t>(JointVelocitySize(j.type));
  if (!j.position.empty() && j.position.size() != nq) {
    fail("a " + std::string(JointTypeName(j.type)) + " joint's position has " + std::to_string(nq) + " numbers, got " +
         std::to_string(j.position.size()));
  }
  if (!j.velocity.empty() && j.velocity.size() != nv) {
    fail("a " + std::string(JointTypeName(j.type)) + " joint's velocity has " + std::to_string(nv) + " numbers, got " +
         std::to_string(j.velocity.size()));
  }
  for (double x : j.position) {
    if (!std::isfinite(x)) fail("the initial position must be finite");
  }
  for (double x : j.velocity) {
    if (!std::isfinite(x)) fail("the initial velocity must be finite");
  }
  if (one_dof && !j.position.empty() && (j.position[0] < j.limits.lower || j.position[0] > j.limits.upper)) {
    fail("the initial position " + number(j.position[0]) + " is outside its limits [" + number(j.limits.lower) + ", " +
         number(j.limits.upper) + "]");
  }
  const std::size_t quat = j.type == JointType::kSpherical ? 0 : 3;
  if ((j.type == JointType::kSpherical || j.type == JointType::kFree) && !j.position.empty()) {
    const double n2 = j.position[quat] * j.position[quat] + j.position[quat + 1] * j.position[quat + 1] +
                      j.position[quat + 2] * j.position[quat + 2] + j.position[quat + 3] * j.position[quat + 3];
    if (!(n2 > 1e-24)) fail("the initial quaternion must be non-zero");
  }
}

}  // namespace dynamics::internal
