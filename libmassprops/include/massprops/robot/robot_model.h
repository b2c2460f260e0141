#pragma once
/// @file
/// Robot descriptions as kinematic trees (target massprops::robot): the links of a URDF,
/// SDFormat or MJCF file with their inertials and collision geometries, and the joints between
/// them, in one convention whatever the format — for simulators (libdynamics' AddRobot).
///
/// Frames. Each link has its frame L (URDF's link frame, SDFormat's link pose, an MJCF body's
/// frame); its inertial and geometries are placed in L. A joint has its frame J: placed in the
/// parent's L by `parent_to_joint`, and the child's L placed in J by `joint_to_child`; the axis is
/// in J. At position q the child is placed by parent_to_joint · motion(q) · joint_to_child, with
/// motion(q) a turn by q about the axis (revolute, continuous), a shift by q along it (prismatic),
/// a quaternion (ball) or nothing (fixed).
///
/// Beyond the tree: URDF <mimic> and MJCF <equality joint|tendon> as couplings, MJCF <equality
/// connect|weld> as loops, MJCF <tendon> (fixed and spatial through sites) as tendons. What cannot
/// be simulated is refused, naming the element: planar/universal/screw joints, a link that is the
/// child of two joints in URDF (SDFormat's second joint of a link is a loop), xacro left
/// unexpanded, nested SDFormat models. What does not move a rigid
/// body (transmissions, Gazebo blocks, sensors, cameras, lights) is noted, one note per kind.
/// URDF's "world" link is the world frame; MJCF files are read as MuJoCo 3 reads them
/// (<include>, autolimits, inertiafromgeom, worldbody floors, contype/conaffinity, <contact>
/// pairs and excludes, friction per geom).

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "massprops/primitive.h"
#include "massprops/robot/robot.h"
#include "massprops/wording.h"

