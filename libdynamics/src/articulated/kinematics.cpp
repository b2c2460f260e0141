// The articulation's tree, kinematics, mass matrix and momentum rate (see articulation.h).

#include <algorithm>
#include <cmath>
#include <deque>
#include <sstream>
#include <stdexcept>

#include "articulation.h"

namespace dynamics::internal {
namespace {

Quaternion QuatAt(const Eigen::VectorXd& q, int at) {
  return Quaternion(q[at], q[at + 1], q[at + 2], q[at + 3]).normalized();
}

void PutQuat(const Quaternion& r, Eigen::VectorXd& q, int at) {
  q[at] = r.w();
  q[at + 1] = r.x();
  q[at + 2] = r.y();
  q[at + 3] = r.z();
}

/// exp of the rotation vector θ as a unit quaternion.
Quaternion ExpRotation(const Vector3& theta) {
  const double angle = theta.norm();
  const double half = 0.5 * angle;
  // sin(θ/2)/θ, by its series where θ is small.
  const double s = angle < 1e-4 ? 0.5 - angle * angle / 48.0 : std::sin(half) / angle;
  return Quaternion(std::cos(half), s * theta.x(), s * theta.y(), s * theta.z());
}

/// Spatial force cross product V ×* h.
Vector6 CrossForce(const Vector6& V, const Vector6& h) {
  const Vector3 w = V.head<3>(), u = V.tail<3>(), n = h.head<3>(), f = h.tail<3>();
  Vector6 r;
  r << w.cross(n) + u.cross(f), w.cross(f);
  return r;
}

/// The joint's relative turn and shift (J_c in J_p) at q.
void Relative(const Node& n, const Eigen::VectorXd& q, Matrix3& R, Vector3& t) {
  R.setIdentity();
  t.setZero();
  switch (n.type) {
    case JointType::kFixed: break;
    case JointType::kRevolute: R = Eigen::AngleAxisd(q[n.q], n.axis).toRotationMatrix(); break;
    case JointType::kPrismatic: t = q[n.q] * n.axis; break;
    case JointType::kSpherical: R = QuatAt(q, n.q).toRotationMatrix(); break;
    case JointType::kFree:
      t = q.segment<3>(n.q);
      R = QuatAt(q, n.q + 3).toRotationMatrix();
      break;
  }
}

/// A body's spatial inertia about a point at c from its centre of mass (world axes): its mass m
/// and its rotational inertia Ic about the centre, in world axes.
Matrix6 SpatialInertia(double m, const Matrix3& Ic, const Vector3& c) {
  const Matrix3 C = CrossMatrix(c);
  Matrix6 I;
  // m C Cᵀ = m (|c|² 1 − c cᵀ)
  I.topLeftCorner<3, 3>() = Ic + m * (c.squaredNorm() * Matrix3::Identity() - c * c.transpose());
  I.topRightCorner<3, 3>() = m * C;
  I.bottomLeftCorner<3, 3>() = m * C.transpose();
  I.bottomRightCorner<3, 3>() = m * Matrix3::Identity();
  return I;
}

}  // namespace

void FreeJointFromBody(const Node& node, const Matrix3& parent_R, const Vector3& parent_x, const Vector6& parent_V,
                       const RigidBody& b, double* q, double* v) {
  const Matrix3 Rj = parent_R * node.parent_rotation;
  const Vector3 oj = parent_x + parent_R * node.parent_origin;
  const Matrix3 Rb = b.Rotation();
  const Matrix3 Rc = Rb * node.child_rotation;
  const Vector3 o = b.position + Rb * node.child_origin;
  const Vector3 t = Rj.transpose() * (o - oj);
  const Quaternion r(Rj.transpose() * Rc);
  q[0] = t.x(), q[1] = t.y(), q[2] = t.z();
  q[3] = r.w(), q[4] = r.x(), q[5] = r.y(), q[6] = r.z();
  const Vector3 w = b.AngularVelocity();
  const Vector3 dw = w - parent_V.head<3>();
  const Vector3 dvo = (b.velocity - w.cross(b.position)) - parent_V.tail<3>();
  const Vector3 vr = Rc.transpose() * dw;
  const Vector3 vl = Rj.transpose() * (dvo + dw.cross(o));
  v[0] = vr.x(), v[1] = vr.y(), v[2] = vr.z(), v[3] = vl.x(), v[4] = vl.y(), v[5] = vl.z();
}

JointState JointStateFromBodies(const Joint& joint, const std::vector<RigidBody>& bodies) {
  Node n;
  n.parent_rotation = joint.parent_frame.orientation.normalized().toRotationMatrix();
  n.parent_origin = joint.parent_frame.origin;
  n.child_rotation = joint.child_frame.orientation.normalized().toRotationMatrix();
  n.child_origin = joint.child_frame.origin;
  Matrix3 Rp = Matrix3::Identity();
  Vector3 xp = Vector3::Zero();
  Vector6 Vp = Vector6::Zero();
  if (joint.parent >= 0) {
    const RigidBody& p = bodies[static_cast<std::size_t>(joint.parent)];
    Rp = p.Rotation();
    xp = p.position;
    const Vector3 w = p.AngularVelocity();
    Vp << w, p.velocity - w.cross(p.position);
  }
  JointState s;
  s.position.resize(7);
  s.velocity.resize(6);
  FreeJointFromBody(n, Rp, xp, Vp, bodies[static_cast<std::size_t>(joint.child)], s.position.data(), s.velocity.data());
  return s;
}

Articulation::Articulation(const std::vector<Joint>& joints, std::vector<RigidBody>& bodies)
    : joints_(joints), inertias_(bodies) {
  const int nb = static_cast<int>(bodies.size());
  std::vector<int> joint_of(static_cast<std::size_t>(nb), -1);
  for (std::size_t j = 0; j < joints.size(); ++j)
    joint_of[static_cast<std::size_t>(joints[j].child)] = static_cast<int>(j);
  std::vector<std::vector<int>> kids(static_cast<std::size_t>(nb));
  std::deque<int> queue;
  for (int b = 0; b < nb; ++b) {
    const int j = joint_of[static_cast<std::size_t>(b)];
    const int parent = j < 0 ? -1 : joints[static_cast<std::size_t>(j)].parent;
    if (parent < 0) {
      queue.push_back(b);
    } else {
      kids[static_cast<std::size_t>(parent)].push_back(b);
    }
  }
  std::vector<int>& node_of_body = node_of_body_;
  node_of_body.assign(static_cast<std::size_t>(nb), -1);
  node_of_joint_.assign(joints.size(), -1);
  int nq = 0, nv = 0;
  while (!queue.empty()) {
    const int b = queue.front();
    queue.pop_front();
    Node n;
    n.body = b;
    n.joint = joint_of[static_cast<std::size_t>(b)];
    if (n.joint >= 0) {
      const Joint& jt = joints[static_cast<std::size_t>(n.joint)];
      n.parent = jt.parent < 0 ? -1 : node_of_body[static_cast<std::size_t>(jt.parent)];
      n.type = jt.type;
      n.axis = jt.axis.normalized();
      n.parent_rotation = jt.parent_frame.orientation.normalized().toRotationMatrix();
      n.parent_origin = jt.parent_frame.origin;
      n.child_rotation = jt.child_frame.orientation.normalized().toRotationMatrix();
      n.child_origin = jt.child_frame.origin;
      node_of_joint_[static_cast<std::size_t>(n.joint)] = static_cast<int>(nodes_.size());
    }
    n.q = nq;
    n.nq = JointPositionSize(n.type);
    n.v = nv;
    n.nv = JointVelocitySize(n.type);
    nq += n.nq;
    nv += n.nv;
    node_of_body[static_cast<std::size_t>(b)] = static_cast<int>(nodes_.size());
    nodes_.push_back(n);
    for (int k : kids[static_cast<std::size_t>(b)]) queue.push_back(k);
  }
  if (static_cast<int>(nodes_.size()) != nb) {
    for (int b = 0; b < nb; ++b) {
      if (node_of_body[static_cast<std::size_t>(b)] >= 0) continue;
      std::ostringstream msg;
      // The joint just added (the last) is the one that closed it.
      msg << "World::AddJoint: joint '" << joints.back().name << "': closes a loop of joints through body " << b
          << " (joints must form a tree: each body hangs from one parent, down from the world)";
      throw std::invalid_argument(msg.str());
    }
  }
  // The initial state, parents first; the bodies that take it from their own state are left as
  // they are (a lone free body keeps its bits).
  q_ = Eigen::VectorXd::Zero(nq);
  v_ = Eigen::VectorXd::Zero(nv);
  limit_impulse_.assign(joints.size(), 0.0);
  drive_impulse_.assign(joints.size(), 0.0);
  std::vector<char> placed(static_cast<std::size_t>(nb), 0);
  Configuration& c = end_;
  c.frames.resize(nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    const Joint* jt = n.joint >= 0 ? &joints[static_cast<std::size_t>(n.joint)] : nullptr;
    const bool from_body = n.type == JointType::kFree && (!jt || jt->position.empty());
    const bool velocity_from_body = n.type == JointType::kFree && (!jt || jt->velocity.empty());
    Matrix3 Rp = Matrix3::Identity();
    Vector3 xp = Vector3::Zero();
    Vector6 Vp = Vector6::Zero();
    if (n.parent >= 0) {
      const NodeFrame& pf = c.frames[static_cast<std::size_t>(n.parent)];
      Rp = pf.R, xp = pf.x, Vp = pf.V;
    }
    double fq[7], fv[6];
    if (from_body || velocity_from_body) {
      FreeJointFromBody(n, Rp, xp, Vp, bodies[static_cast<std::size_t>(n.body)], fq, fv);
    }
    for (int k = 0; k < n.nq; ++k) {
      q_[n.q + k] = from_body ? fq[k] : (jt->position.empty() ? 0.0 : jt->position[static_cast<std::size_t>(k)]);
    }
    if (n.type == JointType::kSpherical && jt->position.empty()) q_[n.q] = 1.0;
    if (n.type == JointType::kFree && !from_body && jt->position.empty()) q_[n.q + 3] = 1.0;
    const int quat = n.quaternion();
    if (quat >= 0) q_.segment<4>(quat).normalize();  // a given quaternion of any length (checked non-zero)
    for (int k = 0; k < n.nv; ++k) {
      v_[n.v + k] =
          velocity_from_body ? fv[k] : (jt->velocity.empty() ? 0.0 : jt->velocity[static_cast<std::size_t>(k)]);
    }
    PlaceNode(static_cast<int>(i), q_, c);
    NodeFrame& f = c.frames[i];
    f.V = Vp;
    if (n.nv > 0) f.V += f.S * v_.segment(n.v, n.nv);
    placed[static_cast<std::size_t>(n.body)] = !(from_body && velocity_from_body);
  }
  // The momenta wait for the first step (EnsureMomenta): a mass matrix for every joint added
  // would make adding n joints cost O(n⁴).
  momenta_ready_ = false;
  recursion_ok_ = std::all_of(nodes_.begin(), nodes_.end(), [](const Node& n) { return n.nv <= 1 || n.parent < 0; });
  Sync(end_, bodies, &placed);
}

bool Articulation::EnsureMomenta() {
  if (momenta_ready_) return true;
  if (!Configure(q_, end_, StepForm())) return false;
  Momenta(end_, v_, p_);
  momenta_ready_ = true;
  return true;
}

void Articulation::Momenta(Configuration& c, const Eigen::VectorXd& v, Eigen::VectorXd& p) {
  Velocities(v, c);
  p = Eigen::VectorXd::Zero(v.size());  // (an empty product is UB in Eigen's self-adjoint kernel)
  if (v.size() > 0 && c.dense) p = c.M.selfadjointView<Eigen::Lower>() * v;
  if (c.dense) return;
  // (M v)_i = S_iᵀ Σ over i's subtree of I_j V_j (+ the armature's a v_i): the momenta of the
  // subtrees, O(n).
  SubtreeMomenta(c);
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Node& ni = nodes_[i];
    if (ni.nv == 0) continue;
    p.segment(ni.v, ni.nv) = c.frames[i].S.transpose() * subtree_momentum_[i];
    if (ni.nv == 1 && ni.joint >= 0) p[ni.v] += joints_[static_cast<std::size_t>(ni.joint)].armature * v[ni.v];
  }
}

