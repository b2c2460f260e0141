#pragma once
/// @file
/// Joints between the bodies of a World: fixed, revolute (hinge), prismatic (slider), spherical
/// (ball) and free, with position limits, damping, Coulomb friction, springs and motors.
///
/// Joined bodies are stepped in reduced (joint) coordinates, so a joint holds by construction:
/// the bodies' poses are computed from the joint positions, never corrected towards them. A joint
/// connects a frame J_p fixed in its parent (a body, or the world) to a frame J_c fixed in its
/// child; its position q says how J_c sits in J_p:
///
/// | type | q (numbers) | v (numbers) | J_c in J_p |
/// |---|---|---|---|
/// | fixed | — | — | J_c = J_p |
/// | revolute | angle, rad | rate, rad/s | turned by q about `axis` |
/// | prismatic | offset, m | speed, m/s | moved by q along `axis` |
/// | spherical | unit quaternion w, x, y, z | ω in J_c's axes, rad/s | turned by the quaternion |
/// | free | origin x, y, z (J_p's axes), quaternion | ω (J_c's axes), origin's velocity (J_p's axes) | placed |
///
/// Limits, damping, friction, springs and motors act on revolute and prismatic joints (their
/// "effort" is a torque in N·m or a force in N).

#include <limits>
#include <string>
#include <vector>

#include "dynamics/rigid_body.h"

namespace dynamics {

enum class JointType { kFixed, kRevolute, kPrismatic, kSpherical, kFree };

/// Every joint type, in the order above.
inline constexpr JointType kAllJointTypes[] = {JointType::kFixed, JointType::kRevolute, JointType::kPrismatic,
                                               JointType::kSpherical, JointType::kFree};
/// "fixed", "revolute", "prismatic", "spherical", "free".
const char* JointTypeName(JointType type);
/// Parses a joint type's name. @throws std::invalid_argument for an unknown name, listing the known ones.
JointType ParseJointType(const std::string& name);
/// Revolute and prismatic joints: one coordinate, on which limits, friction, springs and motors act.
inline bool HasOneCoordinate(JointType type) { return type == JointType::kRevolute || type == JointType::kPrismatic; }
/// Numbers in a joint's position and velocity (table above).
int JointPositionSize(JointType type);
int JointVelocitySize(JointType type);

/// A frame fixed in a body (body coordinates: origin at the center of mass, principal axes) or in
/// the world.
struct Frame {
  Vector3 origin = Vector3::Zero();
  Quaternion orientation = Quaternion::Identity();  ///< frame axes → body (or world) axes
};

/// Hard stops at `lower` ≤ q ≤ `upper`. A joint that would pass one in a step is stopped on it by
/// an impulse (and placed on it): it never overshoots. `restitution` e in [0, 1]: the joint
/// leaves the stop at e times the speed it arrived with.
struct JointLimits {
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  double restitution = 0;
};

/// A drive on the joint's coordinate. kVelocity holds q̇ at `target` with an effort of at most
/// `max_effort` (an impulse solved with the limits and friction, so the rate is held exactly when
/// the load is below the limit). kPosition is a PD servo, effort = kp (target − q) + kd
/// (target_velocity − q̇), clipped to ±max_effort (with kp = 0 a damper toward a rate: MuJoCo's
/// velocity actuator). kEffort is a constant effort, `target` clipped to ±max_effort (MuJoCo's
/// motor).
struct JointMotor {
  enum class Mode { kOff, kVelocity, kPosition, kEffort };
  Mode mode = Mode::kOff;
  double target = 0;  ///< rad/s or m/s (velocity); rad or m (position); N·m or N (effort)
  double max_effort = std::numeric_limits<double>::infinity();
  double kp = 0;               ///< N·m/rad or N/m
  double kd = 0;               ///< N·m·s/rad or N·s/m
  double target_velocity = 0;  ///< position: the rate kd drives toward, rad/s or m/s
};

struct Joint {
  std::string name;  ///< for messages and outputs
  JointType type = JointType::kRevolute;
  int parent = -1;                  ///< body index, or -1 for the world
  int child = 0;                    ///< body index; each body is the child of at most one joint
  Frame parent_frame;               ///< J_p in the parent's body coordinates (world coordinates for the world)
  Frame child_frame;                ///< J_c in the child's body coordinates
  Vector3 axis = Vector3::UnitZ();  ///< revolute and prismatic: unit axis in J_p (and J_c) axes
  JointLimits limits;
  double damping = 0;        ///< effort −c q̇, N·m·s/rad or N·s/m
  double friction = 0;       ///< Coulomb: the joint sticks while the other efforts stay below this, N·m or N
  double stiffness = 0;      ///< spring effort −k (q − rest), N·m/rad or N/m
  double rest_position = 0;  ///< the spring's rest position
  /// Added to the joint's diagonal of the mass matrix, kg·m² or kg (revolute and prismatic): a
  /// motor's rotor reflected through its gearbox (MJCF's armature). Its kinetic energy ½ a q̇² is
  /// counted in the world's energy; it carries no momentum of the bodies'.
  double armature = 0;
  JointMotor motor;
  /// Initial position and velocity (sizes from the table; empty: zero, identity quaternion).
  /// Adding the joint places the child (and everything hanging from it) accordingly.
  std::vector<double> position;
  std::vector<double> velocity;
};

/// A joint's state after a step.
struct JointState {
  std::vector<double> position;
  std::vector<double> velocity;
  double limit_impulse = 0;  ///< generalized impulse of the stops in the last step, N·m·s or N·s
  double drive_impulse = 0;  ///< of friction and the velocity motor in the last step
};

/// Frames for a joint that holds the bodies as they are now: J_p and J_c both at `anchor` (world
/// point) with their z axis along `axis` (world direction; the joint's axis becomes +z), so that
/// q = 0 is the current placement. `parent` -1 is the world. Sets parent_frame, child_frame, axis.
/// World::AddJoint moves the child (and what hangs from it) to the joint's initial position, after
/// which the bodies are no longer at q = 0: place every joint before adding any, or use
/// World::PlaceJoint, which places at the bodies as they were added.
/// @throws std::invalid_argument for a zero axis.
void PlaceJointAt(Joint& joint, const std::vector<RigidBody>& bodies, const Vector3& anchor, const Vector3& axis);

/// The frame at `anchor` (world point) with its z axis along `axis` (world direction), in body
/// `body`'s coordinates as `bodies` place it (-1: in the world's) — a joint's, loop's or tendon
/// point's frame given in the world. @throws std::invalid_argument for a body that does not exist
/// or an axis or anchor that is zero or not finite.
Frame FrameAt(const std::vector<RigidBody>& bodies, int body, const Vector3& anchor, const Vector3& axis);

}  // namespace dynamics
