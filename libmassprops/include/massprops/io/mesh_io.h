#pragma once
/// @file
/// Reading mesh files (target massprops::io). Coordinates are kept in double precision as
/// written in the file; nothing goes through 32-bit floats except binary STL, which stores them.

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "massprops/implicit.h"
#include "massprops/mesh.h"
#include "massprops/triangle_soup.h"
#include "massprops/units.h"

namespace massprops {

/// A file could not be read as a mesh. what() names the file and the fault.
class MeshFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The file itself could not be opened or read (missing, unreadable, not a regular file), as
/// opposed to content that is not a valid mesh. Bindings map it to the OS error type (OSError).
class FileAccessError : public MeshFileError {
 public:
  using MeshFileError::MeshFileError;
};

/// How a CAD file (STEP, IGES, BREP) is read: OpenCASCADE's exact B-rep, and its BRepMesh
/// tessellation per part (the check mesh, or the answer when the mesh is).
struct CadOptions {
  /// Chordal deflection (the largest distance between a triangle and the surface), in the file's
  /// unit; 0: `relative_deflection` times each part's bounding-box diagonal. Below 1e-6 of a
  /// part's diagonal it is refused (the triangles would not fit in memory).
  double deflection = 0;
  /// 0: chosen by the load (LoadSolid: 1e-3 when the exact B-rep is the answer and the mesh only
  /// its check, 1e-4 when the mesh is the answer).
  double relative_deflection = 0;
  double angular_deflection = 0.5;  ///< rad: the largest angle between neighbouring triangles' normals
  /// Interference: how many pairs of solids whose boxes overlap get their exact common volume
  /// (a count, so that the output does not depend on the machine's speed); 0: none.
  int interference_pairs = 100;
  /// Threads that mesh and integrate the parts (0: every core); the same triangles for any count.
  /// LoadSolid takes it from LoadOptions::num_threads.
  int num_threads = 0;
};

/// The validation properties a CAD file carries for a part (STEP's geometric validation
/// properties, written by the exporting system), in the file's unit, placed.
struct CadFileProperties {
  std::optional<double> volume;
  std::optional<Vector3> centroid;
  std::optional<double> area;
};

/// What a CAD reader knows about one part beyond its triangles.
struct CadPart {
  std::string material;  ///< the file's material name (STEP AP242), "" when it names none
  double density = 0;    ///< kg/m^3, from the file's material; 0: none
  bool solid = false;    ///< the part has solids (false: surfaces only, no exact volume)
  std::string instance;  ///< the assembly component's name, when it has its own ("bolt:2")
  /// The length unit the part's own representation declares, as the file names it ("INCH"),
  /// "" when not known; its coordinates are in the file's unit (LoadedMesh) all the same.
  std::string unit;
  /// The exact B-rep's integrals (OpenCASCADE's Gauss integration), unit density, in the file's
  /// unit and axes, the placement applied.
  VolumeIntegrals brep;
  double brep_area = 0;                  ///< the B-rep solids' surface area, file unit squared
  double brep_error = 0;                 ///< OpenCASCADE's estimate of their relative error
  double deflection = 0;                 ///< the chordal deflection its triangles were made with, file unit
  std::int64_t untessellated_faces = 0;  ///< B-rep faces OpenCASCADE made no triangles of (holes in the mesh)
  std::int64_t unwelded_edges = 0;       ///< B-rep edges whose two sides were meshed differently
  /// What was done to the B-rep to find its solids (sewing, shells made solids, turned outward).
  std::vector<std::string> fixes;
  CadFileProperties file;  ///< the exporting system's own numbers, when the file has them
};

/// Two CAD parts that share volume (interference), or two solids inside one part (a == b).
struct CadOverlap {
  std::size_t a = 0, b = 0;  ///< indices into LoadedMesh::cad_parts
  double volume = -1;        ///< the common volume, file unit cubed; -1: the boolean failed
};

/// The interference test of a CAD file's solids (after their numbers: a slow boolean cannot lose them).
struct CadInterference {
  bool done = false;             ///< false: the test did not finish (`not_done` says why)
  std::string not_done;          ///< why not
  std::uint64_t candidates = 0;  ///< pairs whose boxes overlap
  std::uint64_t measured = 0;    ///< of them, pairs whose common volume was computed (the budget)
  std::vector<CadOverlap> overlaps;
};

/// What was read, and how.
struct LoadedMesh {
  PolygonMesh mesh;         ///< faces as in the file (OBJ n-gons are kept whole)
  std::string format;       ///< "obj", "stl-binary" or "stl-ascii"
  std::int64_t welded = 0;  ///< corners merged because they had bit-identical positions
  /// True when the coordinates went through 32-bit floats (binary STL stores them so; Debian's
  /// assimp reads every format so): expect ~7 significant digits of the input, not 16.
  bool float32_coordinates = false;
  /// The unit the file declares for its coordinates (3MF, AMF; glTF is metres by its
  /// specification; COLLADA is converted to metres by its reader), and the file's word for it.
  std::optional<LengthUnit> declared_unit;
  std::string declared_unit_name;
  /// The parts the file names (OBJ objects, or groups when it has no objects; assimp's nodes),
  /// and the part of each face; both empty when the file names none.
  std::vector<std::string> part_names;
  std::vector<std::int32_t> face_part;
  /// CAD files: one entry per part (as part_names; one when the file names none).
  std::vector<CadPart> cad_parts;
  std::vector<std::string> cad_notes;  ///< CAD files: what was left out of the file, and why
  CadInterference cad_interference;    ///< CAD files: which solids share volume
};

/// Reads an OBJ (v/f records, n-gons, negative indices, several objects, `\` continuations) or an
/// STL (binary or ASCII, detected from the content, not the `solid` keyword) with our own parsers,
/// and every other format assimp knows (PLY, OFF, glTF/GLB, 3MF, COLLADA, ...) through assimp.
/// Corners with bit-identical positions are welded into shared vertices in every format
/// (-0.0 equals 0.0).
/// @throws MeshFileError for a missing, empty, truncated or malformed file, an unknown extension,
///         non-finite coordinates, or a face index out of range.
LoadedMesh ReadMeshFile(const std::string& path);

/// As ReadMeshFile, with the tessellation options for CAD files (STEP, IGES, BREP), which
/// OpenCASCADE reads in a child process with a time limit (a plugin, optional at build time);
/// `cad.num_threads` also bounds the threads of every other reader's parse and weld.
LoadedMesh ReadMeshFile(const std::string& path, const CadOptions& cad);

/// Whether `path` is a CAD file by its extension (.step, .stp, .iges, .igs, .brep, .brp).
bool IsCadFile(const std::string& path);

/// Parses a mesh held in memory with the readers of our own: `extension` is "obj", "stl", "ply",
/// "off" or "3mf"; `name` is used in messages. The same checks as ReadMeshFile. `num_threads`:
/// the threads the parse and the weld may use (0: every core; the same mesh for any count).
/// @throws MeshFileError as ReadMeshFile.
LoadedMesh ParseMeshBuffer(const std::string& name, const std::string& extension, std::string_view bytes,
                           int num_threads = 0);

/// Whether ReadMeshFile reads `path` with a reader of our own (OBJ, STL, PLY, OFF, by extension),
/// in this process; the other formats go through assimp in a child process.
bool HasOwnReader(const std::string& path);

/// Whether ReadMeshFile can read `path` at all, by its extension: a reader of our own, or one of
/// assimp's formats (asks the assimp plugin, loading it on first use).
bool IsMeshFile(const std::string& path);

/// Reads any format through assimp, even those with a reader of our own (for comparison); the
/// weld on up to `num_threads` threads (0: every core).
/// @throws MeshFileError as ReadMeshFile.
LoadedMesh ReadMeshFileWithAssimp(const std::string& path, int num_threads = 0);

/// The fast path for binary STL: memory-maps the file and integrates its records as they lie
/// (no indexed mesh, memory independent of the triangle count), with the streaming closed-surface
/// check of SoupIntegrals. Returns nothing for an ASCII STL.
/// @throws MeshFileError for a missing, empty or truncated file, or a non-finite coordinate.
std::optional<SoupIntegrals> IntegrateBinaryStlFile(const std::string& path, const IntegrationOptions& options = {});

/// Reads a signed-distance grid file (README, "Signed-distance grids"):
///
///     sdfgrid 1
///     NX NY NZ
///     X0 Y0 Z0        position of sample (0, 0, 0)
///     HX HY HZ        spacing
///     NX·NY·NZ values, x fastest, then y, then z (φ ≤ 0 inside)
///
/// Only regular files; a header that promises more values than the file can hold is refused
/// before anything is allocated. Pass it to implicit::ParseShape for grid(file=...).
/// @throws std::runtime_error naming the file and what is wrong.
ImplicitPtr ReadSdfGridFile(const std::string& path);

}  // namespace massprops
