// The pipeline of load.h: from a file (or an implicit solid) to checked mass properties.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "io/io_internal.h"
#include "io/text_tokens.h"
#include "io/wire.h"
#include "massprops/composition.h"
#include "massprops/implicit.h"
#include "massprops/io/isolation.h"
#include "massprops/io/load.h"
#include "massprops/repair/exact.h"
#include "massprops/repair/repair.h"
#include "massprops/shell.h"
#include "massprops/text.h"
#include "pipeline/geometry_steps_internal.h"
#include "pipeline/load_internal.h"
#include "pipeline/plausibility.h"

namespace massprops {
namespace {

using internal::CheckPlausible;
using internal::Fixed;
using internal::Plausibility;
using internal::Warn;

// Below this many triangles a binary STL is always welded and fully checked; at or above it the
// records are integrated as they lie, with the streaming closed-cycle check. Chosen by measurement
// (bench/end_to_end.py, README): the checked path costs about 190 ns a triangle on the 2-core
// reference machine and the streamed one about 30 ns (45 with its face keys), so below 10^5 triangles the full check
// takes under 20 ms, less than a person notices, and above it streaming saves 4–6× the time.
constexpr std::int64_t kStreamingThreshold = 100000;

double SignedVolumeOf(const PolygonMesh& mesh) {
  IntegrationOptions io;
  io.num_threads = 1;
  return IntegratePolygons(mesh, io).volume;
}

double Diagonal(const PolygonMesh& mesh) {
  // One pass over the rows (Eigen's column-wise reductions of a row-major matrix make six strided
  // passes: 5 ms at 10^6 vertices).
  const double* p = mesh.V.data();
  const Eigen::Index n = mesh.V.rows();
  if (n == 0) return 0.0;
  double lo[3] = {p[0], p[1], p[2]}, hi[3] = {p[0], p[1], p[2]};
  for (Eigen::Index i = 1; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[3 * i + k]);
      hi[k] = std::max(hi[k], p[3 * i + k]);
    }
  }
  const Vector3 extent(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const double d = extent.norm();
  return std::isfinite(d) ? d : extent.stableNorm();  // squares overflow beyond 1e154
}

void Stage(const LoadOptions& o, const char* stage) {
  if (o.progress) o.progress(stage);
}

// Which number a part `size` across (in metres) at `density` would take beyond double precision:
// the volume (∝ size³), the mass, or the inertia (∝ size⁵); "" when all are normal doubles.
std::string BeyondDoubles(double size, double density) {
  const auto ok = [](double x) { return std::isnormal(x) && x < 1e305; };
  if (!ok(size)) return "volume";
  const double volume = size * size * size;
  if (!ok(volume)) return "volume";
  if (!ok(volume * density)) return "mass";
  if (!ok(volume * density * size * size)) return "inertia";
  return "";
}

[[noreturn]] void RefuseMagnitude(const SolidResult& r, double size, LengthUnit unit, const std::string& quantity) {
  const char* law = quantity == "volume"    ? " (it goes as the size cubed)"
                    : quantity == "inertia" ? " (it goes as the size to the fifth power)"
                                            : "";
  throw LoadError(r.source + ": the part is " + Fixed(size, "%.3g") + " " + UnitName(unit) + " across: its " +
                  quantity + law + " would " + (size < 1 ? "underflow" : "overflow") +
                  " double precision (zeros, infinities or noise, not numbers); rescale with {unit}");
}

// A result whose numbers are all normal doubles, or a refusal naming the first that is not.
void RequireRepresentable(const SolidResult& r, const MassProperties& mp, double size_m) {
  const auto ok = [](double x) { return std::isnormal(x) && std::isfinite(x); };
  const char* bad = !ok(mp.volume)                                               ? "volume"
                    : !ok(mp.mass)                                               ? "mass"
                    : !ok(mp.inertia_com.trace()) || !mp.inertia_com.allFinite() ? "inertia"
                    : !mp.center_of_mass.allFinite()                             ? "center of mass"
                                                                                 : nullptr;
  if (bad) RefuseMagnitude(r, size_m, LengthUnit::kMetre, bad);
}

// What every path reports once r.mp is known: size and its plausibility, principal axes, and
// validity (with the tolerance an estimate's noise needs).
void Conclude(SolidResult& r, double size_m, const Plausibility& plausibility, double validity_tolerance = 1e-12) {
  r.size_m = size_m;
  CheckPlausible(r, plausibility);
  r.principal = ComputePrincipalInertia(r.mp.inertia_com);
  r.validity = CheckPhysicallyValid(r.principal.moments, validity_tolerance);
}

// Integrals in file units → SI mass properties at the requested density or total mass.
void Finish(SolidResult& r, const VolumeIntegrals& integrals, const LoadOptions& opt, double size_file_units) {
  // Integrated in file units: an integral beyond double range is an infinity here.
  if (!std::isfinite(size_file_units) || !std::isfinite(integrals.volume) || !integrals.first.allFinite() ||
      !integrals.second.allFinite()) {
    RefuseMagnitude(r, size_file_units, opt.unit, std::isfinite(integrals.volume) ? "inertia" : "volume");
  }
  // Rounding leaves about 1e-16 of the part's size cubed where faces cancel: a volume below
  // 1e-12 of it is zero, whatever its sign.
  if (std::abs(integrals.volume) <= 1e-12 * std::pow(size_file_units, 3)) {
    throw LoadError(r.source + ": the volume is zero up to rounding (" + Fixed(integrals.volume, "%.3g") + " " +
                    UnitName(opt.unit) + "^3 for a part " + Fixed(size_file_units, "%.4g") + " " + UnitName(opt.unit) +
                    " across): the faces cancel (a double-sided surface, or a flat one); nothing to compute");
  }
  if (integrals.volume < 0) {
    throw LoadError(r.source + ": the signed volume is negative (" + Fixed(integrals.volume, "%.6g") + " " +
                    UnitName(opt.unit) + "^3): the faces point inward. Reverse the orientation of every face");
  }
  const double scale = MetresPerUnit(opt.unit);
  // Integrate in file units, then scale exactly (no rounding of the coordinates themselves).
  const MassProperties unit_density = Scaled(FromIntegrals(integrals, 1.0), scale);
  r.mp = AtDensity(unit_density, ResolveDensity(opt.mass, unit_density.volume));
  RequireRepresentable(r, r.mp, scale * size_file_units);
  Conclude(r, scale * size_file_units, {opt.unit_stated, opt.mass});
}

// An estimate made at 1/k of the size, brought back: lengths ×k, volumes ×k³, inertias ×k⁵ (×k²
// when the total mass is fixed), error bars alike.
MassPropertiesEstimate ScaledEstimate(MassPropertiesEstimate e, double k, bool mass_fixed) {
  const double inertia = mass_fixed ? k * k : k * k * k * k * k;
  for (MassProperties* mp : {&e.value, &e.standard_error}) {
    const double mass = mp->mass;
    MassProperties out = *mp;
    out.volume *= k * k * k;
    out.mass = mass_fixed ? mass : mass * k * k * k;
    out.center_of_mass *= k;
    out.inertia_com *= inertia;
    out.surface_area *= k * k;
    *mp = out;
  }
  if (mass_fixed) e.value.density = e.value.mass / e.value.volume;  // else the density as given
  e.principal_moments *= inertia;
  e.principal_moments_se *= inertia;
  return e;
}

// Runs the estimator on a solid already in metres and fills the result.
void Estimate(SolidResult& r, const ImplicitSolid& solid, MonteCarloOptions mc, const MassSpec& mass, bool unit_stated,
              int num_threads, const ProgressCallback& progress) {
  mc.num_threads = num_threads;
  mc.fixed_mass = FixesMass(mass) ? std::get<TotalMass>(mass).value : 0.0;
  const double density = FixesMass(mass) ? 1.0 : ResolveDensity(mass, 1.0);
  // Sampled at a size near 1 (scaled by a power of two, exactly) and scaled back, so that no sum or
  // variance of tiny or huge coordinates underflows or overflows; a part whose numbers themselves
  // would is refused, naming which.
  const Vector3 extent = solid.Bounds().sizes();
  const double size = extent.allFinite() ? extent.stableNorm() : std::numeric_limits<double>::infinity();
  if (const std::string beyond = BeyondDoubles(size, FixesMass(mass) ? 1.0 : density); !beyond.empty()) {
    RefuseMagnitude(r, size, LengthUnit::kMetre, beyond);
  }
  const double k = std::ldexp(1.0, std::ilogb(size));
  const ImplicitPtr view(std::shared_ptr<const ImplicitSolid>(), &solid);
  if (progress) progress(mc.tolerance > 0 ? "sampling until the tolerance is met" : "sampling");
  const MassPropertiesEstimate e =
      ScaledEstimate(EstimateMassProperties(*implicit::Scaled(view, 1 / k), density, mc), k, FixesMass(mass));
  const bool qmc = mc.method == SamplingMethod::kQuasiMonteCarlo;
  r.estimate = e;
  r.mp = e.value;
  r.mass_fixed = FixesMass(mass);
  RequireRepresentable(r, r.mp, size);
  Conclude(r, size, {unit_stated, mass}, 1e-6);
  r.path_used = std::string(qmc ? "quasi-Monte Carlo (Owen-scrambled Sobol)" : "Monte Carlo") + ", " +
                std::to_string(e.samples) + " points" +
                (qmc ? " in " + std::to_string(e.randomizations) + " randomizations" : "");
  for (int i = 0; i < 2; ++i) {
    if (e.MomentsIndistinct(i)) {
      Warn(r, FindingKind::kUndeterminedAxes,
           "principal moments " + std::to_string(i + 1) + " and " + std::to_string(i + 2) +
               " are equal within their error bars: the principal axes in their plane are not determined by this "
               "estimate (the printed ones are one choice)");
    }
  }
  if (mc.tolerance > 0 && !e.tolerance_met) {
    Warn(r, FindingKind::kToleranceNotMet,
         "the tolerance " + Fixed(mc.tolerance, "%g") + " was not reached (relative error " +
             Fixed(e.MaxRelativeError(), "%.2g") + " after " + std::to_string(e.samples) + " points)");
  }
}

double SecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Binary STL of kStreamingThreshold triangles or more, closed: integrate the records as they lie.
bool TryStreamedStl(SolidResult& r, const std::string& file, const LoadOptions& opt) {
  const bool stl = io_text::FileExtension(file) == "stl";
  // A binary STL of kStreamingThreshold triangles is at least this big; smaller files skip the
  // streamed pass instead of integrating twice.
  std::error_code size_error;
  const auto bytes = std::filesystem::file_size(file, size_error);
  const bool big = !size_error && bytes >= 84 + 50 * static_cast<std::uintmax_t>(kStreamingThreshold);
  const bool solid = std::holds_alternative<SolidModel>(opt.model);
  if (!(stl && big && solid && opt.path != IntegrationPath::kPolygons && !opt.full_check &&
        opt.reader == Reader::kAuto && !opt.repair && !opt.check_self_intersections && !opt.hull && !opt.exact)) {
    return false;
  }
  IntegrationOptions io;
  io.num_threads = opt.num_threads;
  const auto soup = IntegrateBinaryStlFile(file, io);
  // Open, inconsistent, a face there twice, or more than one shell (which may nest or overlap):
  // the full check says what is wrong, or separates the shells.
  if (!soup || !soup->IsClosedCycle() || soup->repeated_faces || soup->shells != 1 ||
      soup->triangles < kStreamingThreshold) {
    return false;
  }
  r.loaded.format = "stl-binary";
  r.loaded.float32_coordinates = true;
  r.full_topology = false;
  r.topology.faces = soup->triangles;
  r.path_used = "triangles (signed tetrahedra), streamed from the file";
  Warn(r, FindingKind::kStreamedChecks,
       "streamed: every edge has its reverse, no face is there twice and the triangles form one connected shell, "
       "so the volume is well defined; edges shared by more than two faces were not counted ({full_check} does)");
  Finish(r, soup->integrals, opt, (soup->upper - soup->lower).norm());
  return true;
}

[[noreturn]] void RefuseDuplicates(const SolidResult& r) {
  const MeshTopology& t = r.topology;
  if (2 * t.reversed_duplicate_faces == t.faces) {
    throw LoadError(r.source + ": the volume is zero up to rounding (double-sided surface): each of the " +
                    std::to_string(t.faces / 2) + " faces appears with both orientations; keep one side " +
                    "({repair} drops the duplicates)");
  }
  throw LoadError(r.source + ": " + std::to_string(t.duplicate_faces + t.reversed_duplicate_faces) +
                  " faces repeat the corners of another face (" + std::to_string(t.reversed_duplicate_faces) +
                  " of them reversed): the surface is there twice, and its volume and inertia would count it "
                  "twice or cancel it; {repair} resolves them (a face repeated reversed is the internal wall "
                  "where two bodies touch: both copies go, and the bodies unite; same-direction copies keep one)");
}

// "; 288 of its boundary corners lie within 1e-9 of the part's size from another: unwelded corners
// (cracks), not holes" when that is what the boundary is.
std::string UnweldedCorners(const SolidResult& r) {
  if (r.topology.boundary_edges == 0) return "";
  const PolygonMesh& m = r.loaded.mesh;
  const double size = Diagonal(m);
  const std::int64_t n = CountUnweldedBoundaryCorners(m, 1e-9 * size);
  if (n == 0) return "";
  return " (" + std::to_string(n) +
         " of its boundary corners lie within 1e-9 of the part's size from another: "
         "unwelded corners, cracks rather than holes, which {repair} welds)";
}

void RefuseOpen(const SolidResult& r, const LoadOptions& opt, bool wall) {
  if (wall) {
    throw LoadError(r.source + ": " + r.topology.Problems() + UnweldedCorners(r) +
                    ". A wall needs a closed surface to offset inward (try {repair})");
  }
  // A CAD part of surfaces only: the file holds no solid to begin with.
  bool surfaces_only = false;
  std::int64_t untessellated = 0;
  for (const CadPart& p : r.loaded.cad_parts) {
    surfaces_only = surfaces_only || !p.solid;
    untessellated += p.untessellated_faces;
  }
  throw LoadError(r.source + ": " + (opt.repair ? "after {repair}: " : "") + r.topology.Problems() +
                  (opt.repair ? "" : UnweldedCorners(r)) +
                  (surfaces_only ? " (the CAD file holds surfaces, not a solid)" : "") +
                  (untessellated > 0 ? " (OpenCASCADE made no triangles of " + std::to_string(untessellated) +
                                           " of the B-rep's faces: another deflection may mesh them, or {allow_open} "
                                           "with {brep} reports the B-rep's own numbers)"
                                     : "") +
                  (opt.repair && r.repair && r.repair->unfilled_holes > 0
                       ? " (" + std::to_string(r.repair->unfilled_holes) + " holes could not be triangulated)"
                       : "") +
                  ". The mesh does not bound a solid, so its mass properties are not defined; " +
                  (opt.repair ? "close the holes in a modelling tool, "
                              : "try {repair} (it fills holes: planar ones exactly, others within a stated bound), ") +
                  "{winding_number} for an estimate with error bars, or pass {allow_open} to compute anyway (no "
                  "bound)");
}

// What the repair changed that the numbers rest on, said with its counts; and the ambiguity of
// filling non-planar holes, as a bound on every number (relative_error_bound), refused past 1 %.
// Another fill of a hole within the slab that holds its boundary adds or removes at most
// dV = thickness × patch area; that much mass at most R (the farthest corner) from the center of
// mass moves it by at most dc = dV · 2R / (V − dV), and the inertia by at most ρ dV R² about the
// old center plus M dc² for the shift, against the largest principal moment.
void AddRepairFindings(SolidResult& r, const LoadOptions& opt) {
  if (!r.repair) return;
  const RepairReport& rep = *r.repair;
  if (rep.internal_walls > 0) {
    Warn(r, FindingKind::kRepaired,
         "{repair} removed " + std::to_string(rep.internal_walls) +
             " faces that each repeat another reversed: internal walls where bodies exported closed each touch; "
             "the bodies are computed as their union");
  }
  if (rep.repeated_faces > 0) {
    Warn(r, FindingKind::kRepaired,
         "{repair} removed " + std::to_string(rep.repeated_faces) +
             " repeated faces (copies of another face in the same direction; one of each kept)");
  }
  if (rep.filled_holes == 0) return;
  const std::string planar = rep.planar_holes == rep.filled_holes ? "all planar, filled exactly"
                             : rep.planar_holes == 0              ? "none planar"
                                                     : std::to_string(rep.planar_holes) + " planar, filled exactly";
  std::string filled = "{repair} filled " + std::to_string(rep.filled_holes) +
                       (rep.filled_holes == 1 ? " hole (" : " holes (") + planar + "; the largest has " +
                       std::to_string(rep.largest_hole) + " edges)";
  if (!(rep.fill_volume_bound > 0) || !(r.mp.volume > 0)) {
    Warn(r, FindingKind::kRepaired, filled);
    return;
  }
  const double m = MetresPerUnit(opt.unit);
  const double dv = rep.fill_volume_bound * m * m * m, v = r.mp.volume;
  double reach = 0;  // R: the farthest corner from the center of mass, m
  for (Eigen::Index i = 0; i < r.loaded.mesh.V.rows(); ++i) {
    reach = std::max(reach, (r.loaded.mesh.V.row(i).transpose() * m - r.mp.center_of_mass).norm());
  }
  const double dc = dv < v ? dv * 2 * reach / (v - dv) : reach;
  const double largest_moment = r.principal.moments.maxCoeff();
  const double inertia =
      largest_moment > 0 ? (r.mp.density * dv * reach * reach + r.mp.mass * dc * dc) / largest_moment : 1.0;
  const double bound = std::max({dv / v, r.size_m > 0 ? dc / r.size_m : 1.0, inertia});
  if (bound > 1e-2) {
    throw LoadError(r.source + ": after {repair}: " + std::to_string(rep.filled_holes - rep.planar_holes) +
                    " of the holes filled are not planar (the largest hole has " + std::to_string(rep.largest_hole) +
                    " edges): another fill within the slab that holds each hole's boundary could change the numbers "
                    "by up to " +
                    Fixed(100 * std::min(bound, 1e6), "%.2g") +
                    " %, over the 1 % the repair accepts; {winding_number} estimates the solid with error bars, or "
                    "close the holes in a modelling tool");
  }
  Warn(r, FindingKind::kRepaired,
       filled +
           "; the non-planar ones are ambiguous: another fill within the slab that holds each hole's "
           "boundary could change the volume by " +
           Fixed(dv / v, "%.1g") + " relative, and every number by at most " + Fixed(bound, "%.1g") + " relative");
  if (bound > 1e-9) r.relative_error_bound = std::max(r.relative_error_bound, bound);
}

void IntegrateShell(SolidResult& r, const ShellModel& shell, const LoadOptions& opt) {
  // A thin shell is a surface property: holes, orientation and nesting do not matter.
  Stage(opt, "integrating the surface");
  r.model = ModelKind::kShell;
  r.path_used = "surface (thin shell), triangles and planar polygons integrated exactly";
  const PolygonMesh& mesh = r.loaded.mesh;
  const double scale = MetresPerUnit(opt.unit);
  IntegrationOptions io;
  io.num_threads = opt.num_threads;
  const SurfaceIntegrals s = IntegrateSurface(mesh, io);
  if (!(s.area > 0)) throw LoadError(r.source + ": the surface has no area");
  const MassSpec spec = FixesMass(opt.mass) ? opt.mass : MassSpec(Density{shell.area_density});
  r.mp = ShellMassProperties(s, ResolveDensity(spec, s.area * scale * scale), scale);
  r.mass_fixed = FixesMass(opt.mass);
  Conclude(r, scale * Diagonal(mesh), {opt.unit_stated, spec});
  if (!r.topology.BoundsVolume()) Warn(r, FindingKind::kOpenSurface, r.topology.Problems() + "; fine for a thin shell");
}

void IntegrateWall(SolidResult& r, const WallModel& wall, const LoadOptions& opt) {
  Stage(opt, "offsetting the wall inward");
  r.model = ModelKind::kWall;
  r.wall_thickness = wall.thickness;
  const PolygonMesh mesh = r.loaded.mesh;
  double inner_volume = 0;  // the offset surface's, already integrated by OffsetInward
  try {
    const OffsetResult inner = OffsetInward(mesh, wall.thickness);
    inner_volume = inner.inner_volume;
    if (inner.flipped_faces == 0 && inner.inner_volume > 0) {
      Stage(opt, "checking the inner surface for self-intersections (CGAL)");
      const std::int64_t crossings =
          RequireGeometrySteps("the wall's self-intersection check").count_self_intersections(inner.inner, 1);
      if (crossings < 0) {
        throw std::invalid_argument(
            "the inner surface could not be checked for self-intersections (too many overlapping faces around "
            "one corner, in a fan that folds or winds around it more than once), so a wall that does not fit could not "
            "be "
            "told from one that does; not computed (a shell model needs no such check)");
      }
      if (crossings > 0) {
        throw std::invalid_argument("a wall of " + Fixed(wall.thickness, "%g") + " " + UnitName(opt.unit) +
                                    " is thicker than the part allows: the inner surface passes through itself "
                                    "(the part is thinner than twice the wall somewhere); use a thinner wall");
      }
    }
    r.loaded.mesh = WallSolid(mesh, inner);
  } catch (const std::invalid_argument& e) {
    throw LoadError(r.source + ": {wall}: " + e.what());
  }
  r.path_used = "polygons (Mirtich), the surface and its inward offset by " + Fixed(wall.thickness, "%g") + " " +
                UnitName(opt.unit);
  IntegrationOptions io;
  io.num_threads = opt.num_threads;
  r.mass_fixed = FixesMass(opt.mass);
  const VolumeIntegrals wall_integrals = IntegratePolygons(r.loaded.mesh, io);
  // The wall is the outer solid less the inner one: a thin wall is a small difference of two
  // large numbers. Rounding bounds: the sums (a few units in the last place of each solid) and the
  // inner corners' positions (rounded to the last place of the largest coordinate, over both
  // surfaces' area).
  const double u = std::numeric_limits<double>::epsilon() / 2;
  const double outer_volume = wall_integrals.volume + inner_volume;
  const double largest = mesh.V.cwiseAbs().maxCoeff();
  const double error = 8 * u * (outer_volume + inner_volume) + 4 * u * largest * wall_integrals.surface_area;
  const double bound = wall_integrals.volume > 0 ? error / wall_integrals.volume : 1.0;
  if (bound > 1e-2) {
    throw LoadError(r.source + ": {wall}: a wall of " + Fixed(wall.thickness, "%g") + " " + UnitName(opt.unit) +
                    " is too thin for double precision on a part " + Fixed(Diagonal(mesh), "%.4g") + " " +
                    UnitName(opt.unit) + " across: the wall's volume is the difference of two solids that agree to " +
                    Fixed(-std::log10(std::max(bound * wall_integrals.volume / outer_volume, 1e-17)), "%.0f") +
                    " digits, so rounding could be " + Fixed(100 * std::min(bound, 1e9), "%.2g") +
                    " % of it; compute it as a thin shell (the surface carrying the wall's mass per area) instead");
  }
  if (bound > 1e-9) {
    r.relative_error_bound = bound;
    Warn(r, FindingKind::kLimitedPrecision,
         "the wall is thin for its part (" + Fixed(wall.thickness, "%g") + " " + UnitName(opt.unit) + " on a part " +
             Fixed(Diagonal(mesh), "%.4g") +
             " across): it is the difference of two solids, and rounding leaves its "
             "numbers good to about " +
             Fixed(bound, "%.1g") + " relative: the digits beyond are noise");
  }
  Finish(r, wall_integrals, opt, Diagonal(mesh));
}

// A volume within rounding of zero may be a double-sided surface (zero) or a real sliver (a
// tetrahedron 1e-300 high): exact rational sums tell them apart where the build has them. True when
// the exact numbers were taken.
bool IntegrateExactlyIfTiny(SolidResult& r, const LoadOptions& opt, double size, double area_file_units) {
  ExactMassProperties e;
  try {
    Stage(opt, "the volume is within rounding of zero: integrating in exact arithmetic (GMP)");
    e = RequireGeometrySteps("exact integration")
            .exact(r.loaded.mesh, MetresPerUnit(opt.unit), opt.mass, opt.num_threads);
  } catch (const std::exception&) {
    return false;  // zero, negative, or no exact arithmetic here: Finish says why
  }
  r.mp = e.mp;
  r.mp.surface_area = area_file_units * MetresPerUnit(opt.unit) * MetresPerUnit(opt.unit);
  RequireRepresentable(r, r.mp, MetresPerUnit(opt.unit) * size);
  r.path_used +=
      "; the volume is below the double sums' rounding, so it was integrated in exact rational "
      "arithmetic (GMP), each number correctly rounded once";
  Conclude(r, MetresPerUnit(opt.unit) * size, {opt.unit_stated, opt.mass});
  return true;
}

void IntegrateSolid(SolidResult& r, const LoadOptions& opt) {
  Stage(opt, "integrating");
  const PolygonMesh& mesh = r.loaded.mesh;
  IntegrationOptions io;
  io.num_threads = opt.num_threads;
  const bool triangles = IsAllTriangles(mesh);
  const PlanarityReport planarity = triangles ? PlanarityReport{} : CheckPlanarity(mesh);
  VolumeIntegrals integrals;
  if (planarity.non_planar_faces > 0) {
    // A non-planar polygon bounds no unique surface: say which one was taken.
    Warn(r, FindingKind::kNonPlanarFaces,
         std::to_string(planarity.non_planar_faces) +
             (planarity.non_planar_faces == 1 ? " polygon is not planar (face "
                                              : " polygons are not planar (the worst, face ") +
             std::to_string(planarity.worst_face + 1) + ", leaves its plane by " +
             Fixed(planarity.worst_deviation, "%.2g") +
             " of its size): each is integrated as a fan of triangles from its first corner, one of the "
             "surfaces it could mean");
    r.path_used = "triangles (signed tetrahedra), polygons split into fans (some are not planar)";
    const TriangleMesh tri = Triangulate(mesh);
    integrals = IntegrateTriangles(tri.V, tri.F, io);
  } else if (opt.path == IntegrationPath::kPolygons || (opt.path == IntegrationPath::kAuto && !triangles)) {
    r.path_used = "polygons (Mirtich), faces integrated whole";
    integrals = IntegratePolygons(mesh, io);
  } else {
    r.path_used =
        triangles ? "triangles (signed tetrahedra)" : "triangles (signed tetrahedra), polygons split into fans";
    if (triangles) {  // the corners are already an (m, 3) row-major array: integrated in place
      integrals =
          IntegrateTriangles(mesh.V, Eigen::Map<const FaceMatrix>(mesh.indices.data(), mesh.num_faces(), 3), io);
    } else {
      const TriangleMesh tri = Triangulate(mesh);
      integrals = IntegrateTriangles(tri.V, tri.F, io);
    }
  }
  r.mass_fixed = FixesMass(opt.mass);
  const double size = Diagonal(mesh);
  if (std::abs(integrals.volume) <= 1e-12 * std::pow(size, 3) && std::isfinite(size) && !opt.exact &&
      IntegrateExactlyIfTiny(r, opt, size, integrals.surface_area)) {
    return;
  }
  Finish(r, integrals, opt, size);
}

// Replaces the default path's numbers by the certified ones, keeping how far apart they were.
void Certify(SolidResult& r, const LoadOptions& opt) {
  Stage(opt, "integrating in exact arithmetic (GMP)");
  ExactMassProperties e;
  try {
    e = RequireGeometrySteps("exact integration")
            .exact(r.loaded.mesh, MetresPerUnit(opt.unit), opt.mass, opt.num_threads);
  } catch (const std::invalid_argument& error) {
    throw LoadError(r.source + ": exact integration: " + error.what());
  }
  ExactReport report;
  report.moments = e.moments;
  report.distinct_moments = e.distinct_moments;
  report.inertia_difference = (r.mp.inertia_com - e.mp.inertia_com).norm() / e.mp.inertia_com.norm();
  report.com_difference = (r.mp.center_of_mass - e.mp.center_of_mass).norm() / r.size_m;
  const double area = r.mp.surface_area;  // not rational: the default path's
  r.mp = e.mp;
  r.mp.surface_area = area;
  r.principal = ComputePrincipalInertia(r.mp.inertia_com);
  r.validity = CheckPhysicallyValid(r.principal.moments);
  r.path_used += "; certified: exact rational sums (GMP), each number correctly rounded once";
  r.exact = report;
}

// The convex hull's mass properties, at the same density as the part (or the same total mass).
void AddHull(SolidResult& r, const PolygonMesh& surface, const LoadOptions& opt) {
  Stage(opt, "computing the convex hull (CGAL)");
  HullReport h;
  PolygonMesh hull;
  try {
    hull = RequireGeometrySteps("the convex hull").convex_hull(surface);
  } catch (const std::invalid_argument& e) {
    throw LoadError(r.source + ": " + e.what());
  }
  IntegrationOptions io;
  io.num_threads = opt.num_threads;
  const VolumeIntegrals integrals = IntegratePolygons(hull, io);
  const MassProperties unit_density = Scaled(FromIntegrals(integrals, 1.0), MetresPerUnit(opt.unit));
  h.mp = AtDensity(unit_density, FixesMass(opt.mass) ? ResolveDensity(opt.mass, unit_density.volume) : r.mp.density);
  h.principal = ComputePrincipalInertia(h.mp.inertia_com);
  h.vertices = hull.V.rows();
  h.faces = hull.num_faces();
  r.hull = h;
}

}  // namespace

