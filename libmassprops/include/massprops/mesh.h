#pragma once
/// @file
/// Mesh containers: an indexed triangle mesh and an indexed polygon mesh (faces of any size).

#include <array>
#include <cstdint>
#include <vector>

#include "massprops/types.h"

namespace massprops {

/// Indexed triangle mesh. Faces are counter-clockwise seen from outside the solid.
struct TriangleMesh {
  VertexMatrix V;  ///< #V×3 vertex positions
  FaceMatrix F;    ///< #F×3 vertex indices
};

/// Indexed mesh of planar polygons with any number of corners (n >= 3), counter-clockwise seen
/// from outside. Face f has the corners indices[offsets[f]] ... indices[offsets[f+1]-1];
/// offsets has #faces+1 entries and starts with 0.
struct PolygonMesh {
  VertexMatrix V;                     ///< #V×3 vertex positions
  std::vector<std::int32_t> indices;  ///< corners of all faces, face after face
  std::vector<std::int64_t> offsets{0};

  std::int64_t num_faces() const { return static_cast<std::int64_t>(offsets.size()) - 1; }
  int face_size(std::int64_t f) const { return static_cast<int>(offsets[f + 1] - offsets[f]); }
  /// Appends one face given by its corner indices.
  template <typename Range>
  void AddFace(const Range& corners) {
    for (auto c : corners) indices.push_back(static_cast<std::int32_t>(c));
    offsets.push_back(static_cast<std::int64_t>(indices.size()));
  }
};

/// Splits polygon corners[0..n) into n − 2 triangles, appended to `out`, oriented as the polygon.
/// Polygons of up to 32 corners become a fan from the first corner; larger ones a balanced
/// recursive split along chords (triangle (first, middle, last), then each half), whose triangles
/// stay compact: a fan of 10^5 corners makes slivers whose bounding boxes all overlap, and every
/// intersection test and hierarchy over them turns quadratic. For a planar polygon both give the
/// same signed integrals (each chord is traversed once each way).
void SplitPolygon(const std::int32_t* corners, int n, std::vector<std::array<std::int32_t, 3>>& out);

/// Splits every polygon into triangles (SplitPolygon): exact for planar convex polygons, and for
/// any planar polygon as far as the signed integrals are concerned.
TriangleMesh Triangulate(const PolygonMesh& mesh);

/// Views a triangle mesh as a polygon mesh of triangles (to run it through Mirtich's path).
PolygonMesh ToPolygonMesh(const TriangleMesh& mesh);

/// True when every face of the polygon mesh is a triangle.
bool IsAllTriangles(const PolygonMesh& mesh);

/// How far the polygons of a mesh are from planar. A polygon's deviation is the largest distance
/// of a corner from the plane through its centroid with its Newell normal, relative to the
/// polygon's size (the diagonal of its corners' bounding box). A non-planar polygon bounds no
/// unique surface: the two paths (fan of triangles, Mirtich's plane) then differ.
struct PlanarityReport {
  std::int64_t non_planar_faces = 0;  ///< polygons whose deviation exceeds the tolerance
  std::int64_t worst_face = -1;       ///< the polygon with the largest deviation
  double worst_deviation = 0;         ///< relative to its size
};
PlanarityReport CheckPlanarity(const PolygonMesh& mesh, double tolerance = 1e-9);

}  // namespace massprops
