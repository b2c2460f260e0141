// Resting poses of a part file: the part, and the report as JSON (bodies/pose_part.h).

#include "bodies/pose_part.h"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "massprops/io/mesh_io.h"
#include "massprops/repair/repair.h"
#include "massprops/wording.h"

namespace dynamics {
namespace {

namespace dp = dynamics::poses;
using massprops::Vector3;

nlohmann::json Json(const Vector3& v) { return {v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}; }  // + 0.0: no "-0"

nlohmann::json Transform(const dp::Pose& p) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 3; ++r)
    rows.push_back({p.rotation(r, 0) + 0.0, p.rotation(r, 1) + 0.0, p.rotation(r, 2) + 0.0, p.translation(r) + 0.0});
  rows.push_back({0.0, 0.0, 0.0, 1.0});
  return rows;
}

}  // namespace

dp::Part LoadPosePart(const std::string& path, massprops::LoadOptions load, PoseCollision collision,
                      const dynamics::Material& material, const massprops::Vocabulary& words,
                      std::vector<std::string>& warnings, massprops::TriangleMesh* mesh_out) {
  load.full_check = true;  // the mesh whole: the hull and the pictures need it
  massprops::SolidResult solid;
  try {
    solid = massprops::LoadSolid(path, load);
  } catch (const massprops::FileAccessError&) {
    throw;
  } catch (const std::exception& e) {
    const std::string what = massprops::WordedError(e, words);
    throw std::invalid_argument(what.find(path) == std::string::npos ? path + ": " + what : what);
  }
  for (const auto& f : solid.findings) warnings.push_back(path + ": " + massprops::Worded(f.message, words));
  if (!solid.validity.valid) {
    throw std::invalid_argument(path + ": the inertia is not that of a real body (" + solid.validity.reason + ")");
  }
  if (solid.loaded.mesh.num_faces() == 0) throw std::invalid_argument(path + ": resting poses need the part's mesh");
  massprops::TriangleMesh mesh = massprops::Triangulate(solid.loaded.mesh);
  mesh.V *= massprops::MetresPerUnit(solid.unit);
  dp::Part part;
  part.mass_properties = solid.mp;
  part.material = material;
  dynamics::shape::Convex hull = dynamics::ConvexOf(massprops::ConvexHull(massprops::ToPolygonMesh(mesh)));
  part.hull_vertices = std::move(hull.vertices);
  part.hull_triangles = std::move(hull.triangles);
  if (collision == PoseCollision::kMesh) {
    part.collider =
        dynamics::Collider{dynamics::MeshOf(mesh), massprops::Matrix3::Identity(), Vector3::Zero(), material};
  }
  if (mesh_out != nullptr) *mesh_out = std::move(mesh);
  return part;
}

namespace {

nlohmann::json MaterialJson(const dynamics::Material& m) {
  return {
      {"static_friction", m.static_friction}, {"kinetic_friction", m.kinetic_friction}, {"restitution", m.restitution}};
}

}  // namespace

std::string PosesJson(const PosesReport& r, int indent) {
  const dp::Tally& t = r.tally;
  nlohmann::json j;
  j["part"] = r.part;
  j["mass"] = r.pose_part.mass_properties.mass;
  j["center_of_mass"] = Json(r.pose_part.mass_properties.center_of_mass);
  j["hull_faces"] = r.estimate.faces.normals.size();
  j["drops"] = {{"count", r.drops},
                {"height", r.options.height},
                {"seed", r.options.seed},
                {"dt", r.options.dt},
                {"collision", r.collision == PoseCollision::kMesh ? "mesh" : "hull"},
                {"ground", MaterialJson(r.options.ground)},
                {"material", MaterialJson(r.pose_part.material)},
                {"not_settled", t.not_settled},
                {"other_face", t.other_face},
                {"mean_time_to_rest", t.mean_time}};
  j["poses"] = nlohmann::json::array();
  for (std::size_t p = 0; p < r.estimate.poses.size(); ++p) {
    const dp::Pose& pose = r.estimate.poses[p];
    nlohmann::json jp = {{"normal", Json(pose.normal)},
                         {"quasi_static", pose.quasi_static},
                         {"height", pose.height},
                         {"transform", Transform(pose)}};
    if (r.drops > 0) {
      jp["drops"] = static_cast<double>(t.counts[p]) / static_cast<double>(t.drops);
      jp["drop_count"] = t.counts[p];
      jp["drops_interval95"] = {t.binomial[p].low, t.binomial[p].high};
      jp["drops_simultaneous95"] = {t.simultaneous[p].low, t.simultaneous[p].high};
    }
    if (p < r.pictures.size()) jp["picture"] = r.pictures[p];
    j["poses"].push_back(jp);
  }
  return j.dump(indent);
}

}  // namespace dynamics
