#pragma once
// Contact points between posed shapes (internal to the contact solver). Every function appends
// the points where the shapes are closer than `margin` (separation < margin; negative when they
// overlap), with the normal pointing from the second shape (or the ground) into the first.

#include <cstdint>
#include <vector>

#include "dynamics/contact.h"

namespace dynamics::contact {

struct ContactPoint {
  Vector3 point;              ///< world, between the two surfaces
  Vector3 normal;             ///< unit, from the second shape into the first
  double separation = 0;      ///< m, negative when overlapping
  std::uint32_t feature = 0;  ///< which corner, end or rim point: keys warm starting
  /// The material of the first and second shape's part the point is on, when that part of a
  /// compound touches with its own (shape::Compound::part_materials); null: the collider's.
  const Material* material_a = nullptr;
  const Material* material_b = nullptr;
};

struct PlacedPolytope;

/// A shape in the world: x_W = R x_S + t.
struct Posed {
  const Shape* shape = nullptr;
  const Polytope* polytope = nullptr;  ///< boxes and convex shapes
  Matrix3 R = Matrix3::Identity();
  Vector3 t = Vector3::Zero();
  CollisionFilter filter;
  /// The polytope's vertices and face planes in the world, when placed once for the step (a body
  /// in a pair: PairRows); null: placed by each routine that needs them.
  const PlacedPolytope* placed = nullptr;
};

/// Part k of a posed compound, posed in the world with its filter ANDed with the compound's.
Posed PartOf(const Posed& compound, const shape::Compound& c, std::size_t k);

/// The radius of a sphere about the shape's origin that holds it.
double BoundingRadius(const Shape& shape);
/// Throws std::invalid_argument for a size that is not finite and positive.
void ValidateShape(const Shape& shape);

/// Keeps at most kMaxContactPoints of out[first ...]: the deepest, then each time the point
/// farthest from those kept less four times how much shallower than the deepest it is (a support
/// polygon that does not rock, without dropping a point about to close its gap, at a bounded
/// solver cost). Fewer points are left as they are.
inline constexpr std::size_t kMaxContactPoints = 16;
void ReduceContacts(std::vector<ContactPoint>& out, std::size_t first);

/// What the last full scan of a hull's corners against a ground plane kept, so that the next
/// steps test only those while the hull has not turned or moved enough for another corner to come
/// within reach (CollideGround): the corners within `band` beyond the reach then, and what that
/// scan was made against.
struct GroundScan {
  const Polytope* polytope = nullptr;  ///< null: no scan kept
  Vector3 u = Vector3::Zero();         ///< the plane's normal in the shape's frame
  double limit = 0, scale = 0, band = 0;
  std::vector<int> near;  ///< the corners kept, ascending
};

/// The shape against the half-space {x : n·x ≤ offset} whose filter is `ground` (nothing when the
/// filters do not touch; a compound's parts each on their own). `scan` (optional, one per body
/// and plane, kept between steps) lets a hull test only the corners near the plane; the points
/// are the same with it or without.
void CollideGround(const Posed& a, const Vector3& n, double offset, const CollisionFilter& ground, double margin,
                   std::vector<ContactPoint>& out, GroundScan* scan = nullptr);
/// Whether every kind of `a` (a compound's: its parts') has a contact routine against every kind
/// of `b`. ContactWorld asks when a body is added and refuses a pair that has none.
bool SupportsPair(const Shape& a, const Shape& b);
struct PairSampleBounds;
/// Two shapes, through the table of pair routines (nothing when their filters do not touch;
/// compounds part by part, each part's features marked with its index). `bounds` (optional, two
/// meshes): the pair's field bounds kept between steps (CollideMeshes).
void Collide(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out,
             PairSampleBounds* bounds = nullptr);

/// A mesh collider against the half-space (its vertices), and a pair of which at least one is a
/// mesh (mesh_contact.cpp). At most 12 points a pair: the deepest, then the farthest apart.
void CollideMeshGround(const Posed& a, const Vector3& n, double offset, double margin, std::vector<ContactPoint>& out);
void CollideWithMesh(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out);
/// CollideWithMesh with the bounds kept from the steps before for two meshes (sample_bounds.h;
/// null: none); the same points either way.
void CollideMeshes(const Posed& a, const Posed& b, double margin, std::vector<ContactPoint>& out,
                   PairSampleBounds* bounds);

/// A pair for the narrow phase: two posed shapes and the margin, and for two meshes the bounds
/// kept between steps (null: none).
struct PairQuery {
  const Posed* a = nullptr;
  const Posed* b = nullptr;
  double margin = 0;
  PairSampleBounds* bounds = nullptr;
};
class Workers;
/// Collide on each pair: found[c] gets pair c's points (none for a pair whose `a` is null). Pairs run in groups of 16
/// on the workers (null: on the caller), each on its own, so the result does not depend on the thread count.
void CollidePairs(const std::vector<PairQuery>& pairs, Workers* workers, std::vector<std::vector<ContactPoint>>& found);

}  // namespace dynamics::contact
