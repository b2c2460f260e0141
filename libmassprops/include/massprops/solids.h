#pragma once
/// @file
/// Tessellations of simple solids and their closed-form mass properties, shared by tests,
/// benchmarks and apps. Every solid is centred so that its center of mass is at the origin and
/// its axis of symmetry (if any) is z. All meshes are closed and face outward.
///
/// The polyhedra (box, tetrahedron, octahedron, prism) are exact: their mesh *is* the solid.
/// The smooth solids are inscribed tessellations whose vertices lie on the exact surface; their
/// mass properties converge to the closed form as (edge length)², i.e. as 1/n².

#include "massprops/mass_properties.h"
#include "massprops/mesh.h"

namespace massprops::solids {

// ---- exact polyhedra ----
/// Box with edge lengths (a, b, c) along x, y, z; 6 quadrilateral faces.
PolygonMesh Box(const Vector3& size);
/// Regular tetrahedron with the given edge length.
TriangleMesh RegularTetrahedron(Scalar edge);
/// Tetrahedron with the given corners (any order: faces are oriented outward).
TriangleMesh Tetrahedron(const Vector3& p0, const Vector3& p1, const Vector3& p2, const Vector3& p3);
/// Regular octahedron with vertices at ±a on each axis.
TriangleMesh Octahedron(Scalar a);
/// Right prism over a regular n-gon of circumradius r, height h along z; two n-gon caps and n
/// quadrilateral sides (a first vertex on +x).
PolygonMesh RegularPrism(int n, Scalar r, Scalar h);

// ---- tessellated smooth solids; n = resolution (segments per half turn) ----
/// Sphere of radius r: n latitude bands, 2n longitude segments.
TriangleMesh Sphere(Scalar r, int n);
/// Ellipsoid with semi-axes (a, b, c): the sphere mesh scaled.
TriangleMesh Ellipsoid(const Vector3& semi_axes, int n);
/// Cylinder of radius r and height h along z, 2n sides.
TriangleMesh Cylinder(Scalar r, Scalar h, int n);
/// Cone of base radius r and height h along z (apex up), 2n sides; base at z = −h/4.
TriangleMesh Cone(Scalar r, Scalar h, int n);
/// Torus about z with centre-line radius R and tube radius a; 2n × n quads split in triangles.
TriangleMesh Torus(Scalar R, Scalar a, int n);
/// Capsule: cylinder of radius r and length h along z with hemispherical caps.
TriangleMesh Capsule(Scalar r, Scalar h, int n);
/// Thick hollow sphere: outer radius R facing out, inner radius r facing in (one mesh, 2 shells).
TriangleMesh HollowSphere(Scalar R, Scalar r, int n);

// ---- closed forms (center of mass at the origin unless noted) ----
MassProperties BoxProperties(const Vector3& size, Scalar density);
MassProperties RegularTetrahedronProperties(Scalar edge, Scalar density);
MassProperties OctahedronProperties(Scalar a, Scalar density);
MassProperties RegularPrismProperties(int n, Scalar r, Scalar h, Scalar density);
MassProperties SphereProperties(Scalar r, Scalar density);
MassProperties EllipsoidProperties(const Vector3& semi_axes, Scalar density);
MassProperties CylinderProperties(Scalar r, Scalar h, Scalar density);
MassProperties ConeProperties(Scalar r, Scalar h, Scalar density);
MassProperties TorusProperties(Scalar R, Scalar a, Scalar density);
MassProperties CapsuleProperties(Scalar r, Scalar h, Scalar density);
MassProperties HollowSphereProperties(Scalar R, Scalar r, Scalar density);

}  // namespace massprops::solids
