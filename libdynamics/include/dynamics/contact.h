#pragma once
/// @file
/// Contact: bodies that rest, slide, roll, bounce and stack on ground planes, static bodies and
/// each other.
///
/// Model. Rigid, non-penetrating contact with Coulomb friction (distinct static and kinetic
/// coefficients) and Newton restitution, solved at the velocity level each step:
///   1. kick: v⁻ = v + h F/m, L⁻ = L + h τ (the world's forces at the start of the step);
///   2. contacts at the start-of-step positions, within a speculative margin;
///   3. impulses (sequential, warm-started from the previous step's contacts, iterated to
///      convergence) such that every contact's normal velocity after the step is at least
///      −(gap)/h (a gap closes exactly, never overshoots) or, at an impact faster than the
///      resting threshold, e times the approach speed. Friction acts per patch — the points of a
///      pair whose normals agree — as a force at the patch's centre of pressure and a torque
///      about its normal, bounded together by μ times the patch's total normal impulse (an
///      elliptic limit; the torque's reach is the mean distance of the points' outline from its
///      centroid, as under uniform pressure): a patch that held last step holds while the impulse
///      it needs stays within μs N, and otherwise slides at μk N, opposing its sliding (the
///      impulse of least kinetic energy within the limit: Coulomb's maximal dissipation). Whether
///      a body at rest on a face stays so depends on the resultant only, never on how the load is
///      shared among the points;
///   4. drift: x += h v⁺ and the free rotation of the world's integrator with L⁺; overlap beyond
///      a small slop (a quarter of a mesh field's cell; half a percent of a primitive's size) is
///      pushed out by split impulses that move the bodies without changing their velocities
///      (ContactStats::pushed).
/// Jointed bodies (an articulated world) take part through their joints: the kick and the drift
/// are the joints' (symplectic Euler on the joint coordinates and momenta), and an impulse on
/// one link moves its whole tree (its response Φ M⁻¹ Φᵀ through the tree's mass matrix M), with
/// the joints' stops, friction and velocity motors solved after the contacts. Sleeping and shock
/// propagation leave jointed bodies out.
/// With no contact in the world the step is the world's own integrator, bit for bit: free flight
/// is unchanged. Contact steps are first order (semi-implicit Euler) and dissipative: the
/// impulses never add kinetic energy; only the push-out may lift a body (by ContactStats::pushed).

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "dynamics/world.h"
#include "massprops/mesh.h"