namespace {

// Spatial quantities moved from a reference point P to Q = P + d (world axes): a motion's linear
// part v + ω × d; a force's moment τ − d × f; an inertia X* I X⁻¹.
Vector6 MotionAt(const Vector6& m, const Vector3& d) {
  Vector6 out = m;
  out.tail<3>() += m.head<3>().cross(d);
  return out;
}
Vector6 ForceAt(const Vector6& f, const Vector3& d) {
  Vector6 out = f;
  out.head<3>() -= d.cross(f.tail<3>());
  return out;
}
Matrix6 InertiaAt(const Matrix6& I, const Vector3& d) {
  // X* = [1, −D; 0, 1], X⁻¹ = [1, 0; D, 1] with D = [d]×, I = [A, B; Bᵀ, C] (blockwise, A and C
  // symmetric): X* I X⁻¹ = [A − D Bᵀ + E D, E; Eᵀ, C] with E = B − D C. Each product with D is
  // three cross products: column j of D M is d × M_j, row i of M D is M_iᵀ × d.
  const Matrix3 B = I.topRightCorner<3, 3>(), C = I.bottomRightCorner<3, 3>();
  Matrix3 E;
  for (int j = 0; j < 3; ++j) E.col(j) = B.col(j) - d.cross(Vector3(C.col(j)));
  Matrix6 out;
  for (int j = 0; j < 3; ++j) {  // column j of −D Bᵀ is −d × (row j of B)
    out.block<3, 1>(0, j) = I.block<3, 1>(0, j) - d.cross(Vector3(B.row(j).transpose()));
  }
  for (int i = 0; i < 3; ++i) out.block<1, 3>(i, 0) += Vector3(E.row(i).transpose()).cross(d).transpose();
  out.topRightCorner<3, 3>() = E;
  out.bottomLeftCorner<3, 3>() = E.transpose();
  out.bottomRightCorner<3, 3>() = C;
  return out;
}

}  // namespace

