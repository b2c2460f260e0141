#pragma once
/// @file
/// A world of rigid bodies stepped together, with the integrators of the project and energy and
/// momentum diagnostics.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "dynamics/constraints.h"
#include "dynamics/forces.h"
#include "dynamics/joints.h"
#include "dynamics/rigid_body.h"

namespace dynamics {

enum class Integrator {
  /// Default. Kick–drift–kick (Strang) splitting: half kicks of the forces on v and L, a drift of
  /// x, and the free rotation by the implicit midpoint rule on the body angular momentum with a
  /// Cayley update of the attitude (Austin, Krishnaprasad & Wang 1993; Lewis & Simo 1994). Second
  /// order; for a torque-free body energy, |L| and world L are conserved to rounding. Translation
  /// is velocity Verlet (exact under constant gravity).
  kImplicitMidpoint,
  /// Symmetric splitting of the free rotation into exact rotations about the principal axes
  /// (McLachlan 1993; Dullweber, Leimkuhler & McLachlan 1997), in the same kick–drift–kick frame:
  /// explicit, symplectic, |L| exact, bounded energy error.
  kSplitting,
  /// Classical Runge–Kutta 4 on (x, v, q, L), quaternion renormalized after each step.
  kRK4,
  /// The textbook scheme of the seed notes: explicit Euler on world L and R += h[ω]×R, with the
  /// rotation re-projected by SVD. Kept as a reference: its energy drifts.
  kExplicitEuler,
  /// Explicit Euler on the quaternion, renormalized.
  kQuaternionEuler,
  /// Semi-implicit (symplectic) Euler: velocities first, positions with the new velocities.
  kSymplecticEuler,
  /// The game-engine scheme (Catto, GDC 2015; Bullet's default): implicit Euler on the body
  /// angular velocity with one Newton step on the gyroscopic term. Stable, but it dissipates.
  kImplicitGyroscopic,
  /// Kick–drift–kick with the exact flow of the free rigid body (ExactFreeRotation: Jacobi
  /// elliptic functions and quadrature) as the drift: exact without torques, second order with
  /// them. Bodies whose moments are not strictly increasing, or on the separatrix, fall back to
  /// the implicit midpoint drift. Costly (elliptic functions every step): a reference.
  kExactSplitting,
};

/// The name of an integrator as parsed and printed ("implicit-midpoint", ...).
const char* IntegratorName(Integrator integrator);
/// Every name, comma-separated, for messages and help texts.
std::string IntegratorNames();

/// Every integrator, in the order above.
inline constexpr Integrator kAllIntegrators[] = {
    Integrator::kImplicitMidpoint,   Integrator::kSplitting,       Integrator::kRK4,
    Integrator::kExplicitEuler,      Integrator::kQuaternionEuler, Integrator::kSymplecticEuler,
    Integrator::kImplicitGyroscopic, Integrator::kExactSplitting};

/// The seed notes' attitude step R ← R + h[ω]×R, followed (if `reproject`) by the projection
/// onto the rotations through the SVD, R = U Vᵀ with det +1. Without it R drifts off SO(3).
Matrix3 ExplicitEulerRotation(const Matrix3& R, const Vector3& omega_world, double h, bool reproject);
/// Parses an integrator's name (IntegratorNames()).
/// @throws std::invalid_argument for an unknown name, listing the known ones.
Integrator ParseIntegrator(const std::string& name);

/// Energy and momenta of the whole world.
struct Diagnostics {
  double time = 0;
  double kinetic_energy = 0;                   ///< J
  double potential_energy = 0;                 ///< J, of the forces that have one
  double total_energy = 0;                     ///< J
  Vector3 linear_momentum = Vector3::Zero();   ///< kg·m/s
  Vector3 angular_momentum = Vector3::Zero();  ///< kg·m²/s, about the world origin
};

/// Relative change of the diagnostics since a start: energy by the start's |E| (or its kinetic
/// energy when E is 0), momenta by their start magnitude (absolute when that is 0).
struct Drift {
  double energy = 0;
  double linear_momentum = 0;
  double angular_momentum = 0;
};
Drift DriftSince(const Diagnostics& start, const Diagnostics& now);

/// Which quantities the world's physics conserves (from its forces' traits), and what breaks the
/// others ("gravity, damping"), for summaries.
struct Conservation {
  bool energy = true;
  bool momentum = true;  ///< linear and angular
  std::string energy_broken_by;
  std::string momentum_broken_by;
};

/// What a step did that the caller should know.
struct StepStatus {
  /// False when the implicit solve did not converge even with the smallest sub-step (the state
  /// is then left as it was before the call), or when the state stopped being finite (diverged:
  /// the state holds what the step made of it). `message` says which, naming the body and the
  /// quantity.
  bool ok = true;
  bool diverged = false;  ///< the state is no longer finite
  int body = -1;          ///< the first body whose state is not finite
  int substeps = 1;       ///< > 1 when the implicit solve needed a smaller step to converge
  std::string message;
};

namespace internal {
struct StepScratch;
class Articulation;
}  // namespace internal
class World {
 public:
  explicit World(Integrator integrator = Integrator::kImplicitMidpoint);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  /// Adds a body; returns its index. @throws std::invalid_argument for a non-positive mass or
  /// moment, a moment triple that violates I1 + I2 ≥ I3, or a non-finite state.
  int AddBody(const RigidBody& body);
  /// Adds a force. @throws std::invalid_argument if it names a body that does not exist.
  void AddForce(std::unique_ptr<Force> force);
  /// Adds a joint (dynamics/joints.h) and places its child, and whatever hangs from it, at the
  /// joint's initial position (when the bodies are next read or stepped: adding n joints is
  /// O(n) in all); returns its index. A world with joints other than free joints
  /// from the world to a lone body is articulated: every body is stepped in joint coordinates
  /// (a body without a joint on an implicit free joint), by the implicit midpoint rule on (q, p)
  /// or RK4 — the other integrators refuse it. A lone free joint leaves its body's bits alone.
  /// The jointed bodies' states in bodies() are then outputs: writing them changes nothing.
  /// @throws std::invalid_argument for a missing body, a body that already has a parent joint, a
  /// loop, parameters out of range (naming the joint and the field), or after the first step.
  int AddJoint(const Joint& joint);
  /// PlaceJointAt with the bodies as they were added (q = 0 for every joint), whatever joints
  /// added since have moved: `anchor` and `axis` in the world of that placement.
  void PlaceJoint(Joint& joint, const Vector3& anchor, const Vector3& axis) const {
    PlaceJointAt(joint, as_added_, anchor, axis);
  }
  /// FrameAt with the bodies as they were added: a loop's frame or a tendon's point given in the
  /// world of that placement, in body `body`'s coordinates (-1: the world's).
  Frame FrameAsAdded(int body, const Vector3& anchor, const Vector3& axis = Vector3::UnitZ()) const {
    return FrameAt(as_added_, body, anchor, axis);
  }
  /// Body i's state when it was added. @throws std::out_of_range.
  const RigidBody& body_as_added(int i) const { return as_added_.at(static_cast<std::size_t>(i)); }
  const std::vector<Joint>& joints() const { return joints_; }
  /// Position, velocity and last step's impulses of joint j. @throws std::out_of_range.
  JointState joint_state(int j) const;
  /// Adds a loop closure (dynamics/constraints.h) between bodies placed by the joints added so
  /// far; returns its index. The world becomes articulated.
  /// @throws std::invalid_argument for a missing body, a loop of a body with itself, or frames
  /// that do not meet within the loop's tolerance (saying by how much), or after the first step.
  int AddLoop(const Loop& loop);
  /// Adds a coupling; returns its index. @throws std::invalid_argument for a joint or tendon that
  /// does not exist, a joint of other than one coordinate, a coupling of a coordinate to itself,
  /// a coordinate that already follows another, a cycle of couplings, a coefficient that is not
  /// finite, or after the first step.
  int AddCoupling(const Coupling& coupling);
  /// Adds a tendon; returns its index. @throws std::invalid_argument for a joint that does not
  /// exist or has other than one coordinate, a spatial tendon of fewer than two points, one both
  /// fixed and spatial or neither, a missing body, a range whose lower end is above its upper, a
  /// negative stiffness or damping, a velocity motor, or after the first step.
  int AddTendon(const Tendon& tendon);
  const std::vector<Loop>& loops() const { return loops_; }
  const std::vector<Coupling>& couplings() const { return couplings_; }
  const std::vector<Tendon>& tendons() const { return tendons_; }
  /// Gap, impulse (and length) of loop, coupling or tendon k. @throws std::out_of_range.
  ConstraintState loop_state(int k) const;
  ConstraintState coupling_state(int k) const;
  ConstraintState tendon_state(int k) const;
  /// True when the world is stepped in joint coordinates (see AddJoint).
  bool articulated() const { return jointed_; }