const char* ModelName(ModelKind kind) {
  switch (kind) {
    case ModelKind::kSolid: return "solid";
    case ModelKind::kShell: return "shell";
    case ModelKind::kWall: return "wall";
    case ModelKind::kImplicit: return "implicit";
    case ModelKind::kWindingNumber: return "winding-number";
  }
  return "?";
}

LoadError::LoadError(std::string text) : MeshFileError(Worded(text, ApiVocabulary())), text_(std::move(text)) {}

std::string WordedError(const std::exception& error, const Vocabulary& vocabulary) {
  if (const auto* e = dynamic_cast<const LoadError*>(&error)) return Worded(e->text(), vocabulary);
  return error.what();
}

const char* UnitSourceName(UnitSource source) {
  switch (source) {
    case UnitSource::kDefault: return "default";
    case UnitSource::kOption: return "option";
    case UnitSource::kFile: return "file";
  }
  return "?";
}

namespace internal {

// The unit the coordinates are read in: the one stated, else the one the file declares, else the
// default. A stated unit that differs from the file's is a finding.
LoadOptions ResolveUnit(SolidResult& r, const LoadOptions& given) {
  LoadOptions opt = given;
  const LoadedMesh& m = r.loaded;
  r.unit_source = given.unit_stated ? UnitSource::kOption : UnitSource::kDefault;
  if (m.declared_unit && !given.unit_stated) {
    opt.unit = *m.declared_unit;
    opt.unit_stated = true;
    r.unit_source = UnitSource::kFile;
  } else if (m.declared_unit && *m.declared_unit != given.unit) {
    Warn(r, FindingKind::kUnitOverridden,
         std::string("the file declares its coordinates in ") + m.declared_unit_name + "; read in " +
             UnitName(given.unit) + " as {unit=" + UnitName(given.unit) + "} says");
  }
  r.unit = opt.unit;
  return opt;
}

}  // namespace internal

