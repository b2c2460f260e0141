#pragma once
// The options that `massprops` and `massprops batch` share: the flags, and what they become
// (LoadOptions). The rules about which options go together are the library's
// (massprops::FindOptionConflict), worded here as flags; only the rules about flags that have no
// LoadOptions field (--implicit, the sampling flags, --density beside --shell) are the command's.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "massprops/io/load.h"
#include "massprops/monte_carlo.h"

namespace massprops::cli {

// What the command line says, before it becomes typed options.
struct Arguments {
  std::vector<std::string> files;
  double density = 1000.0;
  double mass = 0.0;
  std::string unit = "m";
  std::string path = "auto";
  std::string format = "table";
  std::string frame = "com";
  std::string output;
  int threads = 0;
  bool quiet = false;
  bool allow_open = false;
  bool full_check = false;
  bool repair = false;
  bool check_self_intersections = false;
  bool hull = false;
  bool exact = false;
  bool shell = false;
  double area_density = 0.0;
  double wall = 0.0;
  std::string implicit;
  bool winding_number = false;
  bool mc = false;
  double samples = 1 << 20;
  int randomizations = 16;
  std::uint64_t seed = 1;
  double tolerance = 0;
  std::string reader = "auto";
  std::vector<double> about;       // a point, in the file's unit and axes
  std::vector<double> axes;        // 9 numbers, rows of the rotation whose columns are the axes
  std::vector<double> axes_euler;  // yaw, pitch, roll in degrees (z, y', x'')
  std::string output_units;
  bool parts = false;
  std::string density_map;
  double deflection = 0;           // CAD files: chordal, in the file's unit; 0: relative to each part's size
  double relative_deflection = 0;  // 0: 1e-3 when the B-rep is the answer, 1e-4 when the mesh is
  double angular_deflection = 0.5;
  bool brep = false;         // kept, as a no-op: the exact B-rep is the answer by default
  bool tessellated = false;  // CAD files: the mesh is the answer
  int interference_pairs = 100;
};

/// The value of a name that CLI11's IsMember admitted.
template <typename T>
T FromName(const std::map<std::string, T>& names, const std::string& name) {
  return names.at(name);
}

/// Declares the shared flags on `app`, bound to `a`.
void AddArguments(CLI::App& app, Arguments& a);

/// The sampling the flags ask for (--mc, --samples, ...).
MonteCarloOptions Sampling(const Arguments& a);

/// The typed options (without part masses, which need the density map read).
LoadOptions ToLoadOptions(const Arguments& a, const CLI::App& app);

/// The first argument error (a message for stderr, exit 2), or none; -o is checked too (a
/// regular file, not one of the inputs).
std::optional<std::string> CheckArguments(const Arguments& a, const CLI::App& app);

}  // namespace massprops::cli
