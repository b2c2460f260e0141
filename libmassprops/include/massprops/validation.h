#pragma once
/// @file
/// Validation a user can run: the closed-form solids of solids.h, tessellated at a series of
/// resolutions and placed at the origin and far from it, integrated by both paths, against their
/// closed forms — with the observed order of convergence (2 for the inscribed tessellations of
/// smooth solids, whose error goes as the edge length squared; exact for polyhedra). What
/// `massprops validate` prints and the tests assert.

#include <string>
#include <vector>

namespace massprops {

struct ValidationOptions {
  std::vector<std::string> solids;  ///< names from ValidationSolids(); empty: all
  std::vector<int> resolutions = {8, 16, 32, 64, 128};
};

/// One solid at one resolution, placement and path.
struct ConvergenceRow {
  std::string solid;
  int resolution = 0;  ///< n (segments per half turn); 0 for the exact polyhedra
  long long triangles = 0;
  std::string path;          ///< "triangles" (signed tetrahedra) or "polygons" (Mirtich)
  bool far = false;          ///< turned and moved 10^5 sizes from the origin
  double volume_error = 0;   ///< |ΔV| / V
  double com_error = 0;      ///< |Δc| / size (bounding-box diagonal)
  double inertia_error = 0;  ///< ‖ΔI‖ / ‖I‖ (Frobenius, about the center of mass)
  /// log2 of the error's ratio to the previous resolution's (same solid, path, placement); NaN
  /// for the first resolution and for the polyhedra.
  double volume_order = 0, inertia_order = 0;
};

/// "box", "tetrahedron", "octahedron", "prism", "sphere", "ellipsoid", "cylinder", "cone",
/// "torus", "capsule", "hollow-sphere".
std::vector<std::string> ValidationSolids();

/// @throws std::invalid_argument for an unknown solid or a resolution below 3.
std::vector<ConvergenceRow> ValidateClosedForms(const ValidationOptions& options = {});

}  // namespace massprops
