#pragma once
// The pipeline's pieces shared by load_solid.cpp (one solid) and load_parts.cpp (an assembly).

#include <chrono>

#include "massprops/io/load.h"

namespace massprops::internal {

/// The options with the unit resolved: the one stated, else the one the file declares, else the
/// default; records the unit and its source in `r` (and a finding when a stated unit overrides
/// the file's).
LoadOptions ResolveUnit(SolidResult& r, const LoadOptions& given);

/// Everything after reading one solid: repair, checks, the model's integration, findings.
SolidResult Solve(SolidResult r, const LoadOptions& given, std::chrono::steady_clock::time_point t0);

/// Everything after reading an assembly: each part solved on its own, the whole composed.
SolidResult SolveParts(SolidResult r, const LoadOptions& given, std::chrono::steady_clock::time_point t0);

/// CAD files (load_cad.cpp): whether the parts carry different material densities that the
/// options leave in force (then the parts are computed one by one).
bool MaterialsDiffer(const LoadedMesh& loaded, const LoadOptions& given);

/// CAD files: the density of the file's material when every part has the same one and none is
/// stated (recorded in r.density_source); a finding when a stated one overrides it.
void ApplyFileMaterial(SolidResult& r, LoadOptions& opt);

/// CAD files with solids: the exact B-rep's numbers beside the mesh's (r.brep), or in their place
/// with LoadOptions::brep. After the integration (r.mp, r.size_m set).
void AddBrep(SolidResult& r, const LoadOptions& opt);

/// The whole's B-rep report from its parts' (when every part has one).
void ComposeBrep(SolidResult& whole);

/// CAD files: whether the exact B-rep is the result (LoadOptions::brep, and no option that needs a mesh).
bool BrepIsTheAnswer(const LoadOptions& options);

/// CAD files: the tessellation options for this load (the relative deflection's default: 1e-3 of
/// the diagonal when the B-rep is the answer and the mesh its check, 1e-4 when the mesh is).
CadOptions CadOptionsFor(const LoadOptions& options);

/// CAD files: the reader's notes (parts left out) and its interference report as findings.
void AddCadFindings(SolidResult& r);

/// CAD parts with a solid: the exact B-rep's numbers as the result (unless the options need the
/// mesh), the tessellation as their check. False when the mesh route is to be taken.
bool SolveBrep(SolidResult& r, const LoadOptions& opt);

/// load_solid.cpp's last step for any integrals: SI numbers at the density or mass, size and
/// plausibility, principal axes, validity.
void FinishIntegrals(SolidResult& r, const VolumeIntegrals& integrals, const LoadOptions& opt, double size);

/// The bounding-box diagonal of a mesh's vertices (0 for none).
double MeshDiagonal(const PolygonMesh& mesh);

}  // namespace massprops::internal
