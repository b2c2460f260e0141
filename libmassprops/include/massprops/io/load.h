#pragma once
/// @file
/// The pipeline from a mesh file to mass properties you can trust (target massprops::io):
///
///     read → weld → check → [repair] → integrate (solid | shell | wall | winding number)
///          → principal axes → validity → findings
///
/// This is what the `massprops` command prints, what `rbsim` builds its bodies from and what the
/// bindings call. Options are typed; the result carries typed findings whose messages name the
/// options that would help as markers ({repair}, see wording.h), so each front end words them in
/// its own vocabulary.

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "massprops/io/mesh_io.h"
#include "massprops/mass_properties.h"
#include "massprops/mass_spec.h"
#include "massprops/mesh_topology.h"
#include "massprops/monte_carlo.h"
#include "massprops/principal_axes.h"
#include "massprops/repair/repair.h"
#include "massprops/units.h"
#include "massprops/wording.h"

namespace massprops {

/// Which integrator computes a solid's integrals.
enum class IntegrationPath {
  kAuto,       ///< signed tetrahedra for triangle meshes, Mirtich's polygons for quads and n-gons
  kTriangles,  ///< signed tetrahedra (polygons split into fans from their first corner)
  kPolygons,   ///< Mirtich: every face integrated whole
};

/// Which reader opens the file.
enum class Reader {
  kAuto,    ///< our own parsers for OBJ/STL/PLY/OFF, assimp for the rest
  kAssimp,  ///< assimp for every format (32-bit coordinates; for comparison)
};

/// The solid the closed surface bounds (the default).
struct SolidModel {};
/// A thin shell: the surface itself carries the mass at `area_density` kg/m^2 (a TotalMass in
/// LoadOptions::mass overrides it). Open, unoriented surfaces are fine.
struct ShellModel {
  double area_density = 0;
};
/// A hollow part: the solid between the closed surface and its inward offset by `thickness`, in
/// the file's unit.
struct WallModel {
  double thickness = 0;
};
/// The winding-number route's default sampling: QMC from 2^16 points, doubled until the relative
/// standard error of the mass and of each principal moment is below 1e-3 (2^17 points and 0.35 s
/// on 2 cores for a sphere of 10^4 triangles with three holes).
inline MonteCarloOptions WindingNumberSampling() {
  MonteCarloOptions mc;
  mc.samples = std::int64_t{1} << 16;
  mc.tolerance = 1e-3;
  return mc;
}

/// The sampling a front end asks for (method, seed, ...), with the route's default count and
/// tolerance unless it asked for a count or a tolerance itself.
inline MonteCarloOptions WindingNumberSampling(MonteCarloOptions asked, bool count_or_tolerance_given) {
  if (!count_or_tolerance_given) {
    asked.samples = WindingNumberSampling().samples;
    asked.tolerance = WindingNumberSampling().tolerance;
  }
  return asked;
}

/// The solid where the generalized winding number of the surface is at least 1/2 (holes are
/// bridged), estimated by Monte Carlo or quasi-Monte Carlo with error bars. The sampling options'
/// fixed_mass and num_threads are taken from LoadOptions.
struct WindingNumberModel {
  MonteCarloOptions sampling = WindingNumberSampling();
};
using Model = std::variant<SolidModel, ShellModel, WallModel, WindingNumberModel>;

/// Called with the name of each stage as it begins ("reading", "checking edges", ...), from the
/// calling thread.
using ProgressCallback = std::function<void(const char* stage)>;

struct LoadOptions {
  LengthUnit unit = LengthUnit::kMetre;  ///< unit of the file's coordinates
  /// True when the user chose `unit`; false when it is a default: then the unit a file declares
  /// (3MF, AMF, glTF, COLLADA) is used instead, and with none a part under 2 mm or over 2 m
  /// across draws a finding that names the likely unit.
  bool unit_stated = false;
  MassSpec mass = Density{1000.0};  ///< kg/m^3, or the total mass
  /// True when the user chose `mass`; false when it is a default: then the density a CAD file's
  /// material gives a part (STEP AP242) is used instead.
  bool mass_stated = false;
  Model model = SolidModel{};
  IntegrationPath path = IntegrationPath::kAuto;
  Reader reader = Reader::kAuto;
  /// Weld near-coincident corners, drop degenerate and duplicate faces, orient and stitch with
  /// CGAL before integrating (needs a build with CGAL).
  bool repair = false;
  /// Compute even when the surface is open or inconsistently oriented, or its shells overlap,
  /// with a finding that says so.
  bool allow_open = false;
  /// Binary STL: weld and run every check even when the streamed pass finds the surface closed.
  bool full_check = false;
  /// Count intersecting face pairs with CGAL (needs a build with CGAL).
  bool check_self_intersections = false;
  /// Also compute the mass properties of the convex hull (CGAL), as collision engines see the
  /// body, at the same density (or the same total mass). Solid and wall models.
  bool hull = false;
  /// Certified results (exact.h): volume, mass, center of mass and inertia become the correctly
  /// rounded exact values, with enclosures of the principal moments. Solid model.
  bool exact = false;
  /// Compute every part the file names (OBJ objects or groups, the nodes of glTF, 3MF, COLLADA,
  /// FBX ...) on its own, each through the whole pipeline, and the whole as their composition
  /// (SolidResult::parts). Solid and wall models. A file that names no parts is one part.
  bool parts = false;
  /// With `parts`: densities or total masses per part, first match wins; the others take `mass`
  /// (a TotalMass there is then shared by the parts at one density). Every entry must match a part.
  std::vector<PartMass> part_masses;
  /// CAD files (STEP, IGES, BREP): how they are tessellated, and the interference budget.
  CadOptions cad;
  /// CAD files: the exact B-rep's integrals (OpenCASCADE) are the result of every part with a
  /// solid, and the tessellation is their check, beside them. False: the tessellation is the result
  /// (the command's --tessellated). Options only a mesh can do (repair, hull, exact, a wall, a
  /// shell, the winding number) make the tessellation the result, with a finding that says so.
  bool brep = true;
  int num_threads = 0;  ///< 0: every core; the bits do not depend on it
  ProgressCallback progress;
};

/// What kind of model produced a result.
enum class ModelKind { kSolid, kShell, kWall, kImplicit, kWindingNumber };
/// "solid", "shell", "wall", "implicit", "winding-number".
const char* ModelName(ModelKind kind);

/// What the checks found that a user must know about, though the numbers stand.
enum class FindingKind {
  kOpenSurface,         ///< holes or inconsistent orientation; computed anyway (or bridged, or a shell)
  kOverlappingShells,   ///< shells whose volumes overlap; computed anyway
  kNonManifoldEdges,    ///< edges shared by more than two faces, matched in both directions
  kSelfIntersections,   ///< faces that pass through each other
  kUnitSuspicion,       ///< the size suggests the coordinates are in another unit
  kUndeterminedAxes,    ///< an estimate's principal moments are equal within their error bars
  kToleranceNotMet,     ///< an adaptive estimate stopped at its sample limit
  kNonPlanarFaces,      ///< polygons off their plane: integrated as fans from their first corner
  kStreamedChecks,      ///< the streamed binary-STL path (one shell): edges used by more than two faces not counted
  kUnitOverridden,      ///< the file declares another unit than the one stated
  kLimitedPrecision,    ///< rounding leaves fewer meaningful digits than a double holds (relative_error_bound)
  kMaterialOverridden,  ///< the file gives a part a material density other than the one used
  kNoBrep,              ///< a CAD part without a solid: the exact B-rep comparison is missing
  kCadMeshAnswer,       ///< a CAD file's tessellation is the result: the options need a mesh
  kCadCheck,            ///< a CAD part's check mesh is missing or open, or differs beyond its deflection
  kCadFix,              ///< a CAD part's B-rep was changed to find its solids (sewn, made solid, turned outward)
  kCadLeftOut,          ///< a CAD part with no solid or surface (curves, points, nothing), left out
  kInterference,        ///< two CAD parts (or two solids in one) share volume; or the test was not done
  kFileProperties,      ///< a CAD file's own validation properties disagree with the B-rep's
  kRepaired,            ///< the repair removed repeated faces or internal walls, or filled holes
};

struct Finding {
  FindingKind kind;
  Advice message;  ///< naming options as markers: Worded(message, vocabulary) for people
};

/// Where the unit of the coordinates came from.
enum class UnitSource { kDefault, kOption, kFile };
/// "default", "option", "file".
const char* UnitSourceName(UnitSource source);

/// Everything the pipeline learned about one input.
/// What LoadOptions::exact certified, and how far the default path was from it.
struct ExactReport {
  std::array<std::pair<double, double>, 3> moments{};  ///< each principal moment lies in [first, second]
  int distinct_moments = 3;
  double inertia_difference = 0;  ///< ‖I_default − I_exact‖ / ‖I_exact‖ (Frobenius)
  double com_difference = 0;      ///< |c_default − c_exact| / size
};

/// The convex hull's mass properties beside the exact ones (LoadOptions::hull).
struct HullReport {
  MassProperties mp;  ///< SI, in the file's axes
  PrincipalInertia principal;
  std::int64_t vertices = 0, faces = 0;  ///< of the hull (triangles)
};

/// A CAD file's exact B-rep integrals (OpenCASCADE) beside the mesh's: how far the tessellation
/// moved the numbers.
struct BrepReport {
  MassProperties mp;  ///< SI, in the file's axes, at the result's density
  PrincipalInertia principal;
  double estimated_error = 0;    ///< OpenCASCADE's estimate of the integration's relative error
  double deflection = 0;         ///< the tessellation's chordal deflection, file unit (the largest of the parts')
  double volume_difference = 0;  ///< (V_mesh − V_brep) / V_brep
  double com_difference = 0;     ///< |c_mesh − c_brep| / size
  double inertia_difference = 0;  ///< ‖I_mesh − I_brep‖ / ‖I_brep‖ (Frobenius, about each one's center of mass)
  bool is_result = false;         ///< LoadOptions::brep: these are the result's numbers (mp), the mesh's in `mesh`
  /// Whether the tessellation bounds a volume, so that `mesh` and the differences exist (the
  /// B-rep's numbers stand either way when they are the result).
  bool mesh_checked = true;
  MassProperties mesh;  ///< the tessellation's numbers, SI
  /// The exporting system's own numbers (STEP validation properties), SI, when the file has them,
  /// with their differences from the B-rep's (relative; the centroid over the part's size).
  std::optional<double> file_volume, file_area, file_volume_difference, file_area_difference, file_com_difference;
  std::optional<Vector3> file_centroid;
};

struct SolidResult {
  std::string source;                    ///< the file path, or the implicit shape's text
  LengthUnit unit = LengthUnit::kMetre;  ///< the unit the coordinates were read in
  UnitSource unit_source = UnitSource::kDefault;
  ModelKind model = ModelKind::kSolid;
  LoadedMesh loaded;  ///< the mesh integrated (after repair; for a wall, the wall solid)
  MeshTopology topology;
  ShellReport shells;                    ///< filled when the mesh has more than one component
  std::optional<RepairReport> repair;    ///< what the repair changed
  std::int64_t self_intersections = -1;  ///< -1: not checked
  /// False on the streamed binary-STL path (only the closed-cycle check ran) and for implicit
  /// solids (no mesh).
  bool full_topology = true;
  std::optional<MassPropertiesEstimate> estimate;  ///< the Monte-Carlo models: error bars
  /// SI, in the file's axes. A shell has volume 0 and its area density in `density`.
  MassProperties mp;
  PrincipalInertia principal;
  ValidityReport validity;
  bool mass_fixed = false;    ///< the density came from a TotalMass
  double wall_thickness = 0;  ///< WallModel: in the file's unit
  std::string path_used;      ///< how it was integrated, in words
  double size_m = 0;          ///< bounding-box diagonal, m
  /// > 0 when rounding may leave this relative error in every number (a thin wall: a small
  /// difference of two large solids); the digits beyond it are noise. 0: as a double holds.
  double relative_error_bound = 0;
  double seconds = 0;  ///< wall-clock time of the whole pipeline
  std::vector<Finding> findings;
  std::optional<HullReport> hull;    ///< LoadOptions::hull
  std::optional<ExactReport> exact;  ///< LoadOptions::exact: mp holds the certified values
  std::optional<BrepReport> brep;    ///< CAD files with solids: the exact B-rep's numbers and the difference
  /// Where the density came from when not from the options: "the file's material 'steel'".
  std::string density_source;
  /// LoadOptions::parts: each part's own result (its name in `part`), in the file's order. The
  /// whole's mass properties are their composition; its topology their sums; its findings
  /// theirs, each naming its part.
  std::vector<SolidResult> parts;
  std::string part;      ///< the part's name, in a result of `parts`
  std::string instance;  ///< CAD assemblies: the component's own name ("bolt:2"), when it has one
};

/// An input the pipeline refuses: what() names the file, the fault and (with the C++ option
/// names) what to do. `text()` keeps the option markers for other vocabularies.
class LoadError : public MeshFileError {
 public:
  explicit LoadError(std::string text);
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

/// The message of any exception the pipeline throws, worded in `vocabulary`.
std::string WordedError(const std::exception& error, const Vocabulary& vocabulary);

/// Reads, checks and integrates one mesh file.
/// @throws LoadError when the input does not describe a solid the options can compute (open,
///         inward, overlapping, a wall too thick, ...), MeshFileError when it cannot be read,
///         std::invalid_argument for an invalid option value.
SolidResult LoadSolid(const std::string& path, const LoadOptions& options = {});

/// Whether LoadSolid may run on all of `paths` at once, one file per thread: every file is read by
/// this library's own readers in this process (assimp's formats are read in a child process, forked
/// from one thread at a time). Front ends that load several files ask this rather than knowing it.
bool LoadsSideBySide(const std::vector<std::string>& paths, const LoadOptions& options);

/// A combination of options that cannot be computed — the one home of these rules: LoadSolid
/// refuses them, and the command line and the Python module check them (FindOptionConflict)
/// before any file is read, each wording them in its own terms (massprops/report/words.h).
enum class OptionConflict {
  kShellNeedsDensity,    ///< a shell without a finite, positive area density or a total mass
  kWallNeedsThickness,   ///< a wall without a finite, positive thickness
  kExactNeedsSolid,      ///< exact integration with a shell, a wall or a winding-number estimate
  kHullNeedsSolid,       ///< the convex hull with a shell or a winding-number estimate
  kPartMassesNeedParts,  ///< densities per part without computing the parts
  kPartsNeedSolid,       ///< parts with a shell or a winding-number estimate
  kPartsNotExact,        ///< parts with exact integration
};

/// The first conflict among `options`, in the order of the enum, or none.
std::optional<OptionConflict> FindOptionConflict(const LoadOptions& options);

/// The library's own words for a conflict (what LoadSolid's std::invalid_argument says).
std::string DescribeConflict(OptionConflict conflict);

/// The same checks and integration for a mesh already in memory (arrays from Python, a mesh built
/// in code): `name` stands for the file in messages and in SolidResult::source. Corners at
/// bit-identical positions are welded first, as every reader does. Options about reading
/// (reader, full_check) do not apply.
/// @throws as LoadSolid, except MeshFileError.
SolidResult SolveMesh(LoadedMesh mesh, const std::string& name, const LoadOptions& options = {});

/// Options of an implicit solid's estimate.
struct ImplicitOptions {
  LengthUnit unit = LengthUnit::kMetre;  ///< unit of the shape's coordinates
  bool unit_stated = false;              ///< as LoadOptions::unit_stated
  MassSpec mass = Density{1000.0};
  MonteCarloOptions sampling;  ///< fixed_mass is taken from `mass`, num_threads from here
  int num_threads = 0;
  ProgressCallback progress;
};

/// Estimates the mass properties of an implicit solid (primitives, CSG, SDF grids: implicit.h)
/// with error bars. @throws std::invalid_argument for a bad option or an empty solid.
SolidResult EstimateImplicit(const ImplicitSolid& solid, const ImplicitOptions& options = {});

}  // namespace massprops
