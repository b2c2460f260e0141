// Jacobians and effective masses of the contact rows and patches, and the coupled response of
// jointed bodies (solver_internal.h, solver.h).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "../integrators/integrator.h"
#include "solver_internal.h"

namespace dynamics::contact {
namespace {

double InvMass(const BodyResponse& bodies, int i) {
  return i >= 0 ? bodies.inv_mass[static_cast<std::size_t>(i)] : 0.0;
}

Matrix3 InvInertia(const BodyResponse& bodies, int i) {
  return i >= 0 ? bodies.inv_inertia[static_cast<std::size_t>(i)] : Matrix3::Zero().eval();
}

// K = (1/m) E − [r]× I⁻¹ [r]×: a body's share of a point's response to an impulse at r.
Matrix3 PointResponse(const BodyResponse& bodies, int i, const Vector3& r) {
  const Matrix3 S = internal::Skew(r);
  return InvMass(bodies, i) * Matrix3::Identity() - S * InvInertia(bodies, i) * S;
}

// Jointed bodies: the response of a's generalized directions Wa (columns of wrenches on a) minus
// b's to impulses along them (+ on a, − on b): Waᵀ G_aa Wa + Wbᵀ G_bb Wb − Waᵀ G_ab Wb − Wbᵀ G_ba Wa.
template <int N>
Eigen::Matrix<double, N, N> CoupledResponse(const Coupling& c, int a, int b, const Eigen::Matrix<double, 6, N>& Wa,
                                            const Eigen::Matrix<double, 6, N>& Wb) {
  Eigen::Matrix<double, N, N> K = Wa.transpose() * c.Response(a, a) * Wa;
  if (b >= 0) {
    K += Wb.transpose() * c.Response(b, b) * Wb;
    if (c.Joined(a, b)) {
      K -= Wa.transpose() * c.Response(a, b) * Wb;
      K -= Wb.transpose() * c.Response(b, a) * Wa;
    }
  }
  return K;
}

}  // namespace

// A row's effective masses and Jacobian.
void SetRowJacobian(Row& r, const BodyResponse& bodies) {
  if (bodies.coupling != nullptr) {
    r.coupling = bodies.coupling;
    r.ang_a = r.ra.cross(r.n);
    r.ang_b = r.b >= 0 ? Vector3(r.rb.cross(r.n)) : Vector3::Zero();
    r.Ka.setZero();  // (the point responses serve shock propagation, which leaves jointed bodies out)
    r.Kb.setZero();
    r.mass_n = 1.0 / r.coupling->NormalResponse(r);
    return;
  }
  r.Ka = PointResponse(bodies, r.a, r.ra);
  r.Kb = PointResponse(bodies, r.b, r.rb);
  r.mass_n = 1.0 / r.n.dot((r.Ka + r.Kb) * r.n);
  r.inv_mass_a = InvMass(bodies, r.a);
  r.inv_mass_b = InvMass(bodies, r.b);
  r.ang_a = r.ra.cross(r.n);
  r.turn_a = InvInertia(bodies, r.a) * r.ang_a;
  if (r.b >= 0) {
    r.ang_b = r.rb.cross(r.n);
    r.turn_b = InvInertia(bodies, r.b) * r.ang_b;
  }
}

// A patch's Jacobian and effective masses at its anchor (ra, rb): generalized directions (t1, t2
// at r; ρ n as a turn), each body's K_ij = (1/m) d_i·d_j + a_i·I⁻¹ a_j.
void SetPatchJacobian(Patch& p, const BodyResponse& bodies) {
  if (bodies.coupling != nullptr) {
    p.coupling = bodies.coupling;
    auto directions = [&](const Vector3& r, Matrix3& ang) {
      ang.col(0) = r.cross(p.t1);
      ang.col(1) = r.cross(p.t2);
      ang.col(2) = p.rho * p.n;
      Eigen::Matrix<double, 6, 3> W;
      W.topRows<3>() << p.t1, p.t2, Vector3::Zero();
      W.bottomRows<3>() = ang;
      return W;
    };
    const Eigen::Matrix<double, 6, 3> Wa = directions(p.ra, p.ang_a);
    Eigen::Matrix<double, 6, 3> Wb = Eigen::Matrix<double, 6, 3>::Zero();
    if (p.b >= 0) {
      Wb = directions(p.rb, p.ang_b);
    } else {
      p.ang_b.setZero();
    }
    p.Ka = CoupledResponse<3>(*p.coupling, p.a, p.b, Wa, Wb);
    // A tree may not move a point along every direction (a hinge's bob not along its axis): the
    // response is then singular there, and so is the relative velocity, which no impulse
    // changes. A regularization of 10⁻⁹ of the largest response keeps the inverse finite.
    p.Ka.diagonal().array() += 1e-9 * p.Ka.diagonal().maxCoeff();
    p.Kb.setZero();
    p.mass = PatchMass(p.Ka, p.rho);
    return;
  }
  p.inv_mass_a = InvMass(bodies, p.a);
  p.inv_mass_b = InvMass(bodies, p.b);
  auto side = [&](int i, const Vector3& r, double inv_mass, Matrix3& ang, Matrix3& turn, Matrix3& K) {
    ang.col(0) = r.cross(p.t1);
    ang.col(1) = r.cross(p.t2);
    ang.col(2) = p.rho * p.n;
    turn = InvInertia(bodies, i) * ang;
    K = ang.transpose() * turn;
    K(0, 0) += inv_mass;
    K(1, 1) += inv_mass;
  };
  side(p.a, p.ra, p.inv_mass_a, p.ang_a, p.turn_a, p.Ka);
  if (p.b >= 0) {
    side(p.b, p.rb, p.inv_mass_b, p.ang_b, p.turn_b, p.Kb);
  } else {
    p.ang_b.setZero();
    p.turn_b.setZero();
    p.Kb.setZero();
  }
  p.mass = PatchMass(p.Ka + p.Kb, p.rho);
}

// A patch's normals' coupled response (Patch::block).
void SetNormalBlock(Patch& p, const std::vector<Row>& rows) {
  p.block.setZero();
  if (p.count < 2 || p.count > 4) return;
  const Row* r = &rows[static_cast<std::size_t>(p.first)];
  if (p.coupling != nullptr) {
    Eigen::Matrix<double, 6, 4> Wa = Eigen::Matrix<double, 6, 4>::Zero(), Wb = Eigen::Matrix<double, 6, 4>::Zero();
    for (int i = 0; i < p.count; ++i) {
      Wa.col(i) << r[i].n, r[i].ang_a;
      if (p.b >= 0) Wb.col(i) << r[i].n, r[i].ang_b;
    }
    p.block = CoupledResponse<4>(*p.coupling, p.a, p.b, Wa, Wb);
    return;
  }
  for (int i = 0; i < p.count; ++i) {
    for (int j = 0; j < p.count; ++j) {
      const double nn = r[i].n.dot(r[j].n);
      double a = r[i].inv_mass_a * nn + r[i].ang_a.dot(r[j].turn_a);
      if (r[i].b >= 0) a += r[i].inv_mass_b * nn + r[i].ang_b.dot(r[j].turn_b);
      p.block(i, j) = a;
    }
  }
}

void Coupling::Apply(std::vector<Velocities>& vel, int a, const Vector3& f, const Vector3& tau) const {
  const auto t = static_cast<std::size_t>(tree[static_cast<std::size_t>(a)]);
  const std::vector<int>& m = members[t];
  const std::size_t n = m.size(), k = static_cast<std::size_t>(slot[static_cast<std::size_t>(a)]);
  Vector6 w;
  w << f, tau;
  for (std::size_t j = 0; j < n; ++j) {
    const Vector6 d = response[t][j * n + k] * w;
    Velocities& v = vel[static_cast<std::size_t>(m[j])];
    v.v += d.head<3>();
    v.w += d.tail<3>();
  }
}

double Coupling::NormalResponse(const Row& r) const {
  Vector6 wa, wb = Vector6::Zero();
  wa << r.n, r.ra.cross(r.n);
  if (r.b >= 0) wb << r.n, r.rb.cross(r.n);
  return CoupledResponse<1>(*this, r.a, r.b, Eigen::Matrix<double, 6, 1>(wa), Eigen::Matrix<double, 6, 1>(wb))(0, 0);
}

Vector3 RelativeVelocity(const std::vector<Velocities>& vel, int a, int b, const Vector3& ra, const Vector3& rb) {
  const Velocities& va = vel[static_cast<std::size_t>(a)];
  Vector3 v = va.v + va.w.cross(ra);
  if (b >= 0) {
    const Velocities& vb = vel[static_cast<std::size_t>(b)];
    v -= vb.v + vb.w.cross(rb);
  }
  return v;
}

}  // namespace dynamics::contact
