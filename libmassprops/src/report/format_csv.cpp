// The CSV output (massprops/report/format.h): one row per result, the columns named once.

#include <sstream>

#include "massprops/report/format.h"
#include "massprops/text.h"

namespace massprops::report {
namespace {

std::string Quoted(const std::string& s) {  // RFC 4180
  std::string o = "\"";
  for (char ch : s) o += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return o + "\"";
}

// A unit as a column-name suffix: "g*mm^2" → "g_mm2", "kg/m^3" → "kg_m3".
std::string Suffix(const std::string& unit) {
  std::string o;
  for (char ch : unit) {
    if (ch == '*' || ch == '/') {
      o += '_';
    } else if (ch != '^') {
      o += ch;
    }
  }
  return o;
}

}  // namespace

std::string FormatCsv(const std::vector<SolidResult>& given, const FormatOptions& opt) {
  // An assembly is a row per part, then its whole (the part column empty).
  std::vector<const SolidResult*> results;
  bool parts = false;
  for (const SolidResult& r : given) {
    for (const SolidResult& part : r.parts) results.push_back(&part);
    results.push_back(&r);
    parts = parts || !r.parts.empty();
  }
  std::ostringstream out;
  const bool origin = opt.frame == Frame::kOrigin;
  const ReportUnits& u = opt.units;
  const std::string l = UnitName(u.length);
  // SI keeps the columns' historical names (inertia columns without a unit); other units name theirs.
  const std::string in = u.IsSi() ? "" : "_" + Suffix(UnitName(u.inertia));
  out << (parts ? "file,part,unit,volume_" : "file,unit,volume_") << Suffix(u.VolumeName()) << ",mass_"
      << UnitName(u.mass) << ",density_" << Suffix(u.DensityName()) << ",com_x_" << l << ",com_y_" << l << ",com_z_"
      << l;
  for (const char* name : {"ixx", "iyy", "izz", "ixy", "ixz", "iyz", "i1", "i2", "i3"}) out << "," << name << in;
  out << ",surface_area_" << Suffix(u.AreaName()) << ",closed,physically_valid";
  if (origin) {
    for (const char* name : {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"}) out << ",origin_" << name << in;
  }
  if (opt.reference) {
    for (const char* name : {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"}) out << ",about_" << name << in;
  }
  bool estimates = false, shells = false;
  for (const SolidResult* r : results) {
    estimates = estimates || r->estimate.has_value();
    shells = shells || r->model == ModelKind::kShell;
  }
  if (estimates) {  // standard errors of the Monte-Carlo paths (empty for exact rows)
    out << ",se_volume,se_mass,se_com_x,se_com_y,se_com_z,se_ixx,se_iyy,se_izz,se_ixy,se_ixz,se_iyz,se_i1,se_i2,se_i3";
  }
  // Thin shells have no volume and no volume density: those cells stay empty, and the area
  // density has a column of its own.
  if (shells) out << ",area_density_" << Suffix(u.AreaDensityName());
  bool hulls = false;
  for (const SolidResult* r : results) hulls = hulls || r->hull.has_value();
  if (hulls) {
    out << ",hull_volume_" << Suffix(u.VolumeName()) << ",hull_mass_" << UnitName(u.mass);
    for (const char* name : {"com_x", "com_y", "com_z"}) out << ",hull_" << name << "_" << l;
    for (const char* name : {"ixx", "iyy", "izz", "ixy", "ixz", "iyz", "i1", "i2", "i3"}) out << ",hull_" << name << in;
  }
  out << ",warnings\n";
  for (const SolidResult* row : results) {
    const SolidResult& r = *row;
    const Matrix3 I = r.mp.inertia_com / u.Inertia();
    const Vector3 c = r.mp.center_of_mass / u.Length();
    const Vector3 m = r.principal.moments / u.Inertia();
    const bool shell = r.model == ModelKind::kShell;
    out << Quoted(r.source) << (parts ? "," + (r.part.empty() ? std::string() : Quoted(r.part)) : "") << ","
        << UnitName(r.unit);
    out << "," << (shell ? "" : ExactDecimal(r.mp.volume / u.Volume())) << "," << ExactDecimal(r.mp.mass / u.Mass())
        << "," << (shell ? "" : ExactDecimal(r.mp.density / u.Density()));
    for (double v : {c[0], c[1], c[2], I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2), m[0], m[1], m[2],
                     r.mp.surface_area / u.Area()}) {
      out << "," << ExactDecimal(v);
    }
    out << "," << (r.topology.BoundsVolume() ? "true" : "false") << "," << (r.validity.valid ? "true" : "false");
    if (origin) {
      const Matrix3 O = r.mp.InertiaAbout(Vector3::Zero()) / u.Inertia();
      for (double v : {O(0, 0), O(1, 1), O(2, 2), O(0, 1), O(0, 2), O(1, 2)}) out << "," << ExactDecimal(v);
    }
    if (opt.reference) {
      const Matrix3 A = InertiaInFrame(r.mp, ReferenceOf(r, opt)) / u.Inertia();
      for (double v : {A(0, 0), A(1, 1), A(2, 2), A(0, 1), A(0, 2), A(1, 2)}) out << "," << ExactDecimal(v);
    }
    if (estimates && r.estimate) {
      const MassProperties& e = r.estimate->standard_error;
      const Vector3 p = r.estimate->principal_moments_se / u.Inertia();
      const Matrix3 ei = e.inertia_com / u.Inertia();
      const Vector3 ec = e.center_of_mass / u.Length();
      for (double v : {e.volume / u.Volume(), e.mass / u.Mass(), ec[0], ec[1], ec[2], ei(0, 0), ei(1, 1), ei(2, 2),
                       ei(0, 1), ei(0, 2), ei(1, 2), p[0], p[1], p[2]}) {
        out << "," << ExactDecimal(v);
      }
    } else if (estimates) {
      out << ",,,,,,,,,,,,,,";
    }
    if (shells) out << "," << (shell ? ExactDecimal(r.mp.density / u.AreaDensity()) : "");
    if (hulls && r.hull) {
      const MassProperties& h = r.hull->mp;
      const Matrix3 hi = h.inertia_com / u.Inertia();
      const Vector3 hc = h.center_of_mass / u.Length(), hm = r.hull->principal.moments / u.Inertia();
      for (double v : {h.volume / u.Volume(), h.mass / u.Mass(), hc[0], hc[1], hc[2], hi(0, 0), hi(1, 1), hi(2, 2),
                       hi(0, 1), hi(0, 2), hi(1, 2), hm[0], hm[1], hm[2]}) {
        out << "," << ExactDecimal(v);
      }
    } else if (hulls) {
      out << ",,,,,,,,,,,,,,";
    }
    std::string warnings;  // every finding, "; "-separated
    for (const Finding& f : r.findings) warnings += (warnings.empty() ? "" : "; ") + Worded(f.message, WordsOf(opt));
    out << "," << (warnings.empty() ? "" : Quoted(warnings)) << "\n";
  }
  return out.str();
}

}  // namespace massprops::report
