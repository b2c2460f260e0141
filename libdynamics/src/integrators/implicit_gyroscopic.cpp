// The game-engine scheme (Catto, GDC 2015; Bullet's default): implicit Euler on the body angular
// velocity with one Newton step on the gyroscopic term. Stable, but it dissipates.

#include <Eigen/LU>

#include "integrator.h"

namespace dynamics::internal {

bool StepImplicitGyroscopic(StepContext& c, double t, double h) {
  c.ComputeWrenches(t);
  const std::vector<Wrench>& w = c.wrenches();
  c.ForEachBody([&](std::size_t i) {
    RigidBody& b = c.bodies[i];
    b.velocity += h / b.mass * w[i].force;
    b.position += h * b.velocity;
    // Body frame: explicit torque, then one Newton step of I0(ω' − ω) + h ω' × I0ω' = 0 from ω' = ω.
    const Matrix3 I0 = b.inertia.asDiagonal();
    Vector3 omega = b.BodyAngularVelocity() + h * (b.orientation.conjugate() * w[i].torque).cwiseQuotient(b.inertia);
    const Vector3 f = h * omega.cross(I0 * omega);
    const Matrix3 jac = I0 + h * (Skew(omega) * I0 - Skew(I0 * omega));
    omega -= jac.partialPivLu().solve(f);
    // As engines do, the world angular velocity is the state carried over the attitude update;
    // L follows from it with the new attitude.
    const Vector3 omega_world = b.orientation * omega;
    const Quaternion dq = QuaternionRate(b.orientation, omega_world);
    b.orientation.coeffs() += h * dq.coeffs();
    b.orientation.normalize();
    b.angular_momentum = b.orientation * (I0 * (b.orientation.conjugate() * omega_world));
  });
  return true;
}

}  // namespace dynamics::internal
