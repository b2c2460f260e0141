// The articulation in a contact step (see articulation.h): the kick, the coupling of its bodies'
// responses to impulses, and the end of the step with the contact impulses applied.

#include <algorithm>
#include <cmath>
#include <cstring>

#include "../contact/solver.h"
#include "articulation.h"

namespace dynamics::internal {

void Articulation::BodyJacobian(const Configuration& c, int node, Eigen::MatrixXd& J, Eigen::MatrixXd& P) const {
  // V = Σ S u over the path from the world (the columns of the node and its ancestors), then the
  // (v, ω) of the centre: v = v_O + ω × x = v_O − [x]× ω.
  J.setZero(6, v_.size());
  for (int i = node; i >= 0; i = nodes_[static_cast<std::size_t>(i)].parent) {
    const Node& n = nodes_[static_cast<std::size_t>(i)];
    if (n.nv > 0) J.middleCols(n.v, n.nv) = c.frames[static_cast<std::size_t>(i)].S;
  }
  const Matrix3 X = CrossMatrix(c.frames[static_cast<std::size_t>(node)].x);
  P.resize(6, v_.size());
  P.topRows<3>() = J.bottomRows<3>() - X * J.topRows<3>();
  P.bottomRows<3>() = J.topRows<3>();
}

Eigen::VectorXd Articulation::GeneralizedImpulse(const std::vector<Wrench>& w) const {
  // Φᵀ (f, τ) = Σ over the path of Sᵀ (n_O, f), with n_O = τ + x × f the moment about the origin.
  Eigen::VectorXd g = Eigen::VectorXd::Zero(v_.size());
  if (g.size() == 0) return g;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const Wrench& b = w[static_cast<std::size_t>(nodes_[k].body)];
    if (b.force.squaredNorm() == 0 && b.torque.squaredNorm() == 0) continue;
    Vector6 f;
    f << b.torque + start_.frames[k].x.cross(b.force), b.force;
    for (int i = static_cast<int>(k); i >= 0; i = nodes_[static_cast<std::size_t>(i)].parent) {
      const Node& n = nodes_[static_cast<std::size_t>(i)];
      if (n.nv > 0) g.segment(n.v, n.nv).noalias() += start_.frames[static_cast<std::size_t>(i)].S.transpose() * f;
    }
  }
  return g;
}

