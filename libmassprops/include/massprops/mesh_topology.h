#pragma once
/// @file
/// Combinatorial checks that decide whether a mesh bounds a solid (pure combinatorics, in the core).

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "massprops/mesh.h"

namespace massprops {

/// Edge and component counts of a polygon mesh.
struct MeshTopology {
  std::int64_t faces = 0;
  std::int64_t vertices = 0;  ///< vertices referenced by a face
  std::int64_t unreferenced_vertices = 0;
  std::int64_t edges = 0;               ///< undirected edges
  std::int64_t boundary_edges = 0;      ///< used by one face: the surface has a hole
  std::int64_t holes = 0;               ///< connected loops of boundary edges
  std::int64_t non_manifold_edges = 0;  ///< used by more than two faces
  /// Non-manifold edges not traversed equally often in both directions. Balanced ones (e.g. two
  /// closed solids touching along an edge) keep the volume well defined; unbalanced ones do not.
  std::int64_t unbalanced_edges = 0;
  std::int64_t inconsistent_edges = 0;  ///< two faces traverse it in the same direction
  std::int64_t degenerate_faces = 0;    ///< a repeated corner index
  /// Faces with the same corners as an earlier face, in the same cyclic order (the surface is
  /// there twice), and in the reverse order (a double-sided surface, or two solids touching face
  /// to face). Counted when there are non-manifold edges (a repeated face always makes some).
  std::int64_t duplicate_faces = 0;
  std::int64_t reversed_duplicate_faces = 0;
  std::int64_t components = 0;  ///< connected pieces (through shared vertices)

  /// Closed and consistently oriented (every edge traversed as often forward as backward): the
  /// signed volume integrals are then well defined. Balanced non-manifold edges are allowed.
  bool BoundsVolume() const { return boundary_edges == 0 && unbalanced_edges == 0 && inconsistent_edges == 0; }
  /// One line describing what is wrong, empty when BoundsVolume().
  std::string Problems() const;
};

/// The edge analysis. Meshes of 2^17 faces and more are analysed on up to `num_threads` threads
/// (0: the hardware's; at most four; the same counts on any number).
MeshTopology AnalyzeTopology(const PolygonMesh& mesh, int num_threads = 1);

/// Corners on the boundary (of an open mesh) that lie within `tolerance` (absolute) of another
/// boundary corner at a different position: cracks between corners that should have been one
/// (CAD exporters write 0.0 here and −2.7e-16 there), not holes. Linear (a hash grid).
std::int64_t CountUnweldedBoundaryCorners(const PolygonMesh& mesh, double tolerance);

}  // namespace massprops

namespace massprops {

/// One connected piece of a mesh (faces joined through shared vertices).
struct Shell {
  std::vector<std::int64_t> faces;  ///< indices into the mesh's faces
  double signed_volume = 0;         ///< in the mesh's units³; < 0: the shell faces inward
  bool closed = false;              ///< no boundary or inconsistent edge within the shell
  /// Index of the innermost other shell that contains this one, or -1. Decided by the winding
  /// number of that shell at a point of this one (±1 inside, 0 outside).
  int inside_of = -1;
};

/// How the shells of a mesh combine into one solid.
struct ShellReport {
  std::vector<Shell> shells;
  /// Two shells whose surfaces cross (one partly inside the other), 0-based; {-1, -1}: none.
  std::pair<int, int> crossing{-1, -1};
  /// Empty when the shells form a valid solid: disjoint outward shells, and cavities (inward
  /// shells) each inside an outward one. Otherwise what is wrong, in words, e.g. an outward shell
  /// inside another outward shell (the volumes overlap; a cavity facing the wrong way?). Option
  /// names stand as markers ({repair}) that each app words in its own vocabulary (wording.h).
  std::string problem;
};

/// Splits the mesh into shells and classifies their nesting. Meant for meshes that BoundsVolume();
/// O(shells × faces) for the nesting test.
ShellReport AnalyzeShells(const PolygonMesh& mesh);

}  // namespace massprops
