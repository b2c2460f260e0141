#pragma once
/// @file
/// A rigid body in the state form of the seed notes: position x and velocity v of the center of
/// mass, orientation q (unit quaternion, body → world), and world angular momentum L.
/// The body frame B has its origin at the center of mass and its axes along the principal axes,
/// so the body inertia I0 = diag(I1, I2, I3) is diagonal; the world inertia is I = R I0 Rᵀ and
/// ω = I⁻¹ L. Units SI (m, kg, s, kg·m², rad/s).

#include <Eigen/Geometry>

#include "massprops/mass_properties.h"
#include "massprops/principal_axes.h"

namespace dynamics {

using massprops::Matrix3;
using massprops::Vector3;
using Quaternion = Eigen::Quaterniond;

struct RigidBody {
  double mass = 1.0;                                ///< kg
  Vector3 inertia = Vector3::Ones();                ///< principal moments I1, I2, I3 in frame B, kg·m²
  Vector3 position = Vector3::Zero();               ///< x, center of mass in world, m
  Vector3 velocity = Vector3::Zero();               ///< v, m/s
  Quaternion orientation = Quaternion::Identity();  ///< q: body → world
  Vector3 angular_momentum = Vector3::Zero();       ///< L, world, kg·m²/s

  Matrix3 Rotation() const { return orientation.toRotationMatrix(); }
  /// World inertia about the center of mass, R I0 Rᵀ.
  Matrix3 WorldInertia() const;
  /// Body angular momentum Π = Rᵀ L.
  Vector3 BodyAngularMomentum() const { return orientation.conjugate() * angular_momentum; }
  /// ω in world axes, I⁻¹ L.
  Vector3 AngularVelocity() const;
  /// ω in body axes, I0⁻¹ Π.
  Vector3 BodyAngularVelocity() const;
  /// Sets L from an angular velocity given in world axes.
  void SetAngularVelocity(const Vector3& omega_world);
  /// World position of a point given in body coordinates: x + R p_B.
  Vector3 PointPosition(const Vector3& p_body) const { return position + orientation * p_body; }
  /// World velocity of the material point at world position p: v + ω × (p − x).
  Vector3 PointVelocity(const Vector3& p_world) const { return velocity + AngularVelocity().cross(p_world - position); }
  /// ½ M v² + ½ ωᵀ I ω, J.
  double KineticEnergy() const;
  double RotationalEnergy() const;
  Vector3 LinearMomentum() const { return mass * velocity; }
  /// Angular momentum about a world point: L + (x − p) × M v.
  Vector3 AngularMomentumAbout(const Vector3& p) const {
    return angular_momentum + (position - p).cross(mass * velocity);
  }
};

/// A body and where its frame B sits in the frame M of the mesh (or solid) it was made from.
struct PlacedBody {
  RigidBody body;
  /// x_B = R_MBᵀ (x_M − com): mesh coordinates → body coordinates (massprops::BodyFrameTransform).
  massprops::RigidTransform mesh_to_body;
};

/// A body from mass properties, placed where the mesh is: its center of mass at the mesh's and its
/// orientation the principal axes (R_WB = R_MB: the mesh frame M is the world frame at the start).
/// Takes the principal axes already computed (massprops::SolidResult has them), so that they are
/// computed once.
/// @throws std::invalid_argument if the mass or a principal moment is not positive, or the moments
///         violate the triangle inequality.
PlacedBody BodyFromMassProperties(const massprops::MassProperties& mp, const massprops::PrincipalInertia& principal);
/// The same, computing the principal axes.
PlacedBody BodyFromMassProperties(const massprops::MassProperties& mp);

}  // namespace dynamics
