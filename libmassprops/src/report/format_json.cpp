// The JSON output (massprops/report/format.h): every number of a result, its findings and its
// parts.

#include <cmath>

#include <nlohmann/json.hpp>

#include "massprops/report/format.h"

namespace massprops::report {
namespace {

using Json = nlohmann::ordered_json;

Json Mat(const Matrix3& m) {
  return Json::array({{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}});
}

// The mesh's report: format, counts, closedness and orientation, its shells.
Json MeshJson(const SolidResult& r, const ReportUnits& u) {
  const auto& t = r.topology;
  auto known = [&](std::int64_t v) { return r.full_topology ? Json(v) : Json(nullptr); };
  std::int64_t triangles = t.faces;
  if (r.full_topology) {
    triangles = 0;
    for (std::int64_t f = 0; f < r.loaded.mesh.num_faces(); ++f) triangles += r.loaded.mesh.face_size(f) - 2;
  }
  Json mesh = {{"format", r.loaded.format},
               {"faces", t.faces},
               {"triangles", triangles},  // after splitting n-gons into fans
               {"vertices", known(t.vertices)},
               {"components", known(t.components)},
               {"closed", t.boundary_edges == 0},
               {"oriented", t.inconsistent_edges == 0},
               {"boundary_edges", t.boundary_edges},
               {"non_manifold_edges", known(t.non_manifold_edges)},
               {"degenerate_faces", known(t.degenerate_faces)},
               {"float32_coordinates", r.loaded.float32_coordinates}};
  if (r.shells.shells.size() > 1) {
    const double s3 = std::pow(MetresPerUnit(r.unit), 3) / u.Volume();
    Json shells = Json::array();
    for (const Shell& sh : r.shells.shells) {
      shells.push_back({{"faces", sh.faces.size()},
                        {"volume", sh.signed_volume * s3},
                        {"inside_of", sh.inside_of >= 0 ? Json(sh.inside_of) : Json(nullptr)}});
    }
    mesh["shells"] = shells;
  }
  return mesh;
}

// The exact B-rep's comparison with the tessellation (the side that is not the result), and the
// exporting system's own validation properties.
Json BrepJson(const BrepReport& b, const ReportUnits& u) {
  // The other side of the comparison: the mesh's numbers when the B-rep's are the result.
  const MassProperties& other = b.is_result ? b.mesh : b.mp;
  const Vector3 bc = other.center_of_mass / u.Length();
  Json brep = {{"result", b.is_result ? "brep" : "mesh"},
               {"estimated_error", b.estimated_error},
               {"deflection", b.deflection},
               {"mesh_checked", b.mesh_checked}};
  if (!b.is_result || b.mesh_checked) {
    brep[b.is_result ? "mesh" : "brep"] = {{"volume", other.volume / u.Volume()},
                                           {"mass", other.mass / u.Mass()},
                                           {"center_of_mass", {bc[0], bc[1], bc[2]}},
                                           {"inertia_com", Mat(other.inertia_com / u.Inertia())}};
    brep["volume_difference"] = b.volume_difference;
    brep["com_difference"] = b.com_difference;
    brep["inertia_difference"] = b.inertia_difference;
  }
  Json file = Json::object();
  if (b.file_volume)
    file["volume"] = *b.file_volume / u.Volume(), file["volume_difference"] = *b.file_volume_difference;
  if (b.file_area && b.file_area_difference) file["area_difference"] = *b.file_area_difference;
  if (b.file_centroid && b.file_com_difference) {
    const Vector3 fc = *b.file_centroid / u.Length();
    file["centroid"] = {fc[0], fc[1], fc[2]};
    file["centroid_difference"] = *b.file_com_difference;
  }
  if (!file.empty()) brep["file_properties"] = file;
  return brep;
}

Json ToJson(const SolidResult& r, const FormatOptions& opt) {
  const ReportUnits& u = opt.units;
  const Vector3 c = r.mp.center_of_mass / u.Length();
  const Vector3 m = r.principal.moments / u.Inertia();
  const bool shell = r.model == ModelKind::kShell;
  Json j = {{"file", r.source},
            {"part", r.part},
            {"unit", UnitName(r.unit)},
            {"unit_source", UnitSourceName(r.unit_source)},
            {"model", ModelName(r.model)},
            {"units",
             {{"mass", UnitName(u.mass)},
              {"length", UnitName(u.length)},
              {"area", u.AreaName()},
              {"volume", u.VolumeName()},
              {"density", shell ? u.AreaDensityName() : u.DensityName()},
              {"inertia", UnitName(u.inertia)}}},
            {"volume", r.mp.volume / u.Volume()},
            {"mass", r.mp.mass / u.Mass()},
            {"density", r.mp.density / u.Density()},
            {"center_of_mass", {c[0], c[1], c[2]}},
            {"inertia_com", Mat(r.mp.inertia_com / u.Inertia())}};
  if (shell) {
    j["density"] = nullptr;
    j["area_density"] = r.mp.density / u.AreaDensity();
  }
  if (r.model == ModelKind::kWall) j["wall_thickness_m"] = r.wall_thickness * MetresPerUnit(r.unit);
  // Present when rounding leaves fewer digits than a double holds (a thin wall).
  if (r.relative_error_bound > 0) j["relative_error_bound"] = r.relative_error_bound;
  if (opt.frame == Frame::kOrigin) j["inertia_origin"] = Mat(r.mp.InertiaAbout(Vector3::Zero()) / u.Inertia());
  if (opt.reference) {
    const ReferenceFrame f = ReferenceOf(r, opt);
    const Vector3 p = f.point.value_or(r.mp.center_of_mass) / u.Length();
    j["inertia_about"] = {
        {"point", {p[0], p[1], p[2]}}, {"axes", Mat(f.axes)}, {"tensor", Mat(InertiaInFrame(r.mp, f) / u.Inertia())}};
  }
  j["principal_moments"] = {m[0], m[1], m[2]};
  j["principal_axes"] = Mat(r.principal.axes);
  j["surface_area"] = r.mp.surface_area / u.Area();
  j["physically_valid"] = r.validity.valid;
  j["mesh"] = MeshJson(r, u);
  if (r.self_intersections >= 0) j["mesh"]["self_intersections"] = r.self_intersections;
  if (r.model == ModelKind::kImplicit) j.erase("mesh");
  if (r.estimate) {
    const MassPropertiesEstimate& e = *r.estimate;
    const MassProperties& se = e.standard_error;
    const Vector3 sc = se.center_of_mass / u.Length();
    const Vector3 pm = e.principal_moments_se / u.Inertia();
    j["estimate"] = {{"method", e.method == SamplingMethod::kMonteCarlo ? "monte-carlo" : "quasi-monte-carlo"},
                     {"samples", e.samples},
                     {"randomizations", e.randomizations},
                     {"seed", e.seed},
                     {"interval95_factor", e.interval95_factor},
                     {"tolerance_met", e.tolerance_met},
                     {"standard_errors",
                      {{"volume", se.volume / u.Volume()},
                       {"mass", se.mass / u.Mass()},
                       {"center_of_mass", {sc[0], sc[1], sc[2]}},
                       {"inertia_com", Mat(se.inertia_com / u.Inertia())},
                       {"principal_moments", {pm[0], pm[1], pm[2]}}}}};
    j["surface_area"] = nullptr;
  }
  if (r.repair) j["repair"] = r.repair->Summary();
  if (r.exact) {
    const ExactReport& e = *r.exact;
    Json enclosures = Json::array();
    for (const auto& [lo, hi] : e.moments) enclosures.push_back({lo / u.Inertia(), hi / u.Inertia()});
    j["exact"] = {{"certified", true},
                  {"principal_moments_enclosure", enclosures},
                  {"distinct_principal_moments", e.distinct_moments},
                  {"default_path_inertia_difference", e.inertia_difference},
                  {"default_path_com_difference", e.com_difference}};
  }
  if (r.hull) {
    const HullReport& h = *r.hull;
    const Vector3 hc = h.mp.center_of_mass / u.Length();
    const Vector3 hm = h.principal.moments / u.Inertia();
    j["hull"] = {{"vertices", h.vertices},
                 {"faces", h.faces},
                 {"volume", h.mp.volume / u.Volume()},
                 {"mass", h.mp.mass / u.Mass()},
                 {"center_of_mass", {hc[0], hc[1], hc[2]}},
                 {"inertia_com", Mat(h.mp.inertia_com / u.Inertia())},
                 {"principal_moments", {hm[0], hm[1], hm[2]}},
                 {"principal_axes", Mat(h.principal.axes)}};
  }
  if (r.brep) j["brep"] = BrepJson(*r.brep, u);
  if (!r.density_source.empty()) j["density_source"] = r.density_source;
  Json warnings = Json::array();
  for (const Finding& f : r.findings) warnings.push_back(Worded(f.message, WordsOf(opt)));
  j["warnings"] = warnings;
  if (r.part.empty()) j.erase("part");
  if (!r.instance.empty()) j["instance"] = r.instance;
  if (!r.part.empty() && !r.loaded.cad_parts.empty() && !r.loaded.cad_parts.front().unit.empty()) {
    j["declared_unit"] = r.loaded.cad_parts.front().unit;  // the part's own, as the file names it
  }
  if (!r.parts.empty()) {
    Json parts = Json::array();
    for (const SolidResult& part : r.parts) parts.push_back(ToJson(part, opt));
    j["parts"] = parts;
  }
  return j;
}

}  // namespace

std::string FormatJsonLine(const SolidResult& r, const FormatOptions& opt) { return ToJson(r, opt).dump(); }

std::string FormatJson(const std::vector<SolidResult>& results, const FormatOptions& opt) {
  if (!opt.json_array && results.size() == 1) return ToJson(results[0], opt).dump(2) + "\n";
  Json all = Json::array();
  for (const SolidResult& r : results) all.push_back(ToJson(r, opt));
  return all.dump(2) + "\n";
}

}  // namespace massprops::report
