// massprops: mass properties of the solids that mesh files bound.
//
//   massprops FILE... [--density D | --mass M] [--unit m|cm|mm|in|ft|um]
//                     [--format table|json|csv|urdf|sdf|mjcf] [--frame com|origin]
//                     [--path auto|triangles|polygons] [--threads N] [--allow-open] [-o FILE]
//
// This file only maps the command line onto the library's LoadOptions (massprops/load.h) and
// prints what the formatters make of the results. Errors are one line on stderr naming the file
// and the fault; the exit status is 1 when any file failed, 2 for bad arguments. An output file
// is written whole or not at all.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "batch.h"
#include "cli.h"
#include "fill.h"
#include "massprops/implicit.h"
#include "massprops/io.h"
#include "massprops/load.h"
#include "massprops/principal_axes.h"
#include "massprops/report/atomic_file.h"
#include "massprops/report/density_map.h"
#include "massprops/report/format.h"
#include "massprops/units.h"
#include "massprops/version.h"
#include "progress.h"
#include "validate.h"

namespace {

using namespace massprops;

// What the command line says, before it becomes typed options.
struct Arguments {
  std::vector<std::string> files;
  double density = 1000.0;
  double mass = 0.0;
  std::string unit = "m";
  std::string path = "auto";
  std::string format = "table";
  std::string frame = "com";
  std::string output;
  int threads = 0;
  bool quiet = false;
  bool allow_open = false;
  bool full_check = false;
  bool repair = false;
  bool check_self_intersections = false;
  bool hull = false;
  bool exact = false;
  bool shell = false;
  double area_density = 0.0;
  double wall = 0.0;
  std::string implicit;
  bool winding_number = false;
  bool mc = false;
  double samples = 1 << 20;
  int randomizations = 16;
  std::uint64_t seed = 1;
  double tolerance = 0;
  std::string reader = "auto";
  std::vector<double> about;       // a point, in the file's unit and axes
  std::vector<double> axes;        // 9 numbers, rows of the rotation whose columns are the axes
  std::vector<double> axes_euler;  // yaw, pitch, roll in degrees (z, y', x'')
  std::string output_units;
  bool parts = false;
  std::string density_map;
};

template <typename T>
T FromName(const std::map<std::string, T>& names, const std::string& name) {
  return names.at(name);  // CLI11's IsMember admitted only these
}

MonteCarloOptions Sampling(const Arguments& a) {
  MonteCarloOptions mc;
  mc.method = a.mc ? SamplingMethod::kMonteCarlo : SamplingMethod::kQuasiMonteCarlo;
  mc.samples = static_cast<std::int64_t>(a.samples);
  mc.randomizations = a.randomizations;
  mc.seed = a.seed;
  mc.tolerance = a.tolerance;
  return mc;
}

LoadOptions ToLoadOptions(const Arguments& a) {
  LoadOptions o;
  o.unit = ParseLengthUnit(a.unit);
  o.mass = a.mass > 0 ? MassSpec(TotalMass{a.mass}) : MassSpec(Density{a.density});
  if (a.shell) {
    o.model = ShellModel{a.area_density};
  } else if (a.wall > 0) {
    o.model = WallModel{a.wall};
  } else if (a.winding_number) {
    o.model = WindingNumberModel{Sampling(a)};
  }
  o.path = FromName<IntegrationPath>({{"auto", IntegrationPath::kAuto},
                                      {"triangles", IntegrationPath::kTriangles},
                                      {"polygons", IntegrationPath::kPolygons}},
                                     a.path);
  o.reader = a.reader == "assimp" ? Reader::kAssimp : Reader::kAuto;
  o.repair = a.repair;
  o.allow_open = a.allow_open;
  o.full_check = a.full_check;
  o.check_self_intersections = a.check_self_intersections;
  o.hull = a.hull;
  o.exact = a.exact;
  o.parts = a.parts || !a.density_map.empty();
  o.num_threads = a.threads;
  return o;
}

}  // namespace

