#pragma once
// The pipeline's pieces shared by load_solid.cpp (one solid) and load_parts.cpp (an assembly).

#include <chrono>

#include "massprops/load.h"

namespace massprops::internal {

/// The options with the unit resolved: the one stated, else the one the file declares, else the
/// default; records the unit and its source in `r` (and a finding when a stated unit overrides
/// the file's).
LoadOptions ResolveUnit(SolidResult& r, const LoadOptions& given);

/// Everything after reading one solid: repair, checks, the model's integration, findings.
SolidResult Solve(SolidResult r, const LoadOptions& given, std::chrono::steady_clock::time_point t0);

/// Everything after reading an assembly: each part solved on its own, the whole composed.
SolidResult SolveParts(SolidResult r, const LoadOptions& given, std::chrono::steady_clock::time_point t0);

}  // namespace massprops::internal
