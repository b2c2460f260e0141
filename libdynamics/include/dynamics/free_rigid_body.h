#pragma once
/// @file
/// The exact angular velocity of the torque-free rigid body, in Jacobi elliptic functions
/// (Landau & Lifshitz, Mechanics §37), as ground truth for the integrators.

#include "dynamics/rigid_body.h"

namespace dynamics {

/// ω(t) in the body frame for principal moments I1 < I2 < I3 (strictly) and ω(0) = omega0, away
/// from the separatrix (M² ≠ 2E·I2), and the attitude q(t) (body → world) from q(0) = q0.
///
/// The attitude: with Z along the constant L, body → world is C·Rz(φ)·Rx(θ)·Rz(ψ) where θ, ψ
/// follow from ω(t) (M sinθ sinψ = I1ω1, M sinθ cosψ = I2ω2, M cosθ = I3ω3) and the precession
/// angle has φ̇ = M (I1ω1² + I2ω2²)/(I1²ω1² + I2²ω2²) (Landau & Lifshitz 37.10). φ is integrated by
/// adaptive Gauss–Kronrod quadrature over one period once and over the remainder per query
/// (≈1e-13), which replaces the closed form in the elliptic integral of the third kind.
/// Not safe to share between threads (the per-period integral is cached on first use).
class ExactFreeRotation {
 public:
  /// @throws std::invalid_argument if the moments are not strictly increasing and positive, or the
  ///         motion is on (or within 1e-12 of) the separatrix.
  ExactFreeRotation(const Vector3& inertia, const Vector3& omega0, const Quaternion& q0 = Quaternion::Identity());
  Vector3 Omega(double t) const;
  Quaternion Orientation(double t) const;
  /// Period of ω, 4K(m)/λ.
  double Period() const;
  /// Time between sign changes of ω₂ (the Dzhanibekov flip interval), 2K(m)/λ.
  double FlipInterval() const { return 0.5 * Period(); }
  double parameter_m() const { return m_; }
  double lambda() const { return lambda_; }

 private:
  double Precession(double t) const;                      // φ(t)
  double PrecessionOver(double t) const;                  // ∫0^t φ̇ by quadrature
  Matrix3 Frame(double phi, const Vector3& omega) const;  // Rz(φ) Rx(θ) Rz(ψ)

  Vector3 inertia_ = Vector3::Ones();
  double M_ = 0;
  Matrix3 C_ = Matrix3::Identity();
  mutable double phi_period_ = 0;  // φ gained over one period of ω (computed on first need)
  mutable bool phi_period_known_ = false;
  double period_ = 0;
  Vector3 omega0_ = Vector3::Zero();
  Quaternion q0_ = Quaternion::Identity();
  bool around_axis3_ = true;  // M² > 2E·I2: the polhode circles the I3 axis
  double a1_ = 0, a2_ = 0, a3_ = 0, lambda_ = 0, m_ = 0, tau0_ = 0, sign_ = 1;
};

}  // namespace dynamics
