#include "report.h"

#include <cctype>
#include <chrono>
#include <filesystem>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "massprops/composition.h"
#include "massprops/export.h"
#include "massprops/repair.h"
#include "massprops/implicit.h"
#include "massprops/shell.h"
#include "progress.h"

namespace massprops::app {

double MetresPerUnit(const std::string& unit) {
  static const std::map<std::string, double> kUnits = {
      {"m", 1.0}, {"cm", 0.01}, {"mm", 0.001}, {"in", 0.0254}, {"ft", 0.3048}};
  const auto it = kUnits.find(unit);
  if (it == kUnits.end()) throw std::invalid_argument("unknown unit '" + unit + "'");
  return it->second;
}

namespace {

std::string Fixed(double v, const char* fmt = "%.4g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// Warns when the size in metres suggests the coordinates are in another unit.
void CheckPlausibleSize(Report& r) {
  const double s = r.size_m;
  if (r.unit == "m" && s > 20.0) {
    r.warnings.push_back("the part is " + Fixed(s) + " m across (with --unit m); if the file is in " +
                         "millimetres pass --unit mm (" + Fixed(s / 1000) + " m), centimetres --unit cm, inches --unit in");
  } else if (s > 1000.0) {
    r.warnings.push_back("the part is " + Fixed(s) + " m across: check --unit");
  } else if (s < 1e-4) {
    r.warnings.push_back("the part is only " + Fixed(s * 1000) + " mm across: check --unit (the file's coordinates are taken as " + r.unit + ")");
  }
}

}  // namespace

namespace {

// What every path reports once r.mp is known: size and its plausibility, principal axes,
// validity (with a tolerance that an estimate's noise needs).
void Conclude(Report& r, double size_m, double validity_tolerance = 1e-12) {
  r.size_m = size_m;
  CheckPlausibleSize(r);
  r.principal = ComputePrincipalInertia(r.mp.inertia_com);
  r.validity = CheckPhysicallyValid(r.principal.moments, validity_tolerance);
}

double Diagonal(const PolygonMesh& mesh) {
  return (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
}

// Integral in file units → SI mass properties at the requested density or total mass.
void Finish(Report& r, const VolumeIntegrals& integrals, const Options& opt, double size_file_units) {
  if (integrals.volume < 0) {
    throw MeshFileError(r.file + ": the signed volume is negative (" +
                        Fixed(integrals.volume, "%.6g") + " " + opt.unit +
                        "^3): the faces point inward. Reverse the orientation of every face");
  }
  const double scale = MetresPerUnit(opt.unit);
  // Integrate in file units, then scale exactly (no rounding of the coordinates themselves).
  r.mp = Scaled(FromIntegrals(integrals, 1.0), scale);
  const double density = opt.mass > 0 ? opt.mass / r.mp.volume : opt.density;
  r.mp.mass = r.mp.volume * density;
  r.mp.inertia_com *= density;
  r.mp.density = density;
  Conclude(r, scale * size_file_units);
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

namespace {

// Runs the estimator on a solid already in metres and fills the report.
void Estimate(Report& r, const ImplicitSolid& solid, const Options& opt, Progress& progress) {
  MonteCarloOptions mc;
  mc.method = opt.method == "mc" ? SamplingMethod::kMonteCarlo : SamplingMethod::kQuasiMonteCarlo;
  if (!(opt.samples >= 2 && opt.samples <= 1e13)) throw std::invalid_argument("--samples must be between 2 and 1e13");
  mc.samples = static_cast<std::int64_t>(opt.samples);
  mc.randomizations = opt.randomizations;
  mc.seed = opt.seed;
  mc.tolerance = opt.tolerance;
  mc.num_threads = opt.threads;
  mc.fixed_mass = opt.mass;
  progress.Stage(opt.tolerance > 0 ? "sampling until the tolerance is met" : "sampling");
  const MassPropertiesEstimate e = EstimateMassProperties(solid, opt.density, mc);
  r.estimate = e;
  r.mp = e.value;
  Conclude(r, solid.Bounds().sizes().norm(), 1e-6);
  r.path_used = std::string(opt.method == "mc" ? "Monte Carlo" : "quasi-Monte Carlo (Owen-scrambled Sobol)") + ", " +
                std::to_string(e.samples) + " points" +
                (opt.method == "mc" ? "" : " in " + std::to_string(e.randomizations) + " randomizations");
  for (int i = 0; i < 2; ++i) {
    const double gap = e.principal_moments[i + 1] - e.principal_moments[i];
    if (gap < 3 * (e.principal_moments_se[i] + e.principal_moments_se[i + 1])) {
      r.warnings.push_back("principal moments " + std::to_string(i + 1) + " and " + std::to_string(i + 2) +
                           " are equal within their error bars: the principal axes in their plane are not "
                           "determined by this estimate (the printed ones are one choice)");
    }
  }
  if (opt.tolerance > 0 && !e.tolerance_met) {
    r.warnings.push_back("the tolerance " + Fixed(opt.tolerance, "%g") + " was not reached (relative error " +
                         Fixed(e.MaxRelativeError(), "%.2g") + " after " + std::to_string(e.samples) + " points)");
  }
}

}  // namespace

Report ComputeImplicit(const std::string& shape, const Options& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  Progress progress(shape, !opt.quiet);
  Report r;
  r.unit = opt.unit;
  r.model = "implicit";
  const ImplicitPtr solid = implicit::ParseShape(shape);
  r.file = solid->Describe();
  r.full_topology = false;
  r.loaded.format = "implicit";
  Estimate(r, *implicit::Scaled(solid, MetresPerUnit(opt.unit)), opt, progress);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

Report Compute(const std::string& file, const Options& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  Progress progress(file, !opt.quiet);
  Report r;
  r.file = file;
  r.unit = opt.unit;
  MetresPerUnit(opt.unit);  // validates
  IntegrationOptions io;
  io.num_threads = opt.threads;

  // Binary STL: integrate the mapped records directly; weld and count edges only when the
  // streaming check finds the surface open (to say what is wrong) or when asked to.
  const bool stl = Lower(file.substr(file.find_last_of('.') + 1)) == "stl";
  // Below kStreamingThreshold triangles the full check costs little and runs always.
  constexpr std::int64_t kStreamingThreshold = 200000;
  // A binary STL of kStreamingThreshold triangles is at least this big; smaller files skip the
  // streamed pass instead of integrating twice.
  std::error_code size_error;
  const auto bytes = std::filesystem::file_size(file, size_error);
  const bool big = !size_error && bytes >= 84 + 50 * static_cast<std::uintmax_t>(kStreamingThreshold);
  if (stl && big && opt.path != "polygons" && !opt.full_check && opt.reader == "auto" &&
      !opt.repair && !opt.check_self_intersections && !opt.shell && opt.wall == 0 &&
      !opt.winding_number) {
    if (auto soup = IntegrateBinaryStlFile(file, io);
        soup && soup->IsClosedCycle() && soup->triangles >= kStreamingThreshold) {
      r.loaded.format = "stl-binary";
      r.loaded.float32_coordinates = true;
      r.full_topology = false;
      r.topology.faces = soup->triangles;
      r.path_used = "triangles (signed tetrahedra), streamed from the file";
      Finish(r, soup->integrals, opt, (soup->upper - soup->lower).norm());
      r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      return r;
    }
  }

  progress.Stage("reading");
  r.loaded = opt.reader == "assimp" ? ReadMeshFileWithAssimp(file) : ReadMeshFile(file);
  if (opt.repair) {
    progress.Stage("repairing (CGAL)");
    RepairedMesh repaired = RepairMesh(r.loaded.mesh);
    r.loaded.mesh = std::move(repaired.mesh);
    r.repair_summary = repaired.report.Summary();
  }
  const PolygonMesh& mesh = r.loaded.mesh;
  progress.Stage("checking edges");
  r.topology = AnalyzeTopology(mesh);
  if (opt.check_self_intersections) {
    progress.Stage("checking self-intersections (CGAL)");
    r.self_intersections = CountSelfIntersections(mesh);
  }
  if (r.self_intersections > 0) {
    r.warnings.push_back(std::to_string(r.self_intersections) +
                         " pairs of faces intersect: where the surface passes through itself, "
                         "volume is counted twice or cancelled, and the numbers are not those of "
                         "a solid");
  }
  if (opt.winding_number) {
    // Inside is where the generalized winding number is at least 1/2: holes are bridged, so an
    // open scan gets a sensible solid; the estimate carries error bars.
    r.model = "winding-number";
    r.full_topology = true;
    TriangleMesh tri = Triangulate(mesh);
    tri.V *= MetresPerUnit(opt.unit);
    if (!r.topology.BoundsVolume()) {
      r.warnings.push_back(r.topology.Problems() + "; the winding number bridges the holes");
    }
    progress.Stage("building the winding-number hierarchy");
    Estimate(r, *implicit::WindingNumberSolid(tri), opt, progress);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  }
  if (opt.shell) {
    // A thin shell is a surface property: holes, orientation and nesting do not matter.
    progress.Stage("integrating the surface");
    r.model = "shell";
    r.path_used = "surface (thin shell), triangles and planar polygons integrated exactly";
    const double scale = MetresPerUnit(opt.unit);
    const SurfaceIntegrals s = IntegrateSurface(mesh, io);
    if (!(s.area > 0)) throw MeshFileError(file + ": the surface has no area");
    const double sigma = opt.mass > 0 ? opt.mass / (s.area * scale * scale) : opt.area_density;
    r.mp = ShellMassProperties(s, sigma, scale);
    Conclude(r, scale * Diagonal(mesh));
    if (!r.topology.BoundsVolume()) r.warnings.push_back(r.topology.Problems() + "; fine for a thin shell");
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  }
  if (!r.topology.BoundsVolume()) {
    if (!opt.allow_open || opt.wall > 0) {
      if (opt.wall > 0) {
        throw MeshFileError(file + ": " + r.topology.Problems() +
                            ". A wall needs a closed surface to offset inward (try --repair)");
      }
      throw MeshFileError(file + ": " + (opt.repair ? "after --repair: " : "") +
                          r.topology.Problems() +
                          ". The mesh does not bound a solid, so its mass properties are not "
                          "defined; " +
                          (opt.repair ? std::string("close the holes in a modelling tool, ")
                                      : std::string("try --repair, ")) +
                          "or pass --allow-open to compute anyway");
    }
    r.warnings.push_back(r.topology.Problems() +
                         "; computed anyway (--allow-open): the result depends on the reference "
                         "point and is not trustworthy");
  }
  if (r.topology.non_manifold_edges > 0 && r.topology.BoundsVolume()) {
    r.warnings.push_back(std::to_string(r.topology.non_manifold_edges) +
                         " edges are shared by more than two faces (solids touching along edges); "
                         "each is matched in both directions, so the volume is well defined");
  }
  if (r.topology.components > 1) {
    progress.Stage("checking how the shells nest");
    r.shells = AnalyzeShells(mesh);
    if (!r.shells.problem.empty()) {
      if (!opt.allow_open) throw MeshFileError(file + ": " + r.shells.problem);
      r.warnings.push_back(r.shells.problem + "; computed anyway (--allow-open)");
    }
  }
  if (opt.wall > 0) {
    progress.Stage("offsetting the wall inward");
    r.model = "wall";
    OffsetResult inner;
    try {
      inner = OffsetInward(mesh, opt.wall);
      if (inner.flipped_faces == 0 && inner.inner_volume > 0) {
        progress.Stage("checking the inner surface for self-intersections (CGAL)");
        const std::int64_t crossings = CountSelfIntersections(inner.inner, 1);
        if (crossings > 0) {
          throw std::invalid_argument("a wall of " + Fixed(opt.wall, "%g") + " " + opt.unit +
                                      " is thicker than the part allows: the inner surface passes "
                                      "through itself (the part is thinner than twice the wall "
                                      "somewhere); use a thinner wall");
        }
      }
      r.loaded.mesh = WallSolid(mesh, inner);
    } catch (const std::invalid_argument& e) {
      throw MeshFileError(file + ": --wall: " + e.what());
    }
    r.path_used = "polygons (Mirtich), the surface and its inward offset by " + Fixed(opt.wall, "%g") + " " + opt.unit;
    const VolumeIntegrals integrals = IntegratePolygons(r.loaded.mesh, io);
    Finish(r, integrals, opt, Diagonal(mesh));
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  }
  progress.Stage("integrating");
  const bool triangles = IsAllTriangles(mesh);
  VolumeIntegrals integrals;
  if (opt.path == "polygons" || (opt.path == "auto" && !triangles)) {
    r.path_used = "polygons (Mirtich), faces integrated whole";
    integrals = IntegratePolygons(mesh, io);
  } else {
    r.path_used = triangles ? "triangles (signed tetrahedra)"
                            : "triangles (signed tetrahedra), polygons split into fans";
    const TriangleMesh tri = Triangulate(mesh);
    integrals = IntegrateTriangles(tri.V, tri.F, io);
  }
  Finish(r, integrals, opt, Diagonal(mesh));
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

namespace {

std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "% .10e", v);
  return buf;
}

void PrintMatrix(std::ostream& out, const std::string& indent, const Matrix3& m) {
  for (int i = 0; i < 3; ++i) {
    out << indent << "[" << Num(m(i, 0)) << "  " << Num(m(i, 1)) << "  " << Num(m(i, 2)) << " ]\n";
  }
}

}  // namespace

std::string FormatTable(const Report& r, const Options& opt) {
  std::ostringstream out;
  const auto& t = r.topology;
  if (r.model == "implicit") {
    out << "shape           " << r.file << "\n";
  } else if (r.full_topology) {
    out << "file            " << r.file << "  (" << r.loaded.format << ", " << t.faces << " faces, "
        << t.vertices << " vertices, " << t.components << " component"
        << (t.components == 1 ? "" : "s") << ", "
        << (t.BoundsVolume() ? "closed and consistently oriented" : t.Problems())
        << (t.degenerate_faces ? ", " + std::to_string(t.degenerate_faces) + " degenerate faces" : "")
        << ")\n";
  } else {
    out << "file            " << r.file << "  (" << r.loaded.format << ", " << t.faces
        << " triangles, closed and consistently oriented: every edge matched by its reverse)\n";
  }
  if (!r.repair_summary.empty()) out << "repair          " << r.repair_summary << "\n";
  if (r.self_intersections >= 0) {
    out << "self-intersect  " << (r.self_intersections == 0 ? std::string("none")
                                                              : std::to_string(r.self_intersections) + " intersecting face pairs")
        << "\n";
  }
  if (!r.full_topology && r.model != "implicit") {
    out << "checks          streamed: every edge has its reverse, so the volume is well defined; "
           "shells were not separated (--full-check does, and checks their nesting)\n";
  }
  if (r.shells.shells.size() > 1) {
    const double s3 = std::pow(MetresPerUnit(r.unit), 3);
    out << "shells          ";
    for (std::size_t i = 0; i < r.shells.shells.size(); ++i) {
      const Shell& sh = r.shells.shells[i];
      out << (i ? "; " : "") << "#" << i + 1 << " " << sh.faces.size() << " faces, "
          << Fixed(sh.signed_volume * s3, "%.6g") << " m^3"
          << (sh.inside_of >= 0 ? " (cavity in #" + std::to_string(sh.inside_of + 1) + ")" : "");
    }
    out << "\n";
  }
  if (r.loaded.float32_coordinates) {
    out << "precision       the file's coordinates are 32-bit floats (~7 significant digits)\n";
  }
  out << "units           file coordinates in " << r.unit << " (" << MetresPerUnit(r.unit)
      << " m each), results in SI; " << (r.model == "shell" ? "area density " : "density ") << r.mp.density
      << (r.model == "shell" ? " kg/m^2" : " kg/m^3") << (opt.mass > 0 ? " (from --mass)" : "") << "\n";
  if (r.model == "shell") out << "model           thin shell: the surface itself carries the mass (no volume)\n";
  if (r.model == "wall") {
    out << "model           hollow part: the solid between the surface and its inward offset by " << opt.wall
        << " " << r.unit << "\n";
  }
  out << "integration     " << r.path_used << ", " << Fixed(r.seconds, "%.3g") << " s\n";
  out << "size            " << Num(r.size_m) << " m (bounding-box diagonal)\n";
  const MassProperties* se = r.estimate ? &r.estimate->standard_error : nullptr;
  auto pm = [&](double v) { return "  +- " + Fixed(v, "%.2e"); };
  if (r.estimate) {
    out << "error bars      +- one standard error; 95 % interval = +- " << Fixed(r.estimate->interval95_factor, "%.3g")
        << " standard errors" << (r.estimate->method == SamplingMethod::kQuasiMonteCarlo ? " (Student t over the randomizations)" : "")
        << "\n";
  }
  if (r.model != "shell") out << "volume          " << Num(r.mp.volume) << " m^3" << (se ? pm(se->volume) : "") << "\n";
  if (!r.estimate) out << "surface area    " << Num(r.mp.surface_area) << " m^2\n";
  out << "mass            " << Num(r.mp.mass) << " kg" << (se ? pm(se->mass) : "") << "\n";
  const Vector3& c = r.mp.center_of_mass;
  out << "center of mass  [" << Num(c[0]) << "  " << Num(c[1]) << "  " << Num(c[2])
      << " ] m, in the file's axes\n";
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
  if (opt.frame == "origin") {
    out << "inertia about the file's origin, file's axes (kg m^2):\n";
    PrintMatrix(out, "                ", r.mp.InertiaAbout(Vector3::Zero()));
  }
  out << "                convention: I = integral of rho (|r|^2 E - r r^T) dV; off-diagonal\n"
         "                entries are the NEGATED products of inertia (Ixy = -integral rho x y dV),\n"
         "                as URDF ixy/ixz/iyz and MJCF fullinertia expect them\n";
  const Vector3& m = r.principal.moments;
  out << "principal moments (ascending)  " << Num(m[0]) << "  " << Num(m[1]) << "  " << Num(m[2])
      << " kg m^2\n";
  if (r.estimate) {
    const Vector3& ms = r.estimate->principal_moments_se;
    out << "  +-                             " << Num(ms[0]) << "  " << Num(ms[1]) << "  " << Num(ms[2]) << "\n";
  }
  out << "principal axes (columns, right-handed, in the file's axes):\n";
  PrintMatrix(out, "                ", r.principal.axes);
  out << "physically valid  "
      << (r.validity.valid ? "yes (moments positive, I1 + I2 >= I3)" : "NO: " + r.validity.reason)
      << "\n";
  return out.str();
}

namespace {

nlohmann::ordered_json Mat(const Matrix3& m) {
  return nlohmann::ordered_json::array({{m(0, 0), m(0, 1), m(0, 2)},
                                        {m(1, 0), m(1, 1), m(1, 2)},
                                        {m(2, 0), m(2, 1), m(2, 2)}});
}

nlohmann::ordered_json ToJson(const Report& r, const Options& opt) {
  const auto& c = r.mp.center_of_mass;
  const auto& m = r.principal.moments;
  const auto& t = r.topology;
  nlohmann::ordered_json j = {{"file", r.file},
                              {"unit", r.unit},
                              {"model", r.model},
                              {"volume", r.mp.volume},
                              {"mass", r.mp.mass},
                              {"density", r.mp.density},
                              {"center_of_mass", {c[0], c[1], c[2]}},
                              {"inertia_com", Mat(r.mp.inertia_com)}};
  if (r.model == "shell") {
    j["density"] = nullptr;
    j["area_density"] = r.mp.density;
  }
  if (r.model == "wall") j["wall_thickness_m"] = opt.wall * MetresPerUnit(r.unit);
  if (opt.frame == "origin") j["inertia_origin"] = Mat(r.mp.InertiaAbout(Vector3::Zero()));
  j["principal_moments"] = {m[0], m[1], m[2]};
  j["principal_axes"] = Mat(r.principal.axes);
  j["surface_area"] = r.mp.surface_area;
  j["physically_valid"] = r.validity.valid;
  auto known = [&](std::int64_t v) {
    return r.full_topology ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
  };
  std::int64_t triangles = t.faces;
  if (r.full_topology) {
    triangles = 0;
    for (std::int64_t f = 0; f < r.loaded.mesh.num_faces(); ++f) triangles += r.loaded.mesh.face_size(f) - 2;
  }
  j["mesh"] = {{"format", r.loaded.format},
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
    const double s3 = std::pow(MetresPerUnit(r.unit), 3);
    nlohmann::ordered_json shells = nlohmann::ordered_json::array();
    for (const Shell& sh : r.shells.shells) {
      shells.push_back({{"faces", sh.faces.size()},
                        {"volume", sh.signed_volume * s3},
                        {"inside_of", sh.inside_of >= 0 ? nlohmann::ordered_json(sh.inside_of)
                                                        : nlohmann::ordered_json(nullptr)}});
    }
    j["mesh"]["shells"] = shells;
  }
  if (r.self_intersections >= 0) j["mesh"]["self_intersections"] = r.self_intersections;
  if (r.model == "implicit") j.erase("mesh");
  if (r.estimate) {
    const MassPropertiesEstimate& e = *r.estimate;
    const MassProperties& se = e.standard_error;
    const auto& sc = se.center_of_mass;
    const auto& pm = e.principal_moments_se;
    j["estimate"] = {{"method", e.method == SamplingMethod::kMonteCarlo ? "monte-carlo" : "quasi-monte-carlo"},
                     {"samples", e.samples},
                     {"randomizations", e.randomizations},
                     {"seed", opt.seed},
                     {"interval95_factor", e.interval95_factor},
                     {"tolerance_met", e.tolerance_met},
                     {"standard_errors",
                      {{"volume", se.volume},
                       {"mass", se.mass},
                       {"center_of_mass", {sc[0], sc[1], sc[2]}},
                       {"inertia_com", Mat(se.inertia_com)},
                       {"principal_moments", {pm[0], pm[1], pm[2]}}}}};
    j["surface_area"] = nullptr;
  }
  if (!r.repair_summary.empty()) j["repair"] = r.repair_summary;
  j["warnings"] = r.warnings;
  return j;
}

}  // namespace

std::string FormatJson(const std::vector<Report>& reports, const Options& opt) {
  if (reports.size() == 1) return ToJson(reports[0], opt).dump(2) + "\n";
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const Report& r : reports) all.push_back(ToJson(r, opt));
  return all.dump(2) + "\n";
}

std::string FormatCsv(const std::vector<Report>& reports, const Options& opt) {
  std::ostringstream out;
  const bool origin = opt.frame == "origin";
  out << "file,unit,volume_m3,mass_kg,density_kg_m3,com_x_m,com_y_m,com_z_m,"
         "ixx,iyy,izz,ixy,ixz,iyz,i1,i2,i3,surface_area_m2,closed,physically_valid"
      << (origin ? ",origin_ixx,origin_iyy,origin_izz,origin_ixy,origin_ixz,origin_iyz" : "");
  bool estimates = false;
  for (const Report& r : reports) estimates = estimates || r.estimate.has_value();
  if (estimates) {  // standard errors of the Monte-Carlo paths (empty for exact rows)
    out << ",se_volume,se_mass,se_com_x,se_com_y,se_com_z,se_ixx,se_iyy,se_izz,se_ixy,se_ixz,se_iyz,se_i1,se_i2,se_i3";
  }
  out << "\n";
  auto q = [](const std::string& s) {  // RFC 4180 quoting
    std::string o = "\"";
    for (char ch : s) o += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return o + "\"";
  };
  for (const Report& r : reports) {
    const Matrix3& I = r.mp.inertia_com;
    const Vector3& c = r.mp.center_of_mass;
    const Vector3& m = r.principal.moments;
    out << q(r.file) << "," << r.unit;
    for (double v : {r.mp.volume, r.mp.mass, r.mp.density, c[0], c[1], c[2], I(0, 0), I(1, 1), I(2, 2),
                     I(0, 1), I(0, 2), I(1, 2), m[0], m[1], m[2], r.mp.surface_area}) {
      out << "," << ExactDecimal(v);
    }
    out << "," << (r.topology.BoundsVolume() ? "true" : "false") << ","
        << (r.validity.valid ? "true" : "false");
    if (origin) {
      const Matrix3 O = r.mp.InertiaAbout(Vector3::Zero());
      for (double v : {O(0, 0), O(1, 1), O(2, 2), O(0, 1), O(0, 2), O(1, 2)}) out << "," << ExactDecimal(v);
    }
    if (estimates && r.estimate) {
      const MassProperties& e = r.estimate->standard_error;
      const Vector3& p = r.estimate->principal_moments_se;
      for (double v : {e.volume, e.mass, e.center_of_mass[0], e.center_of_mass[1], e.center_of_mass[2], e.inertia_com(0, 0),
                       e.inertia_com(1, 1), e.inertia_com(2, 2), e.inertia_com(0, 1), e.inertia_com(0, 2), e.inertia_com(1, 2),
                       p[0], p[1], p[2]}) {
        out << "," << ExactDecimal(v);
      }
    } else if (estimates) {
      out << ",,,,,,,,,,,,,,";
    }
    out << "\n";
  }
  return out.str();
}

std::string FormatRobot(const Report& r, const std::string& format) {
  const std::string note = "<!-- " + r.file + ": " + ExactDecimal(r.mp.volume) + " m^3 at " +
                           ExactDecimal(r.mp.density) + " kg/m^3; inertia about the center of "
                           "mass, link axes = the mesh file's axes (unit " + r.unit + ") -->\n";
  if (format == "urdf") return note + UrdfInertial(r.mp);
  if (format == "sdf") return note + SdfInertial(r.mp);
  return note + MjcfInertial(r.mp, r.principal);
}

}  // namespace massprops::app