// Featherstone's articulated-body recursion solving M v = p, each node's quantities about its own
// joint's origin (about the world origin, a chain a metre long lost digits to cancellation in
// the articulated inertias: 10⁻¹ relative error at 22 ball joints). Backward: each node's
// articulated inertia and bias, less what its own coordinates take, handed to its parent's joint
// origin; forward: the coordinates and the frame's velocity, parent first.
void Articulation::Solve(const Configuration& c, const Eigen::VectorXd& p, Eigen::VectorXd& v) {
  if (c.dense) {
    v = c.llt.solve(p);
    return;
  }
  const std::size_t n = nodes_.size();
  aba_inertia_.resize(n);
  aba_bias_.assign(n, Vector6::Zero());
  aba_velocity_.resize(n);
  aba_s_.resize(n);
  aba_u_.resize(n);
  aba_d_inverse_.resize(n);
  aba_rhs_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const NodeFrame& f = c.frames[i];
    const Vector3& o = f.joint_origin;
    aba_inertia_[i] = SpatialInertia(inertias_[static_cast<std::size_t>(nodes_[i].body)].mass, f.rotational, f.x - o);
    aba_s_[i] = f.S;
    for (Eigen::Index k = 0; k < f.S.cols(); ++k) aba_s_[i].col(k) = MotionAt(f.S.col(k), o);
  }
  for (std::size_t i = n; i-- > 0;) {
    const Node& ni = nodes_[i];
    const MotionColumns& S = aba_s_[i];
    Matrix6& handed = aba_inertia_[i];  // (the forward pass does not read it)
    Vector6& bias = aba_bias_[i];
    if (ni.nv == 1) {  // hinges and sliders: D a number
      const Vector6 U = aba_inertia_[i] * S.col(0);
      double D = S.col(0).dot(U);
      if (ni.joint >= 0) D += joints_[static_cast<std::size_t>(ni.joint)].armature;
      if (c.implicit.size() > 0) D += c.implicit[ni.v];
      const double rhs = p[ni.v] - S.col(0).dot(aba_bias_[i]);
      aba_u_[i] = U;
      aba_d_inverse_[i].setConstant(1, 1, 1.0 / D);
      aba_rhs_[i].setConstant(1, rhs);
      handed.noalias() -= (U / D) * U.transpose();
      bias += U * (rhs / D);
    } else if (ni.nv > 1) {
      aba_u_[i] = aba_inertia_[i] * S;
      SmallMatrix D = S.transpose() * aba_u_[i];
      if (c.implicit.size() > 0) D.diagonal() += c.implicit.segment(ni.v, ni.nv);
      aba_d_inverse_[i] = D.inverse();
      aba_rhs_[i] = p.segment(ni.v, ni.nv) - S.transpose() * aba_bias_[i];
      handed.noalias() -= aba_u_[i] * aba_d_inverse_[i] * aba_u_[i].transpose();
      bias.noalias() += aba_u_[i] * (aba_d_inverse_[i] * aba_rhs_[i]);
    }
    if (ni.parent >= 0) {
      const auto parent = static_cast<std::size_t>(ni.parent);
      const Vector3 d = c.frames[parent].joint_origin - c.frames[i].joint_origin;
      aba_inertia_[parent] += InertiaAt(handed, d);
      aba_bias_[parent] += ForceAt(bias, d);
    }
  }
  v.resize(p.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Node& ni = nodes_[i];
    aba_velocity_[i].setZero();
    if (ni.parent >= 0) {
      const auto parent = static_cast<std::size_t>(ni.parent);
      aba_velocity_[i] = MotionAt(aba_velocity_[parent], c.frames[i].joint_origin - c.frames[parent].joint_origin);
    }
    if (ni.nv == 0) continue;
    if (ni.nv == 1) {
      const double vi = aba_d_inverse_[i](0, 0) * (aba_rhs_[i][0] - aba_u_[i].col(0).dot(aba_velocity_[i]));
      v[ni.v] = vi;
      aba_velocity_[i] += aba_s_[i].col(0) * vi;
      continue;
    }
    const SmallVector vi = aba_d_inverse_[i] * (aba_rhs_[i] - aba_u_[i].transpose() * aba_velocity_[i]);
    v.segment(ni.v, ni.nv) = vi;
    aba_velocity_[i] += aba_s_[i] * vi;
  }
}

