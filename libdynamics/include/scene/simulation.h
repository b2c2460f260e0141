#pragma once
// An rbsim run: the scene's bodies loaded into a dynamics::World, stepped to the end with samples
// at the output rate, and the diagnostics summary.

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "dynamics/contact.h"
#include "dynamics/world.h"
#include "massprops/principal_axes.h"
#include "scene/scene.h"

namespace scene {

/// A body of the scene with what the outputs need besides its dynamic state.
struct SimBody {
  std::string name;
  massprops::MassProperties mp;           ///< SI, in the mesh (or solid) frame M
  massprops::PrincipalInertia principal;  ///< axes = R_MB (computed once, by the pipeline)
  massprops::TriangleMesh display;        ///< metres, mesh axes, relative to the center of mass
  /// A robot link's visual geometry, in the frame of `display` (none: it is drawn as `display`,
  /// its collision geometry; with one, the pictures draw it and show `display` on request).
  massprops::TriangleMesh visual;
  Vector3 color = Vector3(0.8, 0.8, 0.8);
  std::string source;     ///< "spot.obj (unit m)" or "cone r=0.1 h=0.3"
  bool collides = false;  ///< it has a collider
};

/// How one body is reported: the pose of its mesh (not of its principal frame).
struct BodyState {
  Vector3 position;         ///< center of mass, world, m
  Quaternion orientation;   ///< mesh axes → world (identity for an unturned body at t = 0)
  Vector3 velocity;         ///< m/s, world
  Vector3 omega_world;      ///< rad/s, world axes
  Vector3 omega_principal;  ///< rad/s, principal axes (moments ascending)
};

/// A static body or ground plane as the outputs draw it: its surface in the world, fixed.
struct SimStatic {
  std::string name;
  massprops::TriangleMesh display;  ///< metres, world coordinates
  Vector3 color = Vector3(0.55, 0.55, 0.55);
};

struct Simulation {
  Scene scene;
  std::vector<SimBody> bodies;
  std::vector<SimStatic> statics;  ///< static bodies and ground planes, for the .glb
  /// The bodies, forces and integrator (world()), with the scene's ground planes, static bodies
  /// and colliders; without any it steps exactly as the world alone.
  dynamics::ContactWorld physics;
  dynamics::Conservation conservation;  ///< what the scene's physics conserves (from the forces)
  bool contact = false;                 ///< the scene has ground, static bodies or colliders
  const dynamics::World& world() const { return physics.world(); }
};

/// Loads every body (mesh files through the massprops checks, solids from closed forms) and
/// builds the world and forces. Nothing runs. @throws SceneError naming the field.
Simulation BuildSimulation(const Scene& scene, std::vector<std::string>& warnings, int threads = 1);

BodyState StateOf(const SimBody& body, const dynamics::RigidBody& rb);

/// A body's reach: its display mesh's farthest corner from its center of mass (m; 0 for none).
double Reach(const SimBody& body);
/// A bound on the speed of the body's fastest point, |v| + |ω| reach (m/s): the rest rule's test.
double FastestPointSpeed(const dynamics::RigidBody& rb, double reach);

struct RunStats {
  std::int64_t steps = 0;
  std::int64_t samples = 0;
  int max_substeps = 1;
  double wall_seconds = 0;
  bool interrupted = false;
  dynamics::Diagnostics start, end;
  dynamics::Drift max_drift;  ///< largest |relative drift| over the samples
  // Contact (scenes with ground, static bodies or colliders).
  int max_contacts = 0;              ///< most contact points in a step
  double max_penetration = 0;        ///< m, the deepest overlap seen
  double dissipated_by_contact = 0;  ///< J, kinetic energy the contact impulses removed
  /// Bodies with a collider that ended the run below every ground by more than their size:
  /// through the floor, never silently (one message each).
  std::vector<std::string> fell_through;
  /// Scenes with until_rest: the time every body came to rest and stayed (the run ended `hold`
  /// later), or none when the duration ran out first.
  std::optional<double> rest_time;
};

/// Steps = ceil(duration / dt) (the last step lands on or just past the duration); a sample is
/// taken at t = 0, every round(1 / (output_rate · dt)) steps, and after the last step.
std::int64_t StepCount(const Scene& scene);
std::int64_t SampleEvery(const Scene& scene);

/// Runs to the end (or until *stop becomes true, or the bodies are at rest when the scene says
/// until_rest), calling on_sample(world, diagnostics) at each
/// sample, on_step(i) after step i (1, 2, ...; before that step's sample) and on_progress(fraction)
/// now and then. @throws std::runtime_error when a step fails or
/// the state diverges (energy, momentum or a body's state no longer finite), naming the time and
/// the body or quantity.
RunStats Run(Simulation& sim,
             const std::function<void(const dynamics::World&, const dynamics::Diagnostics&)>& on_sample,
             const std::function<void(double)>& on_progress = {}, const std::atomic<bool>* stop = nullptr,
             const std::function<void(std::int64_t step)>& on_step = {});

/// The end-of-run summary: energy and momenta at the start and end, their largest drift, and
/// whether the physics of the scene conserves them.
std::string Summary(const Simulation& sim, const RunStats& stats);

}  // namespace scene
