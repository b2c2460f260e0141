// The definitions of massprops/mass_spec.h: how much a solid weighs.

#include "massprops/mass_spec.h"

#include <fnmatch.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace massprops {

double ResolveDensity(const MassSpec& spec, double measure) {
  if (const auto* d = std::get_if<Density>(&spec)) {
    if (!(std::isfinite(d->value) && d->value > 0)) {
      throw std::invalid_argument("the density must be finite and positive, got " + std::to_string(d->value));
    }
    return d->value;
  }
  const double mass = std::get<TotalMass>(spec).value;
  if (!(std::isfinite(mass) && mass > 0)) {
    throw std::invalid_argument("the mass must be finite and positive, got " + std::to_string(mass));
  }
  return mass / measure;
}

MassProperties AtDensity(const MassProperties& unit_density, double density) {
  MassProperties mp = unit_density;
  mp.mass = unit_density.volume * density;
  mp.inertia_com = unit_density.inertia_com * density;
  mp.density = density;
  return mp;
}

const PartMass* MatchPart(const std::vector<PartMass>& map, const std::string& part) {
  for (const PartMass& entry : map) {
    if (entry.pattern == part || ::fnmatch(entry.pattern.c_str(), part.c_str(), 0) == 0) return &entry;
  }
  return nullptr;
}

const PartMass* FirstUnmatched(const std::vector<PartMass>& map, const std::vector<std::string>& names) {
  for (const PartMass& entry : map) {
    const bool used = std::any_of(names.begin(), names.end(),
                                  [&](const std::string& name) { return MatchPart({entry}, name) != nullptr; });
    if (!used) return &entry;
  }
  return nullptr;
}

}  // namespace massprops