void Articulation::PlaceNode(int i, const Eigen::VectorXd& q, Configuration& c) const {
  const Node& n = nodes_[static_cast<std::size_t>(i)];
  NodeFrame& f = c.frames[static_cast<std::size_t>(i)];
  Matrix3 Rp = Matrix3::Identity();
  Vector3 xp = Vector3::Zero();
  if (n.parent >= 0) {
    const NodeFrame& pf = c.frames[static_cast<std::size_t>(n.parent)];
    Rp = pf.R, xp = pf.x;
  }
  Matrix3 Rrel;
  Vector3 trel;
  Relative(n, q, Rrel, trel);
  const Matrix3 Rj = Rp * n.parent_rotation;
  const Vector3 oj = xp + Rp * n.parent_origin;
  f.joint_R = Rj * Rrel;
  f.joint_origin = oj + Rj * trel;
  f.R = f.joint_R * n.child_rotation.transpose();
  f.x = f.joint_origin - f.R * n.child_origin;
  f.S.resize(6, n.nv);
  const Vector3& o = f.joint_origin;
  auto rotation = [&](int col, const Vector3& a) { f.S.col(col) << a, o.cross(a); };
  auto translation = [&](int col, const Vector3& d) { f.S.col(col) << Vector3::Zero(), d; };
  switch (n.type) {
    case JointType::kFixed: break;
    case JointType::kRevolute: rotation(0, Rj * n.axis); break;
    case JointType::kPrismatic: translation(0, Rj * n.axis); break;
    case JointType::kSpherical:
      for (int k = 0; k < 3; ++k) rotation(k, f.joint_R.col(k));
      break;
    case JointType::kFree:  // turning about J_c's axes, moving along J_p's (fixed in the parent)
      for (int k = 0; k < 3; ++k) rotation(k, f.joint_R.col(k));
      for (int k = 0; k < 3; ++k) translation(3 + k, Rj.col(k));
      break;
  }
  const RigidBody& b = inertias_[static_cast<std::size_t>(n.body)];
  f.rotational = f.R * b.inertia.asDiagonal() * f.R.transpose();
  f.inertia = SpatialInertia(b.mass, f.rotational, f.x);
}

