#pragma once
/// @file
/// The closed-form solids, as one list: each primitive has its closed-form mass properties, a
/// tessellation to look at, an implicit form to sample, and a text form. Shape syntax, scene
/// files and the simulator all build on this list. Every primitive is centred on its center of
/// mass with its axis of symmetry along z (as solids.h and implicit.h).

#include <string>
#include <variant>

#include "massprops/implicit.h"
#include "massprops/mass_properties.h"
#include "massprops/mesh.h"

namespace massprops {
namespace primitive {

struct Box {
  Vector3 size = Vector3::Ones();
};  ///< edge lengths along x, y, z
struct Sphere {
  Scalar radius = 1;
};
struct Ellipsoid {
  Vector3 semi_axes = Vector3::Ones();
};
struct Cylinder {
  Scalar radius = 1, height = 1;
};  ///< |z| ≤ height/2
struct Cone {
  Scalar radius = 1, height = 1;
};  ///< base at z = −h/4, apex at 3h/4
struct Torus {
  Scalar major_radius = 1, minor_radius = 0.25;
};
struct Capsule {
  Scalar radius = 1, length = 1;
};  ///< cylinder part |z| ≤ length/2

}  // namespace primitive

using Primitive = std::variant<primitive::Box, primitive::Sphere, primitive::Ellipsoid, primitive::Cylinder,
                               primitive::Cone, primitive::Torus, primitive::Capsule>;

/// "box", "sphere", "ellipsoid", "cylinder", "cone", "torus", "capsule".
const char* PrimitiveName(const Primitive& p);
/// The names above, in the variant's order.
inline constexpr const char* kPrimitiveNames[] = {"box", "sphere", "ellipsoid", "cylinder", "cone", "torus", "capsule"};

/// Checks the sizes: finite and positive, and a torus's tube thinner than its ring.
/// @throws std::invalid_argument naming the primitive and the size.
void Validate(const Primitive& p);

/// Closed-form mass properties at a uniform density (kg/m^3). @throws as Validate.
MassProperties ClosedForm(const Primitive& p, Scalar density);
/// An inscribed tessellation, `resolution` segments per half turn (exact for the box).
TriangleMesh Tessellate(const Primitive& p, int resolution = 24);
/// The implicit solid (φ ≤ 0 inside), for Monte-Carlo sampling and CSG. @throws as Validate.
ImplicitPtr ToImplicit(const Primitive& p);
/// For people: "box 1 x 2 x 3 m", "cone r=0.1 h=0.3 m (apex at z=+3h/4)".
std::string Describe(const Primitive& p);

}  // namespace massprops