bool Articulation::ContactKick(const std::vector<std::unique_ptr<Force>>& forces, double t, double h,
                               std::vector<Vector6>& kicked) {
  kicked.assign(inertias_.size(), Vector6::Zero());
  if (!EnsureMomenta()) return false;
  // The start is the last step's end when nothing has moved the joints since (the same
  // coordinates, bit for bit): its kinematics, mass matrix and factor are kept, not formed again.
  // (Swapped once the start has been formed itself: a factor never computed may not be moved.)
  const bool same = start_formed_ && end_.dense && q_.size() > 0 && end_.q.size() == q_.size() &&
                    std::memcmp(end_.q.data(), q_.data(), sizeof(double) * static_cast<std::size_t>(q_.size())) == 0;
  if (same) {
    std::swap(start_, end_);
  } else if (!Configure(q_, start_)) {
    return false;
  } else {
    start_formed_ = start_.dense && v_.size() > 0;
  }
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
  // (Only its mass matrix and factor are read: the start's frames are not copied.)
  effective_.dense = true;
  effective_.M = start_.M;
  held_.assign(static_cast<std::size_t>(v_.size()), 0);
  for (const Node& n : nodes_) {
    if (n.joint < 0 || n.nv == 0 || n.type == JointType::kFree) continue;
    const Joint& j = joints_[static_cast<std::size_t>(n.joint)];
    for (int k = 0; k < n.nv; ++k) {
      double damping = j.damping, stiffness = n.nv == 1 ? j.stiffness : 0.0;
      if (n.nv == 1 && j.motor.mode == JointMotor::Mode::kPosition &&
          std::abs(j.motor.kp * (j.motor.target - q_[n.q]) + j.motor.kd * (j.motor.target_velocity - v_[n.v])) <
              j.motor.max_effort) {
        damping += j.motor.kd;
        stiffness += j.motor.kp;
      }
      const int i = n.v + k;
      effective_.M(i, i) += h * damping + h * h * stiffness;
      kicked_p_[i] += h * damping * v_[i];
    }
    // A stop the joint would pass in this step at its present rate, or that the last contact
    // step left it pressed on, holds it as a stiff implicit spring — (M + h² k) u = … − h k
    // (q − rest), with h² k a million times the joint's own inertia: rigid, in the very solve
    // that the contacts see (a leg on its stop pressed against the ground).
    if (n.nv != 1) continue;
    const double q = q_[n.q], reach = q + h * v_[n.v];
    const auto dof = static_cast<std::size_t>(n.v);
    const signed char pressed = dof < stuck_.size() ? stuck_[dof] : 0;
    const bool passes = reach < j.limits.lower || reach > j.limits.upper;
    if (!passes && pressed == 0) continue;
    // Toward the limit it would pass from inside; else held where it is (on the stop, or beyond
    // it where the last step's contacts left it: the end of the step places it back on the
    // limit, without a velocity).
    const bool inside = q > j.limits.lower && q < j.limits.upper;
    const double rest = inside && passes ? (reach < j.limits.lower ? j.limits.lower : j.limits.upper) : q;
    const double k = 1e6 * start_.M(n.v, n.v) / (h * h);
    effective_.M(n.v, n.v) += h * h * k;
    kicked_p_[n.v] -= h * k * (q - rest);
    held_[dof] = passes ? (reach < j.limits.lower ? -1 : 1) : pressed;
  }
  driven_.assign(static_cast<std::size_t>(v_.size()), 0);
  drive_gain_.assign(2 * static_cast<std::size_t>(v_.size()), 0.0);
  if (drive_mode_.size() != 2 * static_cast<std::size_t>(v_.size()))
    drive_mode_.assign(2 * static_cast<std::size_t>(v_.size()), kDriveFree);
  for (const Node& n : nodes_) {
    if (n.joint < 0 || n.nv != 1 || held_[static_cast<std::size_t>(n.v)] != 0) continue;  // (a stop holds it)
    DriveInKick(n, joints_[static_cast<std::size_t>(n.joint)], h);
  }
  effective_.llt.compute(effective_.M);
  if (effective_.llt.info() != Eigen::Success) return false;
  Eigen::VectorXd u = effective_.llt.solve(kicked_p_);
  // Loops and couplings held in the contacts' solve: the kicked velocity on their rows, aimed at
  // g = 0 by the step's end, and every response to an impulse restricted to them (Respond).
  held_rows_ = Projector{};
  midpoint_pins_ = Pins{};  // (a contact step's tendon ends are stops, at the step's end)
  if (bilateral_) {
    BilateralRows(start_, q_, Pins{}, held_source_);
    held_rows_.Form(effective_.llt, held_source_.J);
    held_target_ = -held_source_.g / h;
    held_rows_.Hold(u, held_target_);
  }
  Velocities(u, start_);  // (the start's velocities are read no more: ṗ is taken)
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const NodeFrame& f = start_.frames[i];
    const Vector3 w = f.V.head<3>();
    kicked[static_cast<std::size_t>(nodes_[i].body)] << f.V.tail<3>() + w.cross(f.x), w;
  }
  return true;
}

