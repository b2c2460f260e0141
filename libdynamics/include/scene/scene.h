#pragma once
// Scenes (target massprops::scene): what a scene file (JSON) or rbsim's command line describes,
// typed and validated before anything runs. The schema is in docs/scenes.md; every error names the
// scene file, the field (JSON path) and what is wrong. Building and running a simulation from a
// scene: scene/simulation.h.

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bodies/bodies.h"
#include "bodies/robot.h"
#include "dynamics/contact.h"
#include "dynamics/world.h"
#include "massprops/mass_properties.h"
#include "massprops/mass_spec.h"
#include "massprops/mesh.h"
#include "massprops/primitive.h"
#include "massprops/units.h"

namespace scene {

using massprops::Matrix3;
using massprops::Vector3;
using Quaternion = Eigen::Quaterniond;

/// A scene that cannot run. what() names the file and the field.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Where the mass properties of a body come from, and what it collides as (the body builder's
/// types, bodies/bodies.h).
using ShapeSpec = dynamics::BodyShape;
using CollisionSpec = dynamics::CollisionSpec;
using dynamics::CollidesAsItself;
using dynamics::CollisionKind;

enum class VectorFrame { kWorld, kBody, kPrincipal };

/// "world", "body" or "principal" (the scene's and the command line's names; checked by the caller).
VectorFrame ParseVectorFrame(const std::string& name);

/// A ground plane {x : normal·x ≤ offset}, with its material and collision bits: the contact
/// world's own.
using GroundSpec = dynamics::Ground;

struct BodySpec {
  std::string name;
  std::string field;  ///< "bodies[2]", for messages
  ShapeSpec shape;
  std::optional<Vector3> position;                  ///< center of mass in world; empty: where the file puts it
  Quaternion orientation = Quaternion::Identity();  ///< turns the mesh about its center of mass
  Vector3 velocity = Vector3::Zero();               ///< m/s, world
  Vector3 angular_velocity = Vector3::Zero();       ///< rad/s, in angular_velocity_frame
  VectorFrame angular_velocity_frame = VectorFrame::kWorld;
  std::optional<Vector3> color;  ///< linear RGB in [0, 1] for the .glb
  CollisionSpec collision;
};

/// A body fixed in the world: its mesh or solid placed by x_W = R x_M + t.
struct StaticSpec {
  std::string name;
  std::string field;  ///< "static[0]"
  ShapeSpec shape;
  Vector3 position = Vector3::Zero();
  Quaternion orientation = Quaternion::Identity();
  CollisionSpec collision;
};

enum class ForceKind { kGravity, kLinearDamping, kAngularDamping, kForce, kTorque, kSpring, kFluid };

/// The scene's name of a force kind ("gravity", "linear_damping", ...).
const char* ForceName(ForceKind kind);

struct ForceSpec {
  ForceKind kind = ForceKind::kGravity;
  std::string field;                 ///< "forces[1]"
  std::vector<int> bodies;           ///< body indices it acts on (empty: every body)
  Vector3 vector = Vector3::Zero();  ///< g, force or torque
  /// Spring between bodies: its ends in each body's mesh (or solid) coordinates; empty: the
  /// centers of mass.
  std::vector<Vector3> points;
  /// Force, spring to the world: the body point (mesh coordinates); empty: the center of mass.
  std::optional<Vector3> point;
  bool body_frame = false;           ///< force/torque given in body (mesh) axes and turning with it
  Vector3 anchor = Vector3::Zero();  ///< spring to the world: world anchor
  double coefficient = 0;            ///< damping c; spring stiffness k
  double rest_length = 0;
  double damping = 0;       ///< spring damping along its line
  dynamics::Medium medium;  ///< fluid: density, viscosity, wind
  bool buoyancy = false;    ///< fluid: the medium's weight displaced, on bodies with a volume
};

/// A joint (dynamics/joints.h) as the scene gives it: its frames are placed at `anchor` with z
/// along `axis` (both in the world, at the scene's placement of the bodies, where q = 0) when the
/// simulation is built.
struct JointSpec {
  std::string field;              ///< "joints[0]"
  dynamics::Joint joint;          ///< type, parent, child and parameters (frames not yet placed)
  std::optional<Vector3> anchor;  ///< empty: the child's center of mass
  Vector3 axis = Vector3::UnitZ();
};

/// A loop closure (dynamics/constraints.h) as the scene gives it: its frames at `anchor` with z
/// along `axis`, in the world at the scene's placement of the bodies (where every joint is at 0).
struct LoopSpec {
  std::string field;    ///< "loops[0]"
  dynamics::Loop loop;  ///< name, type and bodies (frames not yet placed)
  Vector3 anchor = Vector3::Zero();
  Vector3 axis = Vector3::UnitZ();
};

/// A tendon as the scene gives it: its joints (scene joint indices) or the world points of its
/// path at the scene's placement, each on a body (or "world").
struct TendonSpec {
  std::string field;  ///< "tendons[0]"
  dynamics::Tendon tendon;
  std::vector<Vector3> points;  ///< the path's points (world); tendon.path holds their bodies
  bool rest_given = false;      ///< else the length at the placement
};

/// A coupling as the scene gives it (its coordinates by joint or tendon name).
struct CouplingSpec {
  std::string field;  ///< "couplings[0]"
  dynamics::Coupling coupling;
};

/// A robot description placed in the scene (docs/robots.md).
struct RobotSpec {
  std::string name;   ///< prefixes its bodies' names ("dog/base_link")
  std::string field;  ///< "robots[0]"
  std::string path;   ///< the URDF, SDFormat or MJCF file
  bool fill = false;  ///< inertials computed from the links' geometries first (massprops fill)
  massprops::FillOptions fill_options;
  dynamics::RobotOptions options;  ///< pose, base, positions, motors, colliders, material
  /// No position given: where its file places it, or set down 1 cm above the ground when it does
  /// not (dynamics::PlacedByItsFile).
  bool position_given = false;
  bool material_given = false;  ///< the scene states the robot's material
};

/// When a run ends before its duration: every body slower than `speed` at its fastest point
/// (|v| + |ω| r, r its farthest point from the center of mass) for `hold` seconds.
struct RestRule {
  double speed = 0.005;  ///< m/s
  double hold = 0.2;     ///< s
};

enum class OutputKind { kCsv, kJsonl, kDiagnostics, kPlotSvg, kPlotPng, kGlb, kContacts, kHtml };

struct Scene {
  std::string file;  ///< scene file ("<command line>" for the quick path)
  double dt = 1e-3;
  double duration = 1.0;
  dynamics::Integrator integrator = dynamics::Integrator::kImplicitMidpoint;
  double output_rate = 60.0;  ///< Hz: trajectory rows and animation keys per simulated second
  char up = 'z';              ///< world up axis (the .glb is turned so that it is glTF's +y)
  std::vector<OutputKind> outputs;
  /// Stop once every body is at rest (the duration is then the cap); none: run to the duration.
  std::optional<RestRule> until_rest;
  int plot_body = 0;
  std::vector<BodySpec> bodies;
  std::vector<ForceSpec> forces;
  std::vector<JointSpec> joints;
  std::vector<LoopSpec> loops;
  std::vector<TendonSpec> tendons;
  std::vector<CouplingSpec> couplings;
  std::vector<RobotSpec> robots;
  std::vector<GroundSpec> grounds;
  /// grounds[0] is the floor a robot file run on its own gets (RobotScene): a file with floors of
  /// its own (MJCF worldbody planes) gets those instead.
  bool default_ground = false;
  std::vector<StaticSpec> statics;
  dynamics::ContactOptions contact;
  bool contact_given = false;  ///< the scene has a "contact" section
  /// Materials of particular pairs: body indices, -1 for the ground and static bodies.
  struct PairMaterial {
    int a = -1, b = -1;
    dynamics::Material material;
  };
  std::vector<PairMaterial> pairs;
  /// How the bodies' findings name the options to try (nullptr: a scene file's keys); a drop made
  /// on the command line or in Python says its flags or keywords.
  const massprops::Vocabulary* words = nullptr;
};

/// What a file given to rbsim (or load_scene) is: a scene (.json), a robot description (an XML
/// document whose root element is <robot>, <sdf> or <mujoco>, or a .urdf, .sdf or .xacro file,
/// whose reader then says what is wrong), a mesh or CAD file massprops reads (by extension), or
/// none of these (also a path that is no regular file).
enum class InputKind { kScene, kRobot, kMesh, kUnknown };
InputKind ClassifyInput(const std::string& path);
/// ClassifyInput(path) == kRobot.
bool IsRobotFile(const std::string& path);
/// What a robot file run as its own scene takes besides the file (rbsim's robot options).
struct RobotFileOptions {
  bool fill = false;        ///< every link's inertial from its geometry first (massprops fill)
  bool fixed_base = false;  ///< the root welded to the world where it starts
  std::string keyframe;     ///< an MJCF <key> to start from: its qpos, qvel and ctrl
  /// package://NAME/ (URDF) and model://NAME/ (SDFormat) roots, before ROS's and Gazebo's paths.
  std::vector<std::pair<std::string, std::string>> packages;
};

/// A robot file given on the command line: where its file places it (a free URDF robot dropped
/// from 1 cm; the MJCF keyframe named, which also sets its joints and controls), for `duration`.
Scene RobotScene(const std::string& path, const RobotFileOptions& options = {});

/// Parses and validates a scene given as JSON text. `base_dir` resolves relative mesh paths.
/// Non-fatal findings (a non-unit quaternion, an output rate above 1/dt, ...) are appended to
/// `warnings`. @throws SceneError naming `file` (and the line, for JSON that does not parse), the
/// field and the fault.
Scene ParseSceneText(const std::string& text, const std::string& file, const std::string& base_dir,
                     std::vector<std::string>& warnings);
/// The checks of dt, duration and output_rate (ParseScene runs them; run them again after
/// changing those fields). @throws SceneError naming the file and the field.
void CheckTiming(const Scene& scene, std::vector<std::string>& warnings);
/// Why `path` cannot be read as a mesh ("not found", "is a directory, not a mesh file", "is not a
/// regular file (…)"), or "" when it is a regular file: the scenes' and --mesh's one wording.
std::string MeshFileProblem(const std::filesystem::path& path);
/// Reads, parses and validates a scene file. @throws SceneError.
Scene LoadScene(const std::string& path, std::vector<std::string>& warnings);

/// Output kind names as in the scene ("csv", "jsonl", "diagnostics", "svg", "png", "glb").
const char* OutputName(OutputKind kind);
OutputKind ParseOutputName(const std::string& name);  // throws std::invalid_argument
/// The default outputs: csv, diagnostics, svg plot, png plot, glb.
std::vector<OutputKind> DefaultOutputs();

}  // namespace scene
