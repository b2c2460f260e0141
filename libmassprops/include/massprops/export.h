#pragma once
/// @file
/// Inertial elements for robot descriptions, ready to paste: URDF, SDFormat and MJCF.
///
/// All three take the inertia about the center of mass. URDF and SDF place the inertial frame at
/// the center of mass with the axes of the link (here: the mesh file's axes) and take the tensor
/// entries as they are: ixy = I_xy = −∫ρ x y dV (the negated product of inertia), likewise ixz, iyz.
/// MJCF gets the principal form: `diaginertia` = (I1, I2, I3) and `quat` = the rotation from the
/// mesh axes to the principal axes (w x y z), which MuJoCo uses as given.

#include <string>

#include "massprops/mass_properties.h"
#include "massprops/principal_axes.h"
#include "massprops/text.h"  // ExactDecimal

namespace massprops {

/// `<inertial>` of a URDF link (SI units).
std::string UrdfInertial(const MassProperties& mp, const std::string& indent = "");
/// `<inertial>` of an SDFormat link (SI units).
std::string SdfInertial(const MassProperties& mp, const std::string& indent = "");
/// `<inertial>` of an MJCF body (SI units): pos, quat, mass, diaginertia.
std::string MjcfInertial(const MassProperties& mp, const PrincipalInertia& principal, const std::string& indent = "");

}  // namespace massprops
