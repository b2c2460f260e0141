#pragma once
// Resting poses of a part file, shared by `rbsim poses` and the Python module: the part made from
// the pipeline's result (its mesh in metres, its convex hull, its collider) and the report of both
// estimates as JSON (one home for the schema, README "Resting poses").

#include <cstdint>
#include <string>
#include <vector>

#include "dynamics/poses.h"
#include "massprops/io/load.h"

namespace dynamics {

enum class PoseCollision { kHull, kMesh };

/// A part file through the pipeline (LoadSolid with `load`, whole: the hull needs the mesh) as a
/// part to drop: SI mass properties, the convex hull of its mesh (CGAL), and its collider (the
/// hull, or the mesh as it is). The pipeline's findings are appended to `warnings` and its errors
/// rethrown, both worded in `words` (the caller's option names). `mesh` receives the mesh in
/// metres, file axes. @throws massprops::FileAccessError for a file that cannot be read,
/// std::invalid_argument naming the file for a part that cannot be dropped.
dynamics::poses::Part LoadPosePart(const std::string& path, massprops::LoadOptions load, PoseCollision collision,
                                   const dynamics::Material& material, const massprops::Vocabulary& words,
                                   std::vector<std::string>& warnings, massprops::TriangleMesh* mesh = nullptr);

/// What a run of both estimates found.
struct PosesReport {
  std::string part;  ///< the file, as given
  dynamics::poses::Part pose_part;
  dynamics::poses::Estimate estimate;
  dynamics::poses::DropOptions options;
  PoseCollision collision = PoseCollision::kHull;
  std::int64_t drops = 0;
  dynamics::poses::Tally tally;       ///< of the drops 0 … drops − 1
  std::vector<std::string> pictures;  ///< a picture file's name for each pose, or none
};

/// {"part", "mass", "center_of_mass", "hull_faces", "drops": {...}, "poses": [{"normal",
/// "quasi_static", "height", "transform", and with drops "drops", "drop_count",
/// "drops_interval95", "drops_simultaneous95", and with pictures "picture"}]}, as JSON text
/// indented by `indent` spaces (−1: one line). The materials are {"static_friction",
/// "kinetic_friction", "restitution"}.
std::string PosesJson(const PosesReport& report, int indent = -1);

}  // namespace dynamics
