#pragma once
// The velocity solve of a contact step (internal to ContactWorld): the contact rows, their
// effective masses, and the sequential impulses with static and kinetic friction, iterated from
// the ground up with shock propagation.

#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "dynamics/contact.h"

namespace dynamics::contact {

/// A body's velocities as the solve works on them (world frame).
struct Velocities {
  Vector3 v, w;  // linear, angular
};

/// (body a, body b or -1 - static index (-1 for a ground), feature): which contact a row is,
/// step after step.
using RowKey = std::tuple<int, int, std::uint32_t>;

/// One contact point in the solve. Body b = -1: the ground or a static body.
struct Row {
  int a = -1, b = -1;
  Vector3 ra = Vector3::Zero(), rb = Vector3::Zero(), n = Vector3::UnitZ(), t1 = Vector3::UnitX(),
          t2 = Vector3::UnitY();
  Matrix3 Ka = Matrix3::Zero(), Kb = Matrix3::Zero();  // each body's share of K (below)
  int level = 0;                                       // of its lower body in the support graph
  double mass_n = 0;                                   // 1 / (n·K n)
  Eigen::Matrix2d mass_t = Eigen::Matrix2d::Zero();    // (T K Tᵀ)⁻¹
  double target = 0;                                   // the least normal velocity after the step
  double mu_s = 0, mu_k = 0;
  double mu = 0;         // the bound of this step: μs for a contact that holds, μk for one that slides
  bool sliding = false;  // slid last step, and slides now
  Eigen::Vector2d slip_direction = Eigen::Vector2d::Zero();  // unit, of the sliding at the start
  double lambda_n = 0;
  Eigen::Vector2d lambda_t = Eigen::Vector2d::Zero();
  RowKey key;
  double separation = 0;
  // Mesh contacts only: overlap beyond this is pushed out after the step (< 0: never).
  double slop = -1;
  double push = 0;  // its accumulated pseudo-impulse
};

/// What the solve remembers of a contact between steps: its impulses (the warm start) and
/// whether its friction held.
struct CachedRow {
  double lambda_n;
  Eigen::Vector2d lambda_t;
  bool stuck;  // its friction was inside the cone: it holds with μs next step
};
using ContactCache = std::map<RowKey, CachedRow>;

/// Each body's response to impulses: 0 inverse mass and inertia for a body held still (asleep).
struct BodyResponse {
  std::vector<double> inv_mass;
  std::vector<Matrix3> inv_inertia;
};

/// The velocity of row r's point on a relative to b (a ground or static body: at rest).
Vector3 RelativeVelocity(const std::vector<Velocities>& vel, const Row& r);

/// An impulse at row r's point on a and its opposite on b, into `vel`; the body `frozen` (shock
/// propagation) is not moved.
void ApplyImpulse(std::vector<Velocities>& vel, const BodyResponse& bodies, const Row& r, const Vector3& impulse,
                  int frozen = -1);

/// Sets every row's effective masses, warm-starts it from the cache, and chooses static or
/// kinetic friction: a contact that held last step (or a new one whose point barely slides,
/// within `slow`) holds while its friction stays within μs; one that slid slides at μk until it
/// stops.
void PrepareRows(std::vector<Row>& rows, const ContactCache& cache, const std::vector<Velocities>& vel,
                 const BodyResponse& bodies, double slow);

/// Solves the impulses into `vel`: rows sorted by support level (body_level: 0 on the ground or
/// a static body, k + 1 on level k), warm start, then symmetric Gauss–Seidel sweeps until no
/// impulse changes by more than `tolerance` times the largest, and shock propagation level by
/// level when the sweeps run out. Returns the sweeps used.
int SolveImpulses(std::vector<Row>& rows, std::vector<Velocities>& vel, const BodyResponse& bodies,
                  const std::vector<int>& body_level, int max_iterations, double tolerance);

/// The cache for the next step: the solved rows, and `kept` (contacts of bodies held still).
void StoreImpulses(const std::vector<Row>& rows, ContactCache& cache);

}  // namespace dynamics::contact
