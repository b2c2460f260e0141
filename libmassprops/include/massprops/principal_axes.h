#pragma once
/// @file
/// Principal moments and axes of an inertia tensor, the body frame of a mesh, reference frames a
/// report reads the tensor in, and the physical-validity check of an inertia tensor.

#include <optional>
#include <string>

#include "massprops/mass_properties.h"
#include "massprops/types.h"

namespace massprops {

/// I = axes · diag(moments) · axesᵀ with moments ascending (I1 <= I2 <= I3).
///
/// Sign convention (deterministic, documented so that exports are reproducible):
/// - `axes` is a proper rotation (det = +1); its columns are the principal axes in frame M.
/// - Axis 1 and axis 2 each have their largest-magnitude component positive (the first of
///   equal-magnitude components wins); axis 3 = axis 1 × axis 2.
/// - Repeated moments (equal to within `degenerate_tolerance` relative to I3) have no unique
///   axes. Three equal moments (sphere, cube): the axes of M. Two equal moments (a body of
///   revolution): the distinct axis follows the sign rule above, and the first axis of the
///   repeated pair is the coordinate axis most perpendicular to it (lowest index on ties),
///   projected into the plane of the pair.
struct PrincipalInertia {
  Vector3 moments = Vector3::Zero();   ///< I1 <= I2 <= I3, kg·m^2
  Matrix3 axes = Matrix3::Identity();  ///< columns = principal axes in frame M (R_MB)
};

/// Whether principal moments i and i + 1 (i = 0 or 1, ascending) are repeated: equal to within
/// `degenerate_tolerance` of the largest in magnitude, so that their axes are not unique.
bool RepeatedMoments(const Vector3& moments, int i, double degenerate_tolerance = 1e-10);

/// Eigen-decomposition of a symmetric inertia tensor, with the conventions above.
/// @throws std::invalid_argument if the tensor is not finite or not symmetric (to 1e-12 relative).
PrincipalInertia ComputePrincipalInertia(const Matrix3& inertia, double degenerate_tolerance = 1e-10);

/// A rigid motion x ↦ rotation · x + translation.
struct RigidTransform {
  Matrix3 rotation = Matrix3::Identity();
  Vector3 translation = Vector3::Zero();

  Vector3 Apply(const Vector3& x) const { return rotation * x + translation; }
  RigidTransform Inverse() const { return {rotation.transpose(), -(rotation.transpose() * translation)}; }
};

/// The body frame B of a solid: origin at the center of mass, axes along the principal axes
/// (inertia diagonal, ascending). Returns the transform that carries mesh coordinates into body
/// coordinates, x_B = R_MBᵀ (x_M − com); its inverse is the seed notes' x = R x0 + x_c.
RigidTransform BodyFrameTransform(const MassProperties& mp, const PrincipalInertia& principal);

/// A frame a report reads the inertia tensor in: about `point` (metres, in the input's axes; none:
/// the center of mass), along `axes` (a rotation; its columns are the frame's axes in the input's
/// axes).
struct ReferenceFrame {
  std::optional<Vector3> point;
  Matrix3 axes = Matrix3::Identity();
};
/// The inertia tensor about the frame's point (the parallel-axis theorem) in its axes: Rᵀ I_p R.
Matrix3 InertiaInFrame(const MassProperties& mp, const ReferenceFrame& frame);
/// `m` if it is a rotation: orthonormal to 1e-9 and right-handed (det +1).
/// @throws std::invalid_argument saying which it is not.
Matrix3 RequireRotation(const Matrix3& m);
/// The rotation whose columns are a frame's axes after intrinsic rotations by `yaw` about z, then
/// `pitch` about the new y, then `roll` about the newest x (radians): R = Rz(yaw) Ry(pitch) Rx(roll).
Matrix3 RotationFromEulerZYX(double yaw, double pitch, double roll);

/// Result of the physical-validity check.
struct ValidityReport {
  bool valid = true;
  std::string reason;  ///< empty when valid; otherwise what is wrong, in words
};

/// Checks that principal moments can belong to a real body: finite, positive, and satisfying the
/// triangle inequality I1 + I2 >= I3 (to `relative_tolerance` × I3, for rounding).
ValidityReport CheckPhysicallyValid(const Vector3& principal_moments, double relative_tolerance = 1e-12);

}  // namespace massprops
