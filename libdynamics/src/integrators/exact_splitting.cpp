// Kick–drift–kick with the exact flow of the free rigid body as the drift (Jacobi elliptic
// functions and quadrature, free_rigid_body.h); bodies outside its domain fall back to the
// implicit midpoint rotation.

#include "dynamics/free_rigid_body.h"
#include "integrator.h"

namespace dynamics::internal {
namespace {

// The exact free flow over h; false when the body is outside its domain.
bool ExactRotation(RigidBody& b, double h) {
  const Vector3& I = b.inertia;
  if (!(I[0] < I[1] && I[1] < I[2])) return false;
  try {
    const ExactFreeRotation flow(I, b.BodyAngularVelocity(), b.orientation);
    b.orientation = flow.Orientation(h).normalized();
    return true;
  } catch (const std::invalid_argument&) {
    return false;  // separatrix or L along the third axis
  }
}

}  // namespace

bool StepExactSplitting(StepContext& c, double t, double h) {
  return KickDriftKick(c, t, h,
                       [](RigidBody& b, double dt) { return ExactRotation(b, dt) || MidpointRotation(b, dt); });
}

}  // namespace dynamics::internal
