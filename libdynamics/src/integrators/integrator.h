#pragma once
// The integrators' common ground (internal): what a step may touch, the per-body loop, and the
// table of integrators. Adding one means one file in this folder and one row in table.cpp.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "dynamics/world.h"
#include "massprops/parallel.h"

namespace dynamics::internal {

/// Scratch kept between steps, so that stepping allocates nothing once a world has run.
struct StepScratch {
  std::vector<Wrench> wrenches;
  std::vector<RigidBody> saved;       ///< state at the start of a step that may be retried
  std::vector<RigidBody> rk4_start;   ///< RK4: state at the start of the step
  std::vector<RigidBody> kick_start;  ///< kick–drift–kick: state before an implicit half kick
  std::vector<double> gross_force;    ///< per body: Σ over forces of |force| + |torque| (a rounding scale)
  std::vector<Wrench> one_force;      ///< one force's wrenches
  struct Rate {                       ///< RK4: stage derivative of one body
    Vector3 dx, dv, dL;
    Eigen::Vector4d dq;
  };
  std::vector<Rate> rk4_k[4];
};

/// What a step function works on.
class StepContext {
 public:
  StepContext(std::vector<RigidBody>& all_bodies, const std::vector<std::unique_ptr<Force>>& forces,
              StepScratch& step_scratch, int num_threads)
      : bodies(all_bodies), scratch(step_scratch), forces_(forces), num_threads_(num_threads) {}

  std::vector<RigidBody>& bodies;
  StepScratch& scratch;

  /// scratch.wrenches = the forces at time t on the current states.
  void ComputeWrenches(double t) {
    std::vector<Wrench>& out = scratch.wrenches;
    out.assign(bodies.size(), Wrench{});
    for (const auto& f : forces_) f->Apply(t, bodies, out);
  }
  std::vector<Wrench>& wrenches() { return scratch.wrenches; }
  /// gross[i] = Σ over the forces of |f| + |τ| on body i at time t: the scale of the rounding in
  /// the net wrench.
  void GrossWrenchMagnitudes(double t, std::vector<double>& gross) {
    gross.assign(bodies.size(), 0.0);
    std::vector<Wrench>& one = scratch.one_force;
    for (const auto& f : forces_) {
      one.assign(bodies.size(), Wrench{});
      f->Apply(t, bodies, one);
      for (std::size_t i = 0; i < bodies.size(); ++i) gross[i] += one[i].force.norm() + one[i].torque.norm();
    }
  }
  /// True when a force depends on the velocities.
  bool VelocityDependent() const {
    for (const auto& f : forces_) {
      if (f->Traits().velocity_dependent) return true;
    }
    return false;
  }

  /// fn(i) for every body, on worker threads for large worlds. Bodies are independent within a
  /// phase, so the results do not depend on the thread count.
  template <typename Fn>
  void ForEachBody(const Fn& fn) const {
    const std::size_t n = bodies.size();
    if (n < 4096 || massprops::ThreadCount(num_threads_) <= 1) {  // not worth a thread
      for (std::size_t i = 0; i < n; ++i) fn(i);
      return;
    }
    constexpr std::size_t kChunk = 1024;
    massprops::ParallelForBlocks(static_cast<std::int64_t>((n + kChunk - 1) / kChunk), num_threads_,
                                 [&](std::int64_t c) {
                                   const auto first = static_cast<std::size_t>(c) * kChunk;
                                   for (std::size_t i = first; i < std::min(n, first + kChunk); ++i) fn(i);
                                 });
  }

