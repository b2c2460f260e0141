#pragma once
/// @file
/// Lengths units of mesh coordinates: the one table of names and factors that the commands, the
/// scene files and the bindings all read.

#include <optional>
#include <string>
#include <string_view>

namespace massprops {

enum class LengthUnit { kMetre, kCentimetre, kMillimetre, kInch, kFoot, kMicrometre };

/// Every unit, in the order above.
inline constexpr LengthUnit kAllLengthUnits[] = {LengthUnit::kMetre, LengthUnit::kCentimetre, LengthUnit::kMillimetre,
                                                 LengthUnit::kInch, LengthUnit::kFoot};

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

}  // namespace massprops