namespace {

void RequireValidModel(const LoadOptions& given) {
  if (const auto conflict = FindOptionConflict(given)) throw std::invalid_argument(DescribeConflict(*conflict));
}

// A result for `source`, the options checked.
SolidResult Begin(const std::string& source, const LoadOptions& given) {
  SolidResult r;
  r.source = source;
  r.unit = given.unit;
  r.unit_source = given.unit_stated ? UnitSource::kOption : UnitSource::kDefault;
  RequireValidModel(given);
  return r;
}

}  // namespace

SolidResult LoadSolid(const std::string& file, const LoadOptions& given) {
  const auto t0 = std::chrono::steady_clock::now();
  SolidResult r = Begin(file, given);
  if (!given.parts && TryStreamedStl(r, file, given)) {
    r.seconds = SecondsSince(t0);
    return r;
  }
  Stage(given, "reading");
  const bool cad = IsCadFile(file);
  r.loaded = given.reader == Reader::kAssimp && !cad ? ReadMeshFileWithAssimp(file, given.num_threads)
                                                     : ReadMeshFile(file, internal::CadOptionsFor(given));
  if (cad) internal::AddCadFindings(r);
  if (!given.parts && internal::MaterialsDiffer(r.loaded, given)) {
    // A CAD file whose parts are of different materials: one density would be wrong for the whole.
    LoadOptions as_parts = given;
    as_parts.parts = true;
    if (!FindOptionConflict(as_parts)) {
      r.density_source = "each part's own material (the file gives its parts different densities)";
      return internal::SolveParts(std::move(r), as_parts, t0);
    }
    Warn(r, FindingKind::kMaterialOverridden,
         "the file gives its parts different materials, which these options cannot compute part by part: the "
         "whole is computed at the one density stated or the default");
  }
  if (!given.parts && r.loaded.cad_parts.size() > 1) {
    // A CAD assembly is the composition of its part instances, as every CAD system's mass
    // properties give it: parts that touch or interfere are each counted once, and interference
    // is reported on its own. Without `parts` the whole is printed alone.
    LoadOptions as_parts = given;
    as_parts.parts = true;
    if (!FindOptionConflict(as_parts)) {
      SolidResult whole = internal::SolveParts(std::move(r), as_parts, t0);
      whole.parts.clear();
      return whole;
    }
  }
  return given.parts ? internal::SolveParts(std::move(r), given, t0) : internal::Solve(std::move(r), given, t0);
}

