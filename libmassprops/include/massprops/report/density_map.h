#pragma once
// The file behind `--density-map`: densities or total masses per part, by name or glob pattern,
// in the order given (the first match wins).
//
//   JSON  {"steel*": 7850, "handle": {"mass": 0.2}, "insert": {"density": 2700}}
//   CSV   part,density,mass        (a header; each row fills exactly one of the two)
//         steel*,7850,
//         handle,,0.2
//
// Densities in kg/m^3, masses in kg.

#include <string>
#include <vector>

#include "massprops/mass_spec.h"

namespace massprops::report {

/// @throws std::runtime_error naming the file, the place and the fault.
std::vector<PartMass> ReadDensityMap(const std::string& path);

}  // namespace massprops::report
