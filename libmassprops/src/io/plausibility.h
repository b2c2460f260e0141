#pragma once
// The pipeline's plausibility checks (internal to massprops::io): sizes and densities that suggest
// the coordinates are in another unit, as findings worded with option markers.

#include "massprops/load.h"

namespace massprops::internal {

// What the plausibility checks need to know about the request.
struct Plausibility {
  bool unit_stated = false;
  MassSpec mass = Density{1000.0};
};

/// Adds kUnitSuspicion findings to `r` (whose size_m, unit, model and mass properties are set).
void CheckPlausible(SolidResult& r, const Plausibility& p);

}  // namespace massprops::internal
