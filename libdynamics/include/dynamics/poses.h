#pragma once
/// @file
/// Resting poses: on which face of its convex hull a part comes to rest on a plane, and how often.
///
/// Two estimators (Goldberg et al., "Part pose statistics: estimators and experiments", IEEE T-RA
/// 15(5), 1999):
///  - quasi-static: the part, dropped from a uniformly random orientation with no bounce, falls
///    onto the hull face its center of mass "sees" straight down; the chance of each face is the
///    solid angle it subtends from the center of mass over 4π. A face whose plane does not hold
///    the center of mass's projection inside it topples over the edge nearest that projection
///    onto the face beyond, until a stable face is reached (the topple graph).
///  - drops: the part is dropped many times from uniformly random orientations (uniform on SO(3))
///    from a height onto a ground plane, simulated with contact (ContactWorld) until it sleeps,
///    and classified by the hull face it rests on. Drop k of a seed is the same simulation
///    whatever batch or thread runs it, so batches can run anywhere and be merged.
/// All geometry is in the part's own axes (the mesh file's), SI units.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "dynamics/contact.h"
#include "massprops/mass_properties.h"

namespace dynamics::poses {

/// A part to drop: its mass properties, its convex hull (which classifies the poses) and what it
/// collides as (by default the hull).
struct Part {
  massprops::MassProperties mass_properties;  ///< SI, part axes
  /// The convex hull of the part, outward triangles in part coordinates (massprops::ConvexHull).
  std::vector<Vector3> hull_vertices;
  std::vector<std::array<int, 3>> hull_triangles;
  /// What the drops collide as, placed in part coordinates (x_part = R x_shape + t); empty: the
  /// hull. A shape::Mesh (its own mesh) lets a part rest on concave faces, a cup on its rim.
  std::optional<Collider> collider;
  Material material;  ///< the part's surface (used with the hull; a given collider has its own)
};

/// A face of the hull the part can rest on (coplanar hull triangles are one face).
struct Pose {
  Vector3 normal;  ///< outward unit normal of the face, part axes: it points down at rest
  /// The part at rest on the plane z = 0: x_world = rotation x_part + translation, the center of
  /// mass straight above the world origin, the face's normal turned onto -z by the least turn.
  Matrix3 rotation;
  Vector3 translation;
  double height = 0;            ///< m, center of mass above the plane
  double solid_angle = 0;       ///< sr, of the face itself from the center of mass
  double quasi_static = 0;      ///< probability: solid angles of the faces that end here, / 4π
  std::vector<int> hull_faces;  ///< the triangles of the face (indices into Part::hull_triangles)
  std::vector<int> outline;     ///< its corners (into Part::hull_vertices), counter-clockwise from outside
};

/// Every face of the hull (coplanar triangles merged), in the hull's order: where a part put down
/// on face f ends after toppling (topples_to[f], f itself when stable) and which pose that is.
struct HullFaces {
  std::vector<Vector3> normals;
  std::vector<double> solid_angles;
  std::vector<int> topples_to;  ///< a stable face, after following the topple graph
  std::vector<int> pose_of;     ///< index into Estimate::poses of each stable face, -1 otherwise
};

/// The quasi-static estimate: stable poses, most likely first.
struct Estimate {
  std::vector<Pose> poses;
  HullFaces faces;
};
/// Stable faces whose normals lie within `merge_degrees` of a likelier pose's are merged into it
/// (its normal and rest transform stay those of the likelier face).
/// @throws std::invalid_argument when the hull is not closed and convex, the mass is not positive,
///         or the center of mass is not strictly inside the hull.
Estimate QuasiStatic(const Part& part, double merge_degrees = 1.0);

struct DropOptions {
  double height = 0.1;     ///< m, from the plane to the part's lowest point at release
  std::uint64_t seed = 1;  ///< drop k's orientation depends only on (seed, k)
  Material ground;         ///< the plane's surface
  double dt = 1e-3;        ///< s
  double max_time = 20;    ///< s simulated per drop before it counts as not settled
  /// At rest: every point slower than this (m/s) for `rest_time` seconds (ContactOptions sleep).
  double rest_speed = 1e-3;
  double rest_time = 0.5;
  /// Degrees between the face's normal and straight down for a drop to count as resting on it.
  double face_tolerance_degrees = 3;
  int threads = 1;  ///< 0: every hardware thread; the outcomes are the same bits for any count
};

/// Where one drop ended.
struct DropOutcome {
  static constexpr int kNotSettled = -1;            ///< still moving after max_time
  static constexpr int kOtherFace = -2;             ///< at rest, but not on a stable face of the estimate
  int pose = kNotSettled;                           ///< index into Estimate::poses, or one of the above
  double time = 0;                                  ///< s simulated until at rest
  Quaternion orientation = Quaternion::Identity();  ///< part axes → world at the end
  Vector3 position = Vector3::Zero();               ///< where the part's origin ended, world
};

/// The drops first, first + 1, …, first + count − 1 of options.seed.
/// @throws std::invalid_argument for bad options or a part QuasiStatic refuses;
///         std::runtime_error naming the drop when a step fails (a rotation too fast for dt).
std::vector<DropOutcome> Drop(const Part& part, const Estimate& estimate, const DropOptions& options,
                              std::int64_t first, std::int64_t count);

/// The orientation drop k of a seed starts from: uniform on SO(3) (Shoemake, "Uniform random
/// rotations", Graphics Gems III, 1992), from a counter-based generator (SplitMix64 of seed and k).
Quaternion DropOrientation(std::uint64_t seed, std::int64_t k);

struct Interval {
  double low = 0, high = 0;
};
/// Wilson score interval for a binomial proportion k/n at the given confidence.
Interval BinomialInterval(std::int64_t k, std::int64_t n, double confidence = 0.95);
/// Simultaneous intervals for all cells of a multinomial count (Goodman, Technometrics 7(2), 1965):
/// they hold together with the given confidence.
std::vector<Interval> SimultaneousIntervals(const std::vector<std::int64_t>& counts, double confidence = 0.95);

/// The drops tallied per pose (plus not settled and other faces), with both kinds of interval.
struct Tally {
  std::vector<std::int64_t> counts;  ///< per pose
  std::int64_t not_settled = 0, other_face = 0, drops = 0;
  std::vector<Interval> binomial;      ///< per pose, 95 %
  std::vector<Interval> simultaneous;  ///< per pose, jointly 95 % (cells: poses, then the two others)
  double mean_time = 0;                ///< s to rest, over the settled drops
};
Tally Count(const std::vector<DropOutcome>& outcomes, std::size_t poses, double confidence = 0.95);

}  // namespace dynamics::poses
