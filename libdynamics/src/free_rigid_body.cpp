// The definitions of dynamics/free_rigid_body.h: the exact angular velocity of the torque-free
// rigid body, in Jacobi elliptic functions (Landau & Lifshitz, Mechanics §37), as ground truth for
// the integrators.

#include "dynamics/free_rigid_body.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

namespace dynamics {
namespace {
// Boost.Math evaluates double arguments in long double by default; plain double is accurate
// enough here and an order of magnitude faster.
using NoPromotion = boost::math::policies::policy<boost::math::policies::promote_double<false>>;
}  // namespace

// Landau & Lifshitz §37, in the notation of REFERENCE_VALUES.md. Boost takes the modulus
// k = √m, not the parameter m.
ExactFreeRotation::ExactFreeRotation(const Vector3& I, const Vector3& w0, const Quaternion& q0) {
  if (!(I[0] > 0 && I[0] < I[1] && I[1] < I[2])) {
    throw std::invalid_argument("ExactFreeRotation: needs 0 < I1 < I2 < I3");
  }
  omega0_ = w0;
  q0_ = q0;
  const double I1 = I[0], I2 = I[1], I3 = I[2];
  const double two_e = I1 * w0[0] * w0[0] + I2 * w0[1] * w0[1] + I3 * w0[2] * w0[2];
  const double m2 = I1 * I1 * w0[0] * w0[0] + I2 * I2 * w0[1] * w0[1] + I3 * I3 * w0[2] * w0[2];
  const double sep = m2 - two_e * I2;
  if (std::fabs(sep) <= 1e-12 * m2) {
    throw std::invalid_argument("ExactFreeRotation: the motion is on the separatrix (M² = 2E·I2)");
  }
  around_axis3_ = sep > 0;
  if (around_axis3_) {
    sign_ = w0[2] >= 0 ? 1.0 : -1.0;
    a1_ = std::sqrt((two_e * I3 - m2) / (I1 * (I3 - I1)));
    a2_ = std::sqrt((two_e * I3 - m2) / (I2 * (I3 - I2)));
    a3_ = std::sqrt((m2 - two_e * I1) / (I3 * (I3 - I1)));
    lambda_ = std::sqrt((I3 - I2) * (m2 - two_e * I1) / (I1 * I2 * I3));
    m_ = (I2 - I1) * (two_e * I3 - m2) / ((I3 - I2) * (m2 - two_e * I1));
    const double phi0 = std::atan2(a2_ > 0 ? sign_ * w0[1] / a2_ : 0.0, a1_ > 0 ? w0[0] / a1_ : 1.0);
    tau0_ = boost::math::ellint_1(std::sqrt(m_), phi0, NoPromotion());
  } else {
    sign_ = w0[0] >= 0 ? 1.0 : -1.0;
    a1_ = std::sqrt((two_e * I3 - m2) / (I1 * (I3 - I1)));
    a2_ = std::sqrt((m2 - two_e * I1) / (I2 * (I2 - I1)));
    a3_ = std::sqrt((m2 - two_e * I1) / (I3 * (I3 - I1)));
    lambda_ = std::sqrt((I2 - I1) * (two_e * I3 - m2) / (I1 * I2 * I3));
    m_ = (I3 - I2) * (m2 - two_e * I1) / ((I2 - I1) * (two_e * I3 - m2));
    const double phi0 = std::atan2(a2_ > 0 ? sign_ * w0[1] / a2_ : 0.0, a3_ > 0 ? w0[2] / a3_ : 1.0);
    tau0_ = boost::math::ellint_1(std::sqrt(m_), phi0, NoPromotion());
  }
  period_ = 4.0 * boost::math::ellint_1(std::sqrt(m_), NoPromotion()) / lambda_;
  inertia_ = I;
  M_ = std::sqrt(m2);
  const double I1w1 = I1 * w0[0], I2w2 = I2 * w0[1];
  if (I1w1 * I1w1 + I2w2 * I2w2 <= 1e-24 * m2) {
    throw std::invalid_argument("ExactFreeRotation: L along the third axis (the attitude's Euler angles are singular)");
  }
  C_ = q0.toRotationMatrix() * Frame(0.0, w0).transpose();
}

double ExactFreeRotation::PrecessionOver(double t) const {
  auto rate = [this](double s) {
    const Vector3 w = Omega(s);
    const double a = inertia_[0] * w[0] * w[0] + inertia_[1] * w[1] * w[1];
    const double b = inertia_[0] * inertia_[0] * w[0] * w[0] + inertia_[1] * inertia_[1] * w[1] * w[1];
    return M_ * a / b;
  };
  // φ̇ is smooth and positive; 31-point Gauss–Kronrod on pieces of at most a quarter period
  // meets 1e-12 without deep subdivision (near the separatrix φ̇ has sharp features at the flips).
  if (t <= 0) return 0.0;
  if (t <= period_ / 64) {
    // A step of a splitting: φ̇ is analytic and nearly constant over so short a span; a fixed
    // 20-point Gauss rule is exact to rounding, and adaptivity would only chase rounding noise.
    return boost::math::quadrature::gauss<double, 20>::integrate(rate, 0.0, t);
  }
  const double piece = 0.25 * period_;
  double phi = 0;
  for (double a = 0; a < t; a += piece) {
    phi += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(rate, a, std::min(t, a + piece), 6, 1e-12);
  }
  return phi;
}

double ExactFreeRotation::Precession(double t) const {
  // φ̇ has the period of ω: whole periods from the stored integral, the rest by quadrature.
  const double T = Period();
  const double periods = std::floor(t / T);
  if (periods == 0.0) return PrecessionOver(t);
  if (!phi_period_known_) {  // computed on first need: a step of a splitting never needs it
    phi_period_ = PrecessionOver(T);
    phi_period_known_ = true;
  }
  return periods * phi_period_ + PrecessionOver(t - periods * T);
}

Matrix3 ExactFreeRotation::Frame(double phi, const Vector3& w) const {
  const Vector3 pi = inertia_.cwiseProduct(w);
  const double theta = std::acos(std::clamp(pi[2] / M_, -1.0, 1.0));
  const double psi = std::atan2(pi[0], pi[1]);
  return (Eigen::AngleAxisd(phi, Vector3::UnitZ()) * Eigen::AngleAxisd(theta, Vector3::UnitX()) *
          Eigen::AngleAxisd(psi, Vector3::UnitZ()))
      .toRotationMatrix();
}

Quaternion ExactFreeRotation::Orientation(double t) const {
  if (t == 0.0) return q0_;
  return Quaternion(C_ * Frame(Precession(t), Omega(t))).normalized();
}

Vector3 ExactFreeRotation::Omega(double t) const {
  // The initial condition is known exactly; near the separatrix, τ0 = K(m) is where the elliptic
  // functions lose the most digits.
  if (t == 0.0 && period_ > 0) return omega0_;
  double cn = 0, dn = 0;
  const double sn = boost::math::jacobi_elliptic(std::sqrt(m_), lambda_ * t + tau0_, &cn, &dn, NoPromotion());
  if (around_axis3_) return Vector3(a1_ * cn, sign_ * a2_ * sn, sign_ * a3_ * dn);
  return Vector3(sign_ * a1_ * dn, sign_ * a2_ * sn, a3_ * cn);
}

double ExactFreeRotation::Period() const { return period_; }

}  // namespace dynamics