// A joint's friction and velocity motor — rows q̇ = target with |impulse| ≤ bound · h — in the
// very solve the contacts see (after them, a motor pressing a link onto the ground pushed it in
// every step, and a joint held by its friction gave way under a load the contacts put on it). Each
// row is held at its target rate by a stiff implicit damper, (M + h D) u = … + h D target with h D
// a billion times the joint's own inertia (a damper holds a rate, not a place: at a million, a bar
// its friction held crept by 5·10⁻⁸ rad/s under its load), or, where the last step's impulse
// reached the bound, pushed by the bound as a constant effort. Which of the two is the last
// step's outcome (DriveAfterContacts), as a stop's hold is: a change of regime takes effect a step
// late (a load that a joint's friction cannot hold, put on it while in contact, slips a step
// after). A joint whose rows held their targets in a step without contact (kDriveFree) has them
// solved after the contacts in the first contact step, as before, so that an impact sees the
// joint as it is: held rigid, a motor's link would strike as if infinitely heavy. A joint with
// both: friction cannot hold the joint still while the motor holds it at another rate, so of two
// held rows with different targets the friction slips, against the motor's target; with the same
// target (0) one damper holds both, their bounds added.
void Articulation::DriveInKick(const Node& n, const Joint& j, double h) {
  const DriveRows rows = DriveRowsOf(j, h);
  const auto dof = static_cast<std::size_t>(n.v);
  signed char* mode = drive_mode_.data() + 2 * dof;
  if (!rows.on[0] && !rows.on[1]) return;
  for (int k = 0; k < 2; ++k) {
    if (rows.on[k] && mode[k] == kDriveFree) return;
  }
  driven_[dof] = 1;
  if (rows.on[0] && rows.on[1] && mode[0] == kDriveHeld && mode[1] == kDriveHeld && rows.target[0] != 0) {
    mode[1] = rows.target[0] > 0 ? -1 : 1;
  }
  for (int k = 0; k < 2; ++k) {
    if (!rows.on[k]) continue;
    if (mode[k] != kDriveHeld && std::isfinite(rows.bound[k])) {
      kicked_p_[n.v] += mode[k] * rows.bound[k];
      continue;
    }
    if (k == 1 && rows.on[0] && mode[0] == kDriveHeld) continue;  // (one damper, the motor's, holds both at 0)
    const double gain = 1e9 * start_.M(n.v, n.v);
    effective_.M(n.v, n.v) += gain;
    kicked_p_[n.v] += gain * rows.target[k];
    drive_gain_[2 * dof + static_cast<std::size_t>(k)] = gain;
  }
}

Articulation::DriveRows Articulation::DriveRowsOf(const Joint& j, double h) {
  DriveRows r;
  r.bound[0] = j.motor.max_effort * h;
  r.target[0] = j.motor.target;
  r.on[0] = j.motor.mode == JointMotor::Mode::kVelocity && r.bound[0] > 0;
  r.bound[1] = j.friction * h;
  r.on[1] = r.bound[1] > 0;
  return r;
}

// The driven rows' impulses: a held row's is its damper's, h D (target − u) (a damper that holds
// both rows, its impulse theirs together); past the bound, the row pushes at the bound from the
// next step on (this step's excess stays: the contacts answered it). A row pushed at its bound
// holds again once the rate has passed its target.
void Articulation::DriveAfterContacts(const Eigen::VectorXd& u, double h) {
  for (const Node& n : nodes_) {
    const auto dof = static_cast<std::size_t>(n.v);
    if (n.joint < 0 || n.nv != 1 || dof >= driven_.size() || !driven_[dof]) continue;
    const DriveRows rows = DriveRowsOf(joints_[static_cast<std::size_t>(n.joint)], h);
    signed char* mode = drive_mode_.data() + 2 * dof;
    const double* gain = drive_gain_.data() + 2 * dof;
    const bool shared = rows.on[0] && rows.on[1] && gain[0] > 0 && mode[1] == kDriveHeld;
    double total = 0;
    for (int k = 0; k < 2; ++k) {
      if (!rows.on[k] || (shared && k == 1)) continue;
      const double bound = shared ? rows.bound[0] + rows.bound[1] : rows.bound[k];
      double impulse = mode[k] * rows.bound[k];
      if (gain[k] > 0) {
        impulse = gain[k] * (rows.target[k] - u[n.v]);
        mode[k] = impulse > bound ? 1 : impulse < -bound ? -1 : kDriveHeld;
        if (shared) mode[1] = mode[0];
      } else if (mode[k] * (rows.target[k] - u[n.v]) < 0) {
        mode[k] = kDriveHeld;
      }
      total += impulse;
    }
    drive_impulse_[static_cast<std::size_t>(n.joint)] += total;
  }
  driven_.clear();
}

void Articulation::Classify(contact::Coupling& c) const {
  const std::size_t nb = inertias_.size();
  c.tree.assign(nb, -1);
  c.movable.assign(nb, 0);
  c.parent.assign(nb, -1);
  int trees = 0;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    const auto body = static_cast<std::size_t>(n.body);
    if (n.parent < 0) {
      c.tree[body] = trees++;
    } else {
      const int parent_body = nodes_[static_cast<std::size_t>(n.parent)].body;
      c.tree[body] = c.tree[static_cast<std::size_t>(parent_body)];
      c.parent[body] = parent_body;
    }
    c.movable[body] =
        n.nv > 0 ||
        (n.parent >= 0 && c.movable[static_cast<std::size_t>(nodes_[static_cast<std::size_t>(n.parent)].body)]);
  }
  c.joint_tree = c.tree;
  MergeConstrainedTrees(c.tree);
}

