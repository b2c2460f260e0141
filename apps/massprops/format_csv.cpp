#include <sstream>

#include "format.h"
#include "massprops/text.h"

namespace massprops::cli {
namespace {

std::string Quoted(const std::string& s) {  // RFC 4180
  std::string o = "\"";
  for (char ch : s) o += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return o + "\"";
}

}  // namespace

std::string FormatCsv(const std::vector<SolidResult>& results, const FormatOptions& opt) {
  std::ostringstream out;
  const bool origin = opt.frame == Frame::kOrigin;
  out << "file,unit,volume_m3,mass_kg,density_kg_m3,com_x_m,com_y_m,com_z_m,"
         "ixx,iyy,izz,ixy,ixz,iyz,i1,i2,i3,surface_area_m2,closed,physically_valid"
      << (origin ? ",origin_ixx,origin_iyy,origin_izz,origin_ixy,origin_ixz,origin_iyz" : "");
  bool estimates = false, shells = false;
  for (const SolidResult& r : results) {
    estimates = estimates || r.estimate.has_value();
    shells = shells || r.model == ModelKind::kShell;
  }
  if (estimates) {  // standard errors of the Monte-Carlo paths (empty for exact rows)
    out << ",se_volume,se_mass,se_com_x,se_com_y,se_com_z,se_ixx,se_iyy,se_izz,se_ixy,se_ixz,se_iyz,se_i1,se_i2,se_i3";
  }
  // Thin shells have no volume and no volume density: those cells stay empty, and the area
  // density has a column of its own.
  if (shells) out << ",area_density_kg_m2";
  out << ",warnings\n";
  for (const SolidResult& r : results) {
    const Matrix3& I = r.mp.inertia_com;
    const Vector3& c = r.mp.center_of_mass;
    const Vector3& m = r.principal.moments;
    const bool shell = r.model == ModelKind::kShell;
    out << Quoted(r.source) << "," << UnitName(r.unit);
    out << "," << (shell ? "" : ExactDecimal(r.mp.volume)) << "," << ExactDecimal(r.mp.mass) << ","
        << (shell ? "" : ExactDecimal(r.mp.density));
    for (double v : {c[0], c[1], c[2], I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2), m[0], m[1], m[2],
                     r.mp.surface_area}) {
      out << "," << ExactDecimal(v);
    }
    out << "," << (r.topology.BoundsVolume() ? "true" : "false") << "," << (r.validity.valid ? "true" : "false");
    if (origin) {
      const Matrix3 O = r.mp.InertiaAbout(Vector3::Zero());
      for (double v : {O(0, 0), O(1, 1), O(2, 2), O(0, 1), O(0, 2), O(1, 2)}) out << "," << ExactDecimal(v);
    }
    if (estimates && r.estimate) {
      const MassProperties& e = r.estimate->standard_error;
      const Vector3& p = r.estimate->principal_moments_se;
      for (double v : {e.volume, e.mass, e.center_of_mass[0], e.center_of_mass[1], e.center_of_mass[2],
                       e.inertia_com(0, 0), e.inertia_com(1, 1), e.inertia_com(2, 2), e.inertia_com(0, 1),
                       e.inertia_com(0, 2), e.inertia_com(1, 2), p[0], p[1], p[2]}) {
        out << "," << ExactDecimal(v);
      }
    } else if (estimates) {
      out << ",,,,,,,,,,,,,,";
    }
    if (shells) out << "," << (shell ? ExactDecimal(r.mp.density) : "");
    std::string warnings;  // every finding, "; "-separated
    for (const Finding& f : r.findings) warnings += (warnings.empty() ? "" : "; ") + Worded(f.message, WordsOf(opt));
    out << "," << (warnings.empty() ? "" : Quoted(warnings)) << "\n";
  }
  return out.str();
}

}  // namespace massprops::cli