 private:
  const std::vector<std::unique_ptr<Force>>& forces_;
  int num_threads_;
};

/// Advances the bodies from time t by h. Returns false when an implicit solve did not converge
/// (the caller restores the state and sub-steps); explicit schemes always return true.
using StepFunction = bool (*)(StepContext& context, double t, double h);

struct IntegratorInfo {
  Integrator id;
  const char* name;  ///< as parsed and printed: "implicit-midpoint", ...
  StepFunction step;
  bool may_fail;  ///< an implicit solve that can fail: Step saves the state and sub-steps
};

/// The table, in the order of kAllIntegrators.
const IntegratorInfo& Info(Integrator integrator);

// The step functions (one file each).
bool StepImplicitMidpoint(StepContext& c, double t, double h);
bool StepSplitting(StepContext& c, double t, double h);
bool StepExactSplitting(StepContext& c, double t, double h);
bool StepRK4(StepContext& c, double t, double h);
bool StepExplicitEuler(StepContext& c, double t, double h);
bool StepQuaternionEuler(StepContext& c, double t, double h);
bool StepSymplecticEuler(StepContext& c, double t, double h);
bool StepImplicitGyroscopic(StepContext& c, double t, double h);

// Shared pieces.
Matrix3 Skew(const Vector3& w);
/// q̇ = ½ (0, ω_world) ⊗ q.
Quaternion QuaternionRate(const Quaternion& q, const Vector3& omega_world);
/// Free rotation over h by the implicit midpoint rule with the Cayley update; false when the
/// solve does not converge.
bool MidpointRotation(RigidBody& b, double h);
/// Kick–drift–kick (Strang) splitting: half kicks of the forces on v and L around a drift of x
/// and the free rotation `rotate` (false: not converged).
template <typename Rotate>
bool KickDriftKick(StepContext& c, double t, double h, const Rotate& rotate) {
  std::vector<RigidBody>& bodies = c.bodies;
  auto half_kick = [&] {
    const std::vector<Wrench>& w = c.wrenches();
    c.ForEachBody([&](std::size_t i) {
      bodies[i].velocity += 0.5 * h / bodies[i].mass * w[i].force;
      bodies[i].angular_momentum += 0.5 * h * w[i].torque;
    });
  };
  c.ComputeWrenches(t);
  if (!c.VelocityDependent()) {
    half_kick();
  } else {
    // Velocity-dependent forces: the first half kick is implicit in the velocities it produces,
    // v½ = vₙ + h/2 a(xₙ, v½) (fixed-point iteration), and the second explicit in v½: the two
    // are each other's adjoint, so the composition stays symmetric and second order (an explicit
    // first kick makes it first order: measured 1.00–1.21 with damping).
    std::vector<RigidBody>& start = c.scratch.kick_start;
    start.assign(bodies.begin(), bodies.end());
    // Convergence is judged against what rounding leaves: each body's momenta and the gross size
    // of the forces on it (a body at rest under balanced forces has tiny momenta but not tiny
    // rounding in its net force).
    std::vector<double>& gross = c.scratch.gross_force;
    c.GrossWrenchMagnitudes(t, gross);
    bool converged = false;
    for (int iteration = 0; iteration < 100 && !converged; ++iteration) {
      const std::vector<Wrench>& w = c.wrenches();
      converged = true;
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Vector3 v = start[i].velocity + 0.5 * h / bodies[i].mass * w[i].force;
        const Vector3 L = start[i].angular_momentum + 0.5 * h * w[i].torque;
        const double change =
            std::max((v - bodies[i].velocity).norm() * bodies[i].mass, (L - bodies[i].angular_momentum).norm());
        const double scale = std::max({v.norm() * bodies[i].mass, L.norm(), start[i].velocity.norm() * bodies[i].mass,
                                       start[i].angular_momentum.norm()}) +
                             h * gross[i];
        converged = converged && change <= 4e-15 * scale;
        bodies[i].velocity = v;
        bodies[i].angular_momentum = L;
      }
      if (!converged) c.ComputeWrenches(t);
    }
    if (!converged) {  // the damping is too stiff for this step: the caller sub-steps
      std::copy(start.begin(), start.end(), bodies.begin());
      return false;
    }
  }
  std::atomic<bool> ok{true};
  c.ForEachBody([&](std::size_t i) {  // drift
    bodies[i].position += h * bodies[i].velocity;
    if (!rotate(bodies[i], h)) ok = false;
  });
  if (!ok) return false;
  c.ComputeWrenches(t + h);
  half_kick();
  return true;
}

/// The most sub-steps a step is split into before it gives up.
inline constexpr int kMostSubsteps = 1024;

/// The one halving retry: the step from t0 over h as 1, 2, 4, … kMostSubsteps sub-steps of equal
/// length until every one succeeds. Each attempt starts with begin(); sub_step(t, dt, s) takes
/// sub-step s from t, false when it fails; restore() puts the state back after a failed attempt.
/// Returns the sub-steps that succeeded, or 0 when even the most did not (the state restored).
template <typename Begin, typename SubStep, typename Restore>
int StepWithHalving(double t0, double h, const Begin& begin, const SubStep& sub_step, const Restore& restore) {
  for (int substeps = 1; substeps <= kMostSubsteps; substeps *= 2) {
    begin();
    bool ok = true;
    const double dt = h / substeps;
    for (int s = 0; s < substeps && ok; ++s) ok = sub_step(t0 + dt * s, dt, s);
    if (ok) return substeps;
    restore();
  }
  return 0;
}

/// The one status of a step after which the state is no longer finite: `body`'s `quantity`
/// (World::FirstNonFinite) at `time`, with what to do about it.
StepStatus Diverged(double time, int body, const char* quantity);

}  // namespace dynamics::internal
