#pragma once
/// @file
/// Mesh repair and self-intersection checks with CGAL's Polygon Mesh Processing (target
/// massprops::repair; the only part of the project that includes CGAL).

#include <cstdint>
#include <string>

#include "massprops/mesh.h"

namespace massprops {

struct RepairOptions {
  /// Corners closer than this fraction of the bounding-box diagonal are merged (CAD exporters
  /// write the same point as 0.0 and −2.7e-16). 0 merges only bit-identical positions.
  double weld_tolerance = 1e-9;
};

/// What RepairMesh changed.
struct RepairReport {
  std::int64_t welded_vertices = 0;  ///< vertices merged into another within the tolerance
  std::int64_t removed_faces = 0;    ///< degenerate or duplicate faces dropped
  /// Of removed_faces: faces repeating another in the same direction (one of them kept).
  std::int64_t repeated_faces = 0;
  /// Of removed_faces: faces of internal walls, a face repeated in both directions (every copy
  /// removed): where two bodies, each exported closed, touch; they merge into their union.
  std::int64_t internal_walls = 0;
  /// Holes filled (border cycles closed with triangles on their own corners): how many, how many
  /// of them planar (filled exactly: any triangulation of a planar polygon adds the same
  /// integrals), and the largest's number of edges.
  std::int64_t filled_holes = 0;
  std::int64_t planar_holes = 0;
  std::int64_t largest_hole = 0;
  /// How far another fill could move the volume (mesh units³): per hole, the thickness of the slab
  /// between the two planes that hold its boundary times the patch's area (any fill within the
  /// slab differs from ours by at most that); summed. 0 when nothing was filled.
  double fill_volume_bound = 0;
  std::int64_t unfilled_holes = 0;        ///< border cycles CGAL could not triangulate
  bool reoriented = false;                ///< face orientations were made consistent
  std::int64_t split_vertices = 0;        ///< vertices duplicated to orient non-manifold fans
  std::int64_t stitched_edges = 0;        ///< border edge pairs stitched together
  bool oriented_to_bound_volume = false;  ///< shells oriented outward, cavities inward
  std::int64_t united_shells = 0;         ///< overlapping shells merged into their union
  double volume_before = 0;               ///< signed volume before and after (mesh units³)
  double volume_after = 0;
  /// One line per change, for people.
  std::string Summary() const;
};

struct RepairedMesh {
  /// Polygons as they came when the welded mesh already bounded a volume, or the shells were left
  /// open; triangles (SplitPolygon's) when CGAL oriented closed shells.
  PolygonMesh mesh;
  RepairReport report;
};

/// Tolerance weld (linear: a hash grid) and repeated polygons: copies in the same direction keep
/// one, a pair of reversed copies (an internal wall between two bodies) is removed whole, unless
/// every face is in such a pair (a double-sided surface: one side kept). When the mesh then bounds
/// a volume as it is (closed, manifold edges, consistent, shells outward and cavities inward),
/// that is the result. Otherwise CGAL, on the polygons: repair_polygon_soup (duplicate points and
/// faces, degenerate faces), orient_polygon_soup (consistent orientation),
/// polygon_soup_to_polygon_mesh, stitch_borders, triangulate_hole on each border cycle left (on its
/// own corners, minimal area), and — when the result is closed — orient_to_bound_a_volume (every
/// shell outward, nested cavities inward), then every shell that crosses another turned outward
/// (CGAL takes a pin through a hub for a cavity): a cavity lies wholly inside another shell,
/// touching none of it.
RepairedMesh RepairMesh(const PolygonMesh& mesh, const RepairOptions& options = {});

/// The union of a mesh's closed shells (CGAL corefinement), for shells that overlap, oriented as
/// RepairMesh leaves them: the outward shells are united in a balanced tree of pairs, inward ones
/// (cavities) kept as they are. `merged` is how many shells were united into the first.
/// @throws std::runtime_error when a shell is open or CGAL cannot unite them (a shell that
/// intersects itself).
PolygonMesh UnionOfShells(const PolygonMesh& mesh, std::int64_t& merged);

/// The convex hull of the mesh's corners (CGAL convex_hull_3, exact predicates): triangles facing
/// outward, on the input's own coordinates. What collision engines see of a body (MuJoCo's
/// inertia="convex"). @throws std::invalid_argument when every corner lies in one plane.
PolygonMesh ConvexHull(const PolygonMesh& mesh);

/// Number of pairs of faces that intersect other than along shared edges or vertices, counting up
/// to `limit`: polygons are split into triangles (SplitPolygon), candidate pairs come from CGAL's
/// box intersection, and each pair is decided with exact predicates. Triangles of the same polygon
/// are not tested against each other. Two kinds of groups are tested as wholes, so that the pairs
/// within them are never enumerated:
/// - a polygon of more than 32 corners in one plane (exactly, or within rounding when tilted);
/// - the fan of triangles around a corner of more than 32 triangles (a cone's apex, a cap's or a
///   sphere's pole), when exact predicates certify it free of intersections within itself: seen
///   around a line through the corner, every triangle turns the same way and together they wind
///   once.
/// A triangle is tested against a group as a whole when it touches the group's plane only at a
/// shared corner or boundary edge, its other corners strictly on the far side. Returns −1 (not
/// decided) when the candidate pairs still exceed kSelfIntersectionWork + 50 per triangle (boxes
/// of many faces overlapping around one corner that cannot be certified); the check stops in
/// seconds instead of running for hours.
inline constexpr std::int64_t kSelfIntersectionLimit = 1000000;
inline constexpr std::int64_t kSelfIntersectionWork = 10000000;
struct SelfIntersectionOptions {
  std::int64_t limit = kSelfIntersectionLimit;  ///< stop counting here
  /// Large flat polygons and high-valence corners' fans tested as wholes. false: every pair of
  /// triangles (quadratic around a fan; the second algorithm of the tests).
  bool whole_groups = true;
};
std::int64_t CountSelfIntersections(const PolygonMesh& mesh, const SelfIntersectionOptions& options);
inline std::int64_t CountSelfIntersections(const PolygonMesh& mesh, std::int64_t limit = kSelfIntersectionLimit) {
  SelfIntersectionOptions options;
  options.limit = limit;
  return CountSelfIntersections(mesh, options);
}

}  // namespace massprops
