#pragma once
/// @file
/// Mass properties of the solid bounded by a closed polyhedral surface.
///
/// Conventions (the same everywhere in this project):
/// - SI units when the input is in metres and the density in kg/m^3: volume m^3, mass kg,
///   positions m, inertia kg·m^2.
/// - The inertia tensor is I = ∫ρ (|r|² E − r rᵀ) dV, r measured from the point named.
///   Its diagonal holds the moments of inertia (Ixx = ∫ρ(y²+z²)dV, ...), and its
///   off-diagonal entries are the NEGATED products of inertia: I_xy = −∫ρ x y dV.
///   (URDF's ixy/ixz/iyz and MuJoCo's fullinertia take these tensor entries as they are.)
/// - Tensors are expressed in the axes of the mesh file (frame M) unless a name says otherwise.
/// - Volume is signed: a closed mesh whose faces all point inward gives a negative volume, and
///   then a negative mass and inertia. This is reported, never silently flipped; composition
///   relies on it (an inward-facing inner shell subtracts a cavity).

#include <optional>

#include <Eigen/Core>

#include "massprops/mesh.h"
#include "massprops/types.h"

namespace massprops {

/// Raw volume integrals of a solid about a reference point p (all in mesh frame M):
/// V = ∫dV, first = ∫(x−p)dV, second = ∫(x−p)(x−p)ᵀdV. Additive over faces and over solids
/// that share the reference point.
struct VolumeIntegrals {
  Vector3 reference = Vector3::Zero();  ///< p, m
  Scalar volume = 0.0;                  ///< signed, m^3
  Vector3 first = Vector3::Zero();      ///< m^4
  Matrix3 second = Matrix3::Zero();     ///< symmetric, m^5
  Scalar surface_area = 0.0;            ///< m^2

  /// The same integrals about another reference point (exact shift of the polynomial moments).
  VolumeIntegrals About(const Vector3& new_reference) const;
};

/// Mass properties of a rigid solid of uniform density, expressed in mesh frame M.
struct MassProperties {
  Scalar volume = 0.0;                       ///< signed volume, m^3 (< 0: faces point inward)
  Scalar mass = 0.0;                         ///< kg (density × signed volume)
  Scalar density = 0.0;                      ///< kg/m^3 (mass / volume for a combined body)
  Vector3 center_of_mass = Vector3::Zero();  ///< m, in frame M
  Matrix3 inertia_com = Matrix3::Zero();     ///< kg·m^2, about the center of mass, axes of M
  Scalar surface_area = 0.0;                 ///< m^2 (NaN where it cannot be known)

  /// Inertia tensor about another point (parallel-axis theorem), axes of M, kg·m^2.
  Matrix3 InertiaAbout(const Vector3& point) const;
};

/// Options of the integrators.
struct IntegrationOptions {
  /// Worker threads; 0 uses every hardware thread. The result is bitwise the same for any value.
  int num_threads = 0;
  /// Point the integrals are taken about. Empty: the centre of the vertices' bounding box, which
  /// keeps full precision for parts far from the file origin.
  std::optional<Vector3> reference;
};

/// Volume integrals of the solid bounded by a closed, consistently oriented triangle mesh, by the
/// divergence theorem: each triangle (a,b,c) spans a signed tetrahedron with the reference point,
/// d = a·(b×c), ∫dV = d/6, ∫x dV = d(a+b+c)/24, ∫x xᵀ dV = d(Σ vvᵀ + s sᵀ)/120, s = a+b+c
/// (D. Eberly, "Polyhedral Mass Properties (Revisited)", 2002; Tonon, J. Math. Stat. 2004).
/// Sums are taken per fixed block of faces and the blocks added pairwise, so the bits do not
/// depend on the thread count.
/// @throws std::invalid_argument if an index is out of range or a vertex is not finite.
VolumeIntegrals IntegrateTriangles(const Eigen::Ref<const VertexMatrix>& V, const Eigen::Ref<const FaceMatrix>& F,
                                   const IntegrationOptions& options = {});

/// Volume integrals of the solid bounded by a closed mesh of planar polygons, integrated face by
/// face without triangulation by Mirtich's projection → face → volume reduction
/// (B. Mirtich, "Fast and Accurate Computation of Polyhedral Mass Properties", JGT 1(2), 1996).
/// The face plane comes from Newell's normal; a non-planar face is integrated over the plane
/// through its centroid with that normal (an approximation: such faces have no unique solid).
/// @throws std::invalid_argument if an index is out of range, a face has fewer than 3 corners,
///         or a vertex is not finite.
VolumeIntegrals IntegratePolygons(const PolygonMesh& mesh, const IntegrationOptions& options = {});

/// Mass properties from volume integrals and a uniform density (kg/m^3).
/// @throws std::invalid_argument if the density is not finite and positive, or the volume is zero
///         or not finite (the center of mass is then undefined).
MassProperties FromIntegrals(const VolumeIntegrals& integrals, Scalar density);

/// Mass properties of the solid bounded by a closed triangle mesh (triangle path, the default).
/// Does not check that the mesh is closed: an open mesh gives a number that depends on the
/// reference point; see the mesh checks for that.
/// @throws std::invalid_argument as IntegrateTriangles and FromIntegrals.
MassProperties ComputeMassProperties(const Eigen::Ref<const VertexMatrix>& V, const Eigen::Ref<const FaceMatrix>& F,
                                     Scalar density, const IntegrationOptions& options = {});
MassProperties ComputeMassProperties(const TriangleMesh& mesh, Scalar density, const IntegrationOptions& options = {});

/// Mass properties of the solid bounded by a closed polygon mesh (Mirtich's path).
/// @throws std::invalid_argument as IntegratePolygons and FromIntegrals.
MassProperties ComputeMassProperties(const PolygonMesh& mesh, Scalar density, const IntegrationOptions& options = {});

}  // namespace massprops
