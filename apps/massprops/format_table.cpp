#include <cmath>
#include <sstream>

#include "format.h"
#include "massprops/text.h"

namespace massprops::cli {
namespace {

std::string Num(double v) { return FormatDouble(v, "% .10e"); }

void PrintMatrix(std::ostream& out, const std::string& indent, const Matrix3& m) {
  for (int i = 0; i < 3; ++i) {
    out << indent << "[" << Num(m(i, 0)) << "  " << Num(m(i, 1)) << "  " << Num(m(i, 2)) << " ]\n";
  }
}

}  // namespace

std::string FormatTable(const SolidResult& r, const FormatOptions& opt) {
  std::ostringstream out;
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
          << FormatDouble(sh.signed_volume * s3, "%.6g") << " m^3"
          << (sh.inside_of >= 0 ? " (cavity in #" + std::to_string(sh.inside_of + 1) + ")" : "");
    }
    out << "\n";
  }
  if (r.loaded.float32_coordinates) {
    out << "precision       the file's coordinates are 32-bit floats (~7 significant digits)\n";
  }
  out << "units           file coordinates in " << UnitName(r.unit) << " (" << MetresPerUnit(r.unit) << " m each"
      << (r.unit_source == UnitSource::kFile ? ", declared by the file" : "") << "), results in SI; "
      << (shell ? "area density " : "density ") << r.mp.density << (shell ? " kg/m^2" : " kg/m^3")
      << (r.mass_fixed ? " (from --mass)" : "") << "\n";
  if (shell) out << "model           thin shell: the surface itself carries the mass (no volume)\n";
  if (r.model == ModelKind::kWall) {
    out << "model           hollow part: the solid between the surface and its inward offset by " << r.wall_thickness
        << " " << UnitName(r.unit) << "\n";
  }
  out << "integration     " << r.path_used << ", " << FormatDouble(r.seconds, "%.3g") << " s\n";
  out << "size            " << Num(r.size_m) << " m (bounding-box diagonal)\n";
  const MassProperties* se = r.estimate ? &r.estimate->standard_error : nullptr;
  auto pm = [&](double v) { return "  +- " + FormatDouble(v, "%.2e"); };
  if (r.estimate) {
    out << "error bars      +- one standard error; 95 % interval = +- "
        << FormatDouble(r.estimate->interval95_factor, "%.3g") << " standard errors"
        << (r.estimate->method == SamplingMethod::kQuasiMonteCarlo ? " (Student t over the randomizations)" : "")
        << "\n";
  }
  if (!shell) out << "volume          " << Num(r.mp.volume) << " m^3" << (se ? pm(se->volume) : "") << "\n";
  if (!r.estimate) out << "surface area    " << Num(r.mp.surface_area) << " m^2\n";
  out << "mass            " << Num(r.mp.mass) << " kg" << (se ? pm(se->mass) : "") << "\n";
  const Vector3& c = r.mp.center_of_mass;
  out << "center of mass  [" << Num(c[0]) << "  " << Num(c[1]) << "  " << Num(c[2]) << " ] m, in the file's axes\n";
  if (se) {
    out << "  +-            [" << Num(se->center_of_mass[0]) << "  " << Num(se->center_of_mass[1]) << "  "
        << Num(se->center_of_mass[2]) << " ]\n";
  }
  out << "inertia about the center of mass, file's axes (kg m^2):\n";
  PrintMatrix(out, "                ", r.mp.inertia_com);
  if (se) {
    out << "  +-\n";
    PrintMatrix(out, "                ", se->inertia_com);
  }
  if (opt.frame == Frame::kOrigin) {
    out << "inertia about the file's origin, file's axes (kg m^2):\n";
    PrintMatrix(out, "                ", r.mp.InertiaAbout(Vector3::Zero()));
  }
  out << "                convention: I = integral of rho (|r|^2 E - r r^T) dV; off-diagonal\n"
         "                entries are the NEGATED products of inertia (Ixy = -integral rho x y dV),\n"
         "                as URDF ixy/ixz/iyz and MJCF fullinertia expect them\n";
  const Vector3& m = r.principal.moments;
  out << "principal moments (ascending)  " << Num(m[0]) << "  " << Num(m[1]) << "  " << Num(m[2]) << " kg m^2\n";
  if (r.estimate) {
    const Vector3& ms = r.estimate->principal_moments_se;
    out << "  +-                             " << Num(ms[0]) << "  " << Num(ms[1]) << "  " << Num(ms[2]) << "\n";
  }
  out << "principal axes (columns, right-handed, in the file's axes):\n";
  PrintMatrix(out, "                ", r.principal.axes);
  out << "physically valid  "
      << (r.validity.valid ? "yes (moments positive, I1 + I2 >= I3)" : "NO: " + r.validity.reason) << "\n";
  for (const Finding& f : r.findings) out << "warning         " << Worded(f.message, WordsOf(opt)) << "\n";
  return out.str();
}

}  // namespace massprops::cli
