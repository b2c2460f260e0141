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

#include <array>
#include <cstdint>
#include <vector>

#include "dynamics/contact.h"

namespace dynamics::contact {

struct MeshField {
  Vector3 origin = Vector3::Zero();  // node (0, 0, 0)
  double cell = 0;
  std::array<int, 3> nodes{};    // along x, y, z
  std::vector<double> values;    // x fastest
  std::vector<Vector3> samples;  // in clusters of nearby samples (consecutive)
  struct Cluster {
    Vector3 centre;
    double radius = 0;
    int first = 0, count = 0;
  };
  std::vector<Cluster> clusters;          // a whole cluster is skipped when the other shape is beyond its ball
  double radius = 0;                      // of the sphere about the mesh origin that holds it
  Eigen::AlignedBox<double, 3> mesh_box;  // of the vertices
  double thinnest = 0;                    // the thinnest wall found (m), which bounded the cell
  double build_seconds = 0;

  // φ at x (mesh frame) and its gradient (not normalized).
  double Distance(const Vector3& x, Vector3* gradient) const;
  std::size_t MemoryBytes() const;
};

// @throws std::invalid_argument for fewer than 4 triangles, a bad index, a non-finite vertex, a
// mesh that is not closed and consistently oriented, or a cell that is not finite and positive.
std::shared_ptr<const MeshField> BuildMeshField(const shape::Mesh& mesh);

}  // namespace dynamics::contact