  /// Advances by h seconds. Never clamps angular velocity: when an implicit solve does not
  /// converge it halves the step (up to 2^10 sub-steps) and says so in the status; if even that
  /// fails, the status says so and the state is left as before the call. A world of free bodies
  /// allocates nothing once it has stepped (scratch is kept between steps); an articulated one
  /// allocates a few small vectors a step.
  /// @throws std::invalid_argument if h is not finite and positive, or for an articulated world
  /// and an integrator other than implicit-midpoint and rk4.
  StepStatus Step(double h);

  double time() const { return time_; }
  const std::vector<RigidBody>& bodies() const {
    Place();
    return bodies_;
  }
  std::vector<RigidBody>& bodies() {
    Place();
    return bodies_;
  }
  Integrator integrator() const { return integrator_; }
  void set_integrator(Integrator integrator) { integrator_ = integrator; }
  /// Worker threads for the per-body work of large worlds (0: all cores). Results do not depend
  /// on it: bodies are independent within each phase.
  void set_num_threads(int n) { num_threads_ = n; }
  int num_threads() const { return num_threads_; }
  /// For a stepper that moves the bodies itself (ContactWorld): the clock after its step.
  void set_time(double t) { time_ = t; }

  Diagnostics Diagnose() const;
  Conservation Conserves() const;
  /// The first body whose state (position, velocity, orientation, angular momentum) is not
  /// finite, with the quantity's name; -1 and "" when all are finite.
  std::pair<int, const char*> FirstNonFinite() const;
  const std::vector<std::unique_ptr<Force>>& forces() const { return forces_; }

