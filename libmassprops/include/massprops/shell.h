#pragma once
/// @file
/// Thin shells and walls: mass properties of a surface with an area density (sheet metal, a
/// membrane, an open scan meant as a skin), and of the hollow part of given wall thickness inside
/// a closed surface.

#include "massprops/mass_properties.h"
#include "massprops/mesh.h"

namespace massprops {

/// Surface integrals about a reference point p: A = ∫dA, first = ∫(x−p)dA, second =
/// ∫(x−p)(x−p)ᵀdA. Per triangle (a, b, c relative to p, area A): ∫x dA = A (a+b+c)/3 and
/// ∫x xᵀ dA = A/12 (a aᵀ + b bᵀ + c cᵀ + s sᵀ), s = a+b+c. Polygons are split into fans whose
/// areas are signed against the polygon's Newell normal, which is exact for any planar polygon,
/// convex or not.
struct SurfaceIntegrals {
  Vector3 reference = Vector3::Zero();
  Scalar area = 0.0;
  Vector3 first = Vector3::Zero();
  Matrix3 second = Matrix3::Zero();
};

/// Integrals of a surface (need not be closed, oriented or manifold: orientation plays no part).
/// Taken about the bounding-box centre unless options.reference is set; bitwise the same for any
/// thread count. @throws std::invalid_argument for an out-of-range index or a non-finite vertex.
SurfaceIntegrals IntegrateSurface(const PolygonMesh& mesh, const IntegrationOptions& options = {});

/// Mass properties of a thin shell of uniform area density σ (kg/m²): mass = σA, the center of
/// mass and inertia of the surface. `volume` is 0 (a surface has none) and `density` is σ.
/// `scale` converts the mesh's units to metres (area ∝ scale², inertia ∝ scale⁴).
/// @throws std::invalid_argument if σ or scale is not finite and positive, or the area is zero.
MassProperties ShellMassProperties(const SurfaceIntegrals& integrals, Scalar area_density, Scalar scale = 1.0);

/// The inward offset of a closed, outward-oriented surface by t (mesh units): every vertex moves
/// to the point that lies at distance t inside each plane of its incident faces (least squares
/// over the distinct planes; exact wherever at most three distinct planes meet at a vertex, as on
/// boxes and prisms, and O(h²) on tessellated curved surfaces). Faces keep their corners.
struct OffsetResult {
  PolygonMesh inner;                           ///< same faces, offset vertices, facing outward like the input
  std::int64_t flipped_faces = 0;              ///< faces whose normal turned over: t is more than fits there
  Vector3 first_flipped_at = Vector3::Zero();  ///< a corner of the first such face
  Scalar inner_volume = 0;                     ///< signed volume of the offset surface (mesh units³)
  Scalar thickness = 0;                        ///< the offset distance
};
OffsetResult OffsetInward(const PolygonMesh& mesh, Scalar thickness);

/// The solid between a closed surface and its inward offset, as one mesh: the outer faces as
/// they are and the inner faces reversed (integrates to outer − inner).
/// @throws std::invalid_argument if the thickness is not positive, or is more than the part
///         allows (faces turn over or the inner volume is not positive), saying which.
PolygonMesh WallSolid(const PolygonMesh& mesh, Scalar thickness);
/// The same from an offset already made (and checked further by the caller).
PolygonMesh WallSolid(const PolygonMesh& mesh, const OffsetResult& inner);

}  // namespace massprops
