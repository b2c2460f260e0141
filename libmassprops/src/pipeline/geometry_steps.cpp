// Reaching massprops::repair's steps from the pipeline without linking it (geometry_steps.h).

#include "pipeline/geometry_steps_internal.h"

#include <cstdlib>
#include <string>
#include <vector>

#include "io/plugins.h"

namespace massprops {
namespace {

using TableFn = const GeometrySteps* (*)();

struct Found {
  const GeometrySteps* steps = nullptr;
  std::string error;
};

// Linked into the program already (directly or through another library), or beside this library.
const Found& Find() {
  static const Found found = [] {
    Found f;
    const char* name = "libmassprops_repair.so";
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("MASSPROPS_REPAIR_LIBRARY")) candidates.emplace_back(env);
    candidates.push_back(plugins::HomeDir() + "/" + name);
    candidates.emplace_back(name);  // the library search path
    const plugins::Module m = plugins::LoadModule({"massprops::repair (" + std::string(name) + ", CGAL)",
                                                   candidates,
                                                   "link massprops::repair or set MASSPROPS_REPAIR_LIBRARY to its path",
                                                   {"massprops_geometry_steps"},
                                                   /*program_first=*/true});
    if (!m.loaded()) {
      f.error = m.error;
      return f;
    }
    const GeometrySteps* steps = reinterpret_cast<TableFn>(m.entries[0])();
    if (steps == nullptr || steps->version != GeometrySteps::kVersion) {
      f.error = "massprops::repair does not match this massprops::io (a mismatched build?)";
      return f;
    }
    f.steps = steps;
    return f;
  }();
  return found;
}

}  // namespace

const GeometrySteps& RequireGeometrySteps(const std::string& what) {
  const Found& f = Find();
  if (f.steps == nullptr) throw std::runtime_error(what + " needs " + f.error);
  return *f.steps;
}

}  // namespace massprops
