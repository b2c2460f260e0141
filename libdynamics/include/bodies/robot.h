#pragma once
/// @file
/// Robots in a world (target massprops::bodies): a robot description read by
/// massprops::ReadRobotModel (URDF, SDFormat, MJCF; inertials as written or filled) made into
/// bodies, colliders and joints of a ContactWorld.
///
///   massprops::RobotModel model = massprops::ReadRobotModel("dog.urdf", {.fill = true});
///   dynamics::RobotOptions options;
///   options.pose.translation = {0, 0, 0.5};
///   dynamics::RobotInWorld dog = dynamics::AddRobot(world, model, options);
///
/// Links joined by fixed joints are one body (their inertials combined, as simulators lump
/// them); a body's collider is its links' collision geometries, each as it is (box, sphere,
/// capsule, cylinder; a mesh as its convex hull, or as the mesh itself on request) and each with
/// its collision bits: a compound when there are several. Joints keep their type, axis, limits, damping, friction,
/// spring; a motor per joint comes from the options, its effort bounded by the file's effort
/// limit when the motor names none.

#include <map>
#include <string>
#include <vector>

#include "dynamics/contact.h"
#include "massprops/io/load.h"
#include "massprops/mesh.h"
#include "massprops/robot/robot_model.h"

namespace dynamics {

struct RobotOptions {
  /// The root link's frame in the world. A root the file joins to the world (URDF's "world"
  /// link, SDFormat's, an MJCF top body) is placed where the file puts it relative to this frame,
  /// whatever the base.
  massprops::Placement pose;
  enum class Base {
    kAsWritten,  ///< URDF, SDFormat: floating unless joined to "world"; MJCF: as its top bodies' joints say
    kFixed,      ///< the root welded to the world at `pose`
    kFloating,   ///< the root free
  };
  Base base = Base::kAsWritten;
  std::map<std::string, double> positions;   ///< initial joint positions by joint name (rad, m)
  std::map<std::string, JointMotor> motors;  ///< by joint name (they win over the file's actuators)
  /// An MJCF keyframe's name: its qpos (a free root's pose, the joints' positions), the hinges' and
  /// sliders' qvel and the actuators' ctrl (empty: q = 0, ctrl = 0, actuators limp or holding 0).
  std::string keyframe;
  bool mesh_colliders = false;  ///< meshes collide as meshes (signed distance fields), not hulls
  Material material;
  massprops::LoadOptions load;  ///< how collision meshes are read
};

struct RobotInWorld {
  std::vector<int> bodies;                      ///< the world's indices of the bodies added, in order
  std::vector<std::string> body_names;          ///< each body's (its topmost link's) name
  std::vector<massprops::TriangleMesh> shapes;  ///< each body's collision geometry, body frame, metres
  /// Each body's frame (principal axes at its center of mass) in its topmost link's frame.
  std::vector<massprops::Placement> body_in_link;
  std::vector<int> body_of_link;                   ///< each link's body index in the world (lumped links share one)
  std::vector<massprops::Placement> link_in_body;  ///< each link's frame in its body's frame
  std::vector<int> joint_of;                       ///< each model joint's index in the world's joints (-1: lumped)
  std::vector<std::string> notes;                  ///< lumping, hulls, what the file has that is not simulated
};

/// How high above the ground rbsim, scenes and Python's add_robot set down a robot given no
/// position (m).
inline constexpr double kSetDownClearance = 0.01;

/// Whether the file places the robot in its world, so that it starts there (relative to
/// `options.pose`) and is never set down: MJCF (MuJoCo's qpos0) and SDFormat (the model's and its
/// links' <pose>) always; a URDF whose root a joint attaches to its "world" link; any robot a
/// keyframe places. A URDF with a free root says nothing of where it stands.
bool PlacedByItsFile(const massprops::RobotModel& model, const RobotOptions& options);

/// Where a robot is set down: `options.pose` raised along the first ground's normal so that the
/// robot's lowest collision point (at its initial joint positions) is `clearance` above the highest
/// of the grounds parallel to that one. rbsim, scenes and Python's add_robot set a robot given no
/// position 1 cm above the ground this way. The pose as given when the file places the robot
/// (PlacedByItsFile) or there is no ground. @throws as AddRobot.
massprops::Placement PlaceAboveGround(const massprops::RobotModel& model, const RobotOptions& options,
                                      const std::vector<Ground>& grounds, double clearance);

/// Each body's visual geometry (its links' RobotLink::visuals) as triangles in its body frame,
/// metres — for pictures, as RobotInWorld::shapes holds the colliders'. Meshes are read as they
/// are (open, repeated faces and all: nothing is integrated); one that cannot be read is left
/// out with a note naming the link and the file. `load` gives the unit of meshes that declare none.
std::vector<massprops::TriangleMesh> VisualShapes(const massprops::RobotModel& model, const RobotInWorld& added,
                                                  const massprops::LoadOptions& load, std::vector<std::string>& notes);

/// A file's own floor (an MJCF worldbody plane) as a ground: its collision bits, and its friction
/// mixed as MuJoCo mixes it (the larger of a pair's) when the file gives one.
Ground GroundOf(const massprops::RobotGround& ground);
/// A file's terrain (an MJCF height field) as a static mesh collider in its geom's frame (a signed
/// distance field of the solid; its friction and collision bits the geom's). Add it with
/// ContactWorld::AddStatic(collider, terrain.pose.rotation, terrain.pose.translation).
/// @throws std::invalid_argument naming the terrain when its solid cannot be a collider.
Collider TerrainCollider(const massprops::RobotTerrain& terrain);

/// @throws std::invalid_argument naming the link or joint: a massless link that a joint moves, a
/// joint or position named in the options that the robot has not, a non-positive inertia; or as
/// massprops::LoadSolid for a collision mesh that cannot be read.
RobotInWorld AddRobot(ContactWorld& world, const massprops::RobotModel& model, const RobotOptions& options = {});

}  // namespace dynamics
