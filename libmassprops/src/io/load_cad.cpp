// The pipeline's CAD steps: the density a file's material gives, and the exact B-rep's numbers
// beside the tessellation's.

#include <cmath>
#include <string>
#include <vector>

#include "load_internal.h"
#include "massprops/composition.h"
#include "plausibility.h"

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

void AddBrep(SolidResult& r, const LoadOptions& opt) {
  const std::vector<CadPart>& parts = r.loaded.cad_parts;
  if (parts.empty() || r.model != ModelKind::kSolid) return;
  VolumeIntegrals sum;
  double error = 0, deflection = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (!parts[i].solid) {
      const std::string which =
          parts.size() == 1 || r.loaded.part_names.size() <= i ? "the part" : "part '" + r.loaded.part_names[i] + "'";
      if (opt.brep) {
        throw LoadError(r.source + ": " + which +
                        " has no solid (surfaces only), so the B-rep has no volume to report; the mesh's numbers "
                        "are all there is (without the B-rep result)");
      }
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
  if (opt.brep) {
    b.is_result = true;
    r.mp = b.mp;
    r.principal = b.principal;
    r.validity = CheckPhysicallyValid(r.principal.moments, 1e-12);
    r.path_used = "the exact B-rep (OpenCASCADE's Gauss integration), the mesh's numbers beside it";
  }
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
  }
  if (brep.empty()) return;
  BrepReport b = CompareWithBrep(Combine(mesh), Combine(brep), whole.size_m);
  b.estimated_error = error;
  b.deflection = deflection;
  b.is_result = result;
  whole.brep = b;
}

}  // namespace massprops::internal