SolidResult SolveMesh(LoadedMesh mesh, const std::string& name, const LoadOptions& given) {
  const auto t0 = std::chrono::steady_clock::now();
  SolidResult r = Begin(name, given);
  r.loaded = std::move(mesh);
  // The readers' contract: corners at bit-identical positions are one vertex.
  Stage(given, "welding coincident vertices");
  r.loaded.welded += MergeCoincidentVertices(r.loaded.mesh, given.num_threads);
  return given.parts ? internal::SolveParts(std::move(r), given, t0) : internal::Solve(std::move(r), given, t0);
}

bool LoadsSideBySide(const std::vector<std::string>& paths, const LoadOptions& options) {
  return options.reader == Reader::kAuto && std::all_of(paths.begin(), paths.end(), HasOwnReader);
}

std::optional<OptionConflict> FindOptionConflict(const LoadOptions& o) {
  const bool solid = std::holds_alternative<SolidModel>(o.model), wall = std::holds_alternative<WallModel>(o.model);
  if (const auto* shell = std::get_if<ShellModel>(&o.model);
      shell && !FixesMass(o.mass) && !(std::isfinite(shell->area_density) && shell->area_density > 0)) {
    return OptionConflict::kShellNeedsDensity;
  }
  if (const auto* w = std::get_if<WallModel>(&o.model); w && !(std::isfinite(w->thickness) && w->thickness > 0)) {
    return OptionConflict::kWallNeedsThickness;
  }
  if (o.exact && !solid) return OptionConflict::kExactNeedsSolid;
  if (o.hull && !solid && !wall) return OptionConflict::kHullNeedsSolid;
  if (!o.part_masses.empty() && !o.parts) return OptionConflict::kPartMassesNeedParts;
  if (o.parts && !solid && !wall) return OptionConflict::kPartsNeedSolid;
  if (o.parts && o.exact) return OptionConflict::kPartsNotExact;
  return std::nullopt;
}