 private:
  friend class ContactWorld;  // steps the articulation through contact
  StepStatus Advance(double h);
  /// Builds the articulation the joints added since it was last built make, and places their
  /// bodies — once, when the bodies are next read or stepped: rebuilt at every AddJoint, a chain
  /// of n links took O(n²) (3000 links: 4 s).
  void Place() const;

  Integrator integrator_;
  mutable std::vector<RigidBody> bodies_;  ///< (placed by Place: a read of them places them first)
  std::vector<std::unique_ptr<Force>> forces_;
  std::unique_ptr<internal::StepScratch> scratch_;  ///< kept between steps
  std::vector<Joint> joints_;
  std::vector<Loop> loops_;
  std::vector<Coupling> couplings_;
  std::vector<Tendon> tendons_;
  std::vector<RigidBody> as_added_;  ///< the bodies' states when added (before joints moved them)
  mutable std::unique_ptr<internal::Articulation> articulation_;  ///< null: free bodies only
  mutable bool placed_ = true;  ///< articulation_ and bodies_ follow every joint added
  bool jointed_ = false;        ///< a joint other than a lone body's free joint from the world
  std::vector<int> parent_of_;  ///< each body's parent through its joint (-1: the world or none)
  double time_ = 0;
  int num_threads_ = 0;
};

}  // namespace dynamics
