#pragma once
// The massprops command's computation for one file, and its output formats.

#include <optional>
#include <string>
#include <vector>

#include "massprops/io.h"
#include "massprops/mass_properties.h"
#include "massprops/mesh_topology.h"
#include "massprops/monte_carlo.h"
#include "massprops/principal_axes.h"

namespace massprops::app {

struct Options {
  std::vector<std::string> files;
  double density = 1000.0;    // kg/m^3
  double mass = 0.0;          // kg; > 0 fixes the total mass instead of the density
  std::string unit = "m";     // unit of the file's coordinates
  std::string path = "auto";  // auto | triangles | polygons
  std::string format = "table";
  std::string frame = "com";  // com | origin
  std::string output;         // file to write; empty: stdout
  int threads = 0;
  bool quiet = false;  // no progress line
  bool allow_open = false;
  bool full_check = false;
  bool repair = false;                    // weld, orient, stitch with CGAL before integrating
  bool check_self_intersections = false;  // count intersecting face pairs with CGAL
  bool shell = false;          // thin shell of area density (open meshes allowed)
  double area_density = 0.0;   // kg/m^2 for --shell
  double wall = 0.0;           // > 0: hollow part with this wall thickness (file units)
  // Monte-Carlo path: --implicit SHAPE, or --winding-number for files.
  std::string implicit;
  bool winding_number = false;
  std::string method = "qmc";  // mc | qmc
  double samples = 1 << 20;
  int randomizations = 16;
  std::uint64_t seed = 1;
  double tolerance = 0;
  std::string reader = "auto";  // auto | assimp (force assimp, for comparison)  // binary STL: weld and count edges even when the streaming check passes
};

/// Metres per unit for the --unit names; throws for an unknown name.
double MetresPerUnit(const std::string& unit);

struct Report {
  std::string file;
  std::string unit;
  LoadedMesh loaded;
  MeshTopology topology;
  ShellReport shells;
  std::string repair_summary;             // what --repair changed
  std::int64_t self_intersections = -1;   // -1: not checked         // filled when the mesh has more than one component
  bool full_topology = true;  // false: binary STL fast path, only the streaming closed check ran
  std::string model = "solid";  // solid | shell | wall | implicit | winding-number
  std::optional<MassPropertiesEstimate> estimate;  // the Monte-Carlo paths: error bars
  MassProperties mp;  // SI, in the file's axes (for a shell: volume 0, density = area density)
  PrincipalInertia principal;
  ValidityReport validity;
  std::string path_used;
  std::vector<std::string> warnings;
  double size_m = 0;  // bounding-box diagonal, m
  double seconds = 0;
};

/// Estimates the mass properties of a shape in the shape syntax (Monte Carlo / QMC).
Report ComputeImplicit(const std::string& shape, const Options& options);

/// Reads, checks and integrates one file. Throws MeshFileError (or std::exception) naming the file.
Report Compute(const std::string& file, const Options& options);

std::string FormatTable(const Report& r, const Options& options);
std::string FormatJson(const std::vector<Report>& reports, const Options& options);
std::string FormatCsv(const std::vector<Report>& reports, const Options& options);
std::string FormatRobot(const Report& r, const std::string& format);  // urdf | sdf | mjcf

}  // namespace massprops::app
