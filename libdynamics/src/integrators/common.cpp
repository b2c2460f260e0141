// Pieces several integrators share: the skew matrix, the quaternion rate and the implicit
// midpoint free rotation.

#include <Eigen/LU>

#include "integrator.h"

namespace dynamics::internal {

Matrix3 Skew(const Vector3& w) {
  Matrix3 m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

Quaternion QuaternionRate(const Quaternion& q, const Vector3& omega_world) {
  const Quaternion w(0.0, omega_world.x(), omega_world.y(), omega_world.z());
  Quaternion r = w * q;
  r.coeffs() *= 0.5;
  return r;
}

// The midpoint equation y = Π0 + (h/2) y × I0⁻¹y (y = Π at the midpoint) is solved by
// fixed-point iteration, then Newton. Then Π1 = 2y − Π0 and R1 = R0 cay(h I0⁻¹ y); since
// cay(hω)Π1 = Π0 exactly in exact arithmetic, world L = RΠ is untouched and kept as it is.
bool MidpointRotation(RigidBody& b, double h) {
  const Vector3 J = b.inertia.cwiseInverse();
  const Vector3 pi0 = b.BodyAngularMomentum();
  const double scale = pi0.norm();
  if (scale == 0.0) return true;
  // Fixed-point iteration first: it contracts by about h|ω| per sweep and costs a cross product;
  // Newton (a 3×3 solve per iteration) takes over when h|ω| is not small.
  Vector3 y = pi0;
  bool converged = false;
  for (int it = 0; it < 12 && !converged; ++it) {
    const Vector3 next = pi0 + 0.5 * h * y.cross(J.cwiseProduct(y));
    converged = (next - y).norm() <= 1e-15 * scale;
    y = next;
  }
  for (int it = 0; it < 50 && !converged; ++it) {
    const Vector3 w = J.cwiseProduct(y);
    const Vector3 g = y - pi0 - 0.5 * h * y.cross(w);
    const Matrix3 dg = Matrix3::Identity() - 0.5 * h * (-Skew(w) + Skew(y) * J.asDiagonal());
    const Vector3 dy = dg.partialPivLu().solve(g);
    if (!dy.allFinite()) return false;
    y -= dy;
    converged = dy.norm() <= 1e-15 * scale;
  }
  if (!converged) {
    const Vector3 w = J.cwiseProduct(y);
    converged = (y - pi0 - 0.5 * h * y.cross(w)).norm() <= 1e-13 * scale;
  }
  if (!converged) return false;
  const Vector3 half = 0.5 * h * J.cwiseProduct(y);  // Cayley: (1, hω/2) normalized
  const Quaternion dq = Quaternion(1.0, half.x(), half.y(), half.z()).normalized();
  b.orientation = (b.orientation * dq).normalized();
  return true;
}

}  // namespace dynamics::internal
