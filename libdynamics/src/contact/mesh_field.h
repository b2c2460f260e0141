#pragma once
// The signed distance field of a closed triangle mesh, for contact (internal; shape::Mesh in
// contact.h). Built once per mesh and shared by every collider that copies the shape.
//
// Values: exact distances from each grid node to the surface (closest points through a bounding
// box hierarchy of the triangles), negative inside (the mesh's winding number, which a closed
// mesh gives exactly by counting ray crossings: massprops::implicit). Between nodes, trilinear
// interpolation: its error is second order in the cell near flat parts of the surface and at most
// about half a cell's diagonal near sharp edges. Beyond the grid (which reaches three cells past
// the mesh's box), a bound from below: the larger of the distance to the mesh's box and the value
// at the nearest grid point less the way there.
//
// Samples: the points of the surface that are tested against other shapes — every vertex and
// points along edges longer than a cell, about a cell apart. None inside faces: a face meets
// another shape first at the other's vertices or along edges, which that shape's samples and the
// field find.
//
// Inactive features (Jolt's "inactive edges"): an edge whose faces are coplanar (within
// kFlatEdge) or meet in a concave crease, and a vertex all of whose edges are so, is no corner a
// shape can catch on: a contact there can only push along one of its faces' normals. Their samples
// carry those normals; a contact found at such a sample takes the face normal nearest the other
// shape's, so that a body sliding over a flat tessellation or into a crease feels the faces, not
// the seams between them. Convex edges and corners keep the other shape's normal (a ball still
// rolls off a table's edge).

#include <array>
#include <cstdint>
#include <vector>

#include "dynamics/contact.h"

namespace dynamics::contact {

/// Edges whose faces' normals differ by less than this (rad) are flat.
inline constexpr double kFlatEdge = 0.035;  // 2°

struct MeshField {
  Vector3 origin = Vector3::Zero();  // node (0, 0, 0)
  double cell = 0;
  double inverse_cell = 0;       // 1 / cell (SurelyAbove's bound; Distance divides)
  std::array<int, 3> nodes{};    // along x, y, z
  std::vector<double> values;    // x fastest
  std::vector<Vector3> samples;  // in clusters of nearby samples (consecutive)
  // Each sample's faces: count 0 for an active feature (a convex edge or corner), else the normals
  // normals[first, first + count) of the faces a contact there may push along.
  struct SampleFaces {
    std::uint32_t first = 0, count = 0;
  };
  std::vector<SampleFaces> sample_faces;  // parallel to samples
  std::vector<Vector3> normals;
  struct Cluster {
    Vector3 centre;
    double radius = 0;
    int first = 0, count = 0;
  };
  std::vector<Cluster> clusters;  // a whole cluster is skipped when the other shape is beyond its ball
  // The mesh's vertices in runs of nearby ones (indices vertex_order[first, first + count)), each
  // with its ball: a plane skips a run whose ball lies beyond its margin (CollideMeshGround, which
  // then keeps the vertices it finds in their own order).
  std::vector<int> vertex_order;
  std::vector<Cluster> vertex_runs;
  double radius = 0;                      // of the sphere about the mesh origin that holds it
  Eigen::AlignedBox<double, 3> mesh_box;  // of the vertices
  double thinnest = 0;                    // the thinnest wall found (m), which bounded the cell
  double build_seconds = 0;

  // Each block of kBlock³ cells' least node value (blocks x fastest): inside the grid the trilinear
  // value is at least its cell's least corner, so most samples far from the surface are turned away
  // by this small table without reading `values`.
  static constexpr int kBlock = 2;
  std::array<int, 3> blocks{};
  std::vector<double> block_min;

  // φ at x (mesh frame) and its gradient (not normalized).
  double Distance(const Vector3& x, Vector3* gradient) const;
  // True when φ at x (mesh frame) is surely above `threshold` by the blocks' bound alone (by more
  // than rounding: then Distance(x) > threshold too); false when that is not known. `bound`
  // (optional, when true): a bound from below of Distance(x).
  bool SurelyAbove(const Vector3& x, double threshold, double* bound = nullptr) const;
  std::size_t MemoryBytes() const;
};

// The field, each z-slice of nodes on its own (on `threads`: 0, every core; the same bits on any).
// @throws std::invalid_argument for fewer than 4 triangles, a bad index, a non-finite vertex, a
// mesh that is not closed and consistently oriented, or a cell that is not finite and positive.
std::shared_ptr<const MeshField> BuildMeshField(const shape::Mesh& mesh, int threads);

}  // namespace dynamics::contact
