#pragma once
// The bodies and joints the joint tests build again and again: a solid box, and a joint placed at
// an anchor and axis in the world of the bodies as added.

#include <string>

#include "dynamics/joints.h"
#include "dynamics/world.h"

namespace testing {

/// A solid box of sides a, b, c (kg, m), axes along the world's, its centre at `at`.
inline dynamics::RigidBody SolidBox(double m, double a, double b, double c, const massprops::Vector3& at) {
  dynamics::RigidBody body;
  body.mass = m;
  body.inertia = massprops::Vector3(b * b + c * c, a * a + c * c, a * a + b * b) * (m / 12.0);
  body.position = at;
  return body;
}

/// A joint of `type` from `parent` (-1: the world) to `child`, named "j<child>", placed at
/// `anchor` about (or along) `axis` in the world of the bodies as added.
inline dynamics::Joint PlacedJoint(const dynamics::World& w, int parent, int child, const massprops::Vector3& anchor,
                                   const massprops::Vector3& axis,
                                   dynamics::JointType type = dynamics::JointType::kRevolute) {
  dynamics::Joint j;
  j.name = "j" + std::to_string(child);
  j.type = type;
  j.parent = parent;
  j.child = child;
  w.PlaceJoint(j, anchor, axis);
  return j;
}

}  // namespace testing
