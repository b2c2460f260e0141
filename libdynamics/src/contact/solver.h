#pragma once
// The velocity solve of a contact step (internal to ContactWorld): the contact rows and their
// friction patches, their effective masses, and the sequential impulses with static and kinetic
// friction, iterated from the ground up with shock propagation.

#include <cstdint>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include "dynamics/contact.h"
#include "profile_cholesky.h"

namespace dynamics::contact {

/// A body's velocities as the solve works on them (world frame).
struct Velocities {
  Vector3 v, w;  // linear, angular
};

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

struct Row;

/// Jointed bodies answer an impulse together (an articulated world: every body is in a tree, a
/// lone body alone in its own). Response(j, k) maps an impulsive wrench on body k — force f and
/// torque τ about k's centre — to the change of body j's (v, ω): Φ_j M⁻¹ Φ_kᵀ with M the tree's
/// mass matrix and Φ the bodies' Jacobians. Bodies of different trees do not couple. Only the
/// bodies a step's contacts touch are members (the others' velocities are not read).
struct Coupling {
  std::vector<int> tree;                       ///< each body's tree (trees joined by loops, couplings, tendons: one)
  std::vector<int> joint_tree;                 ///< each body's tree of joints alone: the pairs that never touch
  std::vector<int> slot;                       ///< each member's index among its tree's members
  std::vector<std::vector<int>> members;       ///< each tree's touched bodies
  std::vector<std::vector<Matrix6>> response;  ///< each tree's blocks, [j × size + k]
  /// Bodies that move at all (some joint between them and the world has a degree of freedom).
  std::vector<char> movable;
  std::vector<int> parent;  ///< each body's parent body in its tree (-1: a root)
  const Matrix6& Response(int j, int k) const {
    const auto t = static_cast<std::size_t>(tree[static_cast<std::size_t>(j)]);
    return response[t][static_cast<std::size_t>(slot[static_cast<std::size_t>(j)]) * members[t].size() +
                       static_cast<std::size_t>(slot[static_cast<std::size_t>(k)])];
  }
  bool Joined(int a, int b) const {
    return b >= 0 && tree[static_cast<std::size_t>(a)] == tree[static_cast<std::size_t>(b)];
  }
  /// n·K n of a row: its normal velocity's change per unit impulse (0: no motion of the trees
  /// moves the point along its normal).
  double NormalResponse(const Row& r) const;
  /// Adds to every body of a's tree its response to the impulse (f, τ about a's centre) on a.
  void Apply(std::vector<Velocities>& vel, int a, const Vector3& f, const Vector3& tau) const;
};

/// (body a, the other: a body's index, -2 - a static body's, INT_MIN + a ground's, feature):
/// which contact a row is, step after step.
using RowKey = std::tuple<int, int, std::uint32_t>;

/// One contact point in the solve: its normal impulse. Body b = -1: the ground or a static body.
struct Row {
  int a = -1, b = -1;
  Vector3 ra = Vector3::Zero(), rb = Vector3::Zero(), n = Vector3::UnitZ();
  Vector3 point = Vector3::Zero();                     // world
  Matrix3 Ka = Matrix3::Zero(), Kb = Matrix3::Zero();  // each body's share of K (below)
  double mass_n = 0;                                   // 1 / (n·K n)
  // The normal's Jacobian, set with the effective masses: the angular parts ra × n and rb × n,
  // and what a unit impulse does to each body (its linear part is n times the inverse mass).
  Vector3 ang_a = Vector3::Zero(), ang_b = Vector3::Zero();
  Vector3 turn_a = Vector3::Zero(), turn_b = Vector3::Zero();  // I⁻¹ (r × n)
  double inv_mass_a = 0, inv_mass_b = 0;
  double target = 0;  // the least normal velocity after the step
  double mu_s = 0, mu_k = 0;
  double lambda_n = 0;
  RowKey key;
  double separation = 0;
  // Overlap beyond this is pushed out after the step (< 0: never).
  double slop = -1;
  double push = 0;  // its accumulated pseudo-impulse
  // Its pair's points were kept from an earlier step (ManifoldCache): their layout has not
  // changed, and its patch's torsion radius is the one cached.
  bool kept = false;
  // Jointed bodies (else null): impulses act through the coupling, mass_n is
  // 1 / Coupling::NormalResponse (Ka and Kb zero).
  const Coupling* coupling = nullptr;
};

/// The friction of a contact patch: the rows of one pair of bodies whose normals agree (within
/// kPatchAngle). Friction acts on the patch as a whole, at its anchor (the centre of pressure of
/// the last step's normal impulses — of the present ones, followed through the iterations, while
/// it slides — or the centroid of its points' outline before any load): a force in the tangent
/// plane and a torque about the normal, bounded together by μ times the patch's total normal
/// impulse N — an elliptic limit surface, |f|² + (τ/ρ)² ≤ (μN)², with ρ the mean distance of the
/// outline's area from its centroid (uniform pressure; a segment's quarter length; 0 for one
/// point). Whether a body at rest on a face stays at rest so depends on the resultant only, not on
/// how the solve happens to share the load among points.
struct Patch {
  int a = -1, b = -1;
  int first = 0, count = 0;  // its rows, consecutive
  int level = 0;             // of its lower body in the support graph
  Vector3 n = Vector3::UnitZ(), t1 = Vector3::UnitX(), t2 = Vector3::UnitY();
  Vector3 anchor = Vector3::Zero();                    // world
  Vector3 ra = Vector3::Zero(), rb = Vector3::Zero();  // the anchor from each body's centre
  double rho = 0;                                      // m, the torsion radius (0: no torsion)
  Matrix3 Ka = Matrix3::Zero(), Kb = Matrix3::Zero();  // each body's share of the friction's K
  Matrix3 mass = Matrix3::Zero();                      // K⁻¹ (2 × 2 block alone when rho = 0)
  // The Jacobian's angular columns for each body (r × t1, r × t2, ρ n) and I⁻¹ times them.
  Matrix3 ang_a = Matrix3::Zero(), ang_b = Matrix3::Zero(), turn_a = Matrix3::Zero(), turn_b = Matrix3::Zero();
  double inv_mass_a = 0, inv_mass_b = 0;
  // Its normals' coupled response (2 to 4 points; the rest zero): A_ij, the normal velocity at
  // point i per unit normal impulse at point j.
  Eigen::Matrix4d block = Eigen::Matrix4d::Zero();
  // The Cholesky factor of the block's rows and columns of one set of loaded points (bit i: point
  // i), kept between sweeps, as the set rarely changes: factored is that set (-1: none yet), and
  // factor_ok whether the block was positive definite there.
  int factored = -1;
  bool factor_ok = false;
  double factor[4][4] = {};
  // The same for the patch's whole system (UpdatePatchJointly: its loaded points' normals and its
  // friction), kept between sweeps: the set it was factored for (-1: none) and the factor.
  int joint_set = -1;
  bool joint_ok = false;
  Eigen::Matrix<double, 7, 7> joint = Eigen::Matrix<double, 7, 7>::Zero();
  double mu_s = 0, mu_k = 0;
  double mu = 0;                       // the bound of this step: μs for a patch that holds, μk for one that slides
  bool sliding = false;                // did not hold last step, and slides at the start of this one
  Vector3 lambda = Vector3::Zero();    // impulses (f·t1, f·t2, τ/ρ)
  double nu = 0;                       // the multiplier of its last projection onto the limit
  const Coupling* coupling = nullptr;  // as Row::coupling (Ka the whole response, Kb zero)
};

/// Normals within this angle (rad) of a patch's first belong to it: a flat face's points (a
/// mesh's seams give their faces' normals exactly), not the points of a curved surface, whose
/// shared friction in an averaged tangent plane would push along their own normals.
inline constexpr double kPatchAngle = 0.01;

/// What the solve remembers of a patch between steps.
struct CachedPatch {
  Vector3 n = Vector3::UnitZ();
  Vector3 force = Vector3::Zero();  // the friction impulse (world)
  double torque = 0;                // its moment about n
  bool stuck = false;               // its friction was inside the cone: it holds with μs next step
  double rho = 0;                   // its torsion radius
  int rows = 0;                     // its points
};
/// What the solve remembers of a row: its normal impulse and its patch (an index into its
/// pair's cached patches; -1: its patch was not touching).
struct CachedRow {
  double lambda_n = 0;
  int patch = -1;
};
/// The last step's impulses: each row's, each pair's patches (a pair: the first two parts of a
/// RowKey). Flat and sorted (a step's lookups are binary searches, its building appends and one
/// sort, with no allocation per entry): entries are added, then Finish orders them.
class ContactCache {
 public:
  using Pair = std::pair<int, int>;
  struct PatchEntry {
    Pair pair;
    int index = 0;  // among the pair's patches
    CachedPatch patch;
    std::uint32_t order = 0;  // when it was added (ties in Finish's sort)
  };
  struct RowEntry {
    RowKey key;
    CachedRow row;
    std::uint32_t order = 0;  // when it was set (the last setting of a key counts)
  };
  /// Row `key`'s entry, or null (after Finish).
  const CachedRow* FindRow(const RowKey& key) const;
  /// The pair's patches, in their order (index = position), or an empty range (after Finish).
  std::pair<const PatchEntry*, std::size_t> FindPatches(const Pair& pair) const;
  /// Sets row `key` (of those set for one key since the last Finish, the last one counts).
  void SetRow(const RowKey& key, const CachedRow& row) {
    rows_.push_back({key, row, static_cast<std::uint32_t>(rows_.size())});
  }
  /// Keeps another cache's patches of a pair (FindPatches') as they were (kept twice: once).
  void KeepPatches(std::pair<const PatchEntry*, std::size_t> patches) {
    for (std::size_t k = 0; k < patches.second; ++k) {
      patches_.push_back(patches.first[k]);
      patches_.back().order = static_cast<std::uint32_t>(patches_.size() - 1);
    }
  }
  /// Appends a patch to its pair: index `index` among the pair's.
  void AddPatch(const Pair& pair, int index, const CachedPatch& patch) {
    patches_.push_back({pair, index, patch, static_cast<std::uint32_t>(patches_.size())});
  }
  /// Empties it, keeping its arrays' capacity (a step's cache reuses the one before last's).
  void Clear() {
    rows_.clear();
    patches_.clear();
    sorted_rows_ = sorted_patches_ = 0;
  }
  /// Orders what was added (rows by key, the last setting of a key kept; patches by pair and
  /// index, the first of a repeated (pair, index) kept).
  void Finish();

