#pragma once
/// @file
/// How much a solid weighs: a uniform density, or a total mass that fixes it. The one rule for
/// turning unit-density mass properties into those of the part.

#include <string>
#include <variant>
#include <vector>

#include "massprops/mass_properties.h"

namespace massprops {

/// Uniform density: kg/m^3 for solids, kg/m^2 (area density) for thin shells.
struct Density {
  double value = 1000.0;
};
/// Total mass in kg; the density is then mass / volume (or mass / area for a shell).
struct TotalMass {
  double value = 0.0;
};
using MassSpec = std::variant<Density, TotalMass>;

/// The density that `spec` gives a part of the given measure (volume in m^3, or area in m^2).
/// @throws std::invalid_argument if the value is not finite and positive, or the measure is not.
double ResolveDensity(const MassSpec& spec, double measure);

/// Unit-density mass properties (mass = volume, inertia per unit density) at `density`.
MassProperties AtDensity(const MassProperties& unit_density, double density);

/// The density or total mass of the parts whose names match `pattern`: the exact name, or a
/// shell-style glob (`*`, `?`, `[...]`).
struct PartMass {
  std::string pattern;
  MassSpec mass;
};

/// The first entry of `map` whose pattern matches `part`, or null.
const PartMass* MatchPart(const std::vector<PartMass>& map, const std::string& part);

/// The first entry of `map` that matches none of `names` (a misspelt name, which would silently
/// take the default), or null.
const PartMass* FirstUnmatched(const std::vector<PartMass>& map, const std::vector<std::string>& names);

/// True when the spec fixes the total mass.
inline bool FixesMass(const MassSpec& spec) { return std::holds_alternative<TotalMass>(spec); }

}  // namespace massprops
