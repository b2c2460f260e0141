// The pipeline's CAD steps: the density a file's material gives, the exact B-rep's numbers as the
// result with the tessellation as their check (or beside the tessellation's when the mesh is the
// result), the file's own validation properties, and the reader's notes and interference report.

#include <cmath>
#include <string>
#include <vector>

#include "massprops/composition.h"
#include "massprops/mesh_topology.h"
#include "massprops/text.h"
#include "pipeline/load_internal.h"
#include "pipeline/plausibility.h"

namespace massprops::internal {
namespace {

// "'steel' (7850 kg/m^3)".
std::string MaterialName(const CadPart& part) {
  return (part.material.empty() ? std::string("unnamed") : "'" + part.material + "'") + " (" +
         Fixed(part.density, "%.6g") + " kg/m^3)";
}

// "the file's material 'steel' (7850 kg/m^3)".
std::string MaterialWords(const CadPart& part) { return "the file's material " + MaterialName(part); }

double FrobeniusDifference(const Matrix3& a, const Matrix3& b) {
  const double norm = b.norm();
  return norm > 0 ? (a - b).norm() / norm : 0.0;
}

}  // namespace

bool MaterialsDiffer(const LoadedMesh& loaded, const LoadOptions& given) {
  if (given.mass_stated || loaded.cad_parts.size() < 2) return false;
  for (const CadPart& p : loaded.cad_parts) {
    if (p.density != loaded.cad_parts.front().density) return true;
  }
  return false;
}

void ApplyFileMaterial(SolidResult& r, LoadOptions& opt) {
  const std::vector<CadPart>& parts = r.loaded.cad_parts;
  bool any = false, same = true;
  std::string list;
  for (const CadPart& p : parts) {
    any = any || p.density > 0;
    same = same && p.density == parts.front().density;
    if (p.density > 0 && list.find(MaterialName(p)) == std::string::npos)
      list += (list.empty() ? "" : ", ") + MaterialName(p);
  }
  if (!any) return;
  if (!opt.mass_stated) {
    if (!same) return;  // several materials: a part at a time (SolveParts)
    opt.mass = Density{parts.front().density};
    r.density_source = MaterialWords(parts.front());
    return;
  }
  const auto* stated = std::get_if<Density>(&opt.mass);
  if (same && stated != nullptr && stated->value == parts.front().density) return;
  Warn(r, FindingKind::kMaterialOverridden,
       (same ? MaterialWords(parts.front()) + " gives" : "the file's materials (" + list + ") give") +
           " other densities than the one stated, which was used throughout");
}

BrepReport CompareWithBrep(const MassProperties& mesh, const MassProperties& brep, double size_m) {
  BrepReport b;
  b.mp = brep;
  b.mesh = mesh;
  b.principal = ComputePrincipalInertia(brep.inertia_com);
  b.volume_difference = (mesh.volume - brep.volume) / brep.volume;
  b.com_difference = size_m > 0 ? (mesh.center_of_mass - brep.center_of_mass).norm() / size_m : 0.0;
  b.inertia_difference = FrobeniusDifference(mesh.inertia_com, brep.inertia_com);
  return b;
}

void AddBrep(SolidResult& r, const LoadOptions&) {
  const std::vector<CadPart>& parts = r.loaded.cad_parts;
  if (parts.empty() || r.model != ModelKind::kSolid) return;
  VolumeIntegrals sum;
  double error = 0, deflection = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (!parts[i].solid) {
      const std::string which =
          parts.size() == 1 || r.loaded.part_names.size() <= i ? "the part" : "part '" + r.loaded.part_names[i] + "'";
      Warn(r, FindingKind::kNoBrep,
           which + " has no solid (surfaces only): the exact B-rep numbers are missing, only the mesh's are given");
      return;
    }
    sum.volume += parts[i].brep.volume;
    sum.first += parts[i].brep.first;
    sum.second += parts[i].brep.second;
    error = std::max(error, parts[i].brep_error);
    deflection = std::max(deflection, parts[i].deflection);
  }
  const MassProperties unit = Scaled(FromIntegrals(sum, 1.0), MetresPerUnit(r.unit));
  // The same density; with a total mass stated, the same mass.
  const double density = r.mass_fixed ? r.mp.mass / unit.volume : r.mp.density;
  BrepReport b = CompareWithBrep(r.mp, AtDensity(unit, density), r.size_m);
  b.estimated_error = error;
  b.deflection = deflection;
  r.brep = b;
}

