#pragma once
// The pieces of the velocity solve that its files share (solver.h is what the step sees):
// jacobians.cpp sets effective masses, patches.cpp groups rows into patches, kernels.cpp holds
// the Gauss–Seidel updates and sweeps, solver.cpp solves island by island.

#include <vector>

#include "solver.h"

namespace dynamics::contact {

// The hot helpers of the sweeps, here so that every file inlines them (an out-of-line call costs
// a pile step several per cent).

/// The effective mass of a patch's friction, K⁻¹ (the tangential 2 × 2 block's alone when the
/// patch has no torsion radius ρ).
inline Matrix3 PatchMass(const Matrix3& K, double rho) {
  if (rho > 0) return K.inverse();
  Matrix3 m = Matrix3::Zero();
  m.topLeftCorner<2, 2>() = K.topLeftCorner<2, 2>().inverse();
  return m;
}

/// The patch's generalized sliding velocity: (v·t1, v·t2, ρ ω·n) at its anchor.
[[gnu::always_inline]] inline Vector3 PatchVelocity(const std::vector<Velocities>& vel, const Patch& p) {
  const Velocities& va = vel[static_cast<std::size_t>(p.a)];
  Vector3 v = va.v;
  Vector3 g = p.ang_a.transpose() * va.w;
  if (p.b >= 0) {
    const Velocities& vb = vel[static_cast<std::size_t>(p.b)];
    v -= vb.v;
    g -= p.ang_b.transpose() * vb.w;
  }
  g[0] += p.t1.dot(v);
  g[1] += p.t2.dot(v);
  return g;
}

/// A patch's generalized impulse d at its anchor, on a and (opposite) on b; `frozen` is not moved.
[[gnu::always_inline]] inline void ApplyPatch(std::vector<Velocities>& vel, const Patch& p, const Vector3& d,
                                              int frozen) {
  const Vector3 f = p.t1 * d[0] + p.t2 * d[1];
  if (p.coupling != nullptr) {
    p.coupling->Apply(vel, p.a, f, p.ang_a * d);
    if (p.b >= 0) p.coupling->Apply(vel, p.b, -f, -(p.ang_b * d));
    return;
  }
  if (p.a != frozen) {
    Velocities& va = vel[static_cast<std::size_t>(p.a)];
    va.v += p.inv_mass_a * f;
    va.w += p.turn_a * d;
  }
  if (p.b >= 0 && p.b != frozen) {
    Velocities& vb = vel[static_cast<std::size_t>(p.b)];
    vb.v -= p.inv_mass_b * f;
    vb.w -= p.turn_b * d;
  }
}

// jacobians.cpp
/// A row's effective masses and Jacobian.
void SetRowJacobian(Row& r, const BodyResponse& bodies);
/// A patch's Jacobian and effective masses at its anchor (ra, rb).
void SetPatchJacobian(Patch& p, const BodyResponse& bodies);
/// A patch's normals' coupled response (Patch::block).
void SetNormalBlock(Patch& p, const std::vector<Row>& rows);

// kernels.cpp
/// Coulomb's friction update of patch p (every sweep's): from its impulse `old` and its sliding
/// velocity g = (v·t1, v·t2, ρ ω·n), the impulse that stops the sliding (old − mass g) if it lies
/// within `bound` = μ N; else the one of least kinetic energy on that limit in the metric of the
/// response K (mass = K⁻¹; p.nu keeps the projection's multiplier for the next update).
Vector3 FrictionUpdate(Patch& p, const Vector3& old, const Vector3& g, const Matrix3& mass, const Matrix3& K,
                       double bound);
/// A patch's total normal impulse N, and (when `centre` is given) its centre of pressure.
double Load(const Patch& p, const std::vector<Row>& rows, Vector3* centre = nullptr);
/// A sweep over the patches in `order` (forward or backward): each patch's normals (as one block
/// when `block`), then its friction.
void Sweep(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order, bool forward, bool block,
           std::vector<Velocities>& vel, const BodyResponse& bodies, Progress& progress);
/// One patch's update in a sweep: its normals (as one block when `block`; the rows in sweep order
/// when point by point), then its friction; a patch `alone` in its island, its whole system at
/// once where it holds. Of free bodies, it reads and writes the velocities of the patch's two
/// bodies alone (a jointed body's impulse moves its whole tree).
void SweepPatch(Patch& p, std::vector<Row>& rows, bool forward, bool block, bool alone, std::vector<Velocities>& vel,
                const BodyResponse& bodies, Progress& progress);
/// Shock propagation, level by level from the ground up (body_level as SolveImpulses').
/// A level's passes update its patches (those whose lower body is on that level) with the lower
/// body held still: each writes its upper body's velocity alone (a body on the ground is the
/// upper body of its ground patches, and so moves in its own level's passes).
void PropagateShock(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
                    std::vector<Velocities>& vel, const BodyResponse& bodies, const std::vector<int>& body_level,
                    const SolveSettings& settings);
/// What ShockFrozen says of a patch between two bodies of one level: no update.
inline constexpr int kShockSkipped = -2;
/// The body a patch holds still in shock propagation: its lower one (-1, the ground or a static
/// body, for a patch of a body on one).
int ShockFrozen(const Patch& p, const std::vector<int>& body_level);
/// One patch's update in a pass of shock propagation.
void ShockPatch(Patch& p, std::vector<Row>& rows, std::vector<Velocities>& vel, const BodyResponse& bodies,
                const std::vector<int>& body_level, Progress& progress);

// block_solve.cpp
/// How an island's patches are solved as a block: not at all, all of jointed bodies (SolveBlock),
/// or all of free bodies (PivotFree).
enum class BlockKind { kNone, kJointed, kFree };
/// An island's kind: a block when its patches are all of jointed bodies, or all of free bodies
/// (two patches or more), none sliding since the last step, at most kMaxBlockChannels channels.
BlockKind BlockKindOf(const std::vector<Patch>& patches, const std::vector<int>& order, const BodyResponse& bodies);
/// Of jointed bodies: the sweeps of such an island on its channels' Delassus matrix (a pivoting step on the loaded
/// set, else a projected Gauss–Seidel sweep), from the rows' and patches' impulses (already in
/// `vel`) until the stopping rule holds; then the new impulses into the rows, patches and `vel`.
/// Returns the sweeps used, or max_iterations.
int SolveBlock(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
               std::vector<Velocities>& vel, const BodyResponse& bodies, const SolveSettings& settings,
               BlockScratch& scratch);
/// Of free bodies: the pivoting step alone, from the impulses and velocities the sweeps left, taken
/// (into the rows, patches and `vel`) only where it is the answer — else nothing changes, and the
/// sweeps go on (a projected sweep on A costs more than theirs, and a patch that starts to slide
/// leaves the pivoting step nothing to find). `first`: the island's channels and Delassus matrix
/// are built (once a step: free bodies' responses do not change within it). Returns whether it
/// was taken.
bool PivotFree(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
               std::vector<Velocities>& vel, const BodyResponse& bodies, const SolveSettings& settings,
               BlockScratch& scratch, bool first);

}  // namespace dynamics::contact