std::string DescribeConflict(OptionConflict conflict) {
  switch (conflict) {
    case OptionConflict::kShellNeedsDensity:
      return "a shell needs a finite, positive area density (kg/m^2) or a total mass";
    case OptionConflict::kWallNeedsThickness: return "a wall needs a finite, positive thickness";
    case OptionConflict::kExactNeedsSolid:
      return "exact integration is for solids: not a shell, a wall or a winding-number estimate";
    case OptionConflict::kHullNeedsSolid:
      return "the convex hull is a solid: it goes with the solid and wall models, not a shell or a winding-number "
             "estimate";
    case OptionConflict::kPartMassesNeedParts:
      return "densities per part need the parts to be computed (LoadOptions::parts)";
    case OptionConflict::kPartsNeedSolid:
      return "parts are computed as solids or walls, not as shells or winding-number estimates";
    case OptionConflict::kPartsNotExact:
      return "certified results are for one solid: the composition of parts is not certified (run the exact "
             "integration without parts)";
  }
  return "?";
}

namespace {

// The solid where the mesh's generalized winding number is at least 1/2, estimated with error
// bars (the options' winding-number sampling, or the route's default).
void EstimateByWindingNumber(SolidResult& r, const LoadOptions& opt) {
  r.model = ModelKind::kWindingNumber;
  TriangleMesh tri = Triangulate(r.loaded.mesh);
  tri.V *= MetresPerUnit(opt.unit);
  Stage(opt, "building the winding-number hierarchy");
  const auto* wn = std::get_if<WindingNumberModel>(&opt.model);
  Estimate(r, *implicit::WindingNumberSolid(tri), wn ? wn->sampling : WindingNumberSampling(), opt.mass,
           opt.unit_stated, opt.num_threads, opt.progress);
}

// A library's exception text on one line: CGAL writes "CGAL ERROR: ...!\nExpr: ...\nFile: ...".
std::string LibraryMessage(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (c == '\n') {
      if (!out.empty() && out.back() != ' ') out += "; ";
    } else if (c != '\r') {
      out += c;
    }
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  return out;
}

// How long the union of overlapping shells may take before the winding number estimates it:
// CGAL's corefinement of many shells whose faces are coplanar (pins of one length through a hub)
// falls back to exact arithmetic at every such face and can take minutes.
// Past kUnionPairs pairs of shells whose boxes overlap, the union is not tried (a deterministic
// cost estimate: 40 pins through a hub, 78 such pairs, unite in 0.5 s; 60 pins, 177 pairs, take
// 8 s); kUnionSeconds stops one that runs long all the same.
constexpr double kUnionSeconds = 60;
constexpr std::int64_t kUnionPairs = 120;

// How many pairs of the shells' bounding boxes overlap.
std::int64_t OverlappingShellPairs(const PolygonMesh& mesh, const ShellReport& shells) {
  std::vector<Eigen::AlignedBox<double, 3>> box(shells.shells.size());
  for (std::size_t s = 0; s < box.size(); ++s) {
    for (const std::int64_t f : shells.shells[s].faces) {
      for (std::int64_t k = mesh.offsets[f]; k < mesh.offsets[f + 1]; ++k) {
        box[s].extend(mesh.V.row(mesh.indices[static_cast<std::size_t>(k)]).transpose());
      }
    }
  }
  std::int64_t pairs = 0;
  for (std::size_t a = 0; a < box.size(); ++a)
    for (std::size_t b = a + 1; b < box.size(); ++b) pairs += box[a].intersects(box[b]) ? 1 : 0;
  return pairs;
}

// The union of the mesh's overlapping shells (CGAL corefinement, a balanced tree of pairs), in a
// child process stopped after kUnionSeconds. @throws std::runtime_error saying why there is none
// (CGAL could not, or ran out of its time): the caller then estimates it.
PolygonMesh UniteWithinBudget(const PolygonMesh& mesh, std::int64_t& united) {
  const GeometrySteps& steps = RequireGeometrySteps("the union of overlapping shells");
  std::string reply;
  IsolatedEnd end = IsolatedEnd::kFinished;
  RunIsolated(
      1, 1, kUnionSeconds,
      [&](std::size_t) {
        wire::Writer w;
        try {
          std::int64_t n = 0;
          const PolygonMesh u = steps.union_of_shells(mesh, n);
          w.Str("ok");
          w.U64(static_cast<std::uint64_t>(n));
          w.U64(static_cast<std::uint64_t>(u.V.rows()));
          w.F64s(u.V.data(), static_cast<std::size_t>(u.V.size()));
          w.U64(u.indices.size());
          w.I32s(u.indices.data(), u.indices.size());
          w.U64(u.offsets.size());
          for (const std::int64_t o : u.offsets) w.U64(static_cast<std::uint64_t>(o));
        } catch (const std::runtime_error& e) {  // ours
          w.Str(e.what());
        } catch (const std::exception& e) {  // CGAL's own words, said as the reason
          w.Str("CGAL's corefinement failed: " + LibraryMessage(e.what()));
        }
        return std::move(w.bytes());
      },
      [&](std::size_t, IsolatedOutcome&& o) {
        end = o.end;
        reply = std::move(o.output);
      });
  if (end == IsolatedEnd::kTimedOut) {
    throw std::runtime_error("the union did not finish within " + Fixed(kUnionSeconds, "%g") + " s");
  }
  if (end != IsolatedEnd::kFinished) throw std::runtime_error("the union's process ended without an answer");
  try {
    wire::Reader r(reply);
    const std::string status = r.Str();
    if (status != "ok") throw std::runtime_error(status);
    united = static_cast<std::int64_t>(r.U64());
    PolygonMesh u;
    std::vector<double> v;
    r.F64s(3 * r.U64(), v);
    u.V = Eigen::Map<const VertexMatrix>(v.data(), static_cast<Eigen::Index>(v.size() / 3), 3);
    r.I32s(r.U64(), u.indices);
    u.offsets.resize(r.U64());
    for (std::int64_t& o : u.offsets) o = static_cast<std::int64_t>(r.U64());
    return u;
  } catch (const wire::Truncated&) {
    throw std::runtime_error("the union's process sent a truncated mesh");
  }
}

// The repair (CGAL), its library's own failures (a precondition, "Unauthorized intersections of
// constraints" from a hole's triangulation) turned into the one error form: the file, the stage,
// what failed, what to try. Our own refusals pass as they are.
RepairedMesh RepairInOurWords(const SolidResult& r, const GeometrySteps& steps) {
  try {
    return steps.repair(r.loaded.mesh, RepairOptions{});
  } catch (const MeshFileError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw LoadError(r.source + ": the repair failed in CGAL (" + LibraryMessage(e.what()) +
                    "); {winding_number} estimates the solid with error bars without repairing it");
  }
}

// Overlapping shells not united — CGAL could not (a shell that intersects itself), or the cost
// estimate or the time budget said no: their union is where the winding number is at least 1/2
// (2 inside both, 1 inside one), the route said.
void EstimateUnion(SolidResult& r, const LoadOptions& opt, const std::string& why) {
  Warn(r, FindingKind::kOverlappingShells,
       r.shells.problem + "; their union was not computed exactly (" + why +
           "), so it is estimated as the solid where the winding number is at least 1/2, with error bars");
  r.shells = ShellReport{};
  EstimateByWindingNumber(r, opt);
}

}  // namespace

