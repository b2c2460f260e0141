// The textbook scheme of the seed notes: explicit Euler on world L and R += h[ω]×R, the rotation
// re-projected by SVD. A reference: its energy drifts.

#include <Eigen/SVD>

#include "integrator.h"

namespace dynamics {

Matrix3 ExplicitEulerRotation(const Matrix3& R, const Vector3& omega_world, double h, bool reproject) {
  Matrix3 out = R + h * internal::Skew(omega_world) * R;
  if (!reproject) return out;
  Eigen::JacobiSVD<Matrix3> svd(out, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Matrix3 U = svd.matrixU();
  if ((U * svd.matrixV().transpose()).determinant() < 0) U.col(2) *= -1.0;
  return U * svd.matrixV().transpose();
}

namespace internal {

bool StepExplicitEuler(StepContext& c, double t, double h) {
  c.ComputeWrenches(t);
  const std::vector<Wrench>& w = c.wrenches();
  c.ForEachBody([&](std::size_t i) {
    RigidBody& b = c.bodies[i];
    const Vector3 omega = b.AngularVelocity();
    b.position += h * b.velocity;
    b.velocity += h / b.mass * w[i].force;
    b.orientation = Quaternion(ExplicitEulerRotation(b.Rotation(), omega, h, true)).normalized();
    b.angular_momentum += h * w[i].torque;
  });
  return true;
}

}  // namespace internal
}  // namespace dynamics
