#pragma once
// Convex polytopes for contact (internal): boxes and convex hulls as faces, planes and edges, the
// separating-axis test between two of them with the incident face clipped against the reference
// face (a manifold of up to four points), and a sphere against one.

#include <array>
#include <cstdint>
#include <vector>

#include "narrow_phase.h"

namespace dynamics::contact {

struct Polytope {
  std::vector<Vector3> vertices;                ///< shape frame
  std::vector<std::vector<int>> faces;          ///< counter-clockwise from outside; coplanar triangles merged
  std::vector<Vector3> normals;                 ///< unit, outward, per face
  std::vector<std::pair<int, int>> edges;       ///< each once
  std::vector<std::pair<int, int>> edge_faces;  ///< the two faces that meet at each edge
  std::vector<std::vector<int>> vertex_faces;   ///< the faces each vertex touches
  std::vector<int> triangle_faces;              ///< the face of each triangle given
  Vector3 centroid = Vector3::Zero();
  /// The vertices by coordinate and each one's |v|₁, for scans over all of them (MayLieBelow),
  /// and the largest |v|.
  std::vector<double> xs, ys, zs, l1;
  double max_norm = 0;
};

/// Scan width of MayLieBelow.
constexpr int kScan = 64;

/// Of vertices first .. first + n − 1 of `p` (n ≤ kScan), which may lie at height u·v within
/// `limit` + 10⁻¹² (scale + |v|₁): `maybe[j]` is 0 only for a vertex that lies above that by more
/// than rounding (1e-14 (|v|₁ + |limit|)), so that the exact test need run only on the others.
/// Vectorized (AVX2 or AVX-512 where the CPU has it); `u` is a unit vector.
void MayLieBelow(const Polytope& p, std::size_t first, int n, const Vector3& u, double limit, double scale,
                 std::uint8_t* maybe);

/// A posed polytope's vertices, face planes and edges in the world.
struct PlacedPolytope {
  std::vector<Vector3> v;
  std::vector<Vector3> n;
  std::vector<double> d;     // n·x = d on the face
  std::vector<Vector3> e;    // each edge, second vertex − first
  std::vector<Vector3> arc;  // n(second face) × n(first face): the edge's arc on the Gauss map
};
/// Places `p` as `posed` puts it (into w, whose arrays are reused).
void PlacePolytope(const Polytope& p, const Posed& posed, PlacedPolytope& w);

/// The polytope of a convex hull given as triangles (outward); coplanar triangles become one face.
/// O(n log n) in the triangles. @throws std::invalid_argument when the triangles do not bound a
/// closed convex solid.
Polytope MakePolytope(const std::vector<Vector3>& vertices, const std::vector<std::array<int, 3>>& triangles);
Polytope BoxPolytope(const Vector3& half_extents);

/// Contact points of two posed polytopes (normals from b into a).
void PolytopePolytope(const Polytope& pa, const Posed& a, const Polytope& pb, const Posed& b, double margin,
                      std::vector<ContactPoint>& out);
/// A sphere (centre c, radius r) against a posed polytope; normals into the sphere when
/// `sphere_first`, else into the polytope.
void SpherePolytope(const Vector3& c, double r, const Polytope& p, const Posed& posed, double margin, bool sphere_first,
                    std::uint32_t feature, std::vector<ContactPoint>& out);

}  // namespace dynamics::contact
