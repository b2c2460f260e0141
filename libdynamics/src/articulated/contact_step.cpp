// The articulation in a contact step (see articulation.h): the kick, the coupling of its bodies'
// responses to impulses, and the end of the step with the contact impulses applied.

#include <algorithm>
#include <cmath>

#include "../contact/solver.h"
#include "articulation.h"

namespace dynamics::internal {

void Articulation::BodyJacobians(const Configuration& c, std::vector<Eigen::MatrixXd>& phi) const {
  const auto nv = static_cast<Eigen::Index>(v_.size());
  phi.resize(nodes_.size());
  std::vector<Eigen::MatrixXd> spatial(nodes_.size());  // V = Σ S u over the path from the world
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    Eigen::MatrixXd& J = spatial[i];
    if (n.parent >= 0) {
      J = spatial[static_cast<std::size_t>(n.parent)];
    } else {
      J.setZero(6, nv);
    }
    if (n.nv > 0) J.middleCols(n.v, n.nv) = c.frames[i].S;
    // (v, ω) of the centre: v = v_O + ω × x = v_O − [x]× ω.
    const Vector3& x = c.frames[i].x;
    Matrix3 X;
    X << 0, -x.z(), x.y(), x.z(), 0, -x.x(), -x.y(), x.x(), 0;
    Eigen::MatrixXd& P = phi[i];
    P.resize(6, nv);
    P.topRows<3>() = J.bottomRows<3>() - X * J.topRows<3>();
    P.bottomRows<3>() = J.topRows<3>();
  }
}

Eigen::VectorXd Articulation::GeneralizedImpulse(const std::vector<Wrench>& w) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(v_.size());
  if (g.size() == 0) return g;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Wrench& b = w[static_cast<std::size_t>(nodes_[i].body)];
    if (b.force.squaredNorm() == 0 && b.torque.squaredNorm() == 0) continue;
    Vector6 f;
    f << b.force, b.torque;
    g.noalias() += phi_[i].transpose() * f;
  }
  return g;
}

bool Articulation::ContactKick(const std::vector<std::unique_ptr<Force>>& forces, double t, double h,
                               std::vector<Vector6>& kicked) {
  kicked.assign(inertias_.size(), Vector6::Zero());
  if (!Configure(q_, start_)) return false;
  BodyJacobians(start_, phi_);
  if (p_.size() == 0) {
    kicked_p_.resize(0);
    return true;
  }
  Velocities(v_, start_);
  MomentumRate(forces, t, q_, v_, start_, stage_, rate_);
  // The joints' springs, dampers and unsaturated servos act implicitly (stiff gains stay
  // stable): (M + h D + h² K) u = p + h ṗ + h D v, with D and K their diagonal gains; impulses
  // then act on this effective mass, and the step's momentum is M u.
  kicked_p_ = p_ + h * rate_;
  effective_ = start_;
  held_.assign(static_cast<std::size_t>(v_.size()), 0);
  for (const Node& n : nodes_) {
    if (n.joint < 0 || n.nv == 0 || n.type == JointType::kFree) continue;
    const Joint& j = joints_[static_cast<std::size_t>(n.joint)];
    for (int k = 0; k < n.nv; ++k) {
      double damping = j.damping, stiffness = n.nv == 1 ? j.stiffness : 0.0;
      if (n.nv == 1 && j.motor.mode == JointMotor::Mode::kPosition &&
          std::abs(j.motor.kp * (j.motor.target - q_[n.q]) - j.motor.kd * v_[n.v]) < j.motor.max_effort) {
        damping += j.motor.kd;
        stiffness += j.motor.kp;
      }
      const int i = n.v + k;
      effective_.M(i, i) += h * damping + h * h * stiffness;
      kicked_p_[i] += h * damping * v_[i];
    }
    // A stop the joint is on, or would pass in this step at its present rate, holds it as a
    // stiff implicit spring toward the limit — (M + h² k) u = … − h k (q − limit), with h² k a
    // million times the joint's own inertia: rigid, in the very solve that the contacts see
    // (a leg on its stop pressed against the ground), never pulling it past the limit.
    if (n.nv != 1) continue;
    const double q = q_[n.q], reach = q + h * v_[n.v];
    if (!(reach < j.limits.lower || reach > j.limits.upper)) continue;
    // Toward the limit from inside; from beyond it (where the last step's contacts left it),
    // held where it is: the end of the step places it back on the limit, without a velocity.
    const bool inside = q >= j.limits.lower && q <= j.limits.upper;
    const double rest = !inside ? q : reach < j.limits.lower ? j.limits.lower : j.limits.upper;
    const double k = 1e6 * start_.M(n.v, n.v) / (h * h);
    effective_.M(n.v, n.v) += h * h * k;
    kicked_p_[n.v] -= h * k * (q - rest);
    held_[static_cast<std::size_t>(n.v)] = 1;
  }
  effective_.llt.compute(effective_.M);
  if (effective_.llt.info() != Eigen::Success) return false;
  const Eigen::VectorXd u = effective_.llt.solve(kicked_p_);
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    kicked[static_cast<std::size_t>(nodes_[i].body)] = phi_[i] * u;
  }
  return true;
}