void ComposeBrep(SolidResult& whole) {
  std::vector<MassProperties> brep, mesh;
  double error = 0, deflection = 0;
  bool result = false;
  for (const SolidResult& part : whole.parts) {
    if (!part.brep) return;
    brep.push_back(part.brep->mp);
    mesh.push_back(part.brep->mesh);
    error = std::max(error, part.brep->estimated_error);
    deflection = std::max(deflection, part.brep->deflection);
    result = part.brep->is_result;
    if (!part.brep->mesh_checked) return;  // the whole's check needs every part's
  }
  if (brep.empty()) return;
  BrepReport b = CompareWithBrep(Combine(mesh), Combine(brep), whole.size_m);
  b.estimated_error = error;
  b.deflection = deflection;
  b.is_result = result;
  whole.brep = b;
}

namespace {

// Why the options need the tessellation as the result ("" when they do not).
std::string MeshOnlyOption(const LoadOptions& o) {
  if (std::holds_alternative<ShellModel>(o.model)) return "a shell (the surface's mass)";
  if (std::holds_alternative<WallModel>(o.model)) return "{wall}";
  if (std::holds_alternative<WindingNumberModel>(o.model)) return "the winding-number estimate";
  if (o.repair) return "{repair}";
  if (o.hull) return "the convex hull";
  if (o.exact) return "the exact rational integration";
  return "";
}

std::string PartWords(const SolidResult& r) { return r.part.empty() ? "the part" : "part '" + r.part + "'"; }

// The exporting system's validation properties beside the B-rep's; a warning past 1e-3 (such
// properties are often computed on the exporter's own tessellation, to a few digits).
void CompareWithFile(SolidResult& r, BrepReport& b, const CadFileProperties& file, double scale) {
  constexpr double kAgreement = 1e-3;
  std::string disagree;
  const auto note = [&](const char* what, double difference) {
    if (std::abs(difference) > kAgreement)
      disagree += std::string(disagree.empty() ? "" : ", ") + what + " " + Fixed(difference, "%+.2e");
  };
  if (file.volume) {
    b.file_volume = *file.volume * scale * scale * scale;
    b.file_volume_difference = (*b.file_volume - r.mp.volume) / r.mp.volume;
    note("volume", *b.file_volume_difference);
  }
  if (file.area && r.mp.surface_area > 0) {
    b.file_area = *file.area * scale * scale;
    b.file_area_difference = (*b.file_area - r.mp.surface_area) / r.mp.surface_area;
    note("surface area", *b.file_area_difference);
  }
  if (file.centroid && r.size_m > 0) {
    b.file_centroid = *file.centroid * scale;
    b.file_com_difference = (*b.file_centroid - r.mp.center_of_mass).norm() / r.size_m;
    note("centroid (over the size)", *b.file_com_difference);
  }
  if (!disagree.empty()) {
    Warn(r, FindingKind::kFileProperties,
         PartWords(r) +
             ": the file's own validation properties (its exporter's numbers) differ from the exact "
             "B-rep's beyond 1e-3: " +
             disagree +
             " (file - B-rep, relative); the file may have been "
             "changed after export, or its exporter computed them on an approximation");
  }
}

}  // namespace

bool BrepIsTheAnswer(const LoadOptions& o) { return o.brep && MeshOnlyOption(o).empty(); }

CadOptions CadOptionsFor(const LoadOptions& o) {
  CadOptions cad = o.cad;
  if (cad.relative_deflection == 0) cad.relative_deflection = BrepIsTheAnswer(o) ? 1e-3 : 1e-4;
  cad.num_threads = o.num_threads;
  return cad;
}

void AddCadFindings(SolidResult& r) {
  const LoadedMesh& m = r.loaded;
  for (const std::string& note : m.cad_notes) Warn(r, FindingKind::kCadLeftOut, note);
  const CadInterference& in = m.cad_interference;
  const auto name = [&](std::size_t i) {
    const std::string product =
        i < m.part_names.size() && !m.part_names[i].empty() ? m.part_names[i] : "part " + std::to_string(i + 1);
    const std::string& instance = m.cad_parts[i].instance;
    return "'" + (instance.empty() ? product : instance + "' ('" + product) + (instance.empty() ? "'" : "')");
  };
  const double scale = m.declared_unit ? MetresPerUnit(*m.declared_unit) : 1e-3;
  for (const CadOverlap& o : in.overlaps) {
    const std::string who =
        o.a == o.b ? "two solids inside part " + name(o.a) : "parts " + name(o.a) + " and " + name(o.b);
    if (o.volume < 0) {
      Warn(r, FindingKind::kInterference,
           who +
               " may interfere: their boxes overlap, and OpenCASCADE's boolean "
               "could not measure the common volume");
    } else {
      Warn(r, FindingKind::kInterference,
           who + " interfere: they share " + Fixed(o.volume * scale * scale * scale, "%.4g") + " m^3, counted " +
               (o.a == o.b ? "twice in that part" : "in both") +
               " (the whole is the sum of its parts, as CAD systems give it)");
    }
  }
  const bool several = m.cad_parts.size() > 1 || (!m.cad_parts.empty() && m.cad_parts.front().solid);
  if (!several) return;
  if (!in.done) {
    Warn(r, FindingKind::kInterference, "interference not measured: " + in.not_done);
  } else if (in.measured < in.candidates) {
    Warn(r, FindingKind::kInterference,
         "interference not measured for " + std::to_string(in.candidates - in.measured) + " of " +
             std::to_string(in.candidates) + " pairs of solids whose boxes overlap (the budget is " +
             std::to_string(in.measured) + " pairs)");
  }
}