// Trees joined by a loop, a coupling or a tendon answer impulses together: one tree for the
// contacts' solve (each body's tree renamed to the least of those it is joined with).
void Articulation::MergeConstrainedTrees(std::vector<int>& tree) const {
  if (loops_.empty() && couplings_.empty() && tendons_.empty()) return;
  std::vector<int> root(tree.size());
  for (std::size_t t = 0; t < root.size(); ++t) root[t] = static_cast<int>(t);
  auto find = [&](int t) {
    while (root[static_cast<std::size_t>(t)] != t)
      t = root[static_cast<std::size_t>(t)] = root[static_cast<std::size_t>(root[static_cast<std::size_t>(t)])];
    return t;
  };
  auto join = [&](const std::vector<int>& bodies) {
    int first = -1;
    for (int b : bodies) {
      if (b < 0) continue;
      const int t = find(tree[static_cast<std::size_t>(b)]);
      if (first < 0) first = t;
      root[static_cast<std::size_t>(std::max(t, first))] = std::min(t, first);
      first = std::min(t, first);
    }
  };
  auto body_of_joint = [&](int j) { return joints_[static_cast<std::size_t>(j)].child; };
  // Each tendon's bodies joined; in a coupling, any one of them stands for the tendon.
  std::vector<int> tendon_body;
  for (const Tendon& t : tendons_) {
    std::vector<int> bodies;
    for (const auto& [j, c] : t.joints) bodies.push_back(body_of_joint(j));
    for (const BodyFrame& f : t.path) bodies.push_back(f.body);
    join(bodies);
    const auto moving = std::find_if(bodies.begin(), bodies.end(), [](int b) { return b >= 0; });
    tendon_body.push_back(moving == bodies.end() ? -1 : *moving);
  }
  for (const Loop& l : loops_) join({l.a.body, l.b.body});
  for (const Coupling& cp : couplings_) {
    std::vector<int> bodies;
    for (const Coordinate& x : {cp.follower, cp.leader}) {
      if (x.index < 0) continue;
      bodies.push_back(x.kind == Coordinate::Kind::kJoint ? body_of_joint(x.index)
                                                          : tendon_body[static_cast<std::size_t>(x.index)]);
    }
    join(bodies);
  }
  for (int& t : tree) t = find(t);
}

void Articulation::Respond(contact::Coupling& c, const std::vector<char>& touched) const {
  const std::size_t nb = inertias_.size();
  c.slot.assign(nb, 0);
  // (The arrays of the last step's trees kept: cleared, not freed.)
  c.members.resize(static_cast<std::size_t>(*std::max_element(c.tree.begin(), c.tree.end()) + 1));
  for (std::vector<int>& m : c.members) m.clear();
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const int body = nodes_[i].body;
    if (!touched[static_cast<std::size_t>(body)]) continue;
    auto& m = c.members[static_cast<std::size_t>(c.tree[static_cast<std::size_t>(body)])];
    c.slot[static_cast<std::size_t>(body)] = static_cast<int>(m.size());
    m.push_back(body);
  }
  // G_jk = Φ_j M⁻¹ Φ_kᵀ among the touched bodies of each tree, M the step's effective mass (its
  // factor is the kick's; M is block-diagonal by trees, so the other trees' coordinates stay 0).
  c.response.resize(c.members.size());
  for (std::size_t t = 0; t < c.members.size(); ++t) {
    const std::vector<int>& m = c.members[t];
    std::vector<Matrix6>& G = c.response[t];
    G.assign(m.size() * m.size(), Matrix6::Zero());
    if (m.empty() || v_.size() == 0) continue;
    if (phi_.size() < m.size()) {
      phi_.resize(m.size());
      solved_.resize(m.size());
    }
    std::vector<Eigen::MatrixXd>& phi = phi_;
    std::vector<Eigen::MatrixXd>& solved = solved_;
    for (std::size_t k = 0; k < m.size(); ++k) {
      BodyJacobian(start_, node_of_body_[static_cast<std::size_t>(m[k])], path_, phi[k]);
      // Y_k = L⁻¹ Φ_kᵀ (M = L Lᵀ): G_jk = Y_jᵀ Y_k, one triangular solve instead of two.
      solved[k] = effective_.llt.matrixL().solve(phi[k].transpose());
    }
    // With loops and couplings held, M⁻¹ is restricted to their rows: G_jk −= T_jᵀ A⁺ T_k with
    // T_k = (L⁻¹Jᵀ)ᵀ Y_k = J M⁻¹ Φ_kᵀ.
    std::vector<Eigen::MatrixXd> held(held_rows_.active() ? m.size() : 0);
    if (!held.empty()) {
      const Eigen::MatrixXd Z = effective_.llt.matrixL().solve(held_rows_.J.transpose());
      for (std::size_t k = 0; k < m.size(); ++k) held[k] = Z.transpose() * solved[k];
    }
    // (Each product a 6 × 6 of inner size n: coefficient-wise, not through the matrix-product
    // kernels, whose packing costs more than the arithmetic at a robot's size; G_kj = G_jkᵀ.)
    for (std::size_t j = 0; j < m.size(); ++j) {
      for (std::size_t k = j; k < m.size(); ++k) {
        G[j * m.size() + k].noalias() = solved[j].transpose().lazyProduct(solved[k]);
        if (!held.empty()) G[j * m.size() + k].noalias() -= held[j].transpose() * (held_rows_.Ainv * held[k]);
        if (k != j) G[k * m.size() + j] = G[j * m.size() + k].transpose();
      }
    }
  }
}

