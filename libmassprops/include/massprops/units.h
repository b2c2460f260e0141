#pragma once
/// @file
/// Units: of mesh coordinates (lengths), and of the reports (mass, length, inertia, as CAD
/// mass-property reports use them) — the one table of names and factors that the commands, the
/// scene files and the bindings all read. Every factor is exact by definition (1 lb = 0.45359237 kg).

#include <optional>
#include <string>
#include <string_view>

namespace massprops {

enum class LengthUnit { kMetre, kCentimetre, kMillimetre, kInch, kFoot, kMicrometre };

/// Every unit, in the order above.
inline constexpr LengthUnit kAllLengthUnits[] = {LengthUnit::kMetre, LengthUnit::kCentimetre, LengthUnit::kMillimetre,
                                                 LengthUnit::kInch,  LengthUnit::kFoot,       LengthUnit::kMicrometre};

/// Metres in one unit (exact: 1, 0.01, 0.001, 0.0254, 0.3048, 1e-6).
double MetresPerUnit(LengthUnit unit);
/// The short name: "m", "cm", "mm", "in", "ft", "um".
const char* UnitName(LengthUnit unit);
/// The unit of a short name; nothing for an unknown one.
std::optional<LengthUnit> FindLengthUnit(std::string_view name);
/// As FindLengthUnit. @throws std::invalid_argument naming the known units.
LengthUnit ParseLengthUnit(std::string_view name);
/// "m, cm, mm, in, ft, um", for messages and help texts.
std::string LengthUnitNames();

enum class MassUnit { kKilogram, kGram, kPound };
enum class InertiaUnit { kKgM2, kKgMm2, kGMm2, kGCm2, kLbIn2, kLbFt2 };

/// Kilograms in one unit; "kg", "g", "lb".
double KilogramsPerUnit(MassUnit unit);
const char* UnitName(MassUnit unit);
/// kg·m² in one unit; "kg*m^2", "kg*mm^2", "g*mm^2", "g*cm^2", "lb*in^2", "lb*ft^2".
double KilogramMetre2PerUnit(InertiaUnit unit);
const char* UnitName(InertiaUnit unit);

/// The units a report is read in. Results are computed in SI; a report divides each quantity by
/// its unit's size in SI.
struct ReportUnits {
  MassUnit mass = MassUnit::kKilogram;
  LengthUnit length = LengthUnit::kMetre;
  InertiaUnit inertia = InertiaUnit::kKgM2;

  bool IsSi() const {
    return mass == MassUnit::kKilogram && length == LengthUnit::kMetre && inertia == InertiaUnit::kKgM2;
  }
  double Length() const;   ///< metres per length unit
  double Area() const;     ///< m² per area unit
  double Volume() const;   ///< m³ per volume unit
  double Mass() const;     ///< kg per mass unit
  double Density() const;  ///< kg/m³ per (mass unit / length unit³)
  double AreaDensity() const;
  double Inertia() const;               ///< kg·m² per inertia unit
  std::string VolumeName() const;       ///< "m^3", "mm^3", …
  std::string AreaName() const;         ///< "m^2", …
  std::string DensityName() const;      ///< "kg/m^3", "g/mm^3", …
  std::string AreaDensityName() const;  ///< "kg/m^2", …
  std::string Describe() const;         ///< "g, mm, g*mm^2"
};

/// A system by name — "si" (kg, m, kg*m^2), "mmgs" (g, mm, g*mm^2), "cgs" (g, cm, g*cm^2), "ips"
/// (lb, in, lb*in^2) — or "MASS,LENGTH,INERTIA", e.g. "kg,mm,kg*mm^2".
/// @throws std::invalid_argument naming the choices.
ReportUnits ParseReportUnits(std::string_view spec);

}  // namespace massprops
