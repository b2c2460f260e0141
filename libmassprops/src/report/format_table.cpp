// The table output (massprops/report/format.h): what a person reads at the terminal, parts and all.

#include <algorithm>
#include <cmath>
#include <sstream>

#include "massprops/report/format.h"
#include "massprops/text.h"

namespace massprops::report {
namespace {

// Numbers with `digits` after the point in scientific notation (10: eleven significant digits).
std::string Num(double v, int digits = 10) { return FormatDouble(v, ("% ." + std::to_string(digits) + "e").c_str()); }

void PrintMatrix(std::ostream& out, const std::string& indent, const Matrix3& m, int digits = 10) {
  for (int i = 0; i < 3; ++i) {
    out << indent << "[" << Num(m(i, 0), digits) << "  " << Num(m(i, 1), digits) << "  " << Num(m(i, 2), digits)
        << " ]\n";
  }
}

// The digits a result's numbers carry: all eleven, or those its relative error bound leaves.
int DigitsOf(const SolidResult& r) {
  if (!(r.relative_error_bound > 0)) return 10;
  return std::clamp(static_cast<int>(std::floor(-std::log10(r.relative_error_bound))) - 1, 0, 10);
}

// A part's name, and a CAD component's own name beside it when it has one ("pin [pin:2]").
std::string PartLabel(const SolidResult& part) {
  return part.instance.empty() || part.instance == part.part ? part.part : part.part + " [" + part.instance + "]";
}

std::string FormatOne(const SolidResult& r, const FormatOptions& opt);

}  // namespace

std::string FormatTable(const SolidResult& r, const FormatOptions& opt) {
  if (r.parts.empty()) return FormatOne(r, opt);
  // An assembly: every part in full, a summary line per part, then the whole.
  std::ostringstream out;
  const ReportUnits& u = opt.units;
  for (const SolidResult& part : r.parts) out << FormatOne(part, opt) << "\n";
  // A part's row: its label; when the parts declare different units, each its own ("declared in
  // INCH"), the numbers all in the output's.
  const auto declared = [](const SolidResult& part) {
    return part.loaded.cad_parts.empty() ? std::string() : part.loaded.cad_parts.front().unit;
  };
  const bool mixed_units = std::any_of(r.parts.begin(), r.parts.end(), [&](const SolidResult& part) {
    return declared(part) != declared(r.parts.front());
  });
  auto label = [&](const SolidResult& part) {
    std::string text = PartLabel(part);
    if (mixed_units && !declared(part).empty()) text += " (declared in " + declared(part) + ")";
    return text;
  };
  std::size_t width = 5;  // "whole"; a shorter part name ("Moon") once made the padding negative
  for (const SolidResult& part : r.parts) width = std::max(width, label(part).size());
  auto row = [&](const std::string& name, const SolidResult& x) {
    const Vector3 c = x.mp.center_of_mass / u.Length();
    const Vector3 m = x.principal.moments / u.Inertia();
    out << "  " << name << std::string(width - name.size(), ' ') << "  " << FormatDouble(x.mp.mass / u.Mass(), "%12.6g")
        << "  " << FormatDouble(x.mp.volume / u.Volume(), "%12.6g") << "  [" << FormatDouble(c[0], "% .5e") << " "
        << FormatDouble(c[1], "% .5e") << " " << FormatDouble(c[2], "% .5e") << "]  [" << FormatDouble(m[0], "%.5e")
        << " " << FormatDouble(m[1], "%.5e") << " " << FormatDouble(m[2], "%.5e") << "]\n";
  };
  out << "parts of " << r.source << " (mass " << UnitName(u.mass) << ", volume " << u.VolumeName()
      << ", center of mass " << UnitName(u.length) << ", principal moments "
      << (u.IsSi() ? std::string("kg m^2") : std::string(UnitName(u.inertia))) << "):\n";
  out << "  part" << std::string(width - 4, ' ') << "          mass        volume  center of mass"
      << std::string(30, ' ') << "principal moments\n";
  for (const SolidResult& part : r.parts) row(label(part), part);
  row(std::string(width > 5 ? width - 5 : 0, ' ') + "whole", r);
  out << "\n" << FormatOne(r, opt);
  return out.str();
}

namespace {

// "[ x  y  z ]" in `unit`, to `digits`.
std::string VecText(const Vector3& v, double unit, int digits) {
  return "[" + Num(v[0] / unit, digits) + "  " + Num(v[1] / unit, digits) + "  " + Num(v[2] / unit, digits) + " ]";
}

// " (kg m^2):\n" or the report's inertia unit.
std::string InertiaLabel(const ReportUnits& u) {
  return " (" + (u.IsSi() ? std::string("kg m^2") : UnitName(u.inertia)) + "):\n";
}

// What was read and how: the file (or shape), parts, repair, shells, precision, units, model,
// integration path and size.
void WriteHeader(std::ostream& out, const SolidResult& r, const FormatOptions& opt, int digits) {
  const ReportUnits& u = opt.units;
  const std::string len = UnitName(u.length);
  const auto& t = r.topology;
  const bool implicit = r.model == ModelKind::kImplicit;
  const bool shell = r.model == ModelKind::kShell;
  if (implicit) {
    out << "shape           " << r.source << "\n";
  } else if (r.full_topology) {
    out << "file            " << r.source << "  (" << r.loaded.format << ", " << t.faces << " faces, " << t.vertices
        << " vertices, " << t.components << " component" << (t.components == 1 ? "" : "s") << ", "
        << (t.BoundsVolume() ? "closed and consistently oriented" : t.Problems())
        << (t.degenerate_faces ? ", " + std::to_string(t.degenerate_faces) + " degenerate faces" : "") << ")\n";
  } else {
    out << "file            " << r.source << "  (" << r.loaded.format << ", " << t.faces
        << " triangles, closed and consistently oriented: every edge matched by its reverse)\n";
  }
  if (!r.part.empty()) {
    out << "part            " << PartLabel(r) << "\n";
  }
  if (!r.parts.empty()) {
    out << "parts           " << r.parts.size() << ", each computed on its own; the whole is their composition\n";
  }
  if (r.repair) out << "repair          " << r.repair->Summary() << "\n";
  if (r.self_intersections >= 0) {
    out << "self-intersect  "
        << (r.self_intersections == 0 ? std::string("none")
                                      : std::to_string(r.self_intersections) + " intersecting face pairs")
        << "\n";
  }
  if (r.shells.shells.size() > 1) {
    const double s3 = std::pow(MetresPerUnit(r.unit), 3);
    out << "shells          ";
    for (std::size_t i = 0; i < r.shells.shells.size(); ++i) {
      const Shell& sh = r.shells.shells[i];
      out << (i ? "; " : "") << "#" << i + 1 << " " << sh.faces.size() << " faces, "
          << FormatDouble(sh.signed_volume * s3 / u.Volume(), "%.6g") << " " << u.VolumeName()
          << (sh.inside_of >= 0 ? " (cavity in #" + std::to_string(sh.inside_of + 1) + ")" : "");
    }
    out << "\n";
  }
  if (r.loaded.float32_coordinates) {
    out << "precision       the file's coordinates are 32-bit floats (~7 significant digits)\n";
  }
  if (r.relative_error_bound > 0) {
    const bool filled = r.repair && r.repair->fill_volume_bound > 0;
    out << "precision       " << (filled ? "the filled holes' ambiguity" : "rounding")
        << " leaves these numbers good to about " << FormatDouble(r.relative_error_bound, "%.1g")
        << " relative (printed to " << digits + 1 << " significant digits)\n";
  }
  out << "units           file coordinates in " << UnitName(r.unit) << " (" << MetresPerUnit(r.unit) << " m each"
      << (r.unit_source == UnitSource::kFile ? ", declared by the file" : "") << "), results in "
      << (u.IsSi() ? std::string("SI") : u.Describe()) << "; " << (shell ? "area density " : "density ")
      << (shell ? r.mp.density / u.AreaDensity() : r.mp.density / u.Density()) << " "
      << (shell ? u.AreaDensityName() : u.DensityName()) << (r.mass_fixed ? " (from --mass)" : "")
      << (r.density_source.empty() ? "" : " (" + r.density_source + ")") << "\n";
  if (shell) out << "model           thin shell: the surface itself carries the mass (no volume)\n";
  if (r.model == ModelKind::kWall) {
    out << "model           hollow part: the solid between the surface and its inward offset by " << r.wall_thickness
        << " " << UnitName(r.unit) << "\n";
  }
  out << "integration     " << r.path_used << ", " << FormatDouble(r.seconds, "%.3g") << " s\n";
  out << "size            " << Num(r.size_m / u.Length()) << " " << len << " (bounding-box diagonal)\n";
}

// The results beside the answer: the certified enclosures, the convex hull's, the exact B-rep's
// (or the check mesh's) and the exporting system's own validation properties.
void WriteComparisons(std::ostream& out, const SolidResult& r, const FormatOptions& opt, int digits) {
  const ReportUnits& u = opt.units;
  const std::string len = UnitName(u.length), mass_unit = UnitName(u.mass), inertia_unit = UnitName(u.inertia);
  auto vec = [&](const Vector3& v, double unit) { return VecText(v, unit, digits); };
  const std::string inertia_label = InertiaLabel(u);
  const Vector3& m = r.principal.moments;
  const double ui = u.Inertia();
  if (r.exact) {
    const ExactReport& e = *r.exact;
    out << "certified       volume, mass, center of mass and inertia above are the correctly rounded values of\n"
           "                the exact rationals the stored coordinates define (GMP); principal moments lie in\n";
    for (const auto& [lo, hi] : e.moments) {
      out << "                [" << FormatDouble(lo / ui, "%.17g") << ", " << FormatDouble(hi / ui, "%.17g") << "] "
          << (u.IsSi() ? std::string("kg m^2") : inertia_unit) << "\n";
    }
    out << "                the default path differed by " << FormatDouble(e.inertia_difference, "%.2g")
        << " (|dI|/|I|) and " << FormatDouble(e.com_difference, "%.2g") << " (|dc|/size)\n";
  }
  if (r.hull) {
    const HullReport& h = *r.hull;
    auto pct = [](double a, double b) { return FormatDouble(100 * (a - b) / b, "%+.3g") + " %"; };
    out << "convex hull     as collision engines see the body (" << h.vertices << " vertices, " << h.faces
        << " triangles), " << (r.mass_fixed ? "the same mass" : "the same density") << ":\n";
    out << "  volume        " << Num(h.mp.volume / u.Volume()) << " " << u.VolumeName() << "  ("
        << pct(h.mp.volume, r.mp.volume) << " of the part's)\n";
    out << "  mass          " << Num(h.mp.mass / u.Mass()) << " " << mass_unit << "\n";
    out << "  center of mass " << vec(h.mp.center_of_mass, u.Length()) << " " << len << "\n";
    out << "  inertia about its center of mass, file's axes" << inertia_label;
    PrintMatrix(out, "                ", h.mp.inertia_com / u.Inertia());
    const Vector3& hm = h.principal.moments;
    out << "  principal moments            " << Num(hm[0] / ui) << "  " << Num(hm[1] / ui) << "  " << Num(hm[2] / ui)
        << "  (" << pct(hm[0], m[0]) << ", " << pct(hm[1], m[1]) << ", " << pct(hm[2], m[2]) << ")\n";
  }
  if (r.brep && (!r.brep->is_result || r.brep->mesh_checked)) {
    const BrepReport& b = *r.brep;
    const MassProperties& other = b.is_result ? b.mesh : b.mp;
    out << (b.is_result ? "check mesh      the tessellation (deflection "
                        : "exact B-rep     OpenCASCADE's integral of the solid (")
        << (b.is_result ? FormatDouble(b.deflection, "%.3g") + " " + UnitName(r.unit) + ")"
                        : "estimated error " + FormatDouble(b.estimated_error, "%.1g") + ")")
        << ", the same " << (r.mass_fixed ? "mass" : "density") << ":\n";
    out << "  volume        " << Num(other.volume / u.Volume(), digits) << " " << u.VolumeName() << "\n";
    out << "  mass          " << Num(other.mass / u.Mass(), digits) << " " << mass_unit << "\n";
    out << "  center of mass " << vec(other.center_of_mass, u.Length()) << " " << len << "\n";
    out << "  inertia about its center of mass, file's axes" << inertia_label;
    PrintMatrix(out, "                ", other.inertia_com / u.Inertia(), digits);
    out << "  mesh - B-rep  volume " << FormatDouble(b.volume_difference, "%+.2e") << " relative, center of mass "
        << FormatDouble(b.com_difference, "%.2e") << " of the size, inertia "
        << FormatDouble(b.inertia_difference, "%.2e") << " (|dI|/|I|); tessellated with deflection "
        << FormatDouble(b.deflection, "%.3g") << " " << UnitName(r.unit) << "\n";
  }
  if (r.brep && (r.brep->file_volume || r.brep->file_area || r.brep->file_centroid)) {
    const BrepReport& b = *r.brep;
    out << "file's own      the exporting system's validation properties (file - B-rep):";
    if (b.file_volume)
      out << " volume " << Num(*b.file_volume / u.Volume()) << " " << u.VolumeName() << " ("
          << FormatDouble(*b.file_volume_difference, "%+.2e") << ")";
    if (b.file_area && b.file_area_difference)
      out << ", surface area " << FormatDouble(*b.file_area_difference, "%+.2e");
    if (b.file_centroid && b.file_com_difference)
      out << ", centroid " << FormatDouble(*b.file_com_difference, "%.2e") << " of the size";
    out << "\n";
  }
}

std::string FormatOne(const SolidResult& r, const FormatOptions& opt) {
  std::ostringstream out;
  const ReportUnits& u = opt.units;
  const std::string len = UnitName(u.length), mass_unit = UnitName(u.mass), inertia_unit = UnitName(u.inertia);
  const int digits = DigitsOf(r);
  auto vec = [&](const Vector3& v, double unit) { return VecText(v, unit, digits); };
  WriteHeader(out, r, opt, digits);
  const bool shell = r.model == ModelKind::kShell;
  const MassProperties* se = r.estimate ? &r.estimate->standard_error : nullptr;
  auto pm = [&](double v, double unit) { return "  +- " + FormatDouble(v / unit, "%.2e"); };
  if (r.estimate) {
    out << "error bars      +- one standard error; 95 % interval = +- "
        << FormatDouble(r.estimate->interval95_factor, "%.3g") << " standard errors"
        << (r.estimate->method == SamplingMethod::kQuasiMonteCarlo ? " (Student t over the randomizations)" : "")
        << "\n";
  }
  if (!shell) {
    out << "volume          " << Num(r.mp.volume / u.Volume(), digits) << " " << u.VolumeName()
        << (se ? pm(se->volume, u.Volume()) : "") << "\n";
  }
  if (!r.estimate) out << "surface area    " << Num(r.mp.surface_area / u.Area()) << " " << u.AreaName() << "\n";
  out << "mass            " << Num(r.mp.mass / u.Mass(), digits) << " " << mass_unit
      << (se ? pm(se->mass, u.Mass()) : "") << "\n";
  out << "center of mass  " << vec(r.mp.center_of_mass, u.Length()) << " " << len << ", in the file's axes\n";
  if (se) out << "  +-            " << vec(se->center_of_mass, u.Length()) << "\n";
  const std::string inertia_label = InertiaLabel(u);
  out << "inertia about the center of mass, file's axes" << inertia_label;
  PrintMatrix(out, "                ", r.mp.inertia_com / u.Inertia(), digits);
  if (se) {
    out << "  +-\n";
    PrintMatrix(out, "                ", se->inertia_com / u.Inertia());
  }
  if (opt.frame == Frame::kOrigin) {
    out << "inertia about the file's origin, file's axes" << inertia_label;
    PrintMatrix(out, "                ", r.mp.InertiaAbout(Vector3::Zero()) / u.Inertia(), digits);
  }
  if (opt.reference) {
    const ReferenceFrame f = ReferenceOf(r, opt);
    out << "inertia about " << (f.point ? vec(*f.point, u.Length()) + " " + len : std::string("the center of mass"))
        << (f.axes.isIdentity(0) ? ", file's axes" : ", in the axes given") << inertia_label;
    PrintMatrix(out, "                ", InertiaInFrame(r.mp, f) / u.Inertia(), digits);
    if (!f.axes.isIdentity(0)) {
      out << "  axes (columns, in the file's axes):\n";
      PrintMatrix(out, "                ", f.axes);
    }
  }
  out << "                convention: I = integral of rho (|r|^2 E - r r^T) dV; off-diagonal\n"
         "                entries are the NEGATED products of inertia (Ixy = -integral rho x y dV),\n"
         "                as URDF ixy/ixz/iyz and MJCF fullinertia expect them\n";
  const Vector3& m = r.principal.moments;
  const double ui = u.Inertia();
  out << "principal moments (ascending)  " << Num(m[0] / ui, digits) << "  " << Num(m[1] / ui, digits) << "  "
      << Num(m[2] / ui, digits) << " " << (u.IsSi() ? std::string("kg m^2") : inertia_unit) << "\n";
  if (r.estimate) {
    const Vector3& ms = r.estimate->principal_moments_se;
    out << "  +-                             " << Num(ms[0] / ui) << "  " << Num(ms[1] / ui) << "  " << Num(ms[2] / ui)
        << "\n";
  }
  out << "principal axes (columns, right-handed, in the file's axes):\n";
  PrintMatrix(out, "                ", r.principal.axes, digits);
  WriteComparisons(out, r, opt, digits);
  out << "physically valid  "
      << (r.validity.valid ? "yes (moments positive, I1 + I2 >= I3)" : "NO: " + r.validity.reason) << "\n";
  for (const Finding& f : r.findings) out << "warning         " << Worded(f.message, WordsOf(opt)) << "\n";
  return out.str();
}

}  // namespace

}  // namespace massprops::report