void Articulation::Composites(Configuration& c) const {
  const std::size_t n = nodes_.size();
  c.composite.resize(n);
  for (std::size_t i = 0; i < n; ++i) c.composite[i] = c.frames[i].inertia;
  for (std::size_t i = n; i-- > 0;) {
    if (nodes_[i].parent >= 0) c.composite[static_cast<std::size_t>(nodes_[i].parent)] += c.composite[i];
  }
  c.composites_current = true;
}

bool Articulation::Configure(const Eigen::VectorXd& q, Configuration& c, Form form) const {
  c.q = q;
  const std::size_t n = nodes_.size();
  c.frames.resize(n);
  for (std::size_t i = 0; i < n; ++i) PlaceNode(static_cast<int>(i), q, c);
  c.dense = form == Form::kDense;
  c.composites_current = false;
  if (form == Form::kFrames) return true;
  Composites(c);
  if (c.dense) return Densify(c);
  c.diagonal.resize(v_.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Node& ni = nodes_[i];
    const MotionColumns& S = c.frames[i].S;
    for (int k = 0; k < ni.nv; ++k) c.diagonal[ni.v + k] = S.col(k).dot(c.composite[i] * S.col(k));
    if (ni.nv == 1 && ni.joint >= 0) c.diagonal[ni.v] += joints_[static_cast<std::size_t>(ni.joint)].armature;
  }
  if (c.implicit.size() > 0) c.diagonal += c.implicit;
  for (Eigen::Index k = 0; k < c.diagonal.size(); ++k) {
    if (!(c.diagonal[k] > 0)) return false;  // (M's diagonal of a positive definite M is positive)
  }
  return true;
}

