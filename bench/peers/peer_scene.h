#pragma once
// The rbsim scenes a peer engine (MuJoCo, Bullet) can run: bodies that are box, sphere, capsule or
// cylinder solids or convex hulls, static boxes and hulls, ground planes, gravity, materials. Read through rbsim's own
// scene loader (one home for the schema and its checks), handed to a peer as plain numbers, and written back as rbsim's
// trajectory CSV, so that the same scene's three trajectories compare column for column.

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "dynamics/contact.h"
#include "scene/scene.h"

namespace peers {

using massprops::Matrix3;
using massprops::Vector3;
using Quaternion = Eigen::Quaterniond;

struct PeerBody {
  std::string name;
  enum class Kind { kBox, kSphere, kCapsule, kCylinder, kHull } kind = Kind::kBox;
  Vector3 half_extents = Vector3::Zero();  ///< box
  double radius = 0, half_length = 0;      ///< sphere, capsule (cylinder part), cylinder; axis z
  std::vector<Vector3> hull;               ///< kHull: the convex hull's corners, frame F
  double mass = 0;
  /// The body's frame F, in which its inertia is diagonal: a solid's own axes (F = M) for the
  /// primitives, the principal axes (F = B) for a hull. R_MF: F's axes in the mesh's.
  Matrix3 frame = Matrix3::Identity();
  Vector3 inertia = Vector3::Zero();                            ///< about the center of mass, axes of F
  Vector3 position = Vector3::Zero();                           ///< center of mass, world
  Quaternion orientation = Quaternion::Identity();              ///< F's axes → world
  Vector3 velocity = Vector3::Zero(), omega = Vector3::Zero();  ///< world
  dynamics::Material material;
  Matrix3 principal_axes = Matrix3::Identity();  ///< R_MB: for the CSV's w1, w2, w3 (moments ascending)
};

/// A static body: a box (its centre and axes in the world) or a convex hull (its corners in the
/// world).
struct PeerStatic {
  std::string name;
  bool box = true;
  Vector3 half_extents = Vector3::Zero(), position = Vector3::Zero();
  Quaternion orientation = Quaternion::Identity();
  std::vector<Vector3> hull;
  dynamics::Material material;
};

struct PeerScene {
  std::string file;
  double dt = 1e-3, duration = 1, output_rate = 60;
  Vector3 gravity = Vector3::Zero();
  std::vector<scene::GroundSpec> grounds;
  std::vector<PeerStatic> statics;
  std::vector<PeerBody> bodies;
  std::int64_t steps = 0, sample_every = 1;  ///< as rbsim takes them (StepCount, SampleEvery)
};

/// Reads a scene; `dt` > 0 overrides the scene's step. @throws std::runtime_error naming the
/// scene's file and what a peer cannot run (a mesh collider, a spring, pair materials).
PeerScene LoadPeerScene(const std::string& path, double dt = 0);

/// rbsim's trajectory.csv, kept in memory and written whole at the end.
class TrajectoryCsv {
 public:
  /// `q`: the peer body's frame F → world; written as the mesh's orientation, as rbsim writes it.
  void Add(double time, const PeerBody& body, const Vector3& x, const Quaternion& q, const Vector3& v,
           const Vector3& omega_world);
  /// Writes the CSV whole or not at all; false (after a message naming the path) where it cannot.
  bool Write(const std::string& path) const;

 private:
  std::string text_;
};

/// The command line every peer program takes: SCENE [--dt S] [--out FILE.csv]. Returns false
/// (after a message) on bad arguments.
struct PeerArgs {
  std::string scene, out;
  double dt = 0;
  int threads = 1;  ///< rbsim_peer's worker threads (the peers run on one)
};
bool ParsePeerArgs(int argc, char** argv, const char* program, PeerArgs& args);

/// Parses the command line and loads the scene (messages on stderr). Returns -1 to go on, else
/// the exit status to stop with (2 bad arguments, 1 a scene a peer cannot run).
int StartPeer(int argc, char** argv, const char* program, PeerArgs& args, PeerScene& scene);

/// The run every peer makes: `step` scene.steps times, timing the steps alone; `sample` at t = 0,
/// every sample_every steps and after the last, when there is an output. Returns the seconds.
double RunPeer(const PeerScene& scene, const PeerArgs& args, const std::function<void()>& step,
               const std::function<void()>& sample);

/// One line of JSON on stdout: the engine, steps, wall seconds of stepping, steps per second.
void PrintTiming(const char* engine, const char* version, const PeerScene& scene, double seconds);

}  // namespace peers
