// Reaching massprops::repair's steps from the pipeline without linking it (geometry_steps.h).

#include "geometry_steps_internal.h"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <string>
#include <vector>

#include "plugins.h"

namespace massprops {
namespace {

using TableFn = const GeometrySteps* (*)();

struct Found {
  const GeometrySteps* steps = nullptr;
  std::string error;
};

const Found& Find() {
  static Found found;
  static std::once_flag once;
  std::call_once(once, [] {
    // Linked into the program already (directly or through another library)?
    auto table = reinterpret_cast<TableFn>(::dlsym(RTLD_DEFAULT, "massprops_geometry_steps"));
    if (table == nullptr) {
      const char* name = "libmassprops_repair.so";
      std::vector<std::string> candidates;
      if (const char* env = std::getenv("MASSPROPS_REPAIR_LIBRARY")) candidates.emplace_back(env);
      candidates.push_back(plugins::HomeDir() + "/" + name);
      candidates.emplace_back(name);  // the library search path
      std::string tried;
      void* handle = plugins::Open(candidates, tried);
      if (handle == nullptr) {
        found.error = "massprops::repair (" + std::string(name) + ", CGAL) was not found (" + tried +
                      "; link massprops::repair or set MASSPROPS_REPAIR_LIBRARY to its path)";
        return;
      }
      table = reinterpret_cast<TableFn>(::dlsym(handle, "massprops_geometry_steps"));
    }
    const GeometrySteps* steps = table != nullptr ? table() : nullptr;
    if (steps == nullptr || steps->version != GeometrySteps::kVersion) {
      found.error = "massprops::repair does not match this massprops::io (a mismatched build?)";
      return;
    }
    found.steps = steps;
  });
  return found;
}

}  // namespace

const GeometrySteps& RequireGeometrySteps(const std::string& what) {
  const Found& f = Find();
  if (f.steps == nullptr) throw std::runtime_error(what + " needs " + f.error);
  return *f.steps;
}

}  // namespace massprops