bool Articulation::Densify(Configuration& c) const {
  if (!c.composites_current) Composites(c);
  c.dense = true;
  const std::size_t n = nodes_.size();
  const auto nv = static_cast<Eigen::Index>(v_.size());
  c.M.setZero(nv, nv);
  for (std::size_t i = 0; i < n; ++i) {
    const Node& ni = nodes_[i];
    if (ni.nv == 0) continue;
    if (ni.nv == 1) {  // hinges and sliders: one column, fixed-size products
      const Vector6 F = c.composite[i] * c.frames[i].S.col(0);
      c.M(ni.v, ni.v) = c.frames[i].S.col(0).dot(F);
      if (ni.joint >= 0) c.M(ni.v, ni.v) += joints_[static_cast<std::size_t>(ni.joint)].armature;
      for (int j = ni.parent; j >= 0; j = nodes_[static_cast<std::size_t>(j)].parent) {
        const Node& nj = nodes_[static_cast<std::size_t>(j)];
        const MotionColumns& Sj = c.frames[static_cast<std::size_t>(j)].S;
        for (int k = 0; k < nj.nv; ++k) c.M(ni.v, nj.v + k) = Sj.col(k).dot(F);  // the lower triangle
      }
      continue;
    }
    const MotionColumns F = c.composite[i] * c.frames[i].S;
    c.M.block(ni.v, ni.v, ni.nv, ni.nv) = c.frames[i].S.transpose() * F;
    for (int j = ni.parent; j >= 0; j = nodes_[static_cast<std::size_t>(j)].parent) {
      const Node& nj = nodes_[static_cast<std::size_t>(j)];
      if (nj.nv == 0) continue;
      c.M.block(ni.v, nj.v, ni.nv, nj.nv) = F.transpose() * c.frames[static_cast<std::size_t>(j)].S;
    }
  }
  if (c.implicit.size() > 0) c.M.diagonal() += c.implicit;
  c.diagonal = c.M.diagonal();
  if (nv == 0) return true;
  c.llt.compute(c.M);  // reads the lower triangle, the only one filled
  return c.llt.info() == Eigen::Success;
}

