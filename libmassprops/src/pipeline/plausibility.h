#pragma once
// The pipeline's plausibility checks (internal to massprops::io): sizes and densities that suggest
// the coordinates are in another unit, as findings worded with option markers; and the one helper
// that adds a finding.

#include <string>
#include <utility>

#include "massprops/io/load.h"
#include "massprops/text.h"

namespace massprops::internal {

// What the plausibility checks need to know about the request.
struct Plausibility {
  bool unit_stated = false;
  MassSpec mass = Density{1000.0};
};

/// "%.4g" (or another printf format) of one number, for messages.
inline std::string Fixed(double v, const char* fmt = "%.4g") { return FormatDouble(v, fmt); }

/// A finding, added to the result.
inline void Warn(SolidResult& r, FindingKind kind, std::string message) {
  r.findings.push_back({kind, Advice(std::move(message))});
}

/// Adds kUnitSuspicion findings to `r` (whose size_m, unit, model and mass properties are set).
void CheckPlausible(SolidResult& r, const Plausibility& p);

}  // namespace massprops::internal
