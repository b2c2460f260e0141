#pragma once
/// @file
/// Composition and transformation of mass properties without re-integrating the meshes.

#include <vector>

#include "massprops/mass_properties.h"
#include "massprops/types.h"

namespace massprops {

/// The assembly of parts that occupy disjoint regions (each may have its own density):
/// masses and volumes add, the center of mass is the mass-weighted mean, inertias are shifted to
/// it and added. The density of the result is mass / volume; the surface areas add.
/// Signed parts are welcome: a part with negative mass removes material (see Subtract).
/// @throws std::invalid_argument if the list is empty or the total mass is zero.
MassProperties Combine(const std::vector<MassProperties>& parts);
MassProperties Combine(const MassProperties& a, const MassProperties& b);

/// `whole` with the material of `cavity` removed (cavity must lie inside whole and usually has
/// the same density). The cavity's surface is counted in the surface area.
/// @throws std::invalid_argument if the remaining mass is not positive.
MassProperties Subtract(const MassProperties& whole, const MassProperties& cavity);

/// The same solid moved rigidly: x ↦ R x + t (R must be a rotation; a reflection is refused,
/// use Scaled with a negative factor for mirror images).
/// @throws std::invalid_argument if R is not orthonormal with det +1 (to 1e-9).
MassProperties Transformed(const MassProperties& mp, const Matrix3& R, const Vector3& t);

/// The solid scaled about the origin of frame M by per-axis factors s (x ↦ diag(s) x) at the same
/// density. Negative factors mirror the solid; volume and mass stay positive (|det| scaling).
/// A uniform factor scales the surface area by s²; a non-uniform one leaves it unknown (NaN).
/// @throws std::invalid_argument if a factor is zero or not finite.
MassProperties Scaled(const MassProperties& mp, const Vector3& s);
MassProperties Scaled(const MassProperties& mp, Scalar s);

}  // namespace massprops
