#pragma once
// Shared pieces of the mesh readers.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "massprops/io/mesh_io.h"

namespace massprops {

/// Opens a regular file for reading (never blocks on a FIFO); the descriptor is the caller's.
/// Throws MeshFileError for a missing file or one that is not regular.
int OpenRegularFile(const std::string& path);

/// A read-only memory map of a whole file (POSIX). Throws MeshFileError for a missing or empty file.
class MappedFile {
 public:
  explicit MappedFile(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const unsigned char* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  const unsigned char* data_ = nullptr;
  std::size_t size_ = 0;
};

struct StlLayout {
  bool ascii = false;
  std::uint32_t triangles = 0;  // binary: records
  std::size_t trailing_bytes = 0;
};

/// Binary or ASCII, from the content (not the "solid" keyword). Throws for a truncated binary.
StlLayout DetectStl(const std::string& path, const unsigned char* data, std::size_t size);

[[noreturn]] void Fail(const std::string& path, const std::string& what);
/// As Fail, for a file that cannot be opened or read at all (FileAccessError).
[[noreturn]] void FailAccess(const std::string& path, const std::string& what);

/// Welds corners given one by one (xyz per corner); `face_sizes` gives each face's corner count
/// in order (null: every face a triangle). (num_threads, here and below: as
/// LoadOptions::num_threads, 0 every core; the same bits for any.)
LoadedMesh WeldCorners(const std::string& path, const std::vector<double>& xyz, const std::vector<int>* face_sizes,
                       const char* format, int num_threads = 0);

/// Points the corners of vertices with bit-identical positions (-0.0 == 0.0) at the first such
/// vertex (the others stay, unreferenced), so that a file repeating each corner per face is
/// checked as the surface it describes. Returns how many vertices were merged.
std::int64_t MergeCoincidentVertices(PolygonMesh& mesh, int num_threads = 0);

// One parser per format, each in its own file (mesh_io.cpp holds the table).
LoadedMesh ParseObj(const std::string& path, std::string_view data, int num_threads);
LoadedMesh ParseStl(const std::string& path, std::string_view data, int num_threads);
LoadedMesh ParsePly(const std::string& path, std::string_view data, int num_threads);
LoadedMesh ParseOff(const std::string& path, std::string_view data, int num_threads);
LoadedMesh Parse3mf(const std::string& path, std::string_view data, int num_threads);

/// The length unit a 3MF or AMF unit attribute names ("millimeter", "inch", ...), if it is one.
std::optional<LengthUnit> ModelUnitNamed(const std::string& word);

/// The unit a 3MF or AMF file declares (their default, millimetres, when they declare none), with
/// the file's word for it; nothing for other formats or a package that cannot be read.
struct DeclaredUnitInfo {
  LengthUnit unit;
  std::string name;
};
std::optional<DeclaredUnitInfo> ReadDeclaredUnit(const std::string& path, const std::string& extension);

/// Empty when the assimp plugin is loaded; otherwise why it is not (where it was looked for).
std::string AssimpPluginStatus();
/// True when assimp has an importer for this (lower-case) extension.
bool AssimpCanRead(const std::string& extension);
/// Reads any format assimp knows; node transforms are applied, all meshes are merged, corners
/// welded by position. Debian's assimp stores coordinates as 32-bit floats: LoadedMesh says so.
LoadedMesh ReadWithAssimp(const std::string& path, int num_threads);

/// Reads a STEP, IGES or BREP file through the CAD plugin (cad_loader.cpp): each part's triangles,
/// its B-rep integrals and material, the file's unit.
LoadedMesh ReadCadFile(const std::string& path, const CadOptions& cad);

}  // namespace massprops
