// Stepping the articulation: the implicit midpoint rule on (q, p), RK4, and the impulses of the
// stops, Coulomb friction and velocity motors (see articulation.h).

#include <algorithm>
#include <cmath>
#include <limits>

#include "../integrators/integrator.h"
#include "articulation.h"

namespace dynamics::internal {
namespace {

// Iterations of the midpoint solve without progress after which it gives up (MidpointStep; 8
// gave up on nothing more in the tests and scenes, and cost a 3000-link chain 10 % a step).
constexpr int kStalled = 4;

double MaxAbs(const Eigen::VectorXd& x) { return x.size() ? x.cwiseAbs().maxCoeff() : 0.0; }

// The ratio of a mass matrix's largest diagonal entry to its smallest (a lower bound of its
// condition number; 1 when empty).
double Ratio(const Eigen::VectorXd& diagonal) {
  if (diagonal.size() == 0) return 1.0;
  return diagonal.maxCoeff() / std::max(diagonal.minCoeff(), std::numeric_limits<double>::min());
}

}  // namespace

StepStatus Articulation::Advance(Integrator integrator, const std::vector<std::unique_ptr<Force>>& forces, double t,
                                 double h, std::vector<RigidBody>& bodies) {
  StepStatus status;
  if (!EnsureMomenta()) {
    status.ok = false;
    status.message = "the joints' mass matrix is not positive definite";
    return status;
  }
  held_.clear();  // (a contact step's, when it found no contact)
  stuck_.clear();
  driven_.clear();
  saved_q_ = q_, saved_v_ = v_, saved_p_ = p_;  // into kept capacity
  const int substeps = internal::StepWithHalving(
      t, h,
      [&] {
        std::fill(limit_impulse_.begin(), limit_impulse_.end(), 0.0);
        std::fill(drive_impulse_.begin(), drive_impulse_.end(), 0.0);
        ClearConstraintImpulses();
      },
      [&](double at, double dt, int) {
        return integrator == Integrator::kRK4 ? RK4Step(forces, at, dt, bodies) : MidpointStep(forces, at, dt, bodies);
      },
      [&] { q_ = saved_q_, v_ = saved_v_, p_ = saved_p_; });
  if (substeps > 0) {
    status.substeps = substeps;
    return status;
  }
  if (Configure(q_, end_)) {
    Velocities(v_, end_);
    Sync(end_, bodies);
  }
  status.ok = false;
  status.substeps = internal::kMostSubsteps;
  status.message =
      "the joints' implicit midpoint solve did not converge even with 1024 sub-steps: springs, damping or servo "
      "gains too stiff for this step (reduce the time step), or a state beyond double precision";
  return status;
}

void Articulation::Accept(std::vector<RigidBody>& bodies) {
  q_ = q1_;
  p_ = p1_;
  Solve(end_, p_, v_);
  Velocities(v_, end_);
  Sync(end_, bodies);
}

// Nothing moves (every joint fixed, down from the world): the bodies stay where they are.
bool Articulation::Still(std::vector<RigidBody>& bodies) {
  if (!Configure(q_, end_)) return false;
  Velocities(v_, end_);
  Sync(end_, bodies);
  return true;
}

// The implicit midpoint rule on (q, p): with v̄ the midpoint velocity,
//   q̄ = q0 ⊕ (h/2) v̄,  v̄ = M(q̄)⁻¹ (p0 + p1)/2,  p1 = p0 + h ṗ(q̄, v̄),  q1 = q0 ⊕ h v̄,
// solved by fixed-point iteration (it contracts by about h times the fastest rate). For joints
// that are all revolute or prismatic, q̄ = (q0 + q1)/2 and this is the symplectic implicit
// midpoint rule itself.
bool Articulation::MidpointStep(const std::vector<std::unique_ptr<Force>>& forces, double t, double h,
                                std::vector<RigidBody>& bodies) {
  if (p_.size() == 0) return Still(bodies);
  q0_ = q_;
  p0_ = p_;
  held_rows_ = Projector{};
  midpoint_pins_ = Pins{};
  mid_.implicit = ImplicitDiagonal(h);
  // The start's frames: which tendons are taut there, and the rows' g(q0).
  if (bilateral_ || !tendons_.empty()) Configure(q0_, probe_, Form::kFrames);
  if (!tendons_.empty()) TautTendons(probe_, q0_, midpoint_pins_);
  Eigen::VectorXd held;  // the rows' generalized impulse over the step
  // A taut tendon is held through the step (a string swings its ball at the midpoint rule's
  // order, not a stop's); where holding it would push, it lets go and the step is solved again.
  for (int attempt = 0;; ++attempt) {
    Predict(h);
    if (Holds()) {  // g(q0): the midpoint velocity aims the step's end at g = 0
      BilateralRows(probe_, q0_, midpoint_pins_, rows_scratch_);
      start_gap_ = rows_scratch_.g;
    }
    if (!IterateMidpoint(forces, t, h, held)) return false;
    if (attempt >= 2 || !Holds() || !ReleasePushingPins()) break;
  }
  history_.Push(rate_, vbar_, h);
  if (Holds()) {
    p1_ += held;
    AddRowImpulses(rows_scratch_, held_nu_, 2.0);
  }
  Move(q0_, vbar_, h, q1_);
  if (!Configure(q1_, end_, StepForm())) return false;
  if (Holds()) {  // the stops' impulses see the loops, couplings and taut tendons held at the end
    HoldMomenta(end_, q1_, p1_, midpoint_pins_);
    held_rows_ = projector_;  // (HoldMomenta's: these rows at the end, through end_'s factor)
    held_target_ = Eigen::VectorXd::Zero(held_rows_.J.rows());
  }
  std::vector<std::pair<int, double>> stops;
  if (Impulses(end_, q1_, h, p1_, stops)) {
    // The end velocity the impulses gave (at the end as first found, where their rows hold): kept
    // when the step's end moves onto the stops, its momenta taken there. (M(q)⁻¹ p1 at the moved
    // end would turn a fast base's momenta into joint rates: a robot falling at 75 m/s with a
    // joint on its stop drove it through at 10 rad/s.)
    Solve(end_, p1_, v_end_);
    if (held_rows_.active()) held_rows_.Hold(v_end_, held_target_);
    // The impulses act over the step: the midpoint velocity takes half of them (M⁻¹ itself, not
    // the iteration's M with its implicit diagonal).
    if (mid_.implicit.size() > 0) {
      mid_.implicit.resize(0);
      if (!Configure(qs_, mid_, StepForm())) return false;
    }
    ps_ = 0.5 * (p0_ + p1_);
    Solve(mid_, ps_, vbar_);
    if (Holds()) {
      HoldMidpoint(mid_, qs_, h, vbar_, held);
      p1_ += held;
      AddRowImpulses(rows_scratch_, held_nu_, 2.0);
    }
    Move(q0_, vbar_, h, q1_);
    for (const auto& [qi, limit] : stops) q1_[qi] = limit;
    if (!Configure(q1_, end_, StepForm())) return false;
    Momenta(end_, v_end_, p1_);
  }
  if (Constrained() && !FinishConstrained(stops)) return false;
  Accept(bodies);
  return true;
}

void Articulation::Predict(double h) {
  // Predictor: after three steps of this length, the rate and the midpoint velocity extrapolated
  // from theirs by a parabola (its error O(h³): 300- and 3000-link chains 1.2× and 1.4× faster than
  // the line); after two, the rate by a line and the midpoint velocity from the last one's
  // (v_n ≈ (v̄_{n−½} + v̄_{n+½}) / 2); the first step starts from the current state.
  const MidpointHistory& past = history_;
  if (past.count == 3 && past.h[0] == h && past.h[1] == h && past.h[2] == h) {
    p1_ = p0_ + h * (3 * past.rate[0] - 3 * past.rate[1] + past.rate[2]);
    vbar_ = 3 * past.vbar[0] - 3 * past.vbar[1] + past.vbar[2];
  } else if (past.count >= 2) {
    p1_ = p0_ + h * (2 * past.rate[0] - past.rate[1]);
    vbar_ = 2 * v_ - past.vbar[0];
  } else {
    vbar_ = v_;
    p1_ = p_;
  }
}

// The fixed-point iteration of the midpoint rule (MidpointStep): v̄ and p1 from the predictor's,
// held on the rows (Holds) at each iterate; `held` their impulse over the step.
bool Articulation::IterateMidpoint(const std::vector<std::unique_ptr<Force>>& forces, double t, double h,
                                   Eigen::VectorXd& held) {
  double last_change = std::numeric_limits<double>::infinity();
  double best_pair = last_change;  // the least of max(change, last change) so far
  int since_best = 0;
  bool converged = false;
  for (int iteration = 0; iteration < 100 && !converged; ++iteration) {
    Move(q0_, vbar_, 0.5 * h, qs_);
    // (A large tree's composites and diagonal once a step: the diagonal bounds the rounding floor.)
    if (!Configure(qs_, mid_, iteration > 0 && Sparse() ? Form::kFrames : StepForm())) return false;
    ps_ = 0.5 * (p0_ + p1_);
    // (M + D) v̄ = (p0 + p1)/2 + D v̄_last: the dampers' and springs' share of p1 follows v̄ within
    // the solve (ImplicitDiagonal); at the fixed point it is M v̄ = (p0 + p1)/2.
    if (mid_.implicit.size() > 0) ps_ += mid_.implicit.cwiseProduct(vbar_);
    Solve(mid_, ps_, vnew_);
    if (Holds()) HoldMidpoint(mid_, qs_, h, vnew_, held);
    Velocities(vnew_, mid_);
    MomentumRate(forces, t + 0.5 * h, qs_, vnew_, mid_, stage_, rate_);
    pnew_ = p0_ + h * rate_;
    if (!pnew_.allFinite() || !vnew_.allFinite()) return false;
    const double p_scale = std::max(MaxAbs(p0_), MaxAbs(pnew_)) + h * MaxAbs(rate_) + 1e-300;
    const double v_scale = std::max(MaxAbs(v_), MaxAbs(vnew_)) + 1e-300;
    const double change = std::max(MaxAbs(pnew_ - p1_) / p_scale, MaxAbs(vnew_ - vbar_) / v_scale);
    // Done within 10⁻¹³ (a hundred roundings: over 10⁵ steps a random walk of 3·10⁻¹¹, far
    // below the truncation error), or when the change has stopped shrinking below 10⁻¹¹
    // (rounding then decides the last bits) — or, when M is ill-conditioned (a long chain: its
    // first joint carries the whole chain, its last one link), as soon as the change is below
    // what rounding in M⁻¹p allows: ten times ε times the ratio of M's largest diagonal entry to
    // its smallest, a lower bound of its condition number. (Without that floor a 300-link chain
    // iterated 100 times at 10⁻⁸ and halved its step ten times, every step. Below it, the solve
    // first stopped only where a change did not shrink — as often right away as twenty iterations
    // later, the changes of momenta and velocities taking turns — and the iterations past the
    // floor bought nothing: falling 300- and 3000-link chains solved down to 10⁻¹⁰ end within
    // three times the distance rounding alone puts between two runs of them, 0.03 against 0.011
    // rad after 0.2 s, 2·10⁻⁶ against 2.5·10⁻⁶ rad after 0.02 s: they are chaotic.)
    const double floor = 10 * std::numeric_limits<double>::epsilon() * Ratio(mid_.diagonal);
    converged = change <= 1e-13 || (floor > 1e-11 ? change <= floor : change <= 1e-11 && change >= last_change);
    // The changes of the momenta and of the velocities take turns (each iteration's velocities
    // answer the last one's momenta): a solve whose change over two iterations has not come
    // below its best for kStalled iterations, still far above rounding, does not contract — the
    // step is too long for the stiffest motion — and gives up now rather than at 100 (the step
    // is then halved). So does one whose iterates have stopped resembling each other (a change
    // above 1/2 of their scale twice running, past the first: a 3000-link chain's 1 ms step, whose
    // changes stay at 1 from the second iteration on).
    const double pair = std::max(change, last_change);
    if (iteration >= 2 && change > 0.5 && last_change > 0.5) return false;
    if (pair < best_pair) {
      best_pair = pair, since_best = 0;
    } else if (++since_best >= kStalled && pair > 1e-6 && !converged) {
      return false;
    }
    last_change = change;
    vbar_ = vnew_;
    p1_ = pnew_;
  }
  return converged;
}

// Classical RK4 on (q, p), q̇ from v = M(q)⁻¹ p (quaternions as four numbers, normalized at the
// end of the step).
bool Articulation::RK4Step(const std::vector<std::unique_ptr<Force>>& forces, double t, double h,
                           std::vector<RigidBody>& bodies) {
  if (p_.size() == 0) return Still(bodies);
  q0_ = q_;
  p0_ = p_;
  static constexpr double kAt[4] = {0.0, 0.5, 0.5, 1.0};
  for (int s = 0; s < 4; ++s) {
    if (s == 0) {
      qs_ = q0_, ps_ = p0_;
    } else {
      qs_ = q0_ + kAt[s] * h * kq_[s - 1];
      ps_ = p0_ + kAt[s] * h * k_[s - 1];
    }
    if (!Configure(qs_, mid_)) return false;
    vs_ = mid_.llt.solve(ps_);
    Velocities(vs_, mid_);
    MomentumRate(forces, t + kAt[s] * h, qs_, vs_, mid_, stage_, k_[s]);
    PositionRate(qs_, vs_, kq_[s]);
  }
  q1_ = q0_ + (h / 6) * (kq_[0] + 2 * kq_[1] + 2 * kq_[2] + kq_[3]);
  p1_ = p0_ + (h / 6) * (k_[0] + 2 * k_[1] + 2 * k_[2] + k_[3]);
  for (const Node& n : nodes_) {
    const int at = n.quaternion();
    if (at >= 0) q1_.segment<4>(at).normalize();
  }
  if (!q1_.allFinite() || !p1_.allFinite()) return false;
  if (!Configure(q1_, end_)) return false;
  held_rows_ = Projector{};
  midpoint_pins_ = Pins{};
  std::vector<std::pair<int, double>> stops;
  pnew_ = p1_;
  if (Impulses(end_, q1_, h, p1_, stops)) {
    // Their share of the step's motion: half the velocity change over the step.
    vs_ = end_.llt.solve(p1_ - pnew_);
    qs_ = q1_;
    Move(qs_, vs_, 0.5 * h, q1_);
    for (const auto& [qi, limit] : stops) q1_[qi] = limit;
    if (!Configure(q1_, end_)) return false;
  }
  if (Constrained() && !FinishConstrained(stops)) return false;
  Accept(bodies);
  return true;
}

// Rows on the end-of-step velocity of one joint coordinate each, solved together by projected
// Gauss–Seidel on W = M⁻¹ (a handful of rows; run to rounding):
//   friction:  q̇ = 0 with |impulse| ≤ friction · h
//   velocity motor:  q̇ = target with |impulse| ≤ max_effort · h
//   stop (a coordinate past its limit at the end of the step): q̇ ≥ −e q̇_arrival (at the lower
//   limit; ≤ at the upper), impulse ≥ 0 (≤ 0), and the coordinate is placed on the limit.
bool Articulation::Impulses(Configuration& c, const Eigen::VectorXd& q1, double h, Eigen::VectorXd& p1,
                            std::vector<std::pair<int, double>>& stops) {
  rows_.clear();
  stops.clear();
  tendon_pins_ = Pins{};
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::VectorXd v1;
  // The end velocity, with the loops and couplings held (their rows' target).
  auto velocity = [&] {
    Solve(c, p1, v1);
    if (held_rows_.active()) held_rows_.Hold(v1, held_target_);
  };
  for (const Node& n : nodes_) {
    if (n.joint < 0 || n.nv != 1) continue;
    const Joint& j = joints_[static_cast<std::size_t>(n.joint)];
    const bool driven = static_cast<std::size_t>(n.v) < driven_.size() && driven_[static_cast<std::size_t>(n.v)];
    const DriveRows d = DriveRowsOf(j, h);  // (a motor bound to 0 keeps its row here, as it always did)
    if (j.friction > 0 && !driven)
      rows_.push_back({n.joint, n.v, -d.bound[1], d.bound[1], d.target[1], false, 2 * n.v + 1});
    if (j.motor.mode == JointMotor::Mode::kVelocity && !driven) {
      rows_.push_back({n.joint, n.v, -d.bound[0], d.bound[0], d.target[0], false, 2 * n.v});
    }
    const double qi = q1[n.q];
    if (!held_.empty() && held_[static_cast<std::size_t>(n.v)]) {  // a contact step's implicit stop holds it
      if (qi < j.limits.lower) stops.emplace_back(n.q, j.limits.lower);
      if (qi > j.limits.upper) stops.emplace_back(n.q, j.limits.upper);
      continue;
    }
    if (qi < j.limits.lower || qi > j.limits.upper) {
      if (v1.size() == 0) velocity();
      const double arrival = v1[n.v];
      if (qi < j.limits.lower) {
        rows_.push_back({n.joint, n.v, 0.0, inf, -j.limits.restitution * std::min(arrival, 0.0), true});
        stops.emplace_back(n.q, j.limits.lower);
      } else {
        rows_.push_back({n.joint, n.v, -inf, 0.0, -j.limits.restitution * std::max(arrival, 0.0), true});
        stops.emplace_back(n.q, j.limits.upper);
      }
    }
  }
  row_jacobians_.assign(rows_.size(), Eigen::VectorXd());
  if (!tendons_.empty()) {
    if (v1.size() == 0) velocity();
    TendonStopRows(q1, v1);
  }
  if (rows_.empty()) return false;
  // The rows' coupling W: columns of M⁻¹ (the factor, formed now for a large tree), with the
  // loops and couplings held.
  if (!c.dense && !Densify(c)) return false;
  if (v1.size() == 0) velocity();
  const auto nr = static_cast<Eigen::Index>(rows_.size());
  // Row r's Jacobian applied to x: a dof's coordinate, or a tendon's gradient.
  auto along = [&](Eigen::Index r, const Eigen::VectorXd& x) {
    const Eigen::VectorXd& jac = row_jacobians_[static_cast<std::size_t>(r)];
    return jac.size() ? jac.dot(x) : x[rows_[static_cast<std::size_t>(r)].dof];
  };
  Eigen::MatrixXd W(nr, nr);
  for (Eigen::Index r = 0; r < nr; ++r) {
    Eigen::VectorXd e = row_jacobians_[static_cast<std::size_t>(r)];
    if (e.size() == 0) {
      e = Eigen::VectorXd::Zero(p1.size());
      e[rows_[static_cast<std::size_t>(r)].dof] = 1.0;
    }
    Eigen::VectorXd col = c.llt.solve(e);
    held_rows_.Restrict(col);
    for (Eigen::Index s = 0; s < nr; ++s) W(s, r) = along(s, col);
  }
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(nr);
  for (int sweep = 0; sweep < 1000; ++sweep) {
    double change = 0, size = 1e-300;
    for (Eigen::Index r = 0; r < nr; ++r) {
      const Row& row = rows_[static_cast<std::size_t>(r)];
      const double v = along(r, v1) + W.row(r).dot(lambda);
      if (!(W(r, r) > 1e-300)) continue;  // (a row nothing can move: held by a loop or coupling)
      const double next = std::clamp(lambda[r] + (row.target - v) / W(r, r), row.lo, row.hi);
      change = std::max(change, std::fabs(next - lambda[r]));
      size = std::max(size, std::fabs(next));
      lambda[r] = next;
    }
    if (change <= 1e-15 * size || nr == 1) break;
  }
  for (Eigen::Index r = 0; r < nr; ++r) {
    const Row& row = rows_[static_cast<std::size_t>(r)];
    if (row.tendon >= 0) {
      p1.noalias() += lambda[r] * row_jacobians_[static_cast<std::size_t>(r)];
      tendon_impulse_[static_cast<std::size_t>(row.tendon)] += lambda[r];
      continue;
    }
    p1[row.dof] += lambda[r];
    (row.stop ? limit_impulse_ : drive_impulse_)[static_cast<std::size_t>(row.joint)] += lambda[r];
    // Whether a friction or motor row pushed at its bound, or held (in a contact step, or not):
    // where the next contact step starts (DriveInKick).
    if (row.drive >= 0 && static_cast<std::size_t>(row.drive) < drive_mode_.size()) {
      const signed char held = driven_.empty() ? kDriveFree : kDriveHeld;
      drive_mode_[static_cast<std::size_t>(row.drive)] = lambda[r] == row.hi ? 1 : lambda[r] == row.lo ? -1 : held;
    }
  }
  return true;
}

}  // namespace dynamics::internal