void Articulation::Velocities(const Eigen::VectorXd& v, Configuration& c) const {
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    NodeFrame& f = c.frames[i];
    f.V = n.parent >= 0 ? c.frames[static_cast<std::size_t>(n.parent)].V : Vector6::Zero();
    if (n.nv > 0) f.V += f.S * v.segment(n.v, n.nv);
  }
}

void Articulation::Sync(const Configuration& c, std::vector<RigidBody>& bodies, const std::vector<char>* only) const {
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const NodeFrame& f = c.frames[i];
    RigidBody& b = bodies[static_cast<std::size_t>(nodes_[i].body)];
    if (only && !(*only)[static_cast<std::size_t>(nodes_[i].body)]) continue;
    Quaternion r(f.R);
    if (r.coeffs().dot(b.orientation.coeffs()) < 0) r.coeffs() = -r.coeffs();
    b.orientation = r;
    b.position = f.x;
    const Vector3 w = f.V.head<3>();
    b.velocity = f.V.tail<3>() + w.cross(f.x);
    b.angular_momentum = f.R * b.inertia.asDiagonal() * (f.R.transpose() * w);
  }
}

void Articulation::SubtreeMomenta(const Configuration& c) {
  const std::size_t n = nodes_.size();
  subtree_momentum_.resize(n);
  for (std::size_t i = 0; i < n; ++i) subtree_momentum_[i] = c.frames[i].inertia * c.frames[i].V;
  for (std::size_t i = n; i-- > 0;) {
    const int p = nodes_[i].parent;
    if (p >= 0) subtree_momentum_[static_cast<std::size_t>(p)] += subtree_momentum_[i];
  }
}

Eigen::VectorXd Articulation::ImplicitDiagonal(double h) const {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(v_.size());
  for (const Node& n : nodes_) {
    if (n.joint < 0 || n.nv == 0) continue;
    const Joint& j = joints_[static_cast<std::size_t>(n.joint)];
    double c = j.damping, k = n.nv == 1 ? j.stiffness : 0.0;
    if (n.nv == 1 && j.motor.mode == JointMotor::Mode::kPosition) c += j.motor.kd, k += j.motor.kp;
    if (n.nv == 1) {
      d[n.v] = 0.5 * h * c + 0.25 * h * h * k;
    } else if (n.type == JointType::kSpherical) {
      d.segment(n.v, n.nv).setConstant(0.5 * h * c);
    }
  }
  if (d.isZero(0)) d.resize(0);
  return d;
}

void Articulation::MomentumRate(const std::vector<std::unique_ptr<Force>>& forces, double t, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v, const Configuration& c, std::vector<RigidBody>& stage,
                                Eigen::VectorXd& rate) {
  const std::size_t n = nodes_.size();
  if (stage.size() != inertias_.size()) stage = inertias_;
  Sync(c, stage);
  wrenches_.assign(stage.size(), Wrench{});
  for (const auto& force : forces) force->Apply(t, stage, wrenches_);
  SubtreeMomenta(c);
  subtree_force_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const NodeFrame& f = c.frames[i];
    const Wrench& w = wrenches_[static_cast<std::size_t>(nodes_[i].body)];
    subtree_force_[i] << w.torque + f.x.cross(w.force), w.force;
  }
  for (std::size_t i = n; i-- > 0;) {
    const int p = nodes_[i].parent;
    if (p >= 0) subtree_force_[static_cast<std::size_t>(p)] += subtree_force_[i];
  }
  rate.resize(v.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Node& nd = nodes_[i];
    if (nd.nv == 0) continue;
    const NodeFrame& f = c.frames[i];
    rate.segment(nd.v, nd.nv) = f.S.transpose() * (subtree_force_[i] - CrossForce(f.V, subtree_momentum_[i]));
    if (nd.type == JointType::kFree) {  // its translation columns are fixed in the parent: Ṡ = V_parent × S
      const Vector6 Vp = nd.parent >= 0 ? c.frames[static_cast<std::size_t>(nd.parent)].V : Vector6::Zero();
      rate.segment<3>(nd.v + 3) =
          f.S.rightCols<3>().transpose() * (subtree_force_[i] - CrossForce(Vp, subtree_momentum_[i]));
    }
    if (nd.joint < 0) continue;
    const Joint& j = joints_[static_cast<std::size_t>(nd.joint)];
    if (nd.type == JointType::kSpherical) {
      rate.segment<3>(nd.v) -= j.damping * v.segment<3>(nd.v);
      continue;
    }
    if (nd.nv != 1) continue;
    const double qi = q[nd.q], vi = v[nd.v];
    double effort = -j.stiffness * (qi - j.rest_position) - j.damping * vi;
    if (j.motor.mode == JointMotor::Mode::kPosition) {
      const double servo = j.motor.kp * (j.motor.target - qi) + j.motor.kd * (j.motor.target_velocity - vi);
      effort += std::clamp(servo, -j.motor.max_effort, j.motor.max_effort);
    }
    if (j.motor.mode == JointMotor::Mode::kEffort) {
      effort += std::clamp(j.motor.target, -j.motor.max_effort, j.motor.max_effort);
    }
    rate[nd.v] += effort;
  }
  if (!tendons_.empty()) TendonEfforts(c, q, v, rate);
}