namespace dynamics {

/// Surface properties. A pair uses the geometric mean of the friction coefficients and the
/// larger restitution, unless ContactWorld::SetPairMaterial says otherwise.
struct Material {
  double static_friction = 0.6;   ///< μs: a contact sticks while |f_t| ≤ μs f_n
  double kinetic_friction = 0.5;  ///< μk ≤ μs: sliding friction
  double restitution = 0.0;       ///< e in [0, 1]: normal speed after an impact / before
  /// MuJoCo's mixing (MJCF geoms and floors): a pair of two such surfaces takes the larger of
  /// each coefficient instead of the geometric mean.
  bool mix_by_maximum = false;
};
/// The material of a contact between surfaces a and b: the geometric mean of each friction
/// coefficient (the larger when both mix by maximum) and the larger restitution.
Material CombineMaterials(const Material& a, const Material& b);

/// What is wrong with a material: the field ("static_friction", "kinetic_friction",
/// "restitution") and the problem in words, without the value ("must not exceed
/// static_friction (0.5)", "lies between 0 and 1").
struct MaterialFault {
  std::string field;
  std::string problem;
};
/// The one check of a material (ContactWorld, scene files, `rbsim poses` and Python ask it):
/// finite, non-negative friction coefficients with kinetic ≤ static, and a restitution in [0, 1].
std::optional<MaterialFault> CheckMaterial(const Material& m);

namespace contact {
struct MeshField;  // the signed distance field of a mesh collider (built once, shared)
struct Polytope;   // the faces, edges and corners of a box or convex shape (built when added)
}  // namespace contact

/// MuJoCo's collision filter: two shapes may touch when (a.contype & b.conaffinity) or
/// (b.contype & a.conaffinity) is non-zero. The default (1, 1) touches everything of the default.
struct CollisionFilter {
  std::uint32_t contype = 1;
  std::uint32_t conaffinity = 1;
  bool Touches(const CollisionFilter& other) const {
    return ((contype & other.conaffinity) | (other.contype & conaffinity)) != 0;
  }
};

struct Collider;

/// Collision shapes, in their own frame (centred; axis of symmetry along z).
namespace shape {
struct Sphere {
  double radius = 0.5;
};
struct Box {
  Vector3 half_extents = Vector3::Constant(0.5);
};
/// A cylinder |z| ≤ half_length of radius r with hemispherical caps.
struct Capsule {
  double radius = 0.5, half_length = 0.5;
};
struct Cylinder {
  double radius = 0.5, half_length = 0.5;
};
/// A convex polytope: its vertices and the triangles of its surface, outward (the convex hull of
/// a mesh, massprops::ConvexHull, or a mesh that is convex). Coplanar triangles act as one face.
/// Its faces, edges and corners are built by each world it is added to, unless MakeConvex built
/// them: then every copy shares them (a thousand drops of one part build them once).
struct Convex {
  std::vector<Vector3> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::shared_ptr<const contact::Polytope> polytope = nullptr;  ///< built by MakeConvex (null: by each world)
};
/// A closed, consistently oriented triangle mesh collided as it is — a ring that goes around a
/// peg, a cup that holds a ball, a bin — through a signed distance field: the surface samples of
/// each shape against the other's signed distance (the mesh's from a grid of exact distances,
/// the primitives' in closed form). Make it with MakeMesh, which builds the field once; copies of
/// the shape share it (a pile of 50 copies of one part builds one field).
struct Mesh {
  std::vector<Vector3> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< outward
  /// The field's cell (m); 0: automatic — 64 cells along the longest side of the mesh's box, or a
  /// third of the thinnest wall if that is smaller (README, "Mesh contact").
  double cell = 0;
  std::shared_ptr<const contact::MeshField> field;  ///< built by MakeMesh (or when first added)
};
/// Several shapes fixed to one body, each placed in the compound's frame by its collider's
/// rotation and translation and each colliding on its own (a robot link's box, cylinders and
/// capsules; an L of two boxes standing on its two feet, not on the face of their hull). Parts
/// are not compounds; the compound's material applies to them all unless `part_materials`, and
/// each part's filter is ANDed with the compound's.
struct Compound {
  std::vector<Collider> parts;
  /// Each part touches with its own material (an MJCF link's geoms, each with its friction).
  bool part_materials = false;
  /// Each part's polytope (boxes and convex parts; null otherwise), built when the body is added.
  std::vector<std::shared_ptr<const contact::Polytope>> polytopes;
};
}  // namespace shape
using Shape = std::variant<shape::Sphere, shape::Box, shape::Capsule, shape::Cylinder, shape::Convex, shape::Mesh,
                           shape::Compound>;
/// "sphere", "box", "capsule", "cylinder", "convex", "mesh", "compound".
const char* ShapeName(const Shape& s);

/// A convex collider from a hull as massprops gives it (massprops::ConvexHull: outward polygons,
/// fanned into triangles here).
shape::Convex ConvexOf(const massprops::PolygonMesh& hull);
/// A mesh collider's corners and triangles from a massprops mesh; its field is not built yet
/// (MakeMesh, or the first AddBody, builds it).
shape::Mesh MeshOf(const massprops::TriangleMesh& mesh, double cell = 0);

/// A mesh collider with its field built, on `threads` threads (0: every core; the field's bits do
/// not depend on it). @throws std::invalid_argument for a mesh that is not
/// closed and consistently oriented, a bad index, a non-finite vertex or a negative cell.
shape::Mesh MakeMesh(std::vector<Vector3> vertices, std::vector<std::array<int, 3>> triangles, double cell = 0,
                     int threads = 0);

/// A convex collider with its faces, edges and corners built. @throws std::invalid_argument when
/// the triangles do not bound a closed convex solid.
shape::Convex MakeConvex(std::vector<Vector3> vertices, std::vector<std::array<int, 3>> triangles);

/// What a mesh collider's field holds (for people and benchmarks).
struct MeshFieldInfo {
  std::array<int, 3> nodes{};  ///< grid nodes along x, y, z
  double cell = 0;             ///< m
  double thinnest_wall = 0;    ///< m, the wall the automatic cell resolves (infinite: none found)
  std::size_t samples = 0;     ///< surface points tested against other shapes
  std::size_t bytes = 0;       ///< memory of the field and its samples
  double build_seconds = 0;
};
/// @throws std::invalid_argument when the shape's field is not built.
MeshFieldInfo DescribeMeshField(const shape::Mesh& mesh);

/// A shape attached to a body: placed in the body frame B by x_B = R x_S + t.
struct Collider {
  Collider() = default;
  Collider(Shape shape_, const Matrix3& rotation_ = Matrix3::Identity(), const Vector3& translation_ = Vector3::Zero(),
           const Material& material_ = {}, const CollisionFilter& filter_ = {})
      : shape(std::move(shape_)),
        rotation(rotation_),
        translation(translation_),
        material(material_),
        filter(filter_) {}
  Shape shape;
  Matrix3 rotation = Matrix3::Identity();
  Vector3 translation = Vector3::Zero();
  Material material;
  CollisionFilter filter;
};

/// The half-space {x : n·x ≤ offset} (n a unit normal pointing out of the ground), fixed.
struct Ground {
  Ground() = default;
  Ground(const Vector3& normal_, double offset_ = 0, const Material& material_ = {},
         const CollisionFilter& filter_ = {})
      : normal(normal_), offset(offset_), material(material_), filter(filter_) {}
  Vector3 normal = Vector3::UnitZ();
  double offset = 0;
  Material material;
  CollisionFilter filter;
};

struct ContactOptions {
  /// Solver sweeps per step at most (0: 32, or 64 in exact mode); they stop earlier, island by
  /// island, once no update of a sweep changes a contact point's velocity by more than
  /// `speed_tolerance` (m/s; a patch's turning counts times its torsion radius). 10⁻⁹ m/s moves
  /// a point 1 pm in a 1 ms step. When the sweeps run out (a tall stack), shock propagation —
  /// each level solved with the one below it held still — settles what they left.
  int max_iterations = 0;
  double speed_tolerance = 1e-9;
  /// Exact mode: sweep until no impulse changes by more than `tolerance` times the largest (the
  /// solver of rbsim 0.3 and before) — 2–5× slower, for references: a resting stack's drift
  /// ~10⁻¹⁴ m instead of ~10⁻⁹–10⁻⁶ m; impulses that never add energy, where the default may leave
  /// ~10⁻⁷ of it in a step of a settling pile or a tall stack's first steps.
  bool exact = false;
  double tolerance = 1e-12;
  /// Impacts slower than this (m/s) do not bounce (resting contact under gravity would
  /// otherwise chatter); 0: twice the speed the step's forces give in one step.
  double restitution_threshold = 0;
  /// Sleeping: a group of touching bodies (an island) whose points all move slower than
  /// `sleep_speed` (m/s; the angular speed times the body's radius counts) for `sleep_time`
  /// seconds stops being stepped, and wakes when an awake body touches it. Off by default.
  bool sleeping = false;
  double sleep_speed = 1e-3;
  double sleep_time = 0.5;
  /// Jointed bodies: links of one articulation collide with each other, except a joint's parent
  /// and child (which meet at the joint). Off by default, as in URDF simulators (robot files
  /// often let links' collision shapes overlap where they never touch in motion).
  bool self_collision = false;
  /// Contact points kept from step to step: a pair whose shapes have moved relative to each
  /// other by at most `reuse_distance` times their two bounding radii summed (every point of the
  /// second, in the first's frame) since its points were found takes those points again, carried
  /// with the first shape, each separation brought up to date by that motion along its normal,
  /// instead of running the narrow phase: a corner is where the narrow phase would put it to
  /// within that distance (for 5 cm boxes, 10⁻¹¹ m), its separation to rounding. Not for meshes
  /// (their points are samples of a distance field, chosen afresh every step). 0: the narrow
  /// phase every step; never in exact mode.
  double reuse_distance = 1e-10;
};

/// What the last step's contact did (diagnostics).
struct ContactStats {
  int contacts = 0;            ///< contact points in the step
  int pairs = 0;               ///< touching pairs
  int iterations = 0;          ///< solver iterations used
  double max_penetration = 0;  ///< m, the deepest overlap at the start of the step
  /// J: kinetic energy the contact impulses removed in this step (≥ 0 up to rounding).
  double dissipated = 0;
  int sleeping = 0;  ///< bodies asleep after the step
  /// m: the largest distance a point of a body was moved to push an overlap back to its slop (a
  /// quarter of a mesh field's cell; half a percent of a primitive's bounding radius): kinetic
  /// energy unchanged; the potential energy may rise by the weight times this much.
  double pushed = 0;
  int reused = 0;  ///< pairs whose points were kept from an earlier step (ContactOptions::reuse_distance)
  /// Threads the largest island's sweeps ran on: 1, or up to the step's threads for an island of
  /// free bodies with at least 128 patches (the same results as on one).
  int lanes = 1;
};

/// One contact point of the last step, as the outputs report it (ContactWorld::Contacts).
struct ContactReport {
  int a = -1;                         ///< the body it pushes (world().bodies() index)
  int b = -1;                         ///< the other body; -1: a ground plane or a static body
  Vector3 point = Vector3::Zero();    ///< world, m
  Vector3 normal = Vector3::UnitZ();  ///< unit, from b into a
  /// N·s on a over the step (−impulse on b): the normal impulse along the normal, plus the
  /// point's share of its patch's friction impulse, in proportion to the points' normal impulses.
  Vector3 impulse = Vector3::Zero();
  /// N·m·s on a over the step (−torque on b), a couple: the same share of its patch's torsional
  /// friction, and of the moment that moves the friction from where the solver applied it (the
  /// patch's center of pressure) to this point. A patch's rows so give exactly the wrench the step
  /// applied: the angular impulse on a about a point c is Σ (point − c) × impulse + torque.
  Vector3 torque = Vector3::Zero();
};

/// A World with contact. It owns its world: bodies and forces are added here (each dynamic body
/// with one collider or none), and world() reads them; static bodies and ground planes have no
/// state.
class ContactWorld {
 public:
  /// @throws std::invalid_argument for a world that has bodies already, or options out of range
  /// (negative sweeps, a negative or non-finite tolerance, a non-positive sleep speed or time).
  explicit ContactWorld(World world = World(), ContactOptions options = {});
  ~ContactWorld();
  ContactWorld(ContactWorld&&) noexcept;
  ContactWorld& operator=(ContactWorld&&) noexcept;

