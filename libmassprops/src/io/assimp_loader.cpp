// Loads the assimp plugin (libmassprops_assimp.so) on first use and reads files through it, in a
// child process with a time limit: assimp can crash or loop on malformed files (Debian's 5.2 hangs
// on a PLY header cut short and segfaults on some 3MF files), and neither may take the program down.

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "io/io_internal.h"
#include "io/plugins.h"
#include "io/text_tokens.h"
#include "io/wire.h"

namespace massprops {
namespace {

using CanReadFn = int (*)(const char*);
using ReadFn = int (*)(const char*, double**, std::size_t*, int**, int**, std::size_t*, char**, std::size_t*, char*,
                       std::size_t);
using FreeFn = void (*)(void*);

struct Plugin {
  CanReadFn can_read = nullptr;
  ReadFn read = nullptr;
  FreeFn free = nullptr;
  std::string error;  // why it could not be loaded
  bool loaded() const { return error.empty(); }
};

const Plugin& LoadPlugin() {
  static const Plugin plugin = [] {
    Plugin p;
#ifndef MASSPROPS_WITH_ASSIMP
    p.error =
        "this build of massprops was configured without assimp (MASSPROPS_WITH_ASSIMP=OFF): only "
        "OBJ, STL, PLY and OFF can be read";
    return p;
#endif
    const plugins::Module m =
        plugins::LoadModule({"the assimp plugin (libmassprops_assimp.so)",
                             plugins::ModuleCandidates("libmassprops_assimp.so", "MASSPROPS_ASSIMP_PLUGIN"),
                             "set MASSPROPS_ASSIMP_PLUGIN to its path",
                             {"massprops_assimp_can_read", "massprops_assimp_read_parts", "massprops_assimp_free"}});
    p.error = m.error;
    if (m.loaded()) {
      p.can_read = reinterpret_cast<CanReadFn>(m.entries[0]);
      p.read = reinterpret_cast<ReadFn>(m.entries[1]);
      p.free = reinterpret_cast<FreeFn>(m.entries[2]);
    }
    return p;
  }();
  return plugin;
}

}  // namespace

bool AssimpCanRead(const std::string& extension) {
  const Plugin& p = LoadPlugin();
  return p.loaded() && p.can_read(extension.c_str()) != 0;
}

namespace {

// What the reader child sends back through its pipe.
struct AssimpOutput {
  std::vector<double> xyz;
  std::vector<int> face_sizes;
  std::vector<int> face_parts;
  std::vector<std::string> part_names;
};

// The child's work: reads the file through the plugin and returns, in wire.h's layout, its status
// and then the message or the corners (xyz), faces (sizes, parts) and part names.
std::string ReadInChild(const Plugin& p, const std::string& path) {
  double* xyz = nullptr;
  int* sizes = nullptr;
  int* parts = nullptr;
  char* names = nullptr;
  std::size_t corners = 0, faces = 0, names_size = 0;
  char error[512] = {};
  const int status =
      p.read(path.c_str(), &xyz, &corners, &sizes, &parts, &faces, &names, &names_size, error, sizeof error);
  wire::Writer w;
  w.U64(status != 0 ? 1 : 0);
  if (status != 0) {
    w.Str(error);
    return std::move(w.bytes());
  }
  w.U64(corners);
  w.F64s(xyz, 3 * corners);
  w.U64(faces);
  w.I32s(sizes, faces);
  w.I32s(parts, faces);
  w.Str(std::string_view(names, names_size));
  return std::move(w.bytes());
}

// Runs the plugin in a child process, so that a crash or a hang inside assimp becomes this file's
// error and the program (and its other files) goes on. 10 s plus 1 s per MB of file (assimp reads
// tens of MB a second on the slowest formats): a cut-short or looping file answers in seconds, a
// 500 MB scan still has minutes.
AssimpOutput ReadIsolated(const Plugin& p, const std::string& path) {
  const std::string data =
      plugins::ReadIsolated(path, "assimp", plugins::TimeLimitSeconds(path, "MASSPROPS_ASSIMP_TIMEOUT", 10.0, 1.0),
                            "MASSPROPS_ASSIMP_TIMEOUT", [&] { return ReadInChild(p, path); });
  AssimpOutput out;
  std::string names;
  try {
    wire::Reader r(data);
    if (r.U64() != 0) Fail(path, r.Str());
    const std::uint64_t corners = r.U64();
    if (corners > r.Left() / 3) throw wire::Truncated();
    r.F64s(3 * corners, out.xyz);
    const std::uint64_t faces = r.U64();
    r.I32s(faces, out.face_sizes);
    r.I32s(faces, out.face_parts);
    names = r.Str();
  } catch (const wire::Truncated&) {
    Fail(path, "the assimp reader process sent a truncated result");
  }
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

LoadedMesh ReadWithAssimp(const std::string& path, int num_threads) {
  const Plugin& p = LoadPlugin();
  if (!p.loaded()) Fail(path, p.error);
  const AssimpOutput read = ReadIsolated(p, path);
  if (read.face_sizes.empty()) Fail(path, "no faces found (the file holds no surface mesh)");
  LoadedMesh out = WeldCorners(path, read.xyz, &read.face_sizes, "assimp", num_threads);
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

LoadedMesh ReadMeshFileWithAssimp(const std::string& path, int num_threads) {
  return ReadWithAssimp(path, num_threads);
}

std::string AssimpPluginStatus() {
  const Plugin& p = LoadPlugin();
  return p.error;
}

}  // namespace massprops
