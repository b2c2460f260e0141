// The definitions of massprops/report/words.h: the one home of each front end's words for the
// options that the library's findings advise (massprops/wording.h).

#include "massprops/report/words.h"

#include <string>

#include "massprops/io/load_schema.h"

namespace massprops::report {
namespace {

// The schema's flag and key of the options it declares (massprops/io/load_schema.h).
std::string_view FlagOf(const char* key) { return FindLoadOption(key)->flag; }

std::string CommandLine(Option option, std::string_view value) {
  const std::string suffix = value.empty() ? "" : " " + std::string(value);
  switch (option) {
    case Option::kRepair: return std::string(FlagOf("repair"));
    case Option::kAllowOpen: return std::string(FlagOf("allow_open"));
    case Option::kUnit: return std::string(FlagOf("unit")) + suffix;
    case Option::kFullCheck: return std::string(FlagOf("full_check"));
    case Option::kWall: return "--wall";
    case Option::kBrep: return "--brep";
    case Option::kWindingNumber: return "--winding-number";
    case Option::kPackage: return "--package " + std::string(value) + "=DIR";
  }
  return "?";
}

// A scene names the options by its keys.
std::string Scene(Option option, std::string_view value) {
  switch (option) {
    case Option::kRepair: return "\"repair\": true";
    case Option::kAllowOpen: return "\"allow_open\": true";
    case Option::kUnit: return value.empty() ? "\"unit\"" : "\"unit\": \"" + std::string(value) + "\"";
    case Option::kFullCheck: return "(always done in scenes)";
    case Option::kWall: return "wall";
    case Option::kBrep: return "(the massprops command's --brep)";
    case Option::kWindingNumber: return "(the massprops command's --winding-number)";
    case Option::kPackage: return "\"packages\": {\"" + std::string(value) + "\": \"DIR\"} in the robot's entry";
  }
  return "?";
}

std::string Poses(Option option, std::string_view value) {
  switch (option) {
    case Option::kRepair: return "--repair";
    case Option::kAllowOpen: return "massprops --allow-open (mass properties only: rbsim poses needs a solid)";
    case Option::kUnit: return value.empty() ? "--unit" : "--unit " + std::string(value);
    case Option::kFullCheck: return "(always done by rbsim poses)";
    case Option::kWall: return "(not in rbsim poses)";
    case Option::kBrep: return "(massprops --brep)";
    case Option::kWindingNumber: return "(massprops --winding-number)";
    case Option::kPackage: return "(not in rbsim poses)";
  }
  return "?";
}

std::string Python(Option option, std::string_view value) {
  switch (option) {
    case Option::kRepair: return "repair=True";
    case Option::kAllowOpen: return "allow_open=True";
    case Option::kUnit: return value.empty() ? "unit=..." : "unit='" + std::string(value) + "'";
    case Option::kFullCheck: return "full_check=True";
    case Option::kWall: return "wall=...";
    case Option::kBrep: return "brep=True";
    case Option::kWindingNumber: return "winding_number=True";
    case Option::kPackage: return "packages={'" + std::string(value) + "': DIR}";
  }
  return "?";
}

}  // namespace

const Vocabulary& WordsFor(FrontEnd front_end) {
  static const Vocabulary kCommandLine = CommandLine, kScene = Scene, kPoses = Poses, kPython = Python;
  switch (front_end) {
    case FrontEnd::kScene: return kScene;
    case FrontEnd::kPoses: return kPoses;
    case FrontEnd::kPython: return kPython;
    case FrontEnd::kCommandLine: break;
  }
  return kCommandLine;
}

std::string WordedConflict(OptionConflict conflict, FrontEnd front_end) {
  if (front_end != FrontEnd::kCommandLine) return DescribeConflict(conflict);
  switch (conflict) {
    case OptionConflict::kShellNeedsDensity: return "--shell needs --area-density (kg/m^2) or --mass (kg)";
    case OptionConflict::kWallNeedsThickness: return "--wall needs a finite, positive thickness";
    case OptionConflict::kExactNeedsSolid:
      return "--exact certifies a solid's integrals: not with --shell, --wall or --winding-number";
    case OptionConflict::kHullNeedsSolid:
      return "--hull is the convex hull as a solid: it goes with solids and --wall, not --shell or --winding-number";
    case OptionConflict::kPartMassesNeedParts: return "--density-map needs --parts";
    case OptionConflict::kPartsNeedSolid:
    case OptionConflict::kPartsNotExact:
      return "--parts and --density-map compute solids (or --wall): not --shell, --winding-number or --exact";
  }
  return DescribeConflict(conflict);
}

}  // namespace massprops::report
