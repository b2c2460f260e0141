// The definitions of massprops/principal_axes.h: principal moments and axes of an inertia tensor,
// the body frame of a mesh, reference frames a report reads the tensor in, and the physical-
// validity check of an inertia tensor.

#include "massprops/principal_axes.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace massprops {
namespace {

// Flips v so that its largest-magnitude component (first on ties) is positive.
Vector3 CanonicalSign(const Vector3& v) {
  int k = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::fabs(v[i]) > std::fabs(v[k])) k = i;
  }
  return v[k] < 0 ? Vector3(-v) : v;
}

// The coordinate axis most perpendicular to u (lowest index on ties), projected to ⊥u.
Vector3 PerpendicularAxis(const Vector3& u) {
  int k = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::fabs(u[i]) < std::fabs(u[k])) k = i;
  }
  const Vector3 e = Vector3::Unit(k);
  return (e - e.dot(u) * u).normalized();
}

}  // namespace

bool RepeatedMoments(const Vector3& moments, int i, double degenerate_tolerance) {
  const double tol = degenerate_tolerance * std::max(std::fabs(moments[2]), std::fabs(moments[0]));
  return moments[i + 1] - moments[i] <= tol;
}

PrincipalInertia ComputePrincipalInertia(const Matrix3& inertia, double degenerate_tolerance) {
  if (!inertia.allFinite()) {
    throw std::invalid_argument("ComputePrincipalInertia: the inertia tensor is not finite");
  }
  const double scale = inertia.cwiseAbs().maxCoeff();
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale) {
    throw std::invalid_argument("ComputePrincipalInertia: the inertia tensor is not symmetric");
  }
  Eigen::SelfAdjointEigenSolver<Matrix3> solver(0.5 * (inertia + inertia.transpose()));
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error("ComputePrincipalInertia: eigen-decomposition did not converge");
  }
  PrincipalInertia out;
  out.moments = solver.eigenvalues();  // ascending
  const Matrix3 Q = solver.eigenvectors();
  const bool same01 = RepeatedMoments(out.moments, 0, degenerate_tolerance);
  const bool same12 = RepeatedMoments(out.moments, 1, degenerate_tolerance);

  Vector3 a1, a2;
  if (same01 && same12) {
    out.axes.setIdentity();
    return out;
  } else if (same01) {  // axis 3 is distinct; 1 and 2 span its perpendicular plane
    const Vector3 u = CanonicalSign(Q.col(2));
    a1 = PerpendicularAxis(u);
    a2 = u.cross(a1);   // then a1 × a2 = u
  } else if (same12) {  // axis 1 is distinct
    a1 = CanonicalSign(Q.col(0));
    a2 = PerpendicularAxis(a1);
  } else {
    a1 = CanonicalSign(Q.col(0));
    a2 = CanonicalSign(Q.col(1));
  }
  out.axes.col(0) = a1;
  out.axes.col(1) = a2;
  out.axes.col(2) = a1.cross(a2);
  return out;
}

RigidTransform BodyFrameTransform(const MassProperties& mp, const PrincipalInertia& principal) {
  RigidTransform M_from_B{principal.axes, mp.center_of_mass};  // x_M = R_MB x_B + com
  return M_from_B.Inverse();
}

Matrix3 InertiaInFrame(const MassProperties& mp, const ReferenceFrame& frame) {
  const Matrix3 about = frame.point ? mp.InertiaAbout(*frame.point) : mp.inertia_com;
  return frame.axes.transpose() * about * frame.axes;
}

Matrix3 RequireRotation(const Matrix3& m) {
  if (!m.allFinite()) throw std::invalid_argument("the axes are not finite");
  const double off = (m.transpose() * m - Matrix3::Identity()).cwiseAbs().maxCoeff();
  if (off > 1e-9) {
    std::ostringstream msg;
    msg << "the axes are not orthonormal (|RᵀR − E| = " << off << "; give unit, perpendicular columns)";
    throw std::invalid_argument(msg.str());
  }
  if (m.determinant() < 0) throw std::invalid_argument("the axes are left-handed (determinant −1): give a rotation");
  return m;
}

Matrix3 RotationFromEulerZYX(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw, Vector3::UnitZ()) * Eigen::AngleAxisd(pitch, Vector3::UnitY()) *
          Eigen::AngleAxisd(roll, Vector3::UnitX()))
      .toRotationMatrix();
}

ValidityReport CheckPhysicallyValid(const Vector3& m, double relative_tolerance) {
  ValidityReport r;
  std::ostringstream msg;
  msg.precision(17);
  if (!m.allFinite()) {
    msg << "principal moments are not finite";
  } else if (m.minCoeff() <= 0.0) {
    msg << "principal moment " << m.minCoeff() << " is not positive"
        << (m.maxCoeff() < 0.0 ? " (all are negative: the surface faces inward)" : "");
  } else {
    Vector3 s = m;
    std::sort(s.data(), s.data() + 3);
    if (s[0] + s[1] < s[2] * (1.0 - relative_tolerance)) {
      msg << "principal moments violate the triangle inequality: " << s[0] << " + " << s[1] << " < " << s[2];
    }
  }
  r.reason = msg.str();
  r.valid = r.reason.empty();
  return r;
}

}  // namespace massprops