  /// Adds a moving body with its collider; returns its index in world().bodies().
  /// @throws std::invalid_argument as World::AddBody, or for a shape with non-positive sizes.
  int AddBody(const RigidBody& body, Collider collider);
  /// A body without a collider: it moves through everything (a marker, a body held by springs).
  int AddBody(const RigidBody& body);
  /// A body fixed in the world (a table, a ramp): its collider placed by x_W = R x_B + t.
  void AddStatic(Collider collider, const Matrix3& rotation = Matrix3::Identity(),
                 const Vector3& translation = Vector3::Zero());
  /// @throws std::invalid_argument for a zero or non-finite normal.
  void AddGround(Ground ground);
  void AddForce(std::unique_ptr<Force> force) { world_.AddForce(std::move(force)); }
  /// A joint (World::AddJoint): its bodies then step in joint coordinates, through contact too.
  int AddJoint(const Joint& joint) { return world_.AddJoint(joint); }
  /// Loops, couplings and tendons (World's): held in the contacts' solve too.
  int AddLoop(const Loop& loop) { return world_.AddLoop(loop); }
  int AddCoupling(const Coupling& coupling) { return world_.AddCoupling(coupling); }
  int AddTendon(const Tendon& tendon) { return world_.AddTendon(tendon); }
  /// Bodies a and b never touch each other (MJCF's <contact><exclude>); each still touches the
  /// rest. @throws std::invalid_argument unless a and b are two different bodies of the world.
  void ExcludePair(int a, int b);
  /// The material of contacts between bodies a and b (-1: the ground and static bodies).
  void SetPairMaterial(int a, int b, const Material& material);

  /// Advances by h seconds (see the file comment). @throws as World::Step.
  StepStatus Step(double h);

  /// The bodies, forces, clock and integrator; read-only: bodies and forces are added through
  /// this class, which keeps a collider and contact state for each.
  const World& world() const { return world_; }
  /// Worker threads for the narrow phase, the islands' solve and the world's per-body work (0: all
  /// cores). Results do not depend on it.
  void set_num_threads(int n) { world_.set_num_threads(n); }
  const ContactStats& stats() const { return stats_; }
  /// The ground planes, in the order added.
  const std::vector<Ground>& grounds() const;
  /// The contact points the last step solved (none in free flight; the contacts among sleeping
  /// bodies alone are not solved, and not reported).
  std::vector<ContactReport> Contacts() const;
  /// Whether body k is asleep (ContactOptions::sleeping) after the last step.
  bool asleep(int k) const;

 private:
  struct Impl;
  World world_;
  ContactOptions options_;
  ContactStats stats_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dynamics
