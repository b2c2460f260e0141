#pragma once
// The pieces of the velocity solve that its files share (solver.h is what the step sees):
// jacobians.cpp sets effective masses, patches.cpp groups rows into patches, kernels.cpp holds
// the Gauss–Seidel updates and sweeps, solver.cpp solves island by island.

#include <vector>

#include "solver.h"

namespace dynamics::contact {

// jacobians.cpp
/// A row's effective masses and Jacobian.
void SetRowJacobian(Row& r, const BodyResponse& bodies);
/// A patch's Jacobian and effective masses at its anchor (ra, rb).
void SetPatchJacobian(Patch& p, const BodyResponse& bodies);
/// The effective mass of a patch's friction, K⁻¹ (the tangential 2 × 2 block's alone when the
/// patch has no torsion radius ρ).
Matrix3 PatchMass(const Matrix3& K, double rho);
/// A patch's normals' coupled response (Patch::block).
void SetNormalBlock(Patch& p, const std::vector<Row>& rows);

// kernels.cpp
/// The patch's generalized sliding velocity: (v·t1, v·t2, ρ ω·n) at its anchor.
Vector3 PatchVelocity(const std::vector<Velocities>& vel, const Patch& p);
/// A patch's generalized impulse d at its anchor, on a and (opposite) on b; `frozen` is not moved.
void ApplyPatch(std::vector<Velocities>& vel, const Patch& p, const Vector3& d, int frozen);
/// A patch's total normal impulse N, and (when `centre` is given) its centre of pressure.
double Load(const Patch& p, const std::vector<Row>& rows, Vector3* centre = nullptr);
/// A sweep over the patches in `order` (forward or backward): each patch's normals (as one block
/// when `block`), then its friction.
void Sweep(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order, bool forward, bool block,
           std::vector<Velocities>& vel, const BodyResponse& bodies, Progress& progress);
/// Shock propagation, level by level from the ground up (body_level as SolveImpulses').
void PropagateShock(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
                    std::vector<Velocities>& vel, const BodyResponse& bodies, const std::vector<int>& body_level,
                    const SolveSettings& settings);

}  // namespace dynamics::contact
