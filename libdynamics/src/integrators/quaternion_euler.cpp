// Explicit Euler on the quaternion, renormalized.

#include "integrator.h"

namespace dynamics::internal {

bool StepQuaternionEuler(StepContext& c, double t, double h) {
  c.ComputeWrenches(t);
  const std::vector<Wrench>& w = c.wrenches();
  c.ForEachBody([&](std::size_t i) {
    RigidBody& b = c.bodies[i];
    const Quaternion dq = QuaternionRate(b.orientation, b.AngularVelocity());
    b.position += h * b.velocity;
    b.velocity += h / b.mass * w[i].force;
    b.orientation.coeffs() += h * dq.coeffs();
    b.orientation.normalize();
    b.angular_momentum += h * w[i].torque;
  });
  return true;
}

}  // namespace dynamics::internal
