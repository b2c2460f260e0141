// The readers behind one table: our own parsers by extension, OpenCASCADE (a plugin) for CAD files,
// assimp (a plugin) for the rest.

#include <string>
#include <string_view>

#include "io/io_internal.h"
#include "io/text_tokens.h"

namespace massprops {
namespace {

struct ReaderEntry {
  const char* extension;
  LoadedMesh (*parse)(const std::string& name, std::string_view bytes, int num_threads);
};

// Our own parsers (double precision): one row per format.
constexpr ReaderEntry kReaders[] = {
    {"obj", ParseObj}, {"stl", ParseStl}, {"ply", ParsePly}, {"off", ParseOff}, {"3mf", Parse3mf},
};

const ReaderEntry* FindReader(const std::string& extension) {
  for (const ReaderEntry& r : kReaders) {
    if (extension == r.extension) return &r;
  }
  return nullptr;
}

}  // namespace

LoadedMesh ParseMeshBuffer(const std::string& name, const std::string& extension, std::string_view bytes,
                           int num_threads) {
  const std::string ext = io_text::Lower(extension);
  if (const ReaderEntry* r = FindReader(ext)) {
    LoadedMesh out = r->parse(name, bytes, num_threads);
    // Indexed formats may still repeat a position under several indices (one per face):
    // weld them as the STL and assimp readers do.
    if (ext != "stl") out.welded += MergeCoincidentVertices(out.mesh, num_threads);
    return out;
  }
  Fail(name, "no parser of our own for '" + ext + "' (formats read through assimp need a file)");
}

bool HasOwnReader(const std::string& path) {
  const std::string ext = io_text::FileExtension(path);
  return !ext.empty() && FindReader(ext) != nullptr;
}

bool IsMeshFile(const std::string& path) {
  const std::string ext = io_text::FileExtension(path);
  if (ext.empty()) return false;
  return FindReader(ext) != nullptr || IsCadFile(path) || AssimpCanRead(ext);
}

LoadedMesh ReadMeshFile(const std::string& path) { return ReadMeshFile(path, CadOptions{}); }

LoadedMesh ReadMeshFile(const std::string& path, const CadOptions& cad) {
  const std::string ext = io_text::FileExtension(path);
  if (FindReader(ext)) {
    const MappedFile file(path);
    return ParseMeshBuffer(path, ext, std::string_view(reinterpret_cast<const char*>(file.data()), file.size()),
                           cad.num_threads);
  }
  if (IsCadFile(path)) return ReadCadFile(path, cad);
  if (AssimpCanRead(ext)) return ReadWithAssimp(path, cad.num_threads);
  const std::string plugin = AssimpPluginStatus();
  if (!plugin.empty()) {
    Fail(path,
         "cannot read '" + ext + "' files: our own readers take OBJ, STL, PLY and OFF, and for the rest " + plugin);
  }
  Fail(path, "unknown mesh format '" + ext + "' (neither our readers nor assimp know it)");
}

[[noreturn]] void Fail(const std::string& path, const std::string& what) { throw MeshFileError(path + ": " + what); }
[[noreturn]] void FailAccess(const std::string& path, const std::string& what) {
  throw FileAccessError(path + ": " + what);
}

}  // namespace massprops
