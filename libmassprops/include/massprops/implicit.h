#pragma once
/// @file
/// Solids given implicitly: φ(x) ≤ 0 inside, with a bounding box. Built-in primitives (centred on
/// their center of mass, axis z, as in solids.h, so the closed forms there apply), CSG, rigid
/// motions and scaling, a signed-distance grid from a file, a triangle mesh through its
/// generalized winding number, and a small text syntax for all of it. The Monte-Carlo estimators
/// (monte_carlo.h) integrate these.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "massprops/mesh.h"
#include "massprops/types.h"

namespace massprops {

using AlignedBox3 = Eigen::AlignedBox<Scalar, 3>;

class ImplicitSolid {
 public:
  virtual ~ImplicitSolid() = default;
  /// φ(x): ≤ 0 inside, > 0 outside. Only the sign is integrated; primitives return signed
  /// distances or a function with the same sign.
  virtual Scalar Value(const Vector3& x) const = 0;
  bool Inside(const Vector3& x) const { return Value(x) <= 0; }
  /// A box that contains the solid (the sampling domain).
  virtual AlignedBox3 Bounds() const = 0;
  /// Text form in the shape syntax (for reports).
  virtual std::string Describe() const = 0;
};
using ImplicitPtr = std::shared_ptr<const ImplicitSolid>;

namespace implicit {

/// Primitives; every size must be finite and positive (std::invalid_argument otherwise).
ImplicitPtr Sphere(Scalar r);
ImplicitPtr Ellipsoid(const Vector3& semi_axes);
ImplicitPtr Box(const Vector3& size);
ImplicitPtr Cylinder(Scalar r, Scalar h);       ///< axis z, |z| ≤ h/2
ImplicitPtr Cone(Scalar r, Scalar h);           ///< axis z, base at z = −h/4, apex at z = 3h/4
ImplicitPtr Torus(Scalar major, Scalar minor);  ///< axis z; minor < major
ImplicitPtr Capsule(Scalar r, Scalar h);        ///< axis z, cylinder part |z| ≤ h/2

/// CSG (φ = min, max, max(a, −b)).
ImplicitPtr Union(std::vector<ImplicitPtr> parts);
ImplicitPtr Intersection(std::vector<ImplicitPtr> parts);
ImplicitPtr Difference(ImplicitPtr a, ImplicitPtr b);
/// x ↦ R x + t applied to the solid (R a rotation).
ImplicitPtr Transformed(ImplicitPtr a, const Matrix3& R, const Vector3& t);
/// Uniform scaling about the origin by s > 0.
ImplicitPtr Scaled(ImplicitPtr a, Scalar s);

/// A signed-distance grid: NX·NY·NZ values, x fastest, then y, then z (φ ≤ 0 inside), sample
/// (0, 0, 0) at `origin`, trilinearly interpolated; outside the grid the solid is absent. Files in
/// the sdfgrid format (README, "Signed-distance grids") are read by massprops::io
/// (ReadSdfGridFile in io.h). `description` is what Describe() returns.
/// @throws std::invalid_argument for fewer than 2 samples along an axis, a bad spacing or origin,
///         a value count that does not match, or a non-finite value.
ImplicitPtr SdfGrid(const Eigen::Vector3i& size, const Vector3& origin, const Vector3& spacing,
                    std::vector<Scalar> values, std::string description = "grid(in memory)");

/// The solid a triangle mesh bounds, through its generalized winding number w(x) (Jacobson,
/// Kavan & Sorkine-Hornung 2013): inside where w ≥ 1/2. Exact solid angles for nearby
/// triangles (Van Oosterom & Strackee 1983), a dipole expansion for far clusters of a bounding
/// volume hierarchy (Barill et al., "Fast Winding Numbers for Soups and Clouds", 2018) with
/// accuracy parameter beta (a cluster of radius r is expanded beyond distance beta·r). A mesh
/// with holes gets the sensible answer: the holes are "filled" by the winding number.
/// @throws std::invalid_argument for an empty mesh, a bad index or a non-finite vertex.
ImplicitPtr WindingNumberSolid(const TriangleMesh& mesh, Scalar beta = 2.0);
/// The winding number itself (for tests and diagnostics).
Scalar WindingNumber(const ImplicitSolid& winding_solid, const Vector3& x);

/// A triangle mesh of the surface φ = 0, for display: marching tetrahedra (six per cube of a
/// regular grid with `resolution` cells along the longest side of the bounds), faces oriented
/// outward, corners not welded. Not for integration: its error is O(cell size).
TriangleMesh Polygonize(const ImplicitSolid& solid, int resolution = 48);

/// Parses the shape syntax (README "Shape syntax"):
///   sphere(r=1)  ellipsoid(a=1, b=2, c=3)  box(x=1, y=2, z=3)  cylinder(r=1, h=2)  cone(r=1, h=3)
///   torus(R=1, r=0.25)  capsule(r=0.5, h=2)  grid(file="part.sdf")
///   union(A, B, ...)  intersection(A, B, ...)  difference(A, B)
///   move(A, x=0, y=0, z=1)  rotate(A, axis=[0,0,1], deg=30)  scale(A, s=2)
/// `grid(file=...)` is read by `read_grid` (massprops::io's ReadSdfGridFile); without one it is
/// refused, so the core never opens a file.
/// @throws std::invalid_argument with the position and the fault.
using GridFileReader = std::function<ImplicitPtr(const std::string& path)>;
ImplicitPtr ParseShape(const std::string& text, const GridFileReader& read_grid = nullptr);

}  // namespace implicit
}  // namespace massprops