namespace massprops {

/// A rigid placement x ↦ R x + t.
struct Placement {
  Matrix3 rotation = Matrix3::Identity();
  Vector3 translation = Vector3::Zero();
  Placement Then(const Placement& inner) const {  ///< this ∘ inner
    return {rotation * inner.rotation, rotation * inner.translation + translation};
  }
  Placement Inverse() const { return {rotation.transpose(), -(rotation.transpose() * translation)}; }
};

struct RobotMesh {
  std::string path;  ///< resolved to a file
  Vector3 scale = Vector3::Ones();
};

struct RobotGeometry {
  std::variant<Primitive, RobotMesh> shape;
  Placement pose;     ///< in the link frame
  std::string where;  ///< "link 'thigh' collision 'box'", for messages
  /// MJCF's collision bits (contype, conaffinity; 1 and 1 in the other formats): two geometries
  /// may touch when (a.contype & b.conaffinity) | (b.contype & a.conaffinity) is non-zero.
  std::uint32_t contype = 1, conaffinity = 1;
  /// MJCF: the sliding friction MuJoCo gives it (its own or its class's `friction`, else 1; 0 for
  /// condim 1), mixed with the other side's by taking the larger (MuJoCo's rule). None (URDF,
  /// SDFormat): the simulator's material.
  std::optional<double> friction;
};

/// Mass, center of mass (link frame) and inertia about it (link axes), SI.
struct RobotInertial {
  double mass = 0;
  Vector3 center_of_mass = Vector3::Zero();
  Matrix3 inertia = Matrix3::Zero();
};

struct RobotLink {
  std::string name;
  std::optional<RobotInertial> inertial;  ///< none: the file gives no mass (URDF: massless)
  std::vector<RobotGeometry> collisions;
  /// What is drawn (URDF/SDFormat <visual>s, MJCF geoms that collide with nothing), for pictures;
  /// a visual that cannot be read is left out with a note.
  std::vector<RobotGeometry> visuals;
  /// MJCF gravcomp (MuJoCo 3): the fraction of this link's weight held up by a force at its center
  /// of mass, against the simulator's gravity (scenes and rbsim apply it).
  double gravity_compensation = 0;
  /// A root link's frame in the file's world, where the file places it (SDFormat: the model's
  /// <pose>, then the link's); none: the file says nothing (URDF), the root is at the robot's pose.
  std::optional<Placement> placement;
};

enum class RobotJointType { kFixed, kRevolute, kContinuous, kPrismatic, kBall, kFloating };
/// "fixed", "revolute", "continuous", "prismatic", "ball", "floating".
const char* RobotJointTypeName(RobotJointType type);

struct RobotJoint {
  std::string name;
  RobotJointType type = RobotJointType::kFixed;
  int parent = -1;  ///< link index; -1: the world (an SDFormat joint to "world", an MJCF top body)
  int child = 0;    ///< link index
  Placement parent_to_joint, joint_to_child;
  Vector3 axis = Vector3::UnitX();     ///< unit, in J
  std::optional<double> lower, upper;  ///< rad or m (revolute, prismatic)
  double effort = 0;                   ///< N·m or N; 0: not stated
  double velocity = 0;                 ///< rad/s or m/s; 0: not stated
  double damping = 0, friction = 0, stiffness = 0, rest = 0;
  double armature = 0;  ///< kg·m² or kg, on the joint's diagonal of the mass matrix (MJCF)
  /// rad or m (MJCF `ref`): the position at which the file draws the child (joint_to_child holds
  /// the child at q = 0, the file's drawing turned back by it): where the joint starts without a
  /// keyframe, and its position in the reference configuration (MuJoCo's qpos0).
  double ref = 0;
  /// MJCF actuatorfrcrange (N·m or N): the range of the actuators' total force at the joint (their
  /// forcerange narrowed to it through their gear).
  std::optional<std::pair<double, double>> actuator_force_range;
};

/// A plane of the file's own world (MJCF: a plane geom of the worldbody), the half-space
/// {x : normal·x ≤ offset} in the world frame: the floor the file's robot stands on.
struct RobotGround {
  Vector3 normal = Vector3::UnitZ();
  double offset = 0;
  std::string where;                           ///< "geom 'floor'", for messages
  std::string name;                            ///< the geom's name attribute
  std::uint32_t contype = 1, conaffinity = 1;  ///< as RobotGeometry's
  std::optional<double> friction;              ///< as RobotGeometry's
};

/// An MJCF actuator on a joint, in MuJoCo's general form: force = gain ctrl + bias[0] + bias[1]
/// (gear q) + bias[2] (gear q̇), clamped to `forcerange` when given, acting on the joint as
/// gear force. position: gain kp, bias (0, −kp, −kv); velocity: gain kv, bias (0, 0, −kv);
/// motor: gain 1, no bias; general: its gainprm[0] and biasprm[0..2] (fixed gain, affine bias).
struct RobotActuator {
  std::string name;
  int joint = -1;   ///< index in RobotModel::joints
  int tendon = -1;  ///< or index in RobotModel::tendons (joint -1, "gear q" is then gear L)
  double gear = 1, gain = 1;
  std::array<double, 3> bias{};
  std::optional<std::pair<double, double>> ctrlrange, forcerange;  ///< when limited
};

/// One coordinate follows another: y − y₀ = c₀ + c₁ (x − x₀) + … + c₄ (x − x₀)⁴, with x₀ and y₀
/// the coordinates at the reference configuration (every joint at its ref; a tendon's length there).
/// URDF <mimic multiplier offset>: c₀ = offset, c₁ = multiplier. MJCF <equality joint|tendon
/// polycoef>; without a leader the follower is held at y₀ + c₀.
struct RobotCoupling {
  std::string name;
  bool tendons = false;  ///< follower and leader index RobotModel::tendons, else joints
  int follower = -1, leader = -1;
  std::array<double, 5> polynomial{0, 1, 0, 0, 0};
};

/// A loop closure: a frame of link b held on a frame of link a (-1: the world) — their origins
/// (kBall, MJCF connect), the frames (kWeld, MJCF weld), origins and z axes (kHinge, an SDFormat
/// revolute joint closing a loop) or z axes only, b's origin on a's z (kSlider).
struct RobotLoop {
  std::string name;
  enum class Type { kBall, kWeld, kHinge, kSlider };
  Type type = Type::kBall;
  int link_a = -1, link_b = -1;
  Placement in_a;  ///< in link a's frame
  /// In link b's frame; none: where in_a is at the reference configuration (MuJoCo's rule for
  /// connect's anchor and a weld without relpose).
  std::optional<Placement> in_b;
};

/// A tendon (MJCF <tendon>): fixed, L = Σ c q over joints, or spatial, the length of the straight
/// segments through points of links (sites). Its range is a pair of stops on L.
struct RobotTendon {
  std::string name;
  std::vector<std::pair<int, double>> joints;  ///< fixed: (joint index, coefficient)
  std::vector<std::pair<int, Vector3>> path;   ///< spatial: (link index, -1 the world; point in its frame)
  std::optional<std::pair<double, double>> range;
  double stiffness = 0, damping = 0;
  std::optional<double> rest_length;  ///< none: the length at the reference configuration
};

/// Terrain of the file's own world (MJCF: a worldbody geom of type hfield): a height field as the
/// closed solid it bounds — its top the elevation grid (MuJoCo's: the data scaled to [0, 1], then
/// by the elevation size; x and y spanning ±the radii), its sides and bottom down to −base —
/// static, where the geom puts it.
struct RobotTerrain {
  TriangleMesh mesh;                           ///< in the geom's frame, metres
  Placement pose;                              ///< the geom's frame in the world
  std::string where;                           ///< "geom 'terrain' (hfield 'bumps')", for messages
  std::string name;                            ///< the geom's name attribute
  std::uint32_t contype = 1, conaffinity = 1;  ///< as RobotGeometry's
  std::optional<double> friction;              ///< as RobotGeometry's
};

/// The medium the robot moves through (MJCF <option density viscosity wind>): MuJoCo's
/// inertia-box fluid model (dynamics::Fluid).
struct RobotMedium {
  double density = 0;    ///< kg/m³
  double viscosity = 0;  ///< Pa·s
  Vector3 wind = Vector3::Zero();
};

/// An MJCF keyframe, in MuJoCo's order (joints in body order; a free joint's qpos is x y z and a
/// quaternion w x y z in the world, a ball's a quaternion, a hinge's or slide's one number).
struct RobotKeyframe {
  std::string name;
  std::vector<double> qpos, qvel, ctrl;  ///< empty: not given
};

struct RobotModel {
  std::string path;
  RobotFormat format = RobotFormat::kUrdf;
  std::string name;
  std::vector<RobotLink> links;
  std::vector<RobotJoint> joints;        ///< each link is the child of one joint at most
  std::vector<RobotGround> grounds;      ///< the file's own floors (MJCF); none: the simulator's
  std::vector<RobotTerrain> terrains;    ///< the file's height fields (MJCF), static
  std::vector<RobotActuator> actuators;  ///< MJCF <actuator>s on joints and tendons
  std::vector<RobotCoupling> couplings;  ///< URDF <mimic>, MJCF <equality joint|tendon>
  std::vector<RobotLoop> loops;          ///< MJCF <equality connect|weld>, SDFormat loops
  std::vector<RobotTendon> tendons;      ///< MJCF <tendon>
  std::vector<RobotKeyframe> keyframes;  ///< MJCF <keyframe><key>s
  std::optional<RobotMedium> medium;     ///< MJCF <option density viscosity> (none: a vacuum)
  /// MJCF <contact><exclude body1 body2>: pairs of links (indices into `links`) that never touch.
  std::vector<std::pair<int, int>> excluded;
  std::vector<std::string> notes;  ///< what was read but is not simulated (actuators, armature)
  /// The links no joint moves from a parent link: the roots of the trees.
  std::vector<int> Roots() const;
};

struct RobotModelOptions {
  /// Each link's inertial computed from its geometries first, as `massprops fill` writes it
  /// (the model is read from the filled document, so it matches the filled file bit for bit).
  bool fill = false;
  FillOptions fill_options;  ///< how (density, masses, packages, mesh checks)
  /// How the front end names options in messages (null: the C++ API's names).
  const Vocabulary* words = nullptr;
};

/// @throws FileAccessError (io.h) when the file cannot be read; std::runtime_error naming the
///         file and the element for what cannot be read or simulated, or (fill) a link whose
///         inertial could not be computed.
RobotModel ReadRobotModel(const std::string& path, const RobotModelOptions& options = {});

}  // namespace massprops
