// Loads the assimp plugin (libmassprops_assimp.so) on first use and reads files through it.

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "io_internal.h"

namespace massprops {
namespace {

using CanReadFn = int (*)(const char*);
using ReadFn = int (*)(const char*, double**, std::size_t*, int**, std::size_t*, char*, std::size_t);
using FreeFn = void (*)(void*);

struct Plugin {
  void* handle = nullptr;
  CanReadFn can_read = nullptr;
  ReadFn read = nullptr;
  FreeFn free = nullptr;
  std::string error;  // why it could not be loaded
};

// The folder of the file this code was loaded from: the shared library, or the program a
// static library is linked into (its realpath, so a symlink in /usr/local/bin still leads home).
std::string HomeDir() {
  Dl_info info{};
  std::string file;
  if (::dladdr(reinterpret_cast<void*>(&HomeDir), &info) != 0 && info.dli_fname != nullptr) {
    file = info.dli_fname;
  }
  if (file.empty() || file.find('/') == std::string::npos) file = "/proc/self/exe";
  std::vector<char> buf(4096);
  if (char* real = ::realpath(file.c_str(), buf.data())) file = real;
  const auto slash = file.find_last_of('/');
  return slash == std::string::npos ? "." : file.substr(0, slash);
}

const Plugin& LoadPlugin() {
  static Plugin plugin;
  static std::once_flag once;
  std::call_once(once, [] {
    const char* name = "libmassprops_assimp.so";
    std::vector<std::string> candidates;
#ifndef MASSPROPS_WITH_ASSIMP
    plugin.error = "this build of massprops was configured without assimp (MASSPROPS_WITH_ASSIMP=OFF): only "
                   "OBJ, STL, PLY and OFF can be read";
    return;
#else
    // The environment overrides; then beside the library (a shared libmassprops_io in lib/ has
    // the plugin in lib/massprops/), the install layout seen from bin/, and this build tree.
    if (const char* env = std::getenv("MASSPROPS_ASSIMP_PLUGIN")) candidates.emplace_back(env);
    const std::string dir = HomeDir();
    candidates.push_back(dir + "/massprops/" + name);
    candidates.push_back(dir + "/" + MASSPROPS_PLUGIN_FROM_BINDIR + "/" + name);
    candidates.push_back(dir + "/" + name);
    // The build tree's plugin, only for programs of this build tree (an installed or copied
    // binary must find its own, or say that it cannot).
    if (dir.rfind(MASSPROPS_BUILD_DIR, 0) == 0) {
      candidates.push_back(std::string(MASSPROPS_PLUGIN_BUILD_DIR) + "/" + name);
    }
#endif
    candidates.emplace_back(name);  // the library search path
    std::string tried;
    for (const std::string& c : candidates) {
      plugin.handle = ::dlopen(c.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (plugin.handle != nullptr) break;
      tried += (tried.empty() ? "" : ", ") + c;
    }
    if (plugin.handle == nullptr) {
      plugin.error = "the assimp plugin (" + std::string(name) + ") was not found (tried " + tried +
                     "; set MASSPROPS_ASSIMP_PLUGIN to its path)";
      return;
    }
    plugin.can_read = reinterpret_cast<CanReadFn>(::dlsym(plugin.handle, "massprops_assimp_can_read"));
    plugin.read = reinterpret_cast<ReadFn>(::dlsym(plugin.handle, "massprops_assimp_read"));
    plugin.free = reinterpret_cast<FreeFn>(::dlsym(plugin.handle, "massprops_assimp_free"));
    if (!plugin.can_read || !plugin.read || !plugin.free) {
      plugin.error = "the assimp plugin lacks its entry points (a mismatched build?)";
      plugin.handle = nullptr;
    }
  });
  return plugin;
}

}  // namespace

bool AssimpCanRead(const std::string& extension) {
  const Plugin& p = LoadPlugin();
  return p.handle != nullptr && p.can_read(extension.c_str()) != 0;
}

LoadedMesh ReadWithAssimp(const std::string& path) {
  const Plugin& p = LoadPlugin();
  if (p.handle == nullptr) Fail(path, p.error);
  double* xyz = nullptr;
  int* sizes = nullptr;
  std::size_t corners = 0, faces = 0;
  char error[512] = {};
  if (p.read(path.c_str(), &xyz, &corners, &sizes, &faces, error, sizeof error) != 0) {
    Fail(path, error);
  }
  std::unique_ptr<double, FreeFn> own_xyz(xyz, p.free);
  std::unique_ptr<int, FreeFn> own_sizes(sizes, p.free);
  if (faces == 0) Fail(path, "no faces found (the file holds no surface mesh)");
  const std::vector<double> coords(xyz, xyz + 3 * corners);
  const std::vector<int> face_sizes(sizes, sizes + faces);
  LoadedMesh out = WeldCorners(path, coords, face_sizes, "assimp");
  out.format = "assimp:" + path.substr(path.find_last_of('.') + 1);
  out.float32_coordinates = true;
  return out;
}

LoadedMesh ReadMeshFileWithAssimp(const std::string& path) { return ReadWithAssimp(path); }

std::string AssimpPluginStatus() {
  const Plugin& p = LoadPlugin();
  return p.handle != nullptr ? "" : p.error;
}

}  // namespace massprops