 private:
  std::vector<RowEntry> rows_;
  std::vector<PatchEntry> patches_;
  std::size_t sorted_rows_ = 0, sorted_patches_ = 0;  // the prefixes Finish ordered (the lookups' domain)
};

/// Each body's response to impulses: 0 inverse mass and inertia for a body held still (asleep).
/// With a coupling (an articulated world) the impulses act through it; the inverse masses and
/// inertias are then each body's own, for its kinetic energy.
struct BodyResponse {
  std::vector<double> inv_mass;
  std::vector<Matrix3> inv_inertia;
  const Coupling* coupling = nullptr;
};

/// The velocity of a point (ra from a's centre, rb from b's) on a relative to b (b < 0: at rest).
Vector3 RelativeVelocity(const std::vector<Velocities>& vel, int a, int b, const Vector3& ra, const Vector3& rb);
inline Vector3 RelativeVelocity(const std::vector<Velocities>& vel, const Row& r) {
  return RelativeVelocity(vel, r.a, r.b, r.ra, r.rb);
}

/// The relative normal velocity of a row (the velocity of a's point relative to b's, along n).
inline double NormalSpeed(const std::vector<Velocities>& vel, const Row& r) {
  const Velocities& va = vel[static_cast<std::size_t>(r.a)];
  double s = r.n.dot(va.v) + r.ang_a.dot(va.w);
  if (r.b >= 0) {
    const Velocities& vb = vel[static_cast<std::size_t>(r.b)];
    s -= r.n.dot(vb.v) + r.ang_b.dot(vb.w);
  }
  return s;
}

/// A normal impulse d at a row, on a and (opposite) on b; the body `frozen` is not moved.
inline void ApplyNormal(std::vector<Velocities>& vel, const Row& r, double d, int frozen) {
  if (r.coupling != nullptr) {  // (never frozen: shock propagation skips jointed bodies)
    r.coupling->Apply(vel, r.a, d * r.n, d * r.ang_a);
    if (r.b >= 0) r.coupling->Apply(vel, r.b, -d * r.n, -d * r.ang_b);
    return;
  }
  if (r.a != frozen) {
    Velocities& va = vel[static_cast<std::size_t>(r.a)];
    va.v += (r.inv_mass_a * d) * r.n;
    va.w += d * r.turn_a;
  }
  if (r.b >= 0 && r.b != frozen) {
    Velocities& vb = vel[static_cast<std::size_t>(r.b)];
    vb.v -= (r.inv_mass_b * d) * r.n;
    vb.w -= d * r.turn_b;
  }
}

/// When the sweeps stop (ContactOptions; its automatic sweep count resolved).
struct SolveSettings {
  int max_iterations = 32;
  /// m/s: once no update of a sweep changes a contact's velocity (normal, tangential, or a
  /// patch's turning times its torsion radius) by more than this.
  double speed_tolerance = 1e-9;
  /// Instead: once no impulse changes by more than `tolerance` times the largest
  /// (ContactOptions::exact).
  bool exact = false;
  double tolerance = 1e-12;
};

/// How much a sweep changed: the largest impulse change and impulse (exact mode), and the largest
/// change of a contact's velocity (m/s); Done: the settings' stopping rule holds.
struct Progress {
  double change = 0, scale = 0, speed = 0;
  bool Done(const SolveSettings& s) const {
    return s.exact ? change <= s.tolerance * scale : speed <= s.speed_tolerance;
  }
};

/// A channel of the block solve of jointed bodies: a row's normal or one direction of a patch's
/// friction; its unit impulse is the wrench wa on body a (force, torque about a's centre) and −wb
/// on b (-1: the ground or a static body).
struct BlockChannel {
  int a = -1, b = -1;
  Vector6 wa = Vector6::Zero(), wb = Vector6::Zero();
  double target = 0;    // its least velocity (a row's target; friction: 0)
  bool normal = false;  // a row's normal (else a friction direction)
};

/// The block solve's regularization, relative to the diagonal (block_solve.cpp: iterative
/// refinement solves the determined part of the system exactly; where the impulses are not
/// determined — coplanar points, more channels than a tree has degrees of freedom — it keeps the
/// warm start's).
inline constexpr double kBlockRegularization = 1e-9;

/// Islands with more channels than this are swept point by point.
inline constexpr int kMaxBlockChannels = 96;

/// The block solve's working arrays (block_solve.cpp), kept from step to step.
struct BlockScratch {
  /// Room for the largest island solved as a block, taken once: each island's slot of the solve's
  /// scratch sees islands of every size, and a step allocates nothing.
  void Reserve() {
    if (channels.capacity() >= kMaxBlockChannels) return;
    constexpr auto kMax = static_cast<std::size_t>(kMaxBlockChannels);
    channels.reserve(kMax);
    first.reserve(kMax);
    members.reserve(2 * kMax);
    role.reserve(kMax);
    failed.reserve(kMax);
    index.reserve(kMax);
    factored.reserve(kMax);
    sides.reserve(2 * kMax);
    touch.reserve(2 * kMax);
    touch_first.reserve(2 * kMax + 1);
    touch_fill.reserve(2 * kMax + 1);
  }
  std::vector<BlockChannel> channels;
  std::vector<int> first;    // each patch's first channel (by its place in the island's order)
  std::vector<int> members;  // the bodies that move (sorted)
  Eigen::MatrixXd U;         // each channel's unit impulse's change of every member's (v, ω)
  Eigen::MatrixXd A;         // the Delassus matrix J U
  // Free bodies: each channel's two bodies (places among the members; -1: none), and each
  // member's channels (from touch_first[j] to touch_first[j + 1] in touch).
  std::vector<int> sides, touch_first, touch_fill, touch;
  Eigen::VectorXd u, lambda, start, delta, change_u, change_v, rhs, solved;
  std::vector<char> role, failed;    // the pivoting step's roles; the loaded set it last failed from
  std::vector<int> index, factored;  // the pivoting step's set, and the set its factor is of
  Eigen::MatrixXd S0;                // the set's block of A
  Eigen::VectorXd residual;
  ProfileCholesky cholesky;  // of S0, regularized
  bool factor_ok = false;
};

/// One island's working copy (its bodies, and their velocities and impulses to go back to).
struct IslandScratch {
  std::vector<int> members;
  std::vector<Velocities> velocities;
  std::vector<double> normal;
  std::vector<Vector3> friction;
  BlockScratch block;
};

class SweepLanes;

/// The solve's working arrays, kept from step to step: a step whose contacts are those of the
/// step before allocates nothing.
struct SolveScratch {
  // PreparePatches: a pair's patch leaders, each row's patch, the cached patches taken, the rows
  // in patch order.
  std::vector<const Row*> leaders;
  std::vector<int> patch_of;
  std::vector<char> used;
  std::vector<Row> sorted;
  std::vector<Eigen::Vector2d> points, hull;  // a patch's points in its plane, their convex outline
  // SolveImpulses: the patches by level, each island's group and its patches, the groups by size,
  // each group's sweeps and working copy.
  std::vector<int> order, group_of, sweeps;
  std::vector<std::vector<int>> groups;
  std::vector<std::size_t> by_size;
  std::vector<IslandScratch> islands;
  std::shared_ptr<SweepLanes> lanes;  // the largest island's sweeps on several threads (sweep_lanes.h)
  int lanes_used = 1;                 // how many, in the last solve
  // StoreImpulses: each patch's load, the patches by pair, each one's index among its pair's.
  std::vector<double> load;
  std::vector<std::size_t> by_pair;
  std::vector<int> index;
};

/// Groups the rows (consecutive by pair) into `patches`, reordering a pair's rows so that each
/// patch's are consecutive; sets every row's and patch's effective masses; warm-starts them
/// from the cache and chooses static or kinetic friction: a patch that held last step (or a new
/// one whose anchor barely slides, within `slow`) holds while its friction stays within μs; one
/// that slid slides at μk against its sliding until it stops.
void PreparePatches(std::vector<Row>& rows, const ContactCache& cache, const std::vector<Velocities>& vel,
                    const BodyResponse& bodies, double slow, std::vector<Patch>& patches, SolveScratch& scratch);

/// Solves the impulses into `vel`, island by island (island: each body's island, by any label;
/// the islands may be solved on several threads, with the same result): patches ordered by
/// support level (body_level: 0 on the ground or a static body, k + 1 on level k), warm start,
/// then symmetric Gauss–Seidel sweeps (each patch's normals, then its friction) until the
/// settings' stopping rule holds, and shock propagation level by level when the sweeps run out
/// (by default kept only where it adds no kinetic energy). Returns the most sweeps an island used.
class Workers;
int SolveImpulses(std::vector<Row>& rows, std::vector<Patch>& patches, std::vector<Velocities>& vel,
                  const BodyResponse& bodies, const std::vector<int>& body_level, const std::vector<int>& island,
                  const SolveSettings& settings, Workers* workers, SolveScratch& scratch);

/// Adds the solved rows and patches to the cache for the next step.
void StoreImpulses(const std::vector<Row>& rows, const std::vector<Patch>& patches, ContactCache& cache,
                   SolveScratch& scratch);

}  // namespace dynamics::contact
