// Assemblies (LoadOptions::parts): each part the file names goes through the whole pipeline on
// its own, with its own density or mass; the whole is their composition.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "massprops/composition.h"
#include "massprops/text.h"
#include "pipeline/load_internal.h"
#include "pipeline/plausibility.h"

namespace massprops::internal {
namespace {

// The faces of part `p` (all faces when the file names no parts), with the vertices they use in
// their original order.
LoadedMesh ExtractPart(const LoadedMesh& whole, std::int32_t p) {
  LoadedMesh part;
  part.format = whole.format;
  part.float32_coordinates = whole.float32_coordinates;
  part.declared_unit = whole.declared_unit;
  part.declared_unit_name = whole.declared_unit_name;
  if (static_cast<std::size_t>(p) < whole.cad_parts.size())
    part.cad_parts = {whole.cad_parts[static_cast<std::size_t>(p)]};
  const PolygonMesh& m = whole.mesh;
  std::vector<std::int32_t> new_index(static_cast<std::size_t>(m.V.rows()), -1);
  for (std::int64_t f = 0; f < m.num_faces(); ++f) {
    if (whole.face_part[static_cast<std::size_t>(f)] != p) continue;
    for (std::int64_t k = m.offsets[f]; k < m.offsets[f + 1]; ++k)
      new_index[static_cast<std::size_t>(m.indices[k])] = 0;
  }
  std::int32_t n = 0;
  for (std::int32_t& i : new_index) {
    if (i == 0) i = n++;
  }
  part.mesh.V.resize(n, 3);
  for (std::size_t v = 0; v < new_index.size(); ++v) {
    if (new_index[v] >= 0) part.mesh.V.row(new_index[v]) = m.V.row(static_cast<Eigen::Index>(v));
  }
  for (std::int64_t f = 0; f < m.num_faces(); ++f) {
    if (whole.face_part[static_cast<std::size_t>(f)] != p) continue;
    for (std::int64_t k = m.offsets[f]; k < m.offsets[f + 1]; ++k) {
      part.mesh.indices.push_back(new_index[static_cast<std::size_t>(m.indices[k])]);
    }
    part.mesh.offsets.push_back(static_cast<std::int64_t>(part.mesh.indices.size()));
  }
  return part;
}

std::string Stem(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

void AddTopology(MeshTopology& sum, const MeshTopology& t) {
  sum.faces += t.faces;
  sum.vertices += t.vertices;
  sum.unreferenced_vertices += t.unreferenced_vertices;
  sum.edges += t.edges;
  sum.boundary_edges += t.boundary_edges;
  sum.holes += t.holes;
  sum.non_manifold_edges += t.non_manifold_edges;
  sum.unbalanced_edges += t.unbalanced_edges;
  sum.inconsistent_edges += t.inconsistent_edges;
  sum.degenerate_faces += t.degenerate_faces;
  sum.duplicate_faces += t.duplicate_faces;
  sum.reversed_duplicate_faces += t.reversed_duplicate_faces;
  sum.components += t.components;
}

// Whether a part without triangles still has its exact numbers: a CAD solid whose B-rep is the answer.
bool HasExactSolid(const LoadedMesh& part, const LoadOptions& opt) {
  return part.cad_parts.size() == 1 && part.cad_parts.front().solid && BrepIsTheAnswer(opt);
}

}  // namespace

SolidResult SolveParts(SolidResult r, const LoadOptions& given, std::chrono::steady_clock::time_point t0) {
  const LoadOptions opt = ResolveUnit(r, given);
  LoadedMesh& loaded = r.loaded;
  std::vector<std::string> names = loaded.part_names;
  if (names.empty()) {
    names.push_back(Stem(r.source));
    loaded.face_part.assign(static_cast<std::size_t>(loaded.mesh.num_faces()), 0);
  }
  for (std::size_t p = 0; p < names.size(); ++p) {
    if (names[p].empty()) names[p] = "part " + std::to_string(p + 1);  // faces before the first name
  }
  // Every entry of the map must name a part: a misspelt name would silently take the default.
  if (const PartMass* entry = FirstUnmatched(opt.part_masses, names)) {
    std::string list;
    for (const std::string& name : names) list += (list.empty() ? "'" : ", '") + name + "'";
    throw std::invalid_argument("the density map's entry '" + entry->pattern + "' matches no part of " + r.source +
                                " (its parts: " + list + ")");
  }
  // A total mass for the whole (not per part) is shared at one density: solve at 1 kg/m^3, scale.
  const bool shared_mass = FixesMass(opt.mass);
  std::vector<MassProperties> mps;
  double unmapped_volume = 0, mapped_mass = 0;
  for (std::size_t p = 0; p < names.size(); ++p) {
    LoadOptions part_opt = opt;
    part_opt.parts = false;
    part_opt.part_masses.clear();
    part_opt.unit_stated = true;  // resolved for the whole: a small part is not a unit mistake
    const PartMass* entry = MatchPart(opt.part_masses, names[p]);
    part_opt.mass_stated = opt.mass_stated || entry != nullptr;  // else the part's material, if it has one
    if (entry != nullptr) {
      part_opt.mass = entry->mass;
    } else if (shared_mass) {
      part_opt.mass = Density{1.0};
    }
    SolidResult part;
    part.source = r.source + " (part '" + names[p] + "')";
    part.part = names[p];
    part.loaded = ExtractPart(loaded, static_cast<std::int32_t>(p));
    if (!part.loaded.cad_parts.empty()) part.instance = part.loaded.cad_parts.front().instance;
    if (part.loaded.mesh.num_faces() == 0 && !HasExactSolid(part.loaded, part_opt)) {
      // Nothing to integrate: an empty group, a product of curves or points, a tessellation with
      // no triangles. Named and left out, never integrated as nothing.
      Warn(r, FindingKind::kCadLeftOut,
           "part '" + names[p] + "' has no faces (" +
               (part.loaded.cad_parts.empty() ? std::string("an empty group") : "OpenCASCADE made no triangles of it") +
               "): left out of the whole");
      continue;
    }
    if (opt.progress) opt.progress(("part '" + names[p] + "'").c_str());
    part = Solve(std::move(part), part_opt, std::chrono::steady_clock::now());
    part.source = r.source;
    part.unit_source = r.unit_source;
    if (entry == nullptr && shared_mass) {
      unmapped_volume += part.mp.volume;
    } else {
      mapped_mass += part.mp.mass;
    }
    r.parts.push_back(std::move(part));
  }
  if (r.parts.empty()) throw LoadError(r.source + ": no part has faces to integrate");
  if (shared_mass) {
    // The parts without an entry share what the total mass leaves them, at one density.
    const double rest = std::get<TotalMass>(opt.mass).value - mapped_mass;
    if (!(std::isfinite(rest) && rest > 0)) {
      throw std::invalid_argument("the total mass " + Fixed(std::get<TotalMass>(opt.mass).value) +
                                  " kg leaves nothing for the parts without an entry in the density map (" +
                                  Fixed(mapped_mass) + " kg are mapped)");
    }
    const double density = rest / unmapped_volume;
    for (SolidResult& part : r.parts) {
      if (MatchPart(opt.part_masses, part.part) != nullptr) continue;
      part.mp = AtDensity(part.mp, density);  // solved at 1 kg/m^3
      if (part.hull) part.hull->mp = AtDensity(part.hull->mp, density);
      if (part.brep) {
        part.brep->mp = AtDensity(part.brep->mp, density);
        part.brep->mesh = AtDensity(part.brep->mesh, density);
      }
      part.principal = ComputePrincipalInertia(part.mp.inertia_com);
      part.mass_fixed = true;
    }
  }
  // The whole: the composition of the parts.
  r.topology = {};
  r.full_topology = true;
  bool fixed = false;
  std::string paths;
  for (const SolidResult& part : r.parts) {
    mps.push_back(part.mp);
    AddTopology(r.topology, part.topology);
    fixed = fixed || part.mass_fixed;
    if (paths.find(part.path_used) == std::string::npos) paths += (paths.empty() ? "" : "; ") + part.path_used;
    for (const Finding& f : part.findings)
      r.findings.push_back({f.kind, f.message.After("part '" + part.part + "': ")});
    if (part.repair) {
      if (!r.repair) r.repair = RepairReport{};
      RepairReport& sum = *r.repair;
      const RepairReport& pr = *part.repair;
      sum.welded_vertices += pr.welded_vertices;
      sum.removed_faces += pr.removed_faces;
      sum.reoriented = sum.reoriented || pr.reoriented;
      sum.split_vertices += pr.split_vertices;
      sum.stitched_edges += pr.stitched_edges;
      sum.oriented_to_bound_volume = sum.oriented_to_bound_volume || pr.oriented_to_bound_volume;
      sum.united_shells += pr.united_shells;
      sum.volume_before += pr.volume_before;
      sum.volume_after += pr.volume_after;
    }
  }
  r.model = r.parts.front().model;
  r.wall_thickness = r.parts.front().wall_thickness;
  r.mass_fixed = fixed;
  r.path_used = "the composition of " + std::to_string(r.parts.size()) + (r.parts.size() == 1 ? " part" : " parts") +
                " (" + paths + ")";
  r.mp = Combine(mps);
  // One density throughout is that density, not the quotient of the sums (which rounds).
  if (std::all_of(r.parts.begin(), r.parts.end(),
                  [&](const SolidResult& p) { return p.mp.density == r.parts.front().mp.density; })) {
    r.mp.density = r.parts.front().mp.density;
  }
  r.size_m = MeshDiagonal(loaded.mesh) * MetresPerUnit(r.unit);
  if (!(r.size_m > 0)) {
    for (const SolidResult& part : r.parts) r.size_m = std::max(r.size_m, part.size_m);
  }
  CheckPlausible(r, {opt.unit_stated, opt.mass});
  ComposeBrep(r);
  r.principal = ComputePrincipalInertia(r.mp.inertia_com);
  r.validity = CheckPhysicallyValid(r.principal.moments, 1e-12);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace massprops::internal
