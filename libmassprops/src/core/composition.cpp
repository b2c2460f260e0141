// The definitions of massprops/composition.h: composition and transformation of mass properties
// without re-integrating the meshes.

#include "massprops/composition.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace massprops {

MassProperties Combine(const std::vector<MassProperties>& parts) {
  if (parts.empty()) throw std::invalid_argument("Combine: no parts");
  MassProperties out;
  Vector3 moment = Vector3::Zero();
  for (const auto& p : parts) {
    out.mass += p.mass;
    out.volume += p.volume;
    out.surface_area += p.surface_area;
    moment += p.mass * p.center_of_mass;
  }
  if (out.mass == 0.0 || !std::isfinite(out.mass)) {
    throw std::invalid_argument("Combine: the total mass is zero, so there is no center of mass");
  }
  out.center_of_mass = moment / out.mass;
  for (const auto& p : parts) out.inertia_com += p.InertiaAbout(out.center_of_mass);
  out.inertia_com = 0.5 * (out.inertia_com + out.inertia_com.transpose()).eval();
  out.density = out.volume != 0.0 ? out.mass / out.volume : 0.0;
  return out;
}

MassProperties Combine(const MassProperties& a, const MassProperties& b) { return Combine({a, b}); }

MassProperties Subtract(const MassProperties& whole, const MassProperties& cavity) {
  MassProperties negative = cavity;
  negative.mass = -cavity.mass;
  negative.volume = -cavity.volume;
  negative.inertia_com = -cavity.inertia_com;
  MassProperties out = Combine({whole, negative});
  out.surface_area = whole.surface_area + cavity.surface_area;
  if (!(out.mass > 0.0)) {
    std::ostringstream msg;
    msg << "Subtract: the cavity (mass " << cavity.mass << ") is not smaller than the whole (mass " << whole.mass
        << ")";
    throw std::invalid_argument(msg.str());
  }
  return out;
}

MassProperties Transformed(const MassProperties& mp, const Matrix3& R, const Vector3& t) {
  if (!R.allFinite() || !t.allFinite() || (R.transpose() * R - Matrix3::Identity()).cwiseAbs().maxCoeff() > 1e-9 ||
      R.determinant() < 0.0) {
    throw std::invalid_argument("Transformed: R is not a rotation (orthonormal, det = +1)");
  }
  MassProperties out = mp;
  out.center_of_mass = R * mp.center_of_mass + t;
  out.inertia_com = R * mp.inertia_com * R.transpose();
  out.inertia_com = 0.5 * (out.inertia_com + out.inertia_com.transpose()).eval();
  return out;
}

MassProperties Scaled(const MassProperties& mp, const Vector3& s) {
  if (!s.allFinite() || (s.array() == 0.0).any()) {
    throw std::invalid_argument("Scaled: scale factors must be finite and non-zero");
  }
  const double det = std::fabs(s.prod());
  // Second moment about the center of mass, C = tr(I)/2·E − I, scales as |det| S C S.
  const Matrix3 C = 0.5 * mp.inertia_com.trace() * Matrix3::Identity() - mp.inertia_com;
  const Matrix3 Cs = det * s.asDiagonal() * C * s.asDiagonal();
  MassProperties out = mp;
  out.volume = mp.volume * det;
  out.mass = mp.mass * det;
  out.center_of_mass = s.cwiseProduct(mp.center_of_mass);
  out.inertia_com = Cs.trace() * Matrix3::Identity() - Cs;
  const bool uniform = std::fabs(s[0]) == std::fabs(s[1]) && std::fabs(s[1]) == std::fabs(s[2]);
  out.surface_area = uniform ? mp.surface_area * s[0] * s[0] : std::numeric_limits<double>::quiet_NaN();
  return out;
}

MassProperties Scaled(const MassProperties& mp, Scalar s) { return Scaled(mp, Vector3(s, s, s)); }

}  // namespace massprops
