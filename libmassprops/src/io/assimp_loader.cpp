// Loads the assimp plugin (libmassprops_assimp.so) on first use and reads files through it, in a
// child process with a time limit: assimp can crash or loop on malformed files (Debian's 5.2 hangs
// on a PLY header cut short and segfaults on some 3MF files), and neither may take the program down.

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "io_internal.h"
#include "plugins.h"
#include "text_tokens.h"

namespace massprops {
namespace {

using CanReadFn = int (*)(const char*);
using ReadFn = int (*)(const char*, double**, std::size_t*, int**, int**, std::size_t*, char**, std::size_t*, char*,
                       std::size_t);
using FreeFn = void (*)(void*);

struct Plugin {
  void* handle = nullptr;
  CanReadFn can_read = nullptr;
  ReadFn read = nullptr;
  FreeFn free = nullptr;
  std::string error;  // why it could not be loaded
};

const Plugin& LoadPlugin() {
  static Plugin plugin;
  static std::once_flag once;
  std::call_once(once, [] {
    const char* name = "libmassprops_assimp.so";
#ifndef MASSPROPS_WITH_ASSIMP
    plugin.error =
        "this build of massprops was configured without assimp (MASSPROPS_WITH_ASSIMP=OFF): only "
        "OBJ, STL, PLY and OFF can be read";
    return;
#endif
    const std::vector<std::string> candidates = plugins::ModuleCandidates(name, "MASSPROPS_ASSIMP_PLUGIN");
    std::string tried;
    plugin.handle = plugins::Open(candidates, tried);
    if (plugin.handle == nullptr) {
      plugin.error = "the assimp plugin (" + std::string(name) + ") was not found (" + tried +
                     "; set MASSPROPS_ASSIMP_PLUGIN to its path)";
      return;
    }
    plugin.can_read = reinterpret_cast<CanReadFn>(::dlsym(plugin.handle, "massprops_assimp_can_read"));
    plugin.read = reinterpret_cast<ReadFn>(::dlsym(plugin.handle, "massprops_assimp_read_parts"));
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

namespace {

// What the reader child sends back through its pipe.
struct AssimpOutput {
  std::vector<double> xyz;
  std::vector<int> face_sizes;
  std::vector<int> face_parts;
  std::vector<std::string> part_names;
};

// The child's work: reads the file through the plugin and returns [status, message | corners,
// xyz, faces, sizes] for the parent, in this process's own layout.
std::string ReadInChild(const Plugin& p, const std::string& path) {
  double* xyz = nullptr;
  int* sizes = nullptr;
  int* parts = nullptr;
  char* names = nullptr;
  std::size_t corners = 0, faces = 0, names_size = 0;
  char error[512] = {};
  const std::int64_t status =
      p.read(path.c_str(), &xyz, &corners, &sizes, &parts, &faces, &names, &names_size, error, sizeof error);
  std::string out;
  auto put = [&out](const void* data, std::size_t n) { out.append(static_cast<const char*>(data), n); };
  put(&status, sizeof status);
  if (status != 0) {
    const std::uint64_t n = std::strlen(error);
    put(&n, sizeof n);
    put(error, n);
  } else {
    const std::uint64_t c = corners, f = faces;
    put(&c, sizeof c);
    put(xyz, 3 * corners * sizeof(double));
    put(&f, sizeof f);
    put(sizes, faces * sizeof(int));
    put(parts, faces * sizeof(int));
    const std::uint64_t n = names_size;
    put(&n, sizeof n);
    put(names, names_size);
  }
  return out;
}

// Runs the plugin in a child process, so that a crash or a hang inside assimp becomes this file's
// error and the program (and its other files) goes on. 10 s plus 1 s per MB of file (assimp reads
// tens of MB a second on the slowest formats): a cut-short or looping file answers in seconds, a
// 500 MB scan still has minutes.
AssimpOutput ReadIsolated(const Plugin& p, const std::string& path) {
  const std::string data =
      plugins::ReadIsolated(path, "assimp", plugins::TimeLimitSeconds(path, "MASSPROPS_ASSIMP_TIMEOUT", 10.0, 1.0),
                            "MASSPROPS_ASSIMP_TIMEOUT", "MASSPROPS_ASSIMP_FAULT", [&] { return ReadInChild(p, path); });
  // Decode: the child wrote it, in this process's own layout.
  std::size_t at = 0;
  auto take = [&](void* dest, std::size_t n) {
    if (data.size() - at < n) Fail(path, "the assimp reader process sent a truncated result");
    std::memcpy(dest, data.data() + at, n);
    at += n;
  };
  std::int64_t read_status = 0;
  take(&read_status, sizeof read_status);
  if (read_status != 0) {
    std::uint64_t n = 0;
    take(&n, sizeof n);
    std::string message(n, '\0');
    take(message.data(), n);
    Fail(path, message);
  }
  AssimpOutput out;
  std::uint64_t corners = 0, faces = 0;
  take(&corners, sizeof corners);
  if (corners > data.size() / (3 * sizeof(double))) Fail(path, "the assimp reader process sent a truncated result");
  out.xyz.resize(3 * corners);
  take(out.xyz.data(), out.xyz.size() * sizeof(double));
  take(&faces, sizeof faces);
  if (faces > data.size() / sizeof(int)) Fail(path, "the assimp reader process sent a truncated result");
  out.face_sizes.resize(faces);
  take(out.face_sizes.data(), faces * sizeof(int));
  out.face_parts.resize(faces);
  take(out.face_parts.data(), faces * sizeof(int));
  std::uint64_t names_size = 0;
  take(&names_size, sizeof names_size);
  if (names_size > data.size()) Fail(path, "the assimp reader process sent a truncated result");
  std::string names(names_size, '\0');
  take(names.data(), names_size);
  for (std::size_t at_name = 0; at_name < names.size();) {
    const std::size_t end = names.find('\0', at_name);
    if (end == std::string::npos) break;
    out.part_names.push_back(names.substr(at_name, end - at_name));
    at_name = end + 1;
  }
  for (int part : out.face_parts) {
    if (part < 0 || static_cast<std::size_t>(part) >= out.part_names.size()) {
      Fail(path, "the assimp reader process sent a malformed result");
    }
  }
  return out;
}

}  // namespace

LoadedMesh ReadWithAssimp(const std::string& path) {
  const Plugin& p = LoadPlugin();
  if (p.handle == nullptr) Fail(path, p.error);
  const AssimpOutput read = ReadIsolated(p, path);
  if (read.face_sizes.empty()) Fail(path, "no faces found (the file holds no surface mesh)");
  LoadedMesh out = WeldCorners(path, read.xyz, read.face_sizes, "assimp");
  const std::string ext = io_text::FileExtension(path);
  out.format = "assimp:" + ext;
  out.float32_coordinates = true;
  out.part_names = read.part_names;
  out.face_part.assign(read.face_parts.begin(), read.face_parts.end());
  if (const auto declared = ReadDeclaredUnit(path, ext)) {
    out.declared_unit = declared->unit;
    out.declared_unit_name = declared->name;
  } else if (ext == "gltf" || ext == "glb") {
    out.declared_unit = LengthUnit::kMetre;
    out.declared_unit_name = "metres (glTF's unit)";
  } else if (ext == "dae") {
    out.declared_unit = LengthUnit::kMetre;
    out.declared_unit_name = "metres (COLLADA's <unit>, applied by its reader)";
  }
  return out;
}

LoadedMesh ReadMeshFileWithAssimp(const std::string& path) { return ReadWithAssimp(path); }

std::string AssimpPluginStatus() {
  const Plugin& p = LoadPlugin();
  return p.handle != nullptr ? "" : p.error;
}

}  // namespace massprops
