#include "dynamics/free_rigid_body.h"

#include <cmath>
#include <stdexcept>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

namespace dynamics {

// Landau & Lifshitz §37, in the notation of REFERENCE_VALUES.md. Boost takes the modulus
// k = √m, not the parameter m.
ExactFreeRotation::ExactFreeRotation(const Vector3& I, const Vector3& w0) {
  if (!(I[0] > 0 && I[0] < I[1] && I[1] < I[2])) {
    throw std::invalid_argument("ExactFreeRotation: needs 0 < I1 < I2 < I3");
  }
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
    tau0_ = boost::math::ellint_1(std::sqrt(m_), phi0);
  } else {
    sign_ = w0[0] >= 0 ? 1.0 : -1.0;
    a1_ = std::sqrt((two_e * I3 - m2) / (I1 * (I3 - I1)));
    a2_ = std::sqrt((m2 - two_e * I1) / (I2 * (I2 - I1)));
    a3_ = std::sqrt((m2 - two_e * I1) / (I3 * (I3 - I1)));
    lambda_ = std::sqrt((I2 - I1) * (two_e * I3 - m2) / (I1 * I2 * I3));
    m_ = (I3 - I2) * (m2 - two_e * I1) / ((I2 - I1) * (two_e * I3 - m2));
    const double phi0 = std::atan2(a2_ > 0 ? sign_ * w0[1] / a2_ : 0.0, a3_ > 0 ? w0[2] / a3_ : 1.0);
    tau0_ = boost::math::ellint_1(std::sqrt(m_), phi0);
  }
}

Vector3 ExactFreeRotation::Omega(double t) const {
  double cn = 0, dn = 0;
  const double sn = boost::math::jacobi_elliptic(std::sqrt(m_), lambda_ * t + tau0_, &cn, &dn);
  if (around_axis3_) return Vector3(a1_ * cn, sign_ * a2_ * sn, sign_ * a3_ * dn);
  return Vector3(sign_ * a1_ * dn, sign_ * a2_ * sn, a3_ * cn);
}

double ExactFreeRotation::Period() const {
  return 4.0 * boost::math::ellint_1(std::sqrt(m_)) / lambda_;
}

}  // namespace dynamics
