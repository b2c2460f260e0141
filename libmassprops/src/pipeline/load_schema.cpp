// The definitions of massprops/io/load_schema.h: the load options every front end takes, and
// their one check.

#include "massprops/io/load_schema.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "massprops/units.h"

namespace massprops {
namespace {

constexpr double kNoLimit = std::numeric_limits<double>::infinity();

std::vector<std::string> UnitChoices() {
  std::vector<std::string> names;
  for (LengthUnit u : kAllLengthUnits) names.emplace_back(UnitName(u));
  return names;
}

LoadOptionSpec Switch(std::string_view key, std::string_view flag, std::string_view help) {
  LoadOptionSpec s;
  s.key = key;
  s.flag = flag;
  s.help = help;
  return s;
}

LoadOptionSpec Number(std::string_view key, std::string_view flag, std::string_view unit, double min, bool min_open,
                      double max, std::string default_text, std::string_view help) {
  LoadOptionSpec s = Switch(key, flag, help);
  s.type = OptionType::kNumber;
  s.unit = unit;
  s.min = min;
  s.min_open = min_open;
  s.max = max;
  s.default_text = std::move(default_text);
  return s;
}

LoadOptionSpec Count(std::string_view key, std::string_view flag, double max, std::string default_text,
                     std::string_view help) {
  LoadOptionSpec s = Number(key, flag, "", 0, false, max, std::move(default_text), help);
  s.type = OptionType::kCount;
  return s;
}

LoadOptionSpec Choice(std::string_view key, std::string_view flag, std::vector<std::string> choices,
                      std::string_view help) {
  LoadOptionSpec s = Switch(key, flag, help);
  s.type = OptionType::kChoice;
  s.default_text = choices.front();
  s.choices = std::move(choices);
  return s;
}

std::vector<LoadOptionSpec> MakeSchema() {
  return {
      Choice("unit", "--unit", UnitChoices(),
             "Unit of the file's coordinates (default: the unit the file declares, else m)"),
      Number("density", "--density", "kg/m^3", 0, true, kNoLimit, "1000", "Uniform density in kg/m^3"),
      Number("mass", "--mass", "kg", 0, true, kNoLimit, "", "Total mass in kg (sets the density; excludes density)"),
      Switch("repair", "--repair",
             "Repair with CGAL first: merge near-coincident vertices (1e-9 of the size), drop degenerate and "
             "duplicate faces, orient faces consistently, stitch borders, orient shells outward and cavities "
             "inward; what changed is reported"),
      Switch("allow_open", "--allow-open",
             "Compute even when the mesh is open or inconsistently oriented (with a warning)"),
      Switch("full_check", "--full-check",
             "Binary STL: weld the corners and count vertices, components and bad edges even when the streaming "
             "check finds the surface closed (slower)"),
      Switch("check_self_intersections", "--check-self-intersections",
             "Count pairs of faces that intersect (CGAL); a warning when there are any"),
      Switch("hull", "--hull",
             "Also the mass properties of the convex hull (CGAL), as collision engines see the body, at the same "
             "density (or mass), printed beside the exact ones"),
      Switch("exact", "--exact",
             "Certified results: exact rational integration of the stored coordinates (GMP); every number "
             "correctly rounded, principal moments as enclosures, the default path's difference shown"),
      Switch("parts", "--parts",
             "Each part the file names (OBJ objects or groups; glTF, 3MF, COLLADA, FBX nodes; CAD solids) on its "
             "own, and the whole as their composition"),
      Choice("path", "--path", {"auto", "triangles", "polygons"},
             "Integration path (auto: triangles, and Mirtich's polygons for quads and n-gons)"),
      Choice("reader", "--reader", {"auto", "assimp"},
             "Mesh reader (auto: our own readers for OBJ/STL/PLY/OFF, assimp for the rest; assimp: assimp for "
             "every format, with 32-bit coordinates, for comparison)"),
      Number("deflection", "--deflection", "file unit", 0, true, kNoLimit, "",
             "CAD files (STEP, IGES, BREP): the tessellation's chordal deflection, in the file's unit (default: "
             "relative_deflection times each part's bounding-box diagonal)"),
      Number("relative_deflection", "--relative-deflection", "", 1e-6, false, 0.5, "",
             "CAD files: the chordal deflection as a fraction of each part's diagonal (default: 1e-3 when the "
             "exact B-rep is the answer and the mesh its check, 1e-4 when the mesh is the answer)"),
      Number("angular_deflection", "--angular-deflection", "rad", 1e-3, false, 3.14159, "0.5",
             "CAD files: the largest angle in radians between the normals of neighbouring triangles"),
      Count("interference_pairs", "--interference-pairs", 1e6, "100",
            "CAD files: how many pairs of solids whose boxes overlap get their exact common volume measured "
            "(0: none)"),
      Count("threads", "--threads", 4096, "0", "Worker threads (0 = all cores); the same bits for any count"),
  };
}

std::string G(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string Said(const OptionValue& v) {
  if (const auto* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  if (const auto* d = std::get_if<double>(&v)) return G(*d);
  if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  return "'" + std::get<std::string>(v) + "'";
}

// The value as the spec's type, or the problem.
std::variant<OptionValue, std::string> Typed(const LoadOptionSpec& spec, const OptionValue& value) {
  switch (spec.type) {
    case OptionType::kSwitch:
      if (std::holds_alternative<bool>(value)) return value;
      return "must be true or false, got " + Said(value);
    case OptionType::kChoice:
      if (std::holds_alternative<std::string>(value)) return value;
      return "must be a name, got " + Said(value);
    case OptionType::kCount:
      if (const auto* d = std::get_if<double>(&value); d && std::floor(*d) == *d && std::abs(*d) < 9e15)
        return OptionValue(static_cast<std::int64_t>(*d));
      if (std::holds_alternative<std::int64_t>(value)) return value;
      return "must be a whole number, got " + Said(value);
    case OptionType::kNumber:
      if (const auto* i = std::get_if<std::int64_t>(&value)) return OptionValue(static_cast<double>(*i));
      if (std::holds_alternative<double>(value)) return value;
      return "must be a number, got " + Said(value);
  }
  return std::string("has an unknown type");
}

std::optional<std::string> CheckRange(const LoadOptionSpec& spec, double x, const OptionValue& value) {
  if (!std::isfinite(x)) return "must be a finite number, got " + Said(value);
  const bool low = spec.min_open ? !(x > spec.min) : !(x >= spec.min);
  if (low || x > spec.max) return "must be " + RangeText(spec) + ", got " + Said(value);
  return std::nullopt;
}

std::optional<std::string> CheckChoice(const LoadOptionSpec& spec, const std::string& name) {
  for (const std::string& c : spec.choices)
    if (c == name) return std::nullopt;
  std::string list;
  for (std::size_t i = 0; i < spec.choices.size(); ++i)
    list += (i == 0 ? "" : i + 1 == spec.choices.size() ? " or " : ", ") + spec.choices[i];
  return "must be " + list + ", got '" + name + "'";
}

// Writes a checked value into the options.
void Apply(LoadOptions& o, std::string_view key, const OptionValue& v) {
  const auto flag = [&] { return std::get<bool>(v); };
  const auto number = [&] { return std::get<double>(v); };
  const auto name = [&] { return std::get<std::string>(v); };
  if (key == "unit") {
    o.unit = ParseLengthUnit(name());
    o.unit_stated = true;
  } else if (key == "density" || key == "mass") {
    o.mass = key == "mass" ? MassSpec(TotalMass{number()}) : MassSpec(Density{number()});
    o.mass_stated = true;
  } else if (key == "repair") {
    o.repair = flag();
  } else if (key == "allow_open") {
    o.allow_open = flag();
  } else if (key == "full_check") {
    o.full_check = flag();
  } else if (key == "check_self_intersections") {
    o.check_self_intersections = flag();
  } else if (key == "hull") {
    o.hull = flag();
  } else if (key == "exact") {
    o.exact = flag();
  } else if (key == "parts") {
    o.parts = flag();
  } else if (key == "path") {
    o.path = name() == "triangles"  ? IntegrationPath::kTriangles
             : name() == "polygons" ? IntegrationPath::kPolygons
                                    : IntegrationPath::kAuto;
  } else if (key == "reader") {
    o.reader = name() == "assimp" ? Reader::kAssimp : Reader::kAuto;
  } else if (key == "deflection") {
    o.cad.deflection = number();
  } else if (key == "relative_deflection") {
    o.cad.relative_deflection = number();
  } else if (key == "angular_deflection") {
    o.cad.angular_deflection = number();
  } else if (key == "interference_pairs") {
    o.cad.interference_pairs = static_cast<int>(std::get<std::int64_t>(v));
  } else if (key == "threads") {
    o.num_threads = static_cast<int>(std::get<std::int64_t>(v));
  }
}

}  // namespace

const std::vector<LoadOptionSpec>& LoadOptionSchema() {
  static const std::vector<LoadOptionSpec> kSchema = MakeSchema();
  return kSchema;
}

const LoadOptionSpec* FindLoadOption(std::string_view key) {
  for (const LoadOptionSpec& s : LoadOptionSchema())
    if (s.key == key) return &s;
  return nullptr;
}

std::string RangeText(const LoadOptionSpec& spec) {
  if (spec.max == kNoLimit) return (spec.min_open ? "> " : ">= ") + G(spec.min);
  return "between " + G(spec.min) + " and " + G(spec.max);
}

std::optional<OptionValue> ReadOptionText(const LoadOptionSpec& spec, const std::string& text, std::string& problem) {
  if (spec.type == OptionType::kChoice) return OptionValue(text);
  if (spec.type == OptionType::kSwitch) {
    if (text == "true" || text == "1") return OptionValue(true);
    if (text == "false" || text == "0") return OptionValue(false);
    problem = "must be true or false, got '" + text + "'";
    return std::nullopt;
  }
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin || *end != '\0') {
    problem = "must be a number, got '" + text + "'";
    return std::nullopt;
  }
  return OptionValue(v);
}

std::optional<std::string> SetLoadOption(LoadOptions& options, const LoadOptionSpec& spec, const OptionValue& value) {
  auto typed = Typed(spec, value);
  if (const auto* problem = std::get_if<std::string>(&typed)) return *problem;
  const OptionValue& v = std::get<OptionValue>(typed);
  if (spec.type == OptionType::kNumber) {
    if (auto p = CheckRange(spec, std::get<double>(v), value)) return p;
  } else if (spec.type == OptionType::kCount) {
    if (auto p = CheckRange(spec, static_cast<double>(std::get<std::int64_t>(v)), value)) return p;
  } else if (spec.type == OptionType::kChoice) {
    if (auto p = CheckChoice(spec, std::get<std::string>(v))) return p;
  }
  if ((spec.key == "density" || spec.key == "mass") && options.mass_stated) {
    const bool was_mass = std::holds_alternative<TotalMass>(options.mass);
    if (was_mass != (spec.key == "mass")) {
      return "cannot be given with " + std::string(was_mass ? "mass" : "density") + " (give density or mass, not both)";
    }
  }
  Apply(options, spec.key, v);
  return std::nullopt;
}

}  // namespace massprops
