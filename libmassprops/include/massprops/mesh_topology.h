#pragma once
/// @file
/// Combinatorial checks that decide whether a mesh bounds a solid (target massprops::io).

#include <cstdint>
#include <string>

#include "massprops/mesh.h"

namespace massprops {

/// Edge and component counts of a polygon mesh.
struct MeshTopology {
  std::int64_t faces = 0;
  std::int64_t vertices = 0;            ///< vertices referenced by a face
  std::int64_t unreferenced_vertices = 0;
  std::int64_t edges = 0;               ///< undirected edges
  std::int64_t boundary_edges = 0;      ///< used by one face: the surface has a hole
  std::int64_t non_manifold_edges = 0;  ///< used by more than two faces
  std::int64_t inconsistent_edges = 0;  ///< two faces traverse it in the same direction
  std::int64_t degenerate_faces = 0;    ///< a repeated corner index
  std::int64_t components = 0;          ///< connected pieces (through shared vertices)

  /// Closed, manifold and consistently oriented: the signed volume is then well defined.
  bool BoundsVolume() const {
    return boundary_edges == 0 && non_manifold_edges == 0 && inconsistent_edges == 0;
  }
  /// One line describing what is wrong, empty when BoundsVolume().
  std::string Problems() const;
};

MeshTopology AnalyzeTopology(const PolygonMesh& mesh);

}  // namespace massprops
