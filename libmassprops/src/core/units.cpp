// The definitions of massprops/units.h: the units of mesh coordinates (lengths) and of reports.

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

double KilogramsPerUnit(MassUnit unit) {
  switch (unit) {
    case MassUnit::kKilogram: return 1.0;
    case MassUnit::kGram: return 1e-3;
    case MassUnit::kPound: return 0.45359237;
  }
  return 1.0;
}

const char* UnitName(MassUnit unit) {
  switch (unit) {
    case MassUnit::kKilogram: return "kg";
    case MassUnit::kGram: return "g";
    case MassUnit::kPound: return "lb";
  }
  return "?";
}

namespace {
struct InertiaParts {
  MassUnit mass;
  LengthUnit length;
};
InertiaParts PartsOf(InertiaUnit unit) {
  switch (unit) {
    case InertiaUnit::kKgM2: return {MassUnit::kKilogram, LengthUnit::kMetre};
    case InertiaUnit::kKgMm2: return {MassUnit::kKilogram, LengthUnit::kMillimetre};
    case InertiaUnit::kGMm2: return {MassUnit::kGram, LengthUnit::kMillimetre};
    case InertiaUnit::kGCm2: return {MassUnit::kGram, LengthUnit::kCentimetre};
    case InertiaUnit::kLbIn2: return {MassUnit::kPound, LengthUnit::kInch};
    case InertiaUnit::kLbFt2: return {MassUnit::kPound, LengthUnit::kFoot};
  }
  return {MassUnit::kKilogram, LengthUnit::kMetre};
}
constexpr InertiaUnit kAllInertiaUnits[] = {InertiaUnit::kKgM2, InertiaUnit::kKgMm2, InertiaUnit::kGMm2,
                                            InertiaUnit::kGCm2, InertiaUnit::kLbIn2, InertiaUnit::kLbFt2};
constexpr MassUnit kAllMassUnits[] = {MassUnit::kKilogram, MassUnit::kGram, MassUnit::kPound};
}  // namespace

double KilogramMetre2PerUnit(InertiaUnit unit) {
  const InertiaParts p = PartsOf(unit);
  return KilogramsPerUnit(p.mass) * MetresPerUnit(p.length) * MetresPerUnit(p.length);
}

const char* UnitName(InertiaUnit unit) {
  switch (unit) {
    case InertiaUnit::kKgM2: return "kg*m^2";
    case InertiaUnit::kKgMm2: return "kg*mm^2";
    case InertiaUnit::kGMm2: return "g*mm^2";
    case InertiaUnit::kGCm2: return "g*cm^2";
    case InertiaUnit::kLbIn2: return "lb*in^2";
    case InertiaUnit::kLbFt2: return "lb*ft^2";
  }
  return "?";
}

double ReportUnits::Length() const { return MetresPerUnit(length); }
double ReportUnits::Area() const { return Length() * Length(); }
double ReportUnits::Volume() const { return Length() * Length() * Length(); }
double ReportUnits::Mass() const { return KilogramsPerUnit(mass); }
double ReportUnits::Density() const { return Mass() / Volume(); }
double ReportUnits::AreaDensity() const { return Mass() / Area(); }
double ReportUnits::Inertia() const { return KilogramMetre2PerUnit(inertia); }
std::string ReportUnits::VolumeName() const { return std::string(UnitName(length)) + "^3"; }
std::string ReportUnits::AreaName() const { return std::string(UnitName(length)) + "^2"; }
std::string ReportUnits::DensityName() const { return std::string(UnitName(mass)) + "/" + VolumeName(); }
std::string ReportUnits::AreaDensityName() const { return std::string(UnitName(mass)) + "/" + AreaName(); }
std::string ReportUnits::Describe() const {
  return std::string(UnitName(mass)) + ", " + UnitName(length) + ", " + UnitName(inertia);
}

ReportUnits ParseReportUnits(std::string_view spec) {
  ReportUnits u;
  if (spec == "si") return u;
  if (spec == "mmgs") return {MassUnit::kGram, LengthUnit::kMillimetre, InertiaUnit::kGMm2};
  if (spec == "cgs") return {MassUnit::kGram, LengthUnit::kCentimetre, InertiaUnit::kGCm2};
  if (spec == "ips") return {MassUnit::kPound, LengthUnit::kInch, InertiaUnit::kLbIn2};
  auto fail = [&]() -> ReportUnits {
    std::string masses, inertias;
    for (MassUnit m : kAllMassUnits) masses += (masses.empty() ? "" : "|") + std::string(UnitName(m));
    for (InertiaUnit i : kAllInertiaUnits) inertias += (inertias.empty() ? "" : "|") + std::string(UnitName(i));
    throw std::invalid_argument("unknown output units '" + std::string(spec) +
                                "': give si, mmgs, cgs or ips, or MASS,LENGTH,INERTIA with MASS " + masses +
                                ", LENGTH " + LengthUnitNames() + ", INERTIA " + inertias);
  };
  const std::size_t a = spec.find(','), b = a == std::string_view::npos ? a : spec.find(',', a + 1);
  if (b == std::string_view::npos) return fail();
  const std::string_view m = spec.substr(0, a), l = spec.substr(a + 1, b - a - 1), i = spec.substr(b + 1);
  bool found_m = false, found_i = false;
  for (MassUnit x : kAllMassUnits) {
    if (m == UnitName(x)) u.mass = x, found_m = true;
  }
  for (InertiaUnit x : kAllInertiaUnits) {
    if (i == UnitName(x)) u.inertia = x, found_i = true;
  }
  const auto length = FindLengthUnit(l);
  if (!found_m || !found_i || !length) return fail();
  u.length = *length;
  return u;
}

}  // namespace massprops
