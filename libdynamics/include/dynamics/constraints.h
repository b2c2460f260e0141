#pragma once
/// @file
/// What a tree of joints cannot say: loops closed between two bodies, couplings of one joint's
/// (or tendon's) position to another's, and tendons — lengths along joints (fixed) or through
/// points of bodies (spatial) with a range, a spring, a damper and a drive.
///
/// A world with any of them is articulated (dynamics/joints.h) and they act in its step as rows
/// beside the joints' stops, friction and motors:
/// - loops and couplings are bilateral and exact: the step's velocities are projected so that
///   the constraint holds at the step's end to the linearization's order (exactly for linear
///   couplings), and the positions are then projected back onto the constraint (a Newton
///   projection in the mass matrix's metric, to rounding), the velocities onto its tangent — no
///   spring, no Baumgarte term, so nothing drifts over long runs;
/// - a tendon's range is unilateral: a row like a joint's stop (a string goes slack, and pulls
///   when taut);
/// - a tendon's spring, damper and drive are efforts along its length, J_Lᵀ f.
/// In a contact step (ContactWorld) the same rows are in the contacts' solve: the contacts see
/// the bodies' response with the loops and couplings held.
///
/// MuJoCo's solref/solimp (a soft constraint's stiffness and damping) have no meaning here:
/// readers note them and hold the constraint exactly.

#include <array>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "dynamics/joints.h"

namespace dynamics {

/// A frame fixed in a body (body coordinates: origin at the center of mass, principal axes), or
/// in the world (body -1).
struct BodyFrame {
  int body = -1;
  Frame frame;
};

/// Where frame `f` is in the world, with the bodies where `bodies` has them (a loop's ends, a
/// tendon's points): its origin, and its axes' orientation.
Frame InWorld(const std::vector<RigidBody>& bodies, const BodyFrame& f);

/// How a loop holds frame b on frame a.
enum class LoopType {
  kBall,    ///< the origins coincide (MJCF <equality connect>)
  kWeld,    ///< the frames coincide (MJCF <equality weld>)
  kHinge,   ///< the origins and the z axes coincide: a turn about z is free (SDFormat revolute)
  kSlider,  ///< the axes coincide and b's origin is on a's z axis: a shift along z is free
};
/// "ball", "weld", "hinge", "slider".
const char* LoopTypeName(LoopType type);

/// A loop closure: a joint that the tree of joints cannot hold (its child already hangs from
/// another). Its frames must (nearly) meet when the world starts: the first step projects them
/// together, and World::AddLoop refuses a gap of more than `tolerance`.
struct Loop {
  std::string name;  ///< for messages and outputs
  LoopType type = LoopType::kBall;
  BodyFrame a, b;
  double tolerance = 1e-6;  ///< m (and rad): the largest gap accepted at the start
};

/// A scalar coordinate of the world: a 1-dof joint's position (rad or m) or a tendon's length (m,
/// or a fixed tendon's units).
struct Coordinate {
  enum class Kind { kJoint, kTendon };
  Kind kind = Kind::kJoint;
  int index = -1;  ///< joint or tendon index; -1: none
};

/// y − y_ref = c₀ + c₁ (x − x_ref) + c₂ (x − x_ref)² + c₃ (x − x_ref)³ + c₄ (x − x_ref)⁴, with y the
/// follower's coordinate and x the leader's (MJCF <equality joint|tendon polycoef>; URDF's
/// <mimic multiplier offset> is c₀ = offset, c₁ = multiplier, references 0). Without a leader
/// (index -1) the follower is held at y_ref + c₀.
struct Coupling {
  std::string name;
  Coordinate follower, leader;
  std::array<double, 5> polynomial{0, 1, 0, 0, 0};
  double follower_reference = 0, leader_reference = 0;
};

/// A tendon's length L: Σ cᵢ qᵢ over 1-dof joints (fixed), or the length of the straight
/// segments through `path`'s points (spatial: frame origins; wrapping around geometry is not
/// modelled). Its range is a pair of stops on L (restitution as a joint's); its spring pulls L
/// toward `rest_length` (stiffness ≥ 0, N/m), its damper resists L̇, and its motor (dynamics/
/// joints.h: kEffort or kPosition on L; kVelocity is refused) pulls along it.
struct Tendon {
  std::string name;
  std::vector<std::pair<int, double>> joints;  ///< fixed: (joint index, coefficient)
  std::vector<BodyFrame> path;                 ///< spatial: two points or more
  JointLimits limits;
  double stiffness = 0;    ///< N/m
  double rest_length = 0;  ///< m
  double damping = 0;      ///< N·s/m
  JointMotor motor;
};

/// A loop's, coupling's or tendon's state after a step.
struct ConstraintState {
  /// The loop's gap (m, and rad for its turns), the coupling's y − y(x), or the tendon's length
  /// beyond its range (0 within it).
  double residual = 0;
  double length = 0;   ///< a tendon's length; a coupling's follower coordinate
  double impulse = 0;  ///< the constraint's impulse in the last step (N·s, N·m·s; a loop's magnitude)
};

}  // namespace dynamics
