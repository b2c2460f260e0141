#pragma once
// The run viewer's page (html.cpp): the viewer script (viewer/viewer.js with three.js, bundled into
// viewer/viewer.bundle.js and linked into rbsim) around the data of a run, as JSON in the schema of
// docs/scenes.md ("The page: run.html"). rbsim's runs (WriteHtml in outputs.h) and rbsim poses build the data.

#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "massprops/mesh.h"

namespace rbsim {

/// A moving body of the schema: name, colour (linear RGB, 0..1), its mesh relative to its center
/// of mass, and its pose at each sample (center of mass; quaternion x, y, z, w).
nlohmann::json ViewerBody(const std::string& name, const massprops::Vector3& color, const massprops::TriangleMesh& mesh,
                          const std::vector<Eigen::Vector3f>& translations,
                          const std::vector<Eigen::Vector4f>& rotations);
/// A fixed body of the schema: its mesh in world coordinates.
nlohmann::json ViewerStatic(const std::string& name, const massprops::Vector3& color,
                            const massprops::TriangleMesh& mesh);
/// The bounds entry (the default camera frames them).
nlohmann::json ViewerBounds(Eigen::AlignedBox3d bounds);
/// The whole page: it plays from file://, with no imports or fetches.
std::string ViewerPage(const std::string& title, const nlohmann::json& data);

}  // namespace rbsim
