#pragma once
/// @file
/// The closed-form solids, as one list: each primitive has its closed-form mass properties, a
/// tessellation to look at, an implicit form to sample, and a text form. Shape syntax, scene
/// files and the simulator all build on this list. Every primitive is centred on its center of
/// mass with its axis of symmetry along z (as solids.h and implicit.h).

#include <string>
#include <string_view>
#include <variant>
#include <vector>

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

/// The syntaxes that name primitives and their sizes.
enum class SizeSyntax {
  kShapeSyntax,  ///< implicit::ParseShape: box(x=1, y=2, z=3), torus(R=1, r=0.25)
  kScene,        ///< rbsim scenes: {"type": "box", "size": [1, 2, 3]}, {"type": "torus", "major_radius": 1, ...}
  kRobot,        ///< URDF and SDFormat geometries: <box size>, <cylinder radius length>, <ellipsoid radii>
};

/// One size of a primitive as a syntax names it.
struct SizeKey {
  const char* key;   ///< "radius", "size", "r"
  int components;    ///< 1, or 3 for a vector
  const char* what;  ///< for messages: "edge lengths [x, y, z]"
};

/// The one place that maps primitives' names and sizes: the keys of primitive `name` in
/// `syntax`, in the order MakePrimitive takes their numbers, each meaning this library's size
/// (full edge lengths, heights and lengths; radii). Empty when the syntax has no such primitive or
/// the name is not a primitive's. (MJCF gives half sizes by position, and `fromto`: its reader
/// converts to these.)
const std::vector<SizeKey>& SizeKeys(std::string_view name, SizeSyntax syntax);

/// The primitive `name` (kPrimitiveNames) from its sizes in SizeKeys' order (a vector's three
/// components in a row). Sizes are not checked here (Validate, ClosedForm and ToImplicit do).
/// @throws std::invalid_argument for an unknown name or a wrong number of sizes.
Primitive MakePrimitive(std::string_view name, const std::vector<double>& sizes);

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
