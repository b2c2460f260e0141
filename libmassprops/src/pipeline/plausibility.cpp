// Plausibility of sizes and densities (see plausibility.h).

#include "pipeline/plausibility.h"

#include <cmath>
#include <string>
#include <utility>

#include "massprops/text.h"

namespace massprops::internal {
namespace {}  // namespace

// Warns when the size or the density suggests the coordinates are in another unit (the
// millimetre/metre mix-up changes the mass by 10⁹) or a density in other units.
void CheckPlausible(SolidResult& r, const Plausibility& p) {
  const double s = r.size_m;
  const double file_size = s / MetresPerUnit(r.unit);  // in the file's unit
  const std::string across = Fixed(s) + " m";
  if (!p.unit_stated && s > 2.0) {
    // Every other unit that would make it a part of hand size (2 mm to 2 m).
    std::string readings;
    for (auto [u, words] :
         {std::pair{LengthUnit::kMillimetre, "millimetres"}, std::pair{LengthUnit::kCentimetre, "centimetres"},
          std::pair{LengthUnit::kInch, "inches"}}) {
      const double there = file_size * MetresPerUnit(u);
      if (there >= 0.002 && there <= 2.0) {
        readings += std::string(readings.empty() ? "; read in " : ", in ") + words + " it would be " +
                    Fixed(there, "%.3g") + " m ({unit=" + UnitName(u) + "})";
      }
    }
    Warn(r, FindingKind::kUnitSuspicion,
         "the part is " + across + " across, with the unit defaulted to " + UnitName(r.unit) + readings +
             "; {unit=" + UnitName(r.unit) + "} says the default is right");
  } else if (!p.unit_stated && s < 0.002 && s > 0) {
    Warn(r, FindingKind::kUnitSuspicion,
         "the part is only " + Fixed(s * 1000) + " mm across, with the unit defaulted to " + UnitName(r.unit) +
             "; {unit=" + UnitName(r.unit) + "} says the default is right");
  } else if (s > 1000.0) {
    Warn(r, FindingKind::kUnitSuspicion, "the part is " + across + " across: check {unit}");
  } else if (s < 1e-4 && s > 0) {
    Warn(r, FindingKind::kUnitSuspicion,
         "the part is only " + Fixed(s * 1000) + " mm across: check {unit} (the file's coordinates are taken as " +
             UnitName(r.unit) + ")");
  }
  // Densities: from the lightest foams to osmium, about 1 to 23 000 kg/m^3.
  constexpr double kLightest = 1.0, kDensest = 25000.0;
  const double rho = r.mp.density;
  if (r.model == ModelKind::kShell || !(rho > 0) || (rho >= kLightest && rho <= kDensest)) return;
  const std::string what = rho > kDensest ? "denser than any material" : "lighter than any solid material";
  if (FixesMass(p.mass)) {
    // Which unit of the coordinates would make the same mass a material's density?
    std::string likely;
    const double volume_file = r.mp.volume / std::pow(MetresPerUnit(r.unit), 3);
    for (LengthUnit u : kAllLengthUnits) {
      const double there = std::get<TotalMass>(p.mass).value / (volume_file * std::pow(MetresPerUnit(u), 3));
      if (u != r.unit && there >= 300 && there <= kDensest) {
        likely = "; with {unit=" + std::string(UnitName(u)) + "} it would be " + Fixed(there) + " kg/m^3";
        break;
      }
    }
    Warn(r, FindingKind::kUnitSuspicion,
         "a mass of " + Fixed(r.mp.mass) + " kg in " + Fixed(r.mp.volume) + " m^3 implies a density of " + Fixed(rho) +
             " kg/m^3, " + what + likely);
  } else {
    Warn(r, FindingKind::kUnitSuspicion,
         "a density of " + Fixed(rho) + " kg/m^3 is " + what + " (densities are in kg/m^3: water is 1000, steel 7850)");
  }
}

}  // namespace massprops::internal
