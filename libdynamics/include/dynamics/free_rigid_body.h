#pragma once
/// @file
/// The exact angular velocity of the torque-free rigid body, in Jacobi elliptic functions
/// (Landau & Lifshitz, Mechanics §37), as ground truth for the integrators.

#include "dynamics/rigid_body.h"

namespace dynamics {

/// ω(t) in the body frame for principal moments I1 < I2 < I3 (strictly) and ω(0) = omega0, away
/// from the separatrix (M² ≠ 2E·I2).
class ExactFreeRotation {
 public:
  /// @throws std::invalid_argument if the moments are not strictly increasing and positive, or the
  ///         motion is on (or within 1e-12 of) the separatrix.
  ExactFreeRotation(const Vector3& inertia, const Vector3& omega0);
  Vector3 Omega(double t) const;
  /// Period of ω, 4K(m)/λ.
  double Period() const;
  /// Time between sign changes of ω₂ (the Dzhanibekov flip interval), 2K(m)/λ.
  double FlipInterval() const { return 0.5 * Period(); }
  double parameter_m() const { return m_; }
  double lambda() const { return lambda_; }

 private:
  bool around_axis3_ = true;  // M² > 2E·I2: the polhode circles the I3 axis
  double a1_ = 0, a2_ = 0, a3_ = 0, lambda_ = 0, m_ = 0, tau0_ = 0, sign_ = 1;
};

}  // namespace dynamics
