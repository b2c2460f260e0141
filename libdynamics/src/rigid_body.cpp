// The definitions of dynamics/rigid_body.h: a rigid body in the state form of the seed notes.

#include "dynamics/rigid_body.h"

#include <sstream>
#include <stdexcept>

namespace dynamics {

Matrix3 RigidBody::WorldInertia() const {
  const Matrix3 R = Rotation();
  return R * inertia.asDiagonal() * R.transpose();
}

Vector3 RigidBody::BodyAngularVelocity() const { return BodyAngularMomentum().cwiseQuotient(inertia); }

Vector3 RigidBody::AngularVelocity() const { return orientation * BodyAngularVelocity(); }

void RigidBody::SetAngularVelocity(const Vector3& omega_world) {
  const Vector3 omega_body = orientation.conjugate() * omega_world;
  angular_momentum = orientation * inertia.cwiseProduct(omega_body);
}

double RigidBody::RotationalEnergy() const {
  const Vector3 pi = BodyAngularMomentum();
  return 0.5 * pi.cwiseProduct(pi).cwiseQuotient(inertia).sum();
}

double RigidBody::KineticEnergy() const { return 0.5 * mass * velocity.squaredNorm() + RotationalEnergy(); }

PlacedBody BodyFromMassProperties(const massprops::MassProperties& mp, const massprops::PrincipalInertia& p) {
  if (!(mp.mass > 0) || !std::isfinite(mp.mass)) {
    std::ostringstream msg;
    msg << "BodyFromMassProperties: mass must be positive, got " << mp.mass;
    throw std::invalid_argument(msg.str());
  }
  const massprops::ValidityReport ok = massprops::CheckPhysicallyValid(p.moments, 1e-9);
  if (!ok.valid) throw std::invalid_argument("BodyFromMassProperties: " + ok.reason);
  PlacedBody out;
  RigidBody& b = out.body;
  b.mass = mp.mass;
  b.inertia = p.moments;
  b.position = mp.center_of_mass;
  b.orientation = Quaternion(p.axes).normalized();  // R_WB = R_MB at the start
  out.mesh_to_body = massprops::BodyFrameTransform(mp, p);
  return out;
}

PlacedBody BodyFromMassProperties(const massprops::MassProperties& mp) {
  return BodyFromMassProperties(mp, massprops::ComputePrincipalInertia(mp.inertia_com));
}

}  // namespace dynamics
