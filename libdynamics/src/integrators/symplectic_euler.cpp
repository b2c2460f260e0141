// Semi-implicit (symplectic) Euler: velocities first, positions with the new velocities.

#include "integrator.h"

namespace dynamics::internal {

bool StepSymplecticEuler(StepContext& c, double t, double h) {
  c.ComputeWrenches(t);
  const std::vector<Wrench>& w = c.wrenches();
  c.ForEachBody([&](std::size_t i) {
    RigidBody& b = c.bodies[i];
    b.velocity += h / b.mass * w[i].force;
    b.angular_momentum += h * w[i].torque;
    b.position += h * b.velocity;
    const Quaternion dq = QuaternionRate(b.orientation, b.AngularVelocity());
    b.orientation.coeffs() += h * dq.coeffs();
    b.orientation.normalize();
  });
  return true;
}

}  // namespace dynamics::internal
