#pragma once
// The contact step as named stages (internal to ContactWorld, contact_world.cpp, which runs them
// in this order): kick, detect (pose the bodies, ground rows, candidate pairs, pair rows, the
// jointed bodies' rows), islands (sleeping bodies held), solve, drift (position correction with
// it), and the sleep that follows. Each stage reads the world's model (what was added), the state
// kept between steps, and the step's scratch, and writes the scratch or the state.

#include <map>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "../articulated/articulation.h"
#include "../integrators/integrator.h"
#include "broad_phase.h"
#include "dynamics/contact.h"
#include "islands.h"
#include "manifold_cache.h"
#include "massprops/parallel.h"
#include "narrow_phase.h"
#include "polytope.h"
#include "sample_bounds.h"
#include "solver.h"
#include "workers.h"

namespace dynamics::contact {

/// A body fixed in the world: its collider and, for a box or convex shape, its polytope.
struct StaticBody {
  Collider collider;
  std::shared_ptr<const Polytope> polytope;
  /// Its polytope placed in the world once (it does not move; Posed::placed points here).
  std::unique_ptr<PlacedPolytope> placed;
};

/// What was added to the world: it changes only when something is added.
struct Model {
  std::vector<Collider> colliders;  // one per dynamic body
  std::vector<bool> collides;       // false: the body has no collider
  std::vector<double> radii;        // each collider's bounding radius (a hull's: a pass over it)
  std::vector<std::shared_ptr<const Polytope>> polytopes;
  std::vector<StaticBody> statics;
  std::vector<BroadStatic> static_broad;  // each static body posed in the world, with its bounds
  std::vector<Ground> grounds;
  std::map<std::pair<int, int>, Material> pair_materials;
  std::set<std::pair<int, int>> excluded;  // body pairs that never touch (ExcludePair), (min, max)
};

/// What one step leaves for the next.
struct State {
  SleepState sleep;  // ContactOptions::sleeping
  // A sleeping body's ground rows, found in its first step asleep: it does not move while it
  // sleeps, so the narrow phase would find the same ones again (only their keys are used: the
  // rows of sleeping bodies keep their cached impulses, HoldSleeping). Empty and unset once awake.
  std::vector<std::vector<Row>> asleep_ground_rows;
  std::vector<char> asleep_ground_known;
  ContactCache cache;               // the last step's impulses: the warm start of the next
  ManifoldCache manifolds;          // pairs' contact points, for the steps that follow (reuse_distance)
  SampleBoundsCache sample_bounds;  // mesh pairs' field bounds, for the steps that follow (exact)
};

/// A step's working memory (kept between steps for its allocations); rows and patches stay
/// readable after the step (ContactWorld::Contacts).
struct Scratch {
  std::vector<Row> rows;
  std::vector<Patch> patches;
  std::vector<Velocities> vel;
  std::vector<Velocities> before_kick;  // the velocities at the start of the step (for impacts)
  BodyResponse response;
  double bounce_threshold = 0;         // impacts slower than this do not bounce
  std::vector<Posed> posed;            // each body's collider in the world
  std::vector<BroadBody> broad;        // and its reach in this step
  std::vector<PlacedPolytope> placed;  // each body's polytope in the world (placed when in a pair)
  ContactCache kept;  // the sleeping contacts' warm start; then the cache before last (its arrays reused)
  std::unique_ptr<Workers> workers;              // kept between steps; null: one thread
  internal::StepScratch step_scratch;            // the forces' wrenches
  std::vector<std::vector<ContactPoint>> found;  // each candidate pair's points
  std::vector<std::vector<ContactPoint>> fresh;  // the narrow phase's (a kept pair's: none)
  std::vector<char> keep;                        // each candidate's points may be kept
  Coupling coupling;                             // an articulated world's bodies (a step's)
  std::vector<internal::Vector6> kicked;         // their (v, ω) after the kick
  // The stages' working arrays, so that a step like the one before allocates nothing.
  std::vector<ContactPoint> points;      // one body's against one ground
  std::vector<GroundScan> ground_scans;  // each body's hull against each ground (body-major)
  std::vector<Candidate> candidates;     // the broad phase's pairs
  std::vector<SweepInterval> intervals;  // and its sweep
  std::vector<PairQuery> queries;        // the narrow phase's
  std::vector<char> touched;             // bodies with contacts (an articulated world)
  Islands islands;                       // the step's islands
  std::vector<int> island, levels;       // each body's island and support level
  SolveScratch solve;                    // the solve's
  std::vector<Velocities> pseudo;        // the position correction's velocities (empty: none)
  std::vector<Wrench> impulses, pushes;  // an articulated world's, per body

  // The worker pool for `threads` (null for one thread).
  Workers* WorkersFor(int threads) {
    const int n = massprops::ThreadCount(threads);
    if (n <= 1) return nullptr;
    if (!workers || workers->threads() != n) workers = std::make_unique<Workers>(n);
    return workers.get();
  }
};

/// What the world hands a step.
struct StepInput {
  std::vector<RigidBody>& bodies;
  const std::vector<std::unique_ptr<Force>>& forces;
  internal::Articulation* jointed;  // null: no joints
  const ContactOptions& options;
  double time = 0, h = 0;
  int threads = 1;
};

/// 1. The kick: velocities after this step's forces, before contact (s.vel), the start-of-step
/// velocities, the bodies' responses and the bounce threshold. False when an articulated world's
/// mass matrix is not positive definite.
bool Kick(const StepInput& in, Scratch& s);

/// 2. Detect: the rows of every contact at the start-of-step positions, within each body's reach
/// in this step — against the grounds, then pair by pair (the narrow phase on the workers, the
/// rows in the pairs' order: the same bits on any thread count); a jointed world's rows that no
/// motion of the trees can serve are dropped. Fails naming a pair of kinds with no routine.
StepStatus Detect(const StepInput& in, const Model& model, State& state, Scratch& s, ContactStats& stats);

/// No contact this step: the warm start and the sleep are forgotten.
void Forget(State& state);

/// 3. Islands: a sleeping island wakes as a whole when an awake body touches it; bodies still
/// asleep are held still (no kick, as heavy as the ground), and contacts among them alone are not
/// solved (their warm start is kept for when the island wakes: in `s.kept`). Returns the step's
/// islands (`s.islands`).
Islands& HoldSleeping(const StepInput& in, State& state, Scratch& s);

/// 4. The impulses: patches, the sweeps island by island, the warm start stored for the next step
/// (`s.kept` joined to it; `s.kept` then holds the old cache's arrays), the kinetic energy the
/// impulses took.
void Solve(const StepInput& in, Islands& islands, State& state, Scratch& s, ContactStats& stats);

/// 5. Position correction of overlap beyond each contact's slop, and 6. the drift (the joints'
/// finish in an articulated world).
StepStatus Drift(const StepInput& in, const Model& model, const State& state, Scratch& s, ContactStats& stats);

/// 7. After the drift: islands that stayed slow long enough fall asleep (ContactOptions::sleeping;
/// free bodies only).
void Sleep(const StepInput& in, const Model& model, Islands& islands, State& state, const Scratch& s,
           ContactStats& stats);

}  // namespace dynamics::contact