// massprops merge OUT SHARD...
int MergeMain(int argc, char** argv) {
  CLI::App app{
      "massprops merge: joins the outputs of `massprops batch --shard i/n` runs into one file, checking "
      "that every file has exactly one record"};
  std::string out;
  std::vector<std::string> shards;
  app.add_option("output", out, "The merged JSON Lines file (written whole or not at all)")->required();
  app.add_option("shards", shards, "The shards' outputs")->required();
  if (const int status = app::ParseArguments(app, argc, argv); status >= 0) return status;
  return cli::RunMerge(out, shards);
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "merge") return MergeMain(argc - 1, argv + 1);
  if (argc > 1 && std::string(argv[1]) == "validate") return cli::ValidateMain(argc - 1, argv + 1);
  if (argc > 1 && std::string(argv[1]) == "fill") return cli::FillMain(argc - 1, argv + 1);
  // massprops batch (DIR | MANIFEST) -o OUT [batch options] [the usual options]
  const bool batch = argc > 1 && std::string(argv[1]) == "batch";
  if (batch) {
    argv[1] = argv[0];
    ++argv;
    --argc;
  }
  CLI::App app{batch ? "massprops batch: every mesh file of a folder or a manifest, each in its own process, one JSON "
                       "line each in the output (see the README's dataset section)"
                     : "massprops: exact mass properties of the solids that mesh files bound.\n"
                       "Reads OBJ, STL, PLY, OFF (own parsers) and other formats through assimp.\n"
                       "Subcommands: massprops batch (DIR | MANIFEST) -o OUT.jsonl; massprops merge OUT SHARD...; "
                       "massprops validate; massprops fill ROBOT -o OUT"};
  app.set_version_flag("--version", std::string("massprops ") + kVersion);
  Arguments a;
  cli::BatchOptions b;
  std::string shard;
  if (batch) {
    app.add_option("--jobs", b.jobs, "Files computed at a time, each in its own process (0 = one per core)")
        ->check(app::NonNegative());
    app.add_option("--shard", shard, "i/n: only the files whose index in sorted order is i mod n (job arrays)");
    app.add_flag("--resume", b.resume, "Go on from the records already in the output (a torn last line is dropped)");
    app.add_option("--timeout", b.timeout_seconds, "Seconds a file may take before it is stopped (a timeout record)")
        ->check(app::Positive())
        ->capture_default_str();
    app.add_flag("--summary", b.summary_json, "Print the summary as JSON on stdout");
  }
  app.add_option("files", a.files, "Mesh files");
  app.add_option("--implicit", a.implicit,
                 "Estimate a solid given in the shape syntax, e.g. 'torus(R=1, r=0.25)' "
                 "(Monte Carlo / QMC, with error bars; see the README)");
  app.add_flag("--winding-number", a.winding_number,
               "Files: the solid where the generalized winding number is >= 1/2, estimated by "
               "Monte Carlo / QMC with error bars (meshes with holes get a sensible answer)");
  auto* mc = app.add_flag("--mc", a.mc, "Plain Monte Carlo (with --implicit or --winding-number)");
  app.add_flag("--qmc", "Randomized quasi-Monte Carlo, scrambled Sobol (the default)")->excludes(mc);
  app.add_option("--samples", a.samples, "Monte-Carlo points in all (e.g. 1e7)")->check(app::InRange(2, 1e13));
  app.add_option("--randomizations", a.randomizations, "QMC: independent scramblings (error bars from their spread)")
      ->check(app::InRange(2, 1000));
  app.add_option("--seed", a.seed, "Random seed (same seed, same bits, any thread count)");
  app.add_option("--tolerance", a.tolerance,
                 "Sample until the relative standard error of the mass and of each principal moment "
                 "is below this")
      ->check(app::InRange(1e-12, 1));
  auto* density = app.add_option("--density", a.density, "Uniform density in kg/m^3")
                      ->check(app::Positive())
                      ->capture_default_str();
  app.add_option("--mass", a.mass, "Total mass in kg (sets the density; excludes --density)")
      ->check(app::Positive())
      ->excludes(density);
  auto* shell = app.add_flag("--shell", a.shell,
                             "Thin shell: the surface itself carries the mass, at --area-density "
                             "(or --mass); open meshes are fine");
  app.add_option("--area-density", a.area_density, "Area density of a --shell, kg/m^2")
      ->check(app::Positive())
      ->needs(shell);
  app.add_option("--wall", a.wall,
                 "Hollow part: the solid between the closed surface and its inward offset by this "
                 "wall thickness (in the file's unit, --unit)")
      ->check(app::Positive())
      ->excludes(shell);
  std::vector<std::string> units;
  for (LengthUnit u : kAllLengthUnits) units.emplace_back(UnitName(u));
  app.add_option("--unit", a.unit, "Unit of the file's coordinates")
      ->check(CLI::IsMember(units))
      ->capture_default_str();
  app.add_option("--format", a.format, "Output format")
      ->check(CLI::IsMember({"table", "json", "csv", "urdf", "sdf", "mjcf"}))
      ->capture_default_str();
  app.add_option("--frame", a.frame,
                 "Also report the inertia about the file's origin (origin), or only about the "
                 "center of mass (com)")
      ->check(CLI::IsMember({"com", "origin"}))
      ->capture_default_str();
  app.add_option("--path", a.path,
                 "Integration path: auto (triangles; Mirtich for quads and n-gons), triangles, "
                 "polygons")
      ->check(CLI::IsMember({"auto", "triangles", "polygons"}))
      ->capture_default_str();
  app.add_option("--threads", a.threads, "Worker threads (0 = all cores); same bits for any count")
      ->check(app::NonNegative());
  app.add_flag("--allow-open", a.allow_open,
               "Compute even when the mesh is open or inconsistently oriented (with a warning)");
  app.add_flag("--repair", a.repair,
               "Repair with CGAL first: merge near-coincident vertices (1e-9 of the size), drop "
               "degenerate and duplicate faces, orient faces consistently, stitch borders, orient "
               "shells outward and cavities inward; what changed is reported");
  app.add_flag("--check-self-intersections", a.check_self_intersections,
               "Count pairs of faces that intersect (CGAL); a warning when there are any");
  app.add_flag("--hull", a.hull,
               "Also the mass properties of the convex hull (CGAL), as collision engines see the body, at the "
               "same density (or --mass), printed beside the exact ones");
  app.add_flag("--exact", a.exact,
               "Certified results: exact rational integration of the stored coordinates (GMP); every number "
               "correctly rounded, principal moments as enclosures, the default path's difference shown");
  app.add_flag("--full-check", a.full_check,
               "Binary STL: weld the corners and count vertices, components and bad edges even "
               "when the streaming check finds the surface closed (slower)");
  app.add_option("--reader", a.reader,
                 "auto: our own readers for OBJ/STL/PLY/OFF, assimp for the rest; assimp: assimp "
                 "for every format (32-bit coordinates; for comparison)")
      ->check(CLI::IsMember({"auto", "assimp"}))
      ->capture_default_str();
  app.add_option("--about", a.about,
                 "Also report the inertia tensor about this point X,Y,Z (in the file's unit and axes)")
      ->delimiter(',')
      ->expected(3);
  auto* axes = app.add_option("--axes", a.axes,
                              "Report that tensor in these axes: a rotation as 9 numbers, row by row, whose "
                              "columns are the axes in the file's axes")
                   ->delimiter(',')
                   ->expected(9);
  app.add_option("--axes-euler", a.axes_euler,
                 "The axes as yaw,pitch,roll in degrees (intrinsic z, y', x'': R = Rz Ry Rx)")
      ->delimiter(',')
      ->expected(3)
      ->excludes(axes);
  app.add_option("--output-units", a.output_units,
                 "Units of the table, JSON and CSV: si (default), mmgs (g, mm, g*mm^2), cgs, ips (lb, in, "
                 "lb*in^2), or MASS,LENGTH,INERTIA such as kg,mm,kg*mm^2");
  app.add_flag("--parts", a.parts,
               "Each part the file names (OBJ objects or groups; glTF, 3MF, COLLADA, FBX nodes) on its own, "
               "and the whole as their composition");
  app.add_option("--density-map", a.density_map,
                 "JSON or CSV: part name or glob pattern -> density (kg/m^3) or mass (kg); first match wins; "
                 "implies --parts");
  app.add_flag("-q,--quiet", a.quiet, "No progress line on stderr");
  app.add_option("-o,--output", a.output, "Write the output to this file (whole or not at all)");
  if (const int status = app::ParseArguments(app, argc, argv); status >= 0) return status;

  auto bad = [](const std::string& what) {
    std::cerr << "error: " << what << "\n";
    return app::kBadArguments;
  };
  if (!std::isfinite(a.density) || !std::isfinite(a.mass) || !std::isfinite(a.area_density) || !std::isfinite(a.wall)) {
    return bad("--density, --mass, --area-density and --wall must be finite");
  }
  if (a.shell && !(a.area_density > 0) && !(a.mass > 0))
    return bad("--shell needs --area-density (kg/m^2) or --mass (kg)");
  if (a.shell && app.count("--density") > 0) return bad("--shell takes --area-density (kg/m^2), not --density");
  if (a.files.empty() && a.implicit.empty()) return bad("give mesh files, or --implicit SHAPE (see --help)");
  const bool sampling_flags = app.count("--mc") + app.count("--qmc") + app.count("--samples") +
                                  app.count("--randomizations") + app.count("--seed") + app.count("--tolerance") >
                              0;
  if (sampling_flags && a.implicit.empty() && !a.winding_number) {
    return bad(
        "--mc/--qmc/--samples/--randomizations/--seed/--tolerance belong to --implicit or "
        "--winding-number (exact integration needs none)");
  }
  if (a.winding_number && (a.shell || a.wall > 0))
    return bad("--winding-number does not combine with --shell or --wall");
  if (a.exact && (a.shell || a.wall > 0 || a.winding_number)) {
    return bad("--exact certifies a solid's integrals: not with --shell, --wall or --winding-number");
  }
  if (a.hull && (a.shell || a.winding_number)) {
    return bad("--hull is the convex hull as a solid: it goes with solids and --wall, not --shell or --winding-number");
  }
  if (!a.implicit.empty() && (a.shell || a.wall > 0)) {
    return bad("--shell and --wall describe a mesh's surface; an --implicit shape is a solid and takes neither");
  }
  if ((a.parts || !a.density_map.empty()) && (a.shell || a.winding_number || a.exact)) {
    return bad("--parts and --density-map compute solids (or --wall): not --shell, --winding-number or --exact");
  }
  if (a.files.empty()) {  // only --implicit: the options about mesh files would be ignored
    for (const char* flag :
         {"--parts", "--density-map", "--repair", "--allow-open", "--full-check", "--check-self-intersections",
          "--path", "--reader", "--winding-number", "--hull", "--exact"}) {
      if (app.count(flag) > 0)
        return bad(std::string(flag) + " applies to mesh files; --implicit shapes take no such option");
    }
  }

  if (!a.output.empty()) {
    try {
      report::CheckOutputPath(a.output, a.files);
    } catch (const std::exception& e) {
      return bad(std::string("-o ") + e.what());
    }
  }

  if (batch) {
    if (a.files.size() != 1) return bad("batch takes one folder or manifest (a text file with one path a line)");
    if (a.output.empty()) return bad("batch needs -o FILE.jsonl (records are appended to it, one line each)");
    if (!a.implicit.empty()) return bad("batch computes mesh files; --implicit has no place in it");
    if (app.count("--format") > 0 || app.count("--frame") > 0) {
      return bad("batch writes JSON Lines records; --format and --frame do not apply");
    }
    if (!shard.empty()) {
      try {
        cli::ParseShard(shard, b.shard_index, b.shard_count);
      } catch (const std::exception& e) {
        return bad(e.what());
      }
    }
    b.input = a.files[0];
    b.output = a.output;
    b.quiet = a.quiet;
    b.threads_given = app.count("--threads") > 0;
    b.load = ToLoadOptions(a);
    b.load.unit_stated = app.count("--unit") > 0;
    if (!a.density_map.empty()) {
      try {
        b.load.part_masses = report::ReadDensityMap(a.density_map);
      } catch (const std::exception& e) {
        return bad(e.what());
      }
    }
    return cli::RunBatch(b);
  }

  report::FormatOptions format;
  format.format = FromName<report::Format>({{"table", report::Format::kTable},
                                            {"json", report::Format::kJson},
                                            {"csv", report::Format::kCsv},
                                            {"urdf", report::Format::kUrdf},
                                            {"sdf", report::Format::kSdf},
                                            {"mjcf", report::Format::kMjcf}},
                                           a.format);
  format.frame = a.frame == "origin" ? report::Frame::kOrigin : report::Frame::kCenterOfMass;
  format.json_array = a.files.size() + (a.implicit.empty() ? 0 : 1) > 1;
  LoadOptions options = ToLoadOptions(a);
  options.unit_stated = app.count("--unit") > 0;
  if (!a.density_map.empty()) {
    try {
      options.part_masses = report::ReadDensityMap(a.density_map);
    } catch (const std::exception& e) {
      return bad(e.what());
    }
  }
  if (!a.output_units.empty()) {
    try {
      format.units = ParseReportUnits(a.output_units);
    } catch (const std::exception& e) {
      return bad(std::string("--output-units: ") + e.what());
    }
  }
  if (!a.about.empty() || !a.axes.empty() || !a.axes_euler.empty()) {
    ReferenceFrame f;
    for (double v : a.about) {
      if (!std::isfinite(v)) return bad("--about needs three finite numbers");
    }
    for (double v : a.axes) {
      if (!std::isfinite(v)) return bad("--axes needs nine finite numbers");
    }
    for (double v : a.axes_euler) {
      if (!std::isfinite(v)) return bad("--axes-euler needs three finite angles");
    }
    // In each file's unit (the one stated, or the one the file declares): scaled per result.
    if (!a.about.empty()) f.point = Vector3(a.about[0], a.about[1], a.about[2]);
    try {
      if (!a.axes.empty()) {
        Matrix3 r;
        r << a.axes[0], a.axes[1], a.axes[2], a.axes[3], a.axes[4], a.axes[5], a.axes[6], a.axes[7], a.axes[8];
        f.axes = RequireRotation(r);
      }
      if (!a.axes_euler.empty()) {
        const double deg = 3.14159265358979323846 / 180;
        f.axes = RotationFromEulerZYX(a.axes_euler[0] * deg, a.axes_euler[1] * deg, a.axes_euler[2] * deg);
      }
    } catch (const std::exception& e) {
      return bad(std::string("--axes: ") + e.what());
    }
    format.reference = f;
  }
  const bool robot = format.format == report::Format::kUrdf || format.format == report::Format::kSdf ||
                     format.format == report::Format::kMjcf;
  if (robot && (!a.output_units.empty() || format.reference)) {
    return bad(
        "URDF, SDF and MJCF give the inertia about the center of mass in SI; --output-units, --about and "
        "--axes are for the table, JSON and CSV");
  }

  int failures = 0;
  std::vector<SolidResult> results;
  std::string text;
  // One input's outcome: its result, or its error (one line, worded for the command line).
  struct Outcome {
    std::optional<SolidResult> result;
    std::string error;
  };
  auto compute = [&](const std::string& name, bool show_progress, const auto& solve) {
    Outcome out;
    try {
      app::Progress progress("massprops", name, show_progress);
      out.result = solve([&progress](const char* stage) { progress.Stage(stage); });
    } catch (const MeshFileError& e) {  // already names the file
      out.error = WordedError(e, report::CliVocabulary());
    } catch (const std::exception& e) {
      out.error = name + ": " + e.what();
    }
    return out;
  };
  // Messages and results in the order of the inputs, whatever order they were computed in.
  auto emit = [&](const std::string& name, Outcome&& o) {
    if (!o.result) {
      ++failures;
      std::cerr << "error: " << o.error << "\n";
      return;
    }
    const SolidResult& r = *o.result;
    for (const Finding& f : r.findings) {
      std::cerr << "warning: " << name << ": " << Worded(f.message, report::CliVocabulary()) << "\n";
    }
    if (format.format == report::Format::kTable) text += (text.empty() ? "" : "\n") + FormatTable(r, format);
    if (robot) text += FormatRobot(r, format.format);
    results.push_back(std::move(*o.result));
  };
  auto load = [&](const std::string& file, bool show_progress) {
    return compute(file, show_progress, [&](const ProgressCallback& progress) {
      LoadOptions o = options;
      o.progress = progress;
      return LoadSolid(file, o);
    });
  };
  // Several files read by our own readers are computed side by side, one per thread (a dataset's
  // small files gain the cores a single file's stages would use); assimp's formats run in a child
  // process, forked from one thread at a time. No progress line then: the lines would interleave.
  const bool side_by_side = a.files.size() > 1 && options.reader == Reader::kAuto &&
                            std::all_of(a.files.begin(), a.files.end(), HasOwnReader);
  if (side_by_side) {
    std::vector<Outcome> outcomes(a.files.size());
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
      for (std::size_t i = next++; i < a.files.size(); i = next++) outcomes[i] = load(a.files[i], false);
    };
    const unsigned cores = a.threads > 0 ? static_cast<unsigned>(a.threads) : std::thread::hardware_concurrency();
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < std::min<std::size_t>(std::max(cores, 1u), a.files.size()); ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
    for (std::size_t i = 0; i < a.files.size(); ++i) emit(a.files[i], std::move(outcomes[i]));
  } else {
    for (const std::string& file : a.files) emit(file, load(file, !a.quiet));
  }
  if (!a.implicit.empty()) {
    emit("--implicit", compute("--implicit", !a.quiet, [&](const ProgressCallback& progress) {
           ImplicitOptions o;
           o.unit = options.unit;
           o.unit_stated = options.unit_stated;
           o.mass = options.mass;
           o.sampling = Sampling(a);
           o.num_threads = a.threads;
           o.progress = progress;
           return EstimateImplicit(*implicit::ParseShape(a.implicit, ReadSdfGridFile), o);
         }));
  }
  if (format.format == report::Format::kJson && (!results.empty() || format.json_array)) {
    text = FormatJson(results, format);  // several inputs: an array, even if some (or all) failed
  }
  if (!results.empty()) {
    if (format.format == report::Format::kCsv) text = FormatCsv(results, format);
  }
  if (!a.output.empty()) {
    try {
      if (!text.empty()) report::WriteFileAtomically(a.output, text);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    }
  } else {
    std::cout << text;
  }
  return failures > 0 ? 1 : 0;
}
