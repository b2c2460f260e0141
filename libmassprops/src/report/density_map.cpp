// The definitions of massprops/report/density_map.h: the file behind `--density-map`.

#include "massprops/report/density_map.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace massprops::report {
namespace {

using Json = nlohmann::ordered_json;

[[noreturn]] void Fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("--density-map " + path + ": " + what);
}

MassSpec Checked(const std::string& path, const std::string& where, const char* kind, double v) {
  if (!(std::isfinite(v) && v > 0)) Fail(path, where + ": the " + kind + " must be a finite, positive number");
  if (std::string(kind) == "mass") return TotalMass{v};
  return Density{v};
}

std::vector<PartMass> FromJson(const std::string& path, const std::string& text) {
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::parse_error& e) {
    Fail(path, std::string("not valid JSON (") + e.what() + ")");
  }
  if (!j.is_object()) Fail(path, "expected an object {\"part or pattern\": density or {\"mass\": kg}, ...}");
  std::vector<PartMass> map;
  for (const auto& [key, value] : j.items()) {
    const std::string where = "entry '" + key + "'";
    if (key.empty()) Fail(path, "an entry has an empty name");
    if (value.is_number()) {
      map.push_back({key, Checked(path, where, "density", value.get<double>())});
    } else if (value.is_object() && value.size() == 1 && (value.contains("density") || value.contains("mass")) &&
               value.begin().value().is_number()) {
      const bool mass = value.contains("mass");
      map.push_back({key, Checked(path, where, mass ? "mass" : "density", value.begin().value().get<double>())});
    } else {
      Fail(path, where + ": expected a density (kg/m^3) or {\"density\": kg/m^3} or {\"mass\": kg}");
    }
  }
  if (map.empty()) Fail(path, "no entries");
  return map;
}

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        cells.back() += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        cells.back() += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      cells.emplace_back();
    } else if (ch != '\r') {
      cells.back() += ch;
    }
  }
  for (std::string& c : cells) {
    while (!c.empty() && (c.back() == ' ' || c.back() == '\t')) c.pop_back();
    c.erase(0, c.find_first_not_of(" \t"));
  }
  return cells;
}

std::vector<PartMass> FromCsv(const std::string& path, const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::size_t number = 0;
  int part_col = -1, density_col = -1, mass_col = -1;
  std::vector<PartMass> map;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = "line " + std::to_string(number);
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    const std::vector<std::string> cells = SplitCsv(line);
    if (part_col < 0) {
      for (std::size_t c = 0; c < cells.size(); ++c) {
        if (cells[c] == "part") part_col = static_cast<int>(c);
        if (cells[c] == "density") density_col = static_cast<int>(c);
        if (cells[c] == "mass") mass_col = static_cast<int>(c);
      }
      if (part_col < 0 || (density_col < 0 && mass_col < 0)) {
        Fail(path, where + ": expected a header naming the columns part and density and/or mass");
      }
      continue;
    }
    auto cell = [&](int c) { return c >= 0 && static_cast<std::size_t>(c) < cells.size() ? cells[c] : std::string(); };
    const std::string name = cell(part_col), density = cell(density_col), mass = cell(mass_col);
    if (name.empty()) Fail(path, where + ": the part is empty");
    if (density.empty() == mass.empty()) Fail(path, where + ": give either a density or a mass for '" + name + "'");
    const std::string& value = density.empty() ? mass : density;
    double v = 0;
    char* end = nullptr;
    v = std::strtod(value.c_str(), &end);
    if (end != value.c_str() + value.size()) Fail(path, where + ": '" + value + "' is not a number");
    map.push_back({name, Checked(path, where, density.empty() ? "mass" : "density", v)});
  }
  if (map.empty()) Fail(path, "no entries");
  return map;
}

}  // namespace

std::vector<PartMass> ReadDensityMap(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) Fail(path, "not a regular file (or it does not exist)");
  std::ifstream file(path, std::ios::binary);
  if (!file) Fail(path, "cannot be opened");
  std::ostringstream buffer;
  buffer << file.rdbuf();
  const std::string text = buffer.str();
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) Fail(path, "the file is empty");
  return text[first] == '{' ? FromJson(path, text) : FromCsv(path, text);
}

}  // namespace massprops::report
