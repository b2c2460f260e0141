// The default: kick–drift–kick with the implicit midpoint free rotation and a Cayley attitude
// update (Austin, Krishnaprasad & Wang 1993; Lewis & Simo 1994).

#include "integrator.h"

namespace dynamics::internal {

bool StepImplicitMidpoint(StepContext& c, double t, double h) {
  return KickDriftKick(c, t, h, [](RigidBody& b, double dt) { return MidpointRotation(b, dt); });
}

}  // namespace dynamics::internal