void Articulation::PositionRate(const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& rate) const {
  rate.resize(q.size());
  auto quat_rate = [&](int qi, int vi) {
    const Quaternion r(q[qi], q[qi + 1], q[qi + 2], q[qi + 3]);
    const Quaternion w(0.0, v[vi], v[vi + 1], v[vi + 2]);
    const Quaternion d = r * w;
    rate[qi] = 0.5 * d.w(), rate[qi + 1] = 0.5 * d.x(), rate[qi + 2] = 0.5 * d.y(), rate[qi + 3] = 0.5 * d.z();
  };
  for (const Node& n : nodes_) {
    switch (n.type) {
      case JointType::kFixed: break;
      case JointType::kRevolute:
      case JointType::kPrismatic: rate[n.q] = v[n.v]; break;
      case JointType::kSpherical: quat_rate(n.q, n.v); break;
      case JointType::kFree:
        rate.segment<3>(n.q) = v.segment<3>(n.v + 3);
        quat_rate(n.q + 3, n.v);
        break;
    }
  }
}

void Articulation::Move(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double h, Eigen::VectorXd& out) const {
  out = q;
  for (const Node& n : nodes_) {
    switch (n.type) {
      case JointType::kFixed: break;
      case JointType::kRevolute:
      case JointType::kPrismatic: out[n.q] = q[n.q] + h * v[n.v]; break;
      case JointType::kSpherical:
        PutQuat((QuatAt(q, n.q) * ExpRotation(h * Vector3(v.segment<3>(n.v)))).normalized(), out, n.q);
        break;
      case JointType::kFree:
        out.segment<3>(n.q) = q.segment<3>(n.q) + h * v.segment<3>(n.v + 3);
        PutQuat((QuatAt(q, n.q + 3) * ExpRotation(h * Vector3(v.segment<3>(n.v)))).normalized(), out, n.q + 3);
        break;
    }
  }
}

JointState Articulation::State(int joint) const {
  const Node& n = nodes_[static_cast<std::size_t>(node_of_joint_[static_cast<std::size_t>(joint)])];
  JointState s;
  s.position.assign(q_.data() + n.q, q_.data() + n.q + n.nq);
  s.velocity.assign(v_.data() + n.v, v_.data() + n.v + n.nv);
  s.limit_impulse = limit_impulse_[static_cast<std::size_t>(joint)];
  s.drive_impulse = drive_impulse_[static_cast<std::size_t>(joint)];
  return s;
}

double Articulation::ArmatureEnergy() const {
  double e = 0;
  for (const Node& n : nodes_) {
    if (n.joint < 0 || n.nv != 1) continue;
    const double vi = v_[n.v];
    e += 0.5 * joints_[static_cast<std::size_t>(n.joint)].armature * vi * vi;
  }
  return e;
}

double Articulation::SpringEnergy() const {
  double e = 0;
  for (const Node& n : nodes_) {
    if (n.joint < 0 || n.nq != 1) continue;
    const Joint& j = joints_[static_cast<std::size_t>(n.joint)];
    const double d = q_[n.q] - j.rest_position;
    e += 0.5 * j.stiffness * d * d;
  }
  return e + TendonEnergy();
}

}  // namespace dynamics::internal