bool Articulation::ContactFinish(const std::vector<Wrench>& impulses, const std::vector<Wrench>& pushes, double h,
                                 std::vector<RigidBody>& bodies) {
  std::fill(limit_impulse_.begin(), limit_impulse_.end(), 0.0);
  std::fill(drive_impulse_.begin(), drive_impulse_.end(), 0.0);
  ClearConstraintImpulses();
  history_.Clear();  // the midpoint rule's predictor starts afresh after contact
  if (p_.size() == 0) return Still(bodies);
  p1_ = kicked_p_ + GeneralizedImpulse(impulses);
  // The step's velocity, with the loops and couplings held (their impulses reported).
  auto velocity = [&] {
    vbar_ = effective_.llt.solve(p1_);
    if (held_rows_.active()) AddRowImpulses(held_source_, held_rows_.Hold(vbar_, held_target_), 1.0);
  };
  velocity();
  Move(q_, vbar_, h, q1_);
  std::vector<std::pair<int, double>> stops;
  if (Impulses(effective_, q1_, h, p1_, stops)) {
    ClearConstraintImpulses(/*tendons=*/false);  // (the held rows' impulses are taken again, whole)
    velocity();
  }
  p1_ = start_.M.selfadjointView<Eigen::Lower>() * vbar_;  // the momentum of the step's velocity
  const Eigen::VectorXd solved = vbar_;
  DriveAfterContacts(solved, h);
  const Eigen::VectorXd push = GeneralizedImpulse(pushes);
  if (push.cwiseAbs().maxCoeff() > 0) {
    Eigen::VectorXd moved = start_.llt.solve(push);
    held_rows_.Restrict(moved);
    vbar_ += moved;
  }
  Move(q_, vbar_, h, q1_);
  for (const auto& [qi, limit] : stops) q1_[qi] = limit;
  // Which stops stay held in the next contact step: those the contacts pressed on (a held
  // joint whose velocity, however small, still points into its stop; a joint the stops' impulses
  // placed on its limit after the contacts). One that would leave is let go.
  stuck_.assign(static_cast<std::size_t>(v_.size()), 0);
  for (const Node& n : nodes_) {
    if (n.joint < 0 || n.nv != 1) continue;
    const auto dof = static_cast<std::size_t>(n.v);
    const Joint& j = joints_[static_cast<std::size_t>(n.joint)];
    if (held_[dof] != 0) {
      const double into = held_[dof] < 0 ? -solved[n.v] : solved[n.v];
      stuck_[dof] = into >= 0 ? held_[dof] : 0;
      continue;
    }
    const auto stop = std::find_if(stops.begin(), stops.end(), [&](const auto& s) { return s.first == n.q; });
    if (stop != stops.end()) stuck_[dof] = stop->second == j.limits.lower ? -1 : 1;
  }
  held_.clear();  // (the midpoint rule's stops are its own)
  if (!q1_.allFinite() || !p1_.allFinite() || !Configure(q1_, end_)) return false;
  if (Constrained() && !FinishConstrained(stops)) return false;
  Accept(bodies);
  return true;
}

}  // namespace dynamics::internal
