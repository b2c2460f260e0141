// Symmetric splitting of the free rotation into exact rotations about the principal axes
// (McLachlan 1993; Dullweber, Leimkuhler & McLachlan 1997) in the kick–drift–kick frame.

#include "integrator.h"

namespace dynamics::internal {
namespace {

Quaternion AxisRotation(int axis, double angle) { return Quaternion(Eigen::AngleAxisd(angle, Vector3::Unit(axis))); }

// T1(h/2) T2(h/2) T3(h) T2(h/2) T1(h/2). Each flow keeps Π_i and rotates the body about e_i at
// the rate Π_i/I_i. World L is untouched.
void SplittingRotation(RigidBody& b, double h) {
  Vector3 pi = b.BodyAngularMomentum();
  Quaternion q = b.orientation;
  auto flow = [&](int i, double t) {
    const double angle = t * pi[i] / b.inertia[i];
    q = q * AxisRotation(i, angle);
    pi = AxisRotation(i, -angle) * pi;
  };
  flow(0, 0.5 * h);
  flow(1, 0.5 * h);
  flow(2, h);
  flow(1, 0.5 * h);
  flow(0, 0.5 * h);
  b.orientation = q.normalized();
}

}  // namespace

bool StepSplitting(StepContext& c, double t, double h) {
  return KickDriftKick(c, t, h, [](RigidBody& b, double dt) {
    SplittingRotation(b, dt);
    return true;
  });
}

}  // namespace dynamics::internal
