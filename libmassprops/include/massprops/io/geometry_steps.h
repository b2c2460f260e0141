#pragma once
/// @file
/// The pipeline's steps that need CGAL, GMP and MPFR (repair, union of shells, self-intersections,
/// convex hull, exact integration) as a table of entry points. massprops::repair provides the
/// table (the C symbol massprops_geometry_steps); massprops::io does not link it: LoadSolid looks
/// the table up in the process, or loads libmassprops_repair beside libmassprops_io, only when an
/// option asks for one of these steps. A program that only reads files needs no CGAL.

#include <cstdint>

#include "massprops/mass_spec.h"
#include "massprops/mesh.h"
#include "massprops/repair/exact.h"
#include "massprops/repair/repair.h"

namespace massprops {

struct GeometrySteps {
  /// Bumped whenever the table changes: a table of another version is refused.
  static constexpr int kVersion = 1;
  int version = kVersion;
  RepairedMesh (*repair)(const PolygonMesh&, const RepairOptions&) = nullptr;
  PolygonMesh (*union_of_shells)(const PolygonMesh&, std::int64_t&) = nullptr;
  std::int64_t (*count_self_intersections)(const PolygonMesh&, std::int64_t) = nullptr;
  PolygonMesh (*convex_hull)(const PolygonMesh&) = nullptr;
  ExactMassProperties (*exact)(const PolygonMesh&, double, const MassSpec&, int) = nullptr;
};

}  // namespace massprops

/// massprops::repair's table (repair.h's functions).
extern "C" const massprops::GeometrySteps* massprops_geometry_steps();
