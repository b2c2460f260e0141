// Classical Runge–Kutta 4 on (x, v, q, L), the quaternion renormalized at every stage.

#include "integrator.h"

namespace dynamics::internal {

bool StepRK4(StepContext& c, double t, double h) {
  using Rate = StepScratch::Rate;
  std::vector<RigidBody>& bodies = c.bodies;
  const std::size_t n = bodies.size();
  // Stages on copies of the whole state, so that coupled forces see consistent states.
  c.scratch.rk4_start = bodies;
  const std::vector<RigidBody>& start = c.scratch.rk4_start;
  auto rates = [&](double time, std::vector<Rate>& k) {
    c.ComputeWrenches(time);
    const std::vector<Wrench>& w = c.wrenches();
    k.resize(n);
    c.ForEachBody([&](std::size_t i) {
      const RigidBody& b = bodies[i];
      k[i].dx = b.velocity;
      k[i].dv = w[i].force / b.mass;
      k[i].dL = w[i].torque;
      k[i].dq = QuaternionRate(b.orientation, b.AngularVelocity()).coeffs();
    });
  };
  auto set_stage = [&](const std::vector<Rate>& k, double a) {
    c.ForEachBody([&](std::size_t i) {
      RigidBody& b = bodies[i];
      b.position = start[i].position + a * k[i].dx;
      b.velocity = start[i].velocity + a * k[i].dv;
      b.angular_momentum = start[i].angular_momentum + a * k[i].dL;
      b.orientation.coeffs() = start[i].orientation.coeffs() + a * k[i].dq;
      b.orientation.normalize();  // stages stay on the unit sphere (ω is then well defined)
    });
  };
  std::vector<Rate>& k1 = c.scratch.rk4_k[0];
  std::vector<Rate>& k2 = c.scratch.rk4_k[1];
  std::vector<Rate>& k3 = c.scratch.rk4_k[2];
  std::vector<Rate>& k4 = c.scratch.rk4_k[3];
  rates(t, k1);
  set_stage(k1, 0.5 * h);
  rates(t + 0.5 * h, k2);
  set_stage(k2, 0.5 * h);
  rates(t + 0.5 * h, k3);
  set_stage(k3, h);
  rates(t + h, k4);
  c.ForEachBody([&](std::size_t i) {
    RigidBody& b = bodies[i];
    b.position = start[i].position + h / 6 * (k1[i].dx + 2 * k2[i].dx + 2 * k3[i].dx + k4[i].dx);
    b.velocity = start[i].velocity + h / 6 * (k1[i].dv + 2 * k2[i].dv + 2 * k3[i].dv + k4[i].dv);
    b.angular_momentum = start[i].angular_momentum + h / 6 * (k1[i].dL + 2 * k2[i].dL + 2 * k3[i].dL + k4[i].dL);
    b.orientation.coeffs() =
        start[i].orientation.coeffs() + h / 6 * (k1[i].dq + 2 * k2[i].dq + 2 * k3[i].dq + k4[i].dq);
    b.orientation.normalize();
  });
  return true;
}

}  // namespace dynamics::internal