bool SolveBrep(SolidResult& r, const LoadOptions& opt) {
  const std::vector<CadPart>& parts = r.loaded.cad_parts;
  if (parts.size() != 1 || !parts.front().solid) return false;  // not CAD, or surfaces: the mesh route
  const CadPart& part = parts.front();
  if (const std::string option = MeshOnlyOption(opt); !option.empty() || !opt.brep) {
    if (opt.brep) {
      Warn(r, FindingKind::kCadMeshAnswer,
           "the tessellation's numbers are the result, because " + option +
               " needs a mesh; the exact B-rep's are beside them");
    }
    return false;
  }
  const PolygonMesh& mesh = r.loaded.mesh;
  r.topology = AnalyzeTopology(mesh, opt.num_threads);
  for (const std::string& fix : part.fixes) Warn(r, FindingKind::kCadFix, PartWords(r) + ": " + fix);
  // The size for the plausibility check and the differences: the check mesh's box, or with no
  // mesh the B-rep's radius of gyration.
  double size = MeshDiagonal(mesh);
  if (!(size > 0)) size = 2 * std::sqrt(std::abs(part.brep.second.trace() / part.brep.volume));
  VolumeIntegrals exact = part.brep;
  exact.surface_area = part.brep_area;
  FinishIntegrals(r, exact, opt, size);
  r.mass_fixed = FixesMass(opt.mass);
  r.path_used = "the exact B-rep (OpenCASCADE's Gauss integration, estimated relative error " +
                Fixed(part.brep_error, "%.1g") + "); its tessellation is the check";
  BrepReport b;
  b.mp = r.mp;
  b.principal = r.principal;
  b.estimated_error = part.brep_error;
  b.deflection = part.deflection;
  b.is_result = true;
  const MeshTopology& t = r.topology;
  b.mesh_checked = t.faces > 0 && t.BoundsVolume() && t.duplicate_faces + t.reversed_duplicate_faces == 0;
  if (b.mesh_checked) {
    IntegrationOptions io;
    io.num_threads = opt.num_threads;
    const TriangleMesh tri = Triangulate(mesh);
    const MassProperties unit = Scaled(FromIntegrals(IntegrateTriangles(tri.V, tri.F, io), 1.0), MetresPerUnit(r.unit));
    const MassProperties checked = AtDensity(unit, r.mass_fixed ? r.mp.mass / unit.volume : r.mp.density);
    const BrepReport c = CompareWithBrep(checked, r.mp, r.size_m);
    b.mesh = checked;
    b.volume_difference = c.volume_difference;
    b.com_difference = c.com_difference;
    b.inertia_difference = c.inertia_difference;
    // A tessellation within the deflection d of the surface moves the volume by at most area × d:
    // beyond twice that, the two routes disagree about the solid.
    const double bound = 2 * part.brep_area * part.deflection / part.brep.volume;
    if (std::abs(b.volume_difference) > bound && std::abs(b.volume_difference) > 1e-9) {
      Warn(r, FindingKind::kCadCheck,
           PartWords(r) + ": the check tessellation's volume differs from the exact B-rep's by " +
               Fixed(b.volume_difference, "%+.2e") + ", more than its deflection allows (" + Fixed(bound, "%.2e") +
               "): the B-rep may be faulty (self-intersecting or gapped faces); compare with the exporting system");
    }
  } else {
    const std::string why = t.faces == 0       ? std::string("OpenCASCADE made no triangles of it")
                            : t.BoundsVolume() ? "it repeats faces"
                                               : t.Problems();
    Warn(r, FindingKind::kCadCheck,
         PartWords(r) + ": no second opinion: the check tessellation does not bound a volume (" + why +
             (part.untessellated_faces > 0
                  ? "; " + std::to_string(part.untessellated_faces) + " B-rep faces were not meshed"
                  : "") +
             "); the exact B-rep's numbers stand on OpenCASCADE's integration alone");
  }
  if (part.file.volume || part.file.area || part.file.centroid) CompareWithFile(r, b, part.file, MetresPerUnit(r.unit));
  r.brep = b;
  return true;
}

}  // namespace massprops::internal