namespace internal {

SolidResult Solve(SolidResult r, const LoadOptions& given, std::chrono::steady_clock::time_point t0) {
  LoadOptions opt = ResolveUnit(r, given);  // the unit the file declares, unless one is stated
  ApplyFileMaterial(r, opt);                // and the density its material gives, unless one is stated
  if (SolveBrep(r, opt)) {
    r.seconds = SecondsSince(t0);
    return r;
  }
  if (opt.repair) {
    Stage(opt, "repairing (CGAL)");
    RepairedMesh repaired = RepairInOurWords(r, RequireGeometrySteps("the repair"));
    r.loaded.mesh = std::move(repaired.mesh);
    r.repair = repaired.report;
  }
  const PolygonMesh& mesh = r.loaded.mesh;
  Stage(opt, "checking edges");
  r.topology = AnalyzeTopology(mesh, opt.num_threads);
  if (opt.check_self_intersections) {
    Stage(opt, "checking self-intersections (CGAL)");
    r.self_intersections =
        RequireGeometrySteps("the self-intersection check").count_self_intersections(mesh, kSelfIntersectionLimit);
  }
  if (r.topology.duplicate_faces + r.topology.reversed_duplicate_faces > 0) RefuseDuplicates(r);
  if (r.self_intersections < 0 && opt.check_self_intersections) {
    Warn(r, FindingKind::kSelfIntersections,
         "self-intersections not checked: the check stopped after its budget of candidate pairs (boxes of many "
         "faces overlap around one corner, in a fan that folds or winds around it more than once); the numbers are "
         "those of the surface "
         "as given");
  }
  if (r.self_intersections > 0) {
    Warn(r, FindingKind::kSelfIntersections,
         std::to_string(r.self_intersections) +
             " pairs of faces intersect: where the surface passes through itself, volume is counted twice or "
             "cancelled, and the numbers are not those of a solid");
  }
  if (std::holds_alternative<WindingNumberModel>(opt.model)) {
    // Inside is where the generalized winding number is at least 1/2: holes are bridged, so an
    // open scan gets a sensible solid; the estimate carries error bars.
    if (!r.topology.BoundsVolume()) {
      Warn(r, FindingKind::kOpenSurface, r.topology.Problems() + "; the winding number bridges the holes");
    }
    EstimateByWindingNumber(r, opt);
    r.seconds = SecondsSince(t0);
    return r;
  }
  if (const auto* shell = std::get_if<ShellModel>(&opt.model)) {
    IntegrateShell(r, *shell, opt);
    r.seconds = SecondsSince(t0);
    return r;
  }
  const auto* wall = std::get_if<WallModel>(&opt.model);
  if (!r.topology.BoundsVolume()) {
    if (!opt.allow_open || wall) RefuseOpen(r, opt, wall != nullptr);
    Warn(r, FindingKind::kOpenSurface,
         r.topology.Problems() + UnweldedCorners(r) +
             "; computed anyway ({allow_open}): the result depends on the reference point and is not trustworthy");
  }
  if (r.topology.non_manifold_edges > 0 && r.topology.BoundsVolume()) {
    Warn(r, FindingKind::kNonManifoldEdges,
         std::to_string(r.topology.non_manifold_edges) +
             " edges are shared by more than two faces (solids touching along edges); each is matched in both "
             "directions, so the volume is well defined");
  }
  if (r.topology.components > 1) {
    Stage(opt, "checking how the shells nest");
    r.shells = AnalyzeShells(mesh);
    if (r.shells.crossing.first >= 0 && opt.repair) {
      // Overlapping shells: their union is the solid they describe together.
      Stage(opt, "uniting the overlapping shells (CGAL)");
      std::int64_t united = 0;
      try {
        const std::int64_t pairs = OverlappingShellPairs(r.loaded.mesh, r.shells);
        if (pairs > kUnionPairs) {
          throw std::runtime_error(std::to_string(r.shells.shells.size()) + " shells in " + std::to_string(pairs) +
                                   " overlapping pairs, more than the " + std::to_string(kUnionPairs) +
                                   " whose union by corefinement takes seconds, not minutes");
        }
        r.loaded.mesh = UniteWithinBudget(r.loaded.mesh, united);
      } catch (const std::runtime_error& e) {
        EstimateUnion(r, opt, e.what());
        r.seconds = SecondsSince(t0);
        return r;
      }
      r.repair->united_shells = united;
      r.repair->volume_after = SignedVolumeOf(r.loaded.mesh);
      r.topology = AnalyzeTopology(r.loaded.mesh, opt.num_threads);
      r.shells = r.topology.components > 1 ? AnalyzeShells(r.loaded.mesh) : ShellReport{};
    }
    if (!r.shells.problem.empty()) {
      if (!opt.allow_open) throw LoadError(r.source + ": " + r.shells.problem);
      Warn(r, FindingKind::kOverlappingShells, r.shells.problem + "; computed anyway ({allow_open})");
    }
  }
  const PolygonMesh surface = opt.hull ? r.loaded.mesh : PolygonMesh{};  // before a wall replaces it
  if (wall) {
    IntegrateWall(r, *wall, opt);
  } else {
    IntegrateSolid(r, opt);
  }
  AddRepairFindings(r, opt);
  if (opt.hull) AddHull(r, surface, opt);
  if (opt.exact) Certify(r, opt);
  if (!wall) AddBrep(r, opt);
  r.seconds = SecondsSince(t0);
  return r;
}

void FinishIntegrals(SolidResult& r, const VolumeIntegrals& integrals, const LoadOptions& opt, double size) {
  Finish(r, integrals, opt, size);
}

double MeshDiagonal(const PolygonMesh& mesh) { return mesh.V.rows() == 0 ? 0.0 : Diagonal(mesh); }

}  // namespace internal

SolidResult EstimateImplicit(const ImplicitSolid& solid, const ImplicitOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  SolidResult r;
  r.unit = opt.unit;
  r.unit_source = opt.unit_stated ? UnitSource::kOption : UnitSource::kDefault;
  r.model = ModelKind::kImplicit;
  r.source = solid.Describe();
  r.full_topology = false;
  r.loaded.format = "implicit";
  // Implicit solids are shared and immutable; scaling wraps without copying.
  const ImplicitPtr view(std::shared_ptr<const ImplicitSolid>(), &solid);
  Estimate(r, *implicit::Scaled(view, MetresPerUnit(opt.unit)), opt.sampling, opt.mass, opt.unit_stated,
           opt.num_threads, opt.progress);
  r.seconds = SecondsSince(t0);
  return r;
}

}  // namespace massprops
