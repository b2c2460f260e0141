#include "massprops/units.h"

#include <stdexcept>

namespace massprops {

double MetresPerUnit(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMetre: return 1.0;
    case LengthUnit::kCentimetre: return 0.01;
    case LengthUnit::kMillimetre: return 0.001;
    case LengthUnit::kInch: return 0.0254;
    case LengthUnit::kFoot: return 0.3048;
    case LengthUnit::kMicrometre: return 1e-6;
  }
  return 1.0;
}

const char* UnitName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMetre: return "m";
    case LengthUnit::kCentimetre: return "cm";
    case LengthUnit::kMillimetre: return "mm";
    case LengthUnit::kInch: return "in";
    case LengthUnit::kFoot: return "ft";
    case LengthUnit::kMicrometre: return "um";
  }
  return "?";
}

std::optional<LengthUnit> FindLengthUnit(std::string_view name) {
  for (LengthUnit u : kAllLengthUnits) {
    if (name == UnitName(u)) return u;
  }
  return std::nullopt;
}

LengthUnit ParseLengthUnit(std::string_view name) {
  if (const auto u = FindLengthUnit(name)) return *u;
  throw std::invalid_argument("unknown unit '" + std::string(name) + "' (" + LengthUnitNames() + ")");
}

std::string LengthUnitNames() {
  std::string s;
  for (LengthUnit u : kAllLengthUnits) s += (s.empty() ? "" : ", ") + std::string(UnitName(u));
  return s;
}

}  // namespace massprops
