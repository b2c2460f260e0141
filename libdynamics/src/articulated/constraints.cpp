// Loops, couplings and tendons of an articulation (dynamics/constraints.h): their rows — value
// and Jacobian at a configuration — and the projections that hold them (see articulation.h).

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "articulation.h"

namespace dynamics {

const char* LoopTypeName(LoopType type) {
  switch (type) {
    case LoopType::kBall: return "ball";
    case LoopType::kWeld: return "weld";
    case LoopType::kHinge: return "hinge";
    case LoopType::kSlider: return "slider";
  }
  return "?";
}

}  // namespace dynamics

namespace dynamics::internal {
namespace {

// How far frame b is turned from frame a: the rotation vector of R_b R_aᵀ to first order (world
// axes; sin θ times the axis), 0 when they agree, changing at ω_b − ω_a there.
Vector3 TurnBetween(const Matrix3& Ra, const Matrix3& Rb) {
  const Matrix3 E = Rb * Ra.transpose();
  return 0.5 * Vector3(E(2, 1) - E(1, 2), E(0, 2) - E(2, 0), E(1, 0) - E(0, 1));
}

}  // namespace

void Articulation::SetConstraints(const std::vector<Loop>& loops, const std::vector<Coupling>& couplings,
                                  const std::vector<Tendon>& tendons) {
  loops_ = loops;
  couplings_ = couplings;
  tendons_ = tendons;
  loop_impulse_.assign(loops.size(), Vector6::Zero());
  coupling_impulse_.assign(couplings.size(), 0.0);
  tendon_impulse_.assign(tendons.size(), 0.0);
  bilateral_ = !loops.empty() || !couplings.empty();
}

Vector3 Articulation::PointOf(const Configuration& c, const BodyFrame& f, Matrix3* rotation,
                              Eigen::MatrixXd* jacobian) const {
  if (f.body < 0) {
    if (rotation) *rotation = f.frame.orientation.normalized().toRotationMatrix();
    if (jacobian) jacobian->setZero(6, v_.size());
    return f.frame.origin;
  }
  const int node = node_of_body_[static_cast<std::size_t>(f.body)];
  const NodeFrame& nf = c.frames[static_cast<std::size_t>(node)];
  const Vector3 r = nf.R * f.frame.origin;
  if (rotation) *rotation = nf.R * f.frame.orientation.normalized().toRotationMatrix();
  if (jacobian) {
    // The point's velocity v − [r]× ω (rows 0–2) and the body's ω (rows 3–5).
    BodyJacobian(c, node, path_, *jacobian);
    jacobian->topRows<3>() -= CrossMatrix(r) * jacobian->bottomRows<3>();
  }
  return nf.x + r;
}

double Articulation::CoordinateOf(const Configuration& c, const Eigen::VectorXd& q, const Coordinate& x,
                                  Eigen::VectorXd* jacobian) const {
  if (x.kind == Coordinate::Kind::kTendon) return TendonLength(c, q, x.index, jacobian);
  const Node& n = nodes_[static_cast<std::size_t>(node_of_joint_[static_cast<std::size_t>(x.index)])];
  if (jacobian) {
    jacobian->setZero(v_.size());
    (*jacobian)[n.v] = 1.0;
  }
  return q[n.q];
}

double Articulation::TendonLength(const Configuration& c, const Eigen::VectorXd& q, int t,
                                  Eigen::VectorXd* jacobian) const {
  const Tendon& tendon = tendons_[static_cast<std::size_t>(t)];
  if (jacobian) jacobian->setZero(v_.size());
  double length = 0;
  for (const auto& [joint, coefficient] : tendon.joints) {
    const Node& n = nodes_[static_cast<std::size_t>(node_of_joint_[static_cast<std::size_t>(joint)])];
    length += coefficient * q[n.q];
    if (jacobian) (*jacobian)[n.v] += coefficient;
  }
  Eigen::MatrixXd ja, jb;
  for (std::size_t k = 0; k + 1 < tendon.path.size(); ++k) {
    const Vector3 a = PointOf(c, tendon.path[k], nullptr, jacobian ? &ja : nullptr);
    const Vector3 b = PointOf(c, tendon.path[k + 1], nullptr, jacobian ? &jb : nullptr);
    const Vector3 d = b - a;
    const double n = d.norm();
    length += n;
    if (jacobian && n > 0) jacobian->noalias() += ((jb.topRows<3>() - ja.topRows<3>()).transpose() * d) / n;
  }
  return length;
}

void Articulation::BilateralRows(const Configuration& c, const Eigen::VectorXd& q, const Pins& pins,
                                 ConstraintRows& rows) const {
  std::vector<double> g;
  std::vector<Eigen::VectorXd> J;
  rows.owner.clear();
  const Eigen::Index nv = v_.size();
  auto add = [&](double value, const Eigen::VectorXd& row, int owner) {
    g.push_back(value);
    J.push_back(row);
    rows.owner.push_back(owner);
  };
  Eigen::MatrixXd ja, jb;
  for (std::size_t k = 0; k < loops_.size(); ++k) {
    const Loop& loop = loops_[k];
    Matrix3 Ra, Rb;
    const Vector3 pa = PointOf(c, loop.a, &Ra, &ja), pb = PointOf(c, loop.b, &Rb, &jb);
    const Vector3 d = pb - pa;
    const Eigen::MatrixXd dv = jb.topRows<3>() - ja.topRows<3>(), dw = jb.bottomRows<3>() - ja.bottomRows<3>();
    const int owner = static_cast<int>(k);
    if (loop.type == LoopType::kSlider) {  // b's origin on a's z axis: d ⊥ a's x and y
      for (int axis = 0; axis < 2; ++axis) {
        const Vector3 u = Ra.col(axis);
        // d/dt uᵀd = uᵀ ḋ + (ω_a × u)ᵀ d = uᵀ ḋ + (u × d)ᵀ ω_a
        add(u.dot(d), dv.transpose() * u + ja.bottomRows<3>().transpose() * u.cross(d), owner);
      }
    } else {
      for (int axis = 0; axis < 3; ++axis) add(d[axis], dv.row(axis).transpose(), owner);
    }
    if (loop.type == LoopType::kWeld || loop.type == LoopType::kSlider) {
      const Vector3 turn = TurnBetween(Ra, Rb);
      for (int axis = 0; axis < 3; ++axis) add(turn[axis], dw.row(axis).transpose(), owner);
    } else if (loop.type == LoopType::kHinge) {  // the z axes together: (z_a × z_b) ⊥ z_a is 0
      const Vector3 tilt = Ra.col(2).cross(Rb.col(2));
      for (int axis = 0; axis < 2; ++axis) {
        const Vector3 u = Ra.col(axis);
        add(u.dot(tilt), dw.transpose() * u, owner);
      }
    }
  }
  Eigen::VectorXd jx, jy;
  for (std::size_t k = 0; k < couplings_.size(); ++k) {
    const double gap = CouplingResidual(c, q, couplings_[k], &jy);
    add(gap, jy, static_cast<int>(loops_.size() + k));
  }
  // Stops and tendon ends the step holds: their coordinate on the limit.
  for (const Pins::Stop& stop : pins.stops) {
    Eigen::VectorXd row = Eigen::VectorXd::Zero(nv);
    row[stop.v] = 1.0;
    add(q[stop.q] - stop.limit, row, -1);
  }
  for (const auto& [t, limit] : pins.tendons) {
    const double length = TendonLength(c, q, t, &jx);
    add(length - limit, jx, -2 - t);
  }
  const auto m = static_cast<Eigen::Index>(g.size());
  rows.g.resize(m);
  rows.J.resize(m, nv);
  for (Eigen::Index r = 0; r < m; ++r) {
    rows.g[r] = g[static_cast<std::size_t>(r)];
    rows.J.row(r) = J[static_cast<std::size_t>(r)].transpose();
  }
}

double Articulation::CouplingResidual(const Configuration& c, const Eigen::VectorXd& q, const Coupling& cp,
                                      Eigen::VectorXd* jacobian) const {
  const double y = CoordinateOf(c, q, cp.follower, jacobian);
  double target = cp.polynomial[0], slope = 0;
  if (cp.leader.index >= 0) {
    Eigen::VectorXd jx;
    const double x = CoordinateOf(c, q, cp.leader, jacobian ? &jx : nullptr) - cp.leader_reference;
    double power = 1;
    for (int i = 1; i < 5; ++i) {
      slope += i * cp.polynomial[static_cast<std::size_t>(i)] * power;
      power *= x;
      target += cp.polynomial[static_cast<std::size_t>(i)] * power;
    }
    if (jacobian) *jacobian -= slope * jx;
  }
  return y - cp.follower_reference - target;
}

void Projector::Form(const Eigen::LLT<Eigen::MatrixXd>& factor, const Eigen::MatrixXd& rows) {
  J = rows;
  if (J.rows() == 0) return;
  Y = factor.solve(J.transpose());
  const Eigen::MatrixXd A = J * Y;
  // Rows that say different things (the common case): A's Cholesky factor, when its pivots stay
  // above 10⁻¹⁰ of A's largest diagonal entry.
  const Eigen::LLT<Eigen::MatrixXd> direct(A);
  if (direct.info() == Eigen::Success) {
    const Eigen::VectorXd pivots = direct.matrixLLT().diagonal().cwiseAbs2();
    if (pivots.minCoeff() > 1e-10 * A.diagonal().maxCoeff()) {
      Ainv = direct.solve(Eigen::MatrixXd::Identity(A.rows(), A.cols()));
      return;
    }
  }
  // The rows' coupling may be singular (a planar loop closed by a ball: its row out of the plane
  // is 0; two couplings saying the same): its pseudo-inverse, eigenvalues below 10⁻¹² of the
  // largest taken as 0, so that redundant rows share nothing and change nothing.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (A + A.transpose()));
  const Eigen::VectorXd& l = eig.eigenvalues();
  const double floor = 1e-12 * std::max(l.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  Eigen::VectorXd inverse(l.size());
  for (Eigen::Index i = 0; i < l.size(); ++i) inverse[i] = l[i] > floor ? 1.0 / l[i] : 0.0;
  Ainv = eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
}

Eigen::VectorXd Projector::Hold(Eigen::VectorXd& x, const Eigen::VectorXd& target) const {
  if (J.rows() == 0) return Eigen::VectorXd();
  const Eigen::VectorXd nu = Ainv * (target - J * x);
  x.noalias() += Y * nu;
  return nu;
}

void Projector::Restrict(Eigen::VectorXd& x) const {
  if (J.rows() == 0) return;
  x.noalias() -= Y * (Ainv * (J * x));
}

bool Articulation::ProjectPositions(const Eigen::LLT<Eigen::MatrixXd>& metric, const Pins& pins,
                                    const Configuration& at_q, Eigen::VectorXd& q, bool& moved) {
  // Newton's method on g(q) = 0, each correction the least in M's metric, Δ = −M⁻¹Jᵀ(JM⁻¹Jᵀ)⁺g,
  // until g is at rounding's level or stops shrinking (rounding decides the rest). `at_q` is q's
  // configuration (its frames), read for the first look.
  double last = std::numeric_limits<double>::infinity();
  const double floor = 1e-15 * std::max(1.0, q.size() ? q.cwiseAbs().maxCoeff() : 0.0);
  Eigen::VectorXd delta, next;
  moved = false;
  for (int iteration = 0; iteration < 12; ++iteration) {
    if (iteration > 0) Configure(q, probe_, Form::kFrames);
    BilateralRows(iteration > 0 ? probe_ : at_q, q, pins, rows_scratch_);
    const double size = rows_scratch_.g.size() ? rows_scratch_.g.cwiseAbs().maxCoeff() : 0.0;
    if (!std::isfinite(size)) return false;
    if (size <= floor || size >= 0.5 * last) return true;
    last = size;
    projector_.Form(metric, rows_scratch_.J);
    delta = Eigen::VectorXd::Zero(v_.size());
    projector_.Hold(delta, -rows_scratch_.g);
    Move(q, delta, 1.0, next);
    q.swap(next);
    moved = true;
  }
  return true;
}

void Articulation::HoldMomenta(const Configuration& c, const Eigen::VectorXd& q, Eigen::VectorXd& p, const Pins& pins) {
  BilateralRows(c, q, pins, rows_scratch_);
  if (rows_scratch_.g.size() == 0) return;
  projector_.Form(c.llt, rows_scratch_.J);
  Eigen::VectorXd v = c.llt.solve(p);
  const Eigen::VectorXd nu = projector_.Hold(v, Eigen::VectorXd::Zero(rows_scratch_.g.size()));
  p.noalias() += rows_scratch_.J.transpose() * nu;
}

void Articulation::AddRowImpulses(const ConstraintRows& rows, const Eigen::VectorXd& nu, double scale) {
  int row_of_loop = 0;  // a loop's rows are consecutive: the index of this one among them
  for (Eigen::Index r = 0; r < nu.size(); ++r) {
    const int owner = rows.owner[static_cast<std::size_t>(r)];
    row_of_loop = r > 0 && rows.owner[static_cast<std::size_t>(r - 1)] == owner ? row_of_loop + 1 : 0;
    const double share = scale * nu[r];
    if (owner <= -2) tendon_impulse_[static_cast<std::size_t>(-2 - owner)] += share;
    if (owner < 0) continue;
    if (owner < static_cast<int>(loops_.size())) {
      loop_impulse_[static_cast<std::size_t>(owner)][row_of_loop] += share;
    } else {
      coupling_impulse_[static_cast<std::size_t>(owner) - loops_.size()] += share;
    }
  }
}

void Articulation::TendonEfforts(const Configuration& c, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                 Eigen::VectorXd& rate) const {
  Eigen::VectorXd jl;
  for (std::size_t t = 0; t < tendons_.size(); ++t) {
    const Tendon& tendon = tendons_[t];
    const JointMotor& m = tendon.motor;
    if (tendon.stiffness == 0 && tendon.damping == 0 && m.mode == JointMotor::Mode::kOff) continue;
    const double length = TendonLength(c, q, static_cast<int>(t), &jl);
    const double rate_of_length = jl.dot(v);
    double force = -tendon.stiffness * (length - tendon.rest_length) - tendon.damping * rate_of_length;
    if (m.mode == JointMotor::Mode::kPosition) {
      force += std::clamp(m.kp * (m.target - length) + m.kd * (m.target_velocity - rate_of_length), -m.max_effort,
                          m.max_effort);
    } else if (m.mode == JointMotor::Mode::kEffort) {
      force += std::clamp(m.target, -m.max_effort, m.max_effort);
    }
    rate.noalias() += force * jl;
  }
}

double Articulation::TendonEnergy() const {
  double e = 0;
  for (std::size_t t = 0; t < tendons_.size(); ++t) {
    const Tendon& tendon = tendons_[t];
    if (tendon.stiffness == 0) continue;
    const double d = TendonLength(end_, q_, static_cast<int>(t), nullptr) - tendon.rest_length;
    e += 0.5 * tendon.stiffness * d * d;
  }
  return e;
}

void Articulation::HoldMidpoint(const Configuration& mid, const Eigen::VectorXd& qbar, double h, Eigen::VectorXd& vbar,
                                Eigen::VectorXd& impulse) {
  // g(q1) ≈ g(q0) + h J(q̄) v̄ (exact for linear rows, O(h³) else: the end's projection takes the
  // rest): v̄ += M⁻¹J̄ᵀν, the step's momentum p1 by 2 J̄ᵀν (v̄ = M⁻¹ (p0 + p1)/2).
  BilateralRows(mid, qbar, midpoint_pins_, rows_scratch_);
  projector_.Form(mid.llt, rows_scratch_.J);
  held_nu_ = projector_.Hold(vbar, -start_gap_ / h);
  impulse = 2.0 * (rows_scratch_.J.transpose() * held_nu_);
}

void Articulation::TendonStopRows(const Eigen::VectorXd& q1, const Eigen::VectorXd& v1) {
  const double inf = std::numeric_limits<double>::infinity();
  Configure(q1, probe_, Form::kFrames);
  Eigen::VectorXd jl;
  for (std::size_t t = 0; t < tendons_.size(); ++t) {
    const JointLimits& limits = tendons_[t].limits;
    if (!std::isfinite(limits.lower) && !std::isfinite(limits.upper)) continue;
    const auto held = std::find_if(midpoint_pins_.tendons.begin(), midpoint_pins_.tendons.end(),
                                   [&](const auto& pin) { return pin.first == static_cast<int>(t); });
    if (held != midpoint_pins_.tendons.end()) continue;  // (held through the step)
    const double length = TendonLength(probe_, q1, static_cast<int>(t), &jl);
    if (length >= limits.lower && length <= limits.upper) continue;
    const double arrival = jl.dot(v1);
    Row row{-1, -1, 0.0, inf, -limits.restitution * std::min(arrival, 0.0), true};
    row.tendon = static_cast<int>(t);
    double limit = limits.lower;
    if (length > limits.upper) {
      row.lo = -inf, row.hi = 0.0, row.target = -limits.restitution * std::max(arrival, 0.0);
      limit = limits.upper;
    }
    rows_.push_back(row);
    row_jacobians_.push_back(jl);
    tendon_pins_.tendons.emplace_back(static_cast<int>(t), limit);
  }
}

void Articulation::TautTendons(const Configuration& c, const Eigen::VectorXd& q, Pins& pins) const {
  for (std::size_t t = 0; t < tendons_.size(); ++t) {
    const JointLimits& limits = tendons_[t].limits;
    if (!std::isfinite(limits.lower) && !std::isfinite(limits.upper)) continue;
    const double length = TendonLength(c, q, static_cast<int>(t), nullptr);
    if (length >= limits.upper - 1e-12 * std::max(1.0, std::abs(limits.upper))) {
      pins.tendons.emplace_back(static_cast<int>(t), limits.upper);
    } else if (length <= limits.lower + 1e-12 * std::max(1.0, std::abs(limits.lower))) {
      pins.tendons.emplace_back(static_cast<int>(t), limits.lower);
    }
  }
}

bool Articulation::ReleasePushingPins() {
  // A pin at the upper end may only shorten the tendon (ν ≤ 0), at the lower only lengthen it.
  std::vector<std::pair<int, double>> kept;
  for (Eigen::Index r = 0; r < held_nu_.size(); ++r) {
    const int owner = rows_scratch_.owner[static_cast<std::size_t>(r)];
    if (owner > -2) continue;
    const int t = -2 - owner;
    const auto pin = std::find_if(midpoint_pins_.tendons.begin(), midpoint_pins_.tendons.end(),
                                  [&](const auto& p) { return p.first == t; });
    const bool upper = pin->second == tendons_[static_cast<std::size_t>(t)].limits.upper;
    if (upper ? held_nu_[r] <= 0 : held_nu_[r] >= 0) kept.push_back(*pin);
  }
  if (kept.size() == midpoint_pins_.tendons.size()) return false;
  midpoint_pins_.tendons = kept;
  return true;
}

bool Articulation::FinishConstrained(const std::vector<std::pair<int, double>>& stops) {
  Pins pins = tendon_pins_;
  pins.tendons.insert(pins.tendons.end(), midpoint_pins_.tendons.begin(), midpoint_pins_.tendons.end());
  for (const auto& [qi, limit] : stops) {
    for (const Node& n : nodes_) {
      if (n.nq == 1 && n.q == qi) pins.stops.push_back({n.q, n.v, limit});
    }
  }
  if (!end_.dense && !Densify(end_)) return false;
  bool moved = false;
  if (!ProjectPositions(end_.llt, pins, end_, q1_, moved) || !q1_.allFinite()) return false;
  if (moved && !Configure(q1_, end_, StepForm())) return false;
  // (A tendon the step's stops pinned keeps the velocity its stop gave it: its restitution's.)
  if (Holds()) HoldMomenta(end_, q1_, p1_, midpoint_pins_);
  return p1_.allFinite();
}

void Articulation::ClearConstraintImpulses(bool tendons) {
  std::fill(loop_impulse_.begin(), loop_impulse_.end(), Vector6::Zero());
  std::fill(coupling_impulse_.begin(), coupling_impulse_.end(), 0.0);
  if (tendons) std::fill(tendon_impulse_.begin(), tendon_impulse_.end(), 0.0);
}

ConstraintState Articulation::LoopState(int k) const {
  Configure(q_, probe_, Form::kFrames);
  const Loop& loop = loops_[static_cast<std::size_t>(k)];
  Matrix3 Ra, Rb;
  Vector3 gap = PointOf(probe_, loop.b, &Rb, nullptr) - PointOf(probe_, loop.a, &Ra, nullptr);
  if (loop.type == LoopType::kSlider) gap -= Ra.col(2) * Ra.col(2).dot(gap);  // (a shift along z is free)
  ConstraintState s;
  s.residual = gap.norm();
  if (loop.type == LoopType::kWeld || loop.type == LoopType::kSlider)
    s.residual = std::max(s.residual, TurnBetween(Ra, Rb).norm());
  if (loop.type == LoopType::kHinge) s.residual = std::max(s.residual, Ra.col(2).cross(Rb.col(2)).norm());
  s.impulse = loop_impulse_[static_cast<std::size_t>(k)].norm();
  return s;
}

ConstraintState Articulation::CouplingState(int k) const {
  Configure(q_, probe_, Form::kFrames);
  const Coupling& cp = couplings_[static_cast<std::size_t>(k)];
  ConstraintState s;
  s.length = CoordinateOf(probe_, q_, cp.follower, nullptr);
  s.residual = CouplingResidual(probe_, q_, cp, nullptr);
  s.impulse = coupling_impulse_[static_cast<std::size_t>(k)];
  return s;
}

ConstraintState Articulation::TendonState(int k) const {
  Configure(q_, probe_, Form::kFrames);
  const Configuration& c = probe_;
  const Tendon& t = tendons_[static_cast<std::size_t>(k)];
  ConstraintState s;
  s.length = TendonLength(c, q_, k, nullptr);
  s.residual = s.length > t.limits.upper   ? s.length - t.limits.upper
               : s.length < t.limits.lower ? s.length - t.limits.lower
                                           : 0.0;
  s.impulse = tendon_impulse_[static_cast<std::size_t>(k)];
  return s;
}

}  // namespace dynamics::internal