void Articulation::Couple(contact::Coupling& c) {
  const std::size_t nb = inertias_.size();
  c.tree.assign(nb, -1);
  c.slot.assign(nb, 0);
  c.movable.assign(nb, 0);
  c.parent.assign(nb, -1);
  c.members.clear();
  c.response.clear();
  std::vector<int> tree_of_node(nodes_.size());
  std::vector<std::vector<int>> nodes_of_tree;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    const auto body = static_cast<std::size_t>(n.body);
    if (n.parent < 0) {
      tree_of_node[i] = static_cast<int>(c.members.size());
      c.members.emplace_back();
      nodes_of_tree.emplace_back();
    } else {
      tree_of_node[i] = tree_of_node[static_cast<std::size_t>(n.parent)];
      c.parent[body] = nodes_[static_cast<std::size_t>(n.parent)].body;
    }
    const auto t = static_cast<std::size_t>(tree_of_node[i]);
    c.tree[body] = static_cast<int>(t);
    c.slot[body] = static_cast<int>(c.members[t].size());
    c.members[t].push_back(n.body);
    nodes_of_tree[t].push_back(static_cast<int>(i));
    c.movable[body] = phi_[i].size() > 0 && phi_[i].cwiseAbs().maxCoeff() > 0;
  }
  // Each tree's own block of the effective mass (block-diagonal by trees): G_jk = Φ_j M_t⁻¹ Φ_kᵀ
  // over its degrees of freedom alone.
  Eigen::MatrixXd full;
  if (v_.size() > 0) full = effective_.M.selfadjointView<Eigen::Lower>();
  c.response.resize(c.members.size());
  for (std::size_t t = 0; t < c.members.size(); ++t) {
    const std::vector<int>& tn = nodes_of_tree[t];
    const std::size_t size = tn.size();
    std::vector<int> dofs;
    for (const int i : tn) {
      const Node& n = nodes_[static_cast<std::size_t>(i)];
      for (int k = 0; k < n.nv; ++k) dofs.push_back(n.v + k);
    }
    std::vector<Matrix6>& G = c.response[t];
    G.assign(size * size, Matrix6::Zero());
    if (dofs.empty()) continue;
    const auto nd = static_cast<Eigen::Index>(dofs.size());
    Eigen::MatrixXd Mt(nd, nd);
    for (Eigen::Index r = 0; r < nd; ++r) {
      for (Eigen::Index s = 0; s < nd; ++s)
        Mt(r, s) = full(dofs[static_cast<std::size_t>(r)], dofs[static_cast<std::size_t>(s)]);
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(Mt);
    std::vector<Eigen::MatrixXd> phi(size), solved(size);
    for (std::size_t j = 0; j < size; ++j) {
      phi[j].resize(6, nd);
      const Eigen::MatrixXd& P = phi_[static_cast<std::size_t>(tn[j])];
      for (Eigen::Index s = 0; s < nd; ++s) phi[j].col(s) = P.col(dofs[static_cast<std::size_t>(s)]);
      solved[j] = llt.solve(phi[j].transpose());
    }
    for (std::size_t j = 0; j < size; ++j) {
      for (std::size_t k = 0; k < size; ++k) G[j * size + k] = phi[j] * solved[k];
    }
  }
}

bool Articulation::ContactFinish(const std::vector<Wrench>& impulses, const std::vector<Wrench>& pushes, double h,
                                 std::vector<RigidBody>& bodies) {
  std::fill(limit_impulse_.begin(), limit_impulse_.end(), 0.0);
  std::fill(drive_impulse_.begin(), drive_impulse_.end(), 0.0);
  older_rate_.resize(0);  // the midpoint rule's predictor starts afresh after contact
  last_rate_.resize(0);
  if (p_.size() == 0) return Still(bodies);
  p1_ = kicked_p_ + GeneralizedImpulse(impulses);
  vbar_ = effective_.llt.solve(p1_);
  Move(q_, vbar_, h, q1_);
  std::vector<std::pair<int, double>> stops;
  if (Impulses(effective_, q1_, h, p1_, stops)) vbar_ = effective_.llt.solve(p1_);
  p1_ = start_.M.selfadjointView<Eigen::Lower>() * vbar_;  // the momentum of the step's velocity
  const Eigen::VectorXd push = GeneralizedImpulse(pushes);
  if (push.cwiseAbs().maxCoeff() > 0) vbar_ += start_.llt.solve(push);
  Move(q_, vbar_, h, q1_);
  for (const auto& [qi, limit] : stops) q1_[qi] = limit;
  held_.clear();  // (the midpoint rule's stops are its own)
  if (!q1_.allFinite() || !p1_.allFinite() || !Configure(q1_, end_)) return false;
  Accept(bodies);
  return true;
}

}  // namespace dynamics::internal
