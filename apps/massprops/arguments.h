#pragma once
// The options that `massprops` and `massprops batch` share: the flags, and what they become
// (LoadOptions). The rules about which options go together are the library's
// (massprops::FindOptionConflict), worded here as flags; only the rules about flags that have no
// LoadOptions field (--implicit, the sampling flags, --density beside --shell) are the command's.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "load_flags.h"
#include "massprops/io/load.h"
#include "massprops/monte_carlo.h"

namespace massprops::cli {

// What the command line says, before it becomes typed options.
struct Arguments {
  std::vector<std::string> files;
  /// The load options (--unit, --density, --mass, --repair, --threads, ...: the schema's flags).
  std::unique_ptr<app::LoadFlags> load;
  std::string format = "table";
  std::string frame = "com";
  std::string output;
  bool quiet = false;
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
  std::vector<double> about;       // a point, in the file's unit and axes
  std::vector<double> axes;        // 9 numbers, rows of the rotation whose columns are the axes
  std::vector<double> axes_euler;  // yaw, pitch, roll in degrees (z, y', x'')
  std::string output_units;
  std::string density_map;
  bool brep = false;         // kept, as a no-op: the exact B-rep is the answer by default
  bool tessellated = false;  // CAD files: the mesh is the answer
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
