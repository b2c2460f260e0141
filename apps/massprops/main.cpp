// massprops: mass properties of the solids that mesh files bound.
//
//   massprops FILE... [--density D | --mass M] [--unit m|cm|mm|in|ft]
//                     [--format table|json|csv|urdf|sdf|mjcf] [--frame com|origin]
//                     [--path auto|triangles|polygons] [--threads N] [--allow-open] [-o FILE]
//
// Errors are one line on stderr naming the file and the fault; the exit status is 1 when any
// file failed, 2 for bad arguments. An output file is written whole or not at all.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "atomic_file.h"
#include "report.h"


int main(int argc, char** argv) {
  using massprops::app::Options;
  using massprops::app::Report;
  CLI::App app{"massprops: exact mass properties of the solids that mesh files bound.\n"
               "Reads OBJ, STL, PLY, OFF (own parsers) and other formats through assimp."};
  Options opt;
  app.add_option("files", opt.files, "Mesh files");
  app.add_option("--implicit", opt.implicit,
                 "Estimate a solid given in the shape syntax, e.g. 'torus(R=1, r=0.25)' "
                 "(Monte Carlo / QMC, with error bars; see the README)");
  app.add_flag("--winding-number", opt.winding_number,
               "Files: the solid where the generalized winding number is >= 1/2, estimated by "
               "Monte Carlo / QMC with error bars (meshes with holes get a sensible answer)");
  auto* mc = app.add_flag("--mc", "Plain Monte Carlo (with --implicit or --winding-number)");
  app.add_flag("--qmc", "Randomized quasi-Monte Carlo, scrambled Sobol (the default)")->excludes(mc);
  app.add_option("--samples", opt.samples, "Monte-Carlo points in all (e.g. 1e7)")->check(CLI::Range(2.0, 1e13));
  app.add_option("--randomizations", opt.randomizations, "QMC: independent scramblings (error bars from their spread)")
      ->check(CLI::Range(2, 1000));
  app.add_option("--seed", opt.seed, "Random seed (same seed, same bits, any thread count)");
  app.add_option("--tolerance", opt.tolerance,
                 "Sample until the relative standard error of the mass and of each principal moment "
                 "is below this")
      ->check(CLI::Range(1e-12, 1.0));
  auto* density = app.add_option("--density", opt.density, "Uniform density in kg/m^3")
                      ->check(CLI::PositiveNumber)
                      ->capture_default_str();
  app.add_option("--mass", opt.mass, "Total mass in kg (sets the density; excludes --density)")
      ->check(CLI::PositiveNumber)
      ->excludes(density);
  auto* shell = app.add_flag("--shell", opt.shell,
                             "Thin shell: the surface itself carries the mass, at --area-density "
                             "(or --mass); open meshes are fine");
  app.add_option("--area-density", opt.area_density, "Area density of a --shell, kg/m^2")
      ->check(CLI::PositiveNumber)
      ->needs(shell);
  app.add_option("--wall", opt.wall,
                 "Hollow part: the solid between the closed surface and its inward offset by this "
                 "wall thickness (in the file's unit, --unit)")
      ->check(CLI::PositiveNumber)
      ->excludes(shell);
  app.add_option("--unit", opt.unit, "Unit of the file's coordinates")
      ->check(CLI::IsMember({"m", "cm", "mm", "in", "ft"}))
      ->capture_default_str();
  app.add_option("--format", opt.format, "Output format")
      ->check(CLI::IsMember({"table", "json", "csv", "urdf", "sdf", "mjcf"}))
      ->capture_default_str();
  app.add_option("--frame", opt.frame,
                 "Also report the inertia about the file's origin (origin), or only about the "
                 "center of mass (com)")
      ->check(CLI::IsMember({"com", "origin"}))
      ->capture_default_str();
  app.add_option("--path", opt.path,
                 "Integration path: auto (triangles; Mirtich for quads and n-gons), triangles, "
                 "polygons")
      ->check(CLI::IsMember({"auto", "triangles", "polygons"}))
      ->capture_default_str();
  app.add_option("--threads", opt.threads, "Worker threads (0 = all cores); same bits for any count")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--allow-open", opt.allow_open,
               "Compute even when the mesh is open or inconsistently oriented (with a warning)");
  app.add_flag("--repair", opt.repair,
               "Repair with CGAL first: merge near-coincident vertices (1e-9 of the size), drop "
               "degenerate and duplicate faces, orient faces consistently, stitch borders, orient "
               "shells outward and cavities inward; what changed is reported");
  app.add_flag("--check-self-intersections", opt.check_self_intersections,
               "Count pairs of faces that intersect (CGAL); a warning when there are any");
  app.add_flag("--full-check", opt.full_check,
               "Binary STL: weld the corners and count vertices, components and bad edges even "
               "when the streaming check finds the surface closed (slower)");
  app.add_option("--reader", opt.reader,
                 "auto: our own readers for OBJ/STL/PLY/OFF, assimp for the rest; assimp: assimp "
                 "for every format (32-bit coordinates; for comparison)")
      ->check(CLI::IsMember({"auto", "assimp"}))
      ->capture_default_str();
  app.add_flag("-q,--quiet", opt.quiet, "No progress line on stderr");
  app.add_option("-o,--output", opt.output, "Write the output to this file (whole or not at all)");
  CLI11_PARSE(app, argc, argv);
  if (!std::isfinite(opt.density) || !std::isfinite(opt.mass) || !std::isfinite(opt.area_density) ||
      !std::isfinite(opt.wall)) {
    std::cerr << "error: --density, --mass, --area-density and --wall must be finite\n";
    return 2;
  }
  if (opt.shell && !(opt.area_density > 0) && !(opt.mass > 0)) {
    std::cerr << "error: --shell needs --area-density (kg/m^2) or --mass (kg)\n";
    return 2;
  }
  if (opt.shell && app.count("--density") > 0) {
    std::cerr << "error: --shell takes --area-density (kg/m^2), not --density\n";
    return 2;
  }
  if (app.count("--mc") > 0) opt.method = "mc";
  if (opt.files.empty() && opt.implicit.empty()) {
    std::cerr << "error: give mesh files, or --implicit SHAPE (see --help)\n";
    return 2;
  }
  const bool sampling_flags = app.count("--mc") + app.count("--qmc") + app.count("--samples") +
                                  app.count("--randomizations") + app.count("--seed") + app.count("--tolerance") > 0;
  if (sampling_flags && opt.implicit.empty() && !opt.winding_number) {
    std::cerr << "error: --mc/--qmc/--samples/--randomizations/--seed/--tolerance belong to --implicit or "
                 "--winding-number (exact integration needs none)\n";
    return 2;
  }
  if (opt.winding_number && (opt.shell || opt.wall > 0)) {
    std::cerr << "error: --winding-number does not combine with --shell or --wall\n";
    return 2;
  }
  const bool robot = opt.format == "urdf" || opt.format == "sdf" || opt.format == "mjcf";

  int failures = 0;
  std::vector<Report> reports;
  std::string text;
  std::vector<std::string> jobs = opt.files;
  if (!opt.implicit.empty()) jobs.push_back("\x01" + opt.implicit);  // marks the shape
  for (const auto& job : jobs) {
    const bool shape = job[0] == '\x01';
    const std::string file = shape ? "--implicit" : job;
    try {
      Report r = shape ? massprops::app::ComputeImplicit(job.substr(1), opt) : massprops::app::Compute(file, opt);
      for (const auto& w : r.warnings) std::cerr << "warning: " << file << ": " << w << "\n";
      if (opt.format == "table") text += (text.empty() ? "" : "\n") + FormatTable(r, opt);
      if (robot) text += FormatRobot(r, opt.format);
      reports.push_back(std::move(r));
    } catch (const massprops::MeshFileError& e) {  // already names the file
      ++failures;
      std::cerr << "error: " << e.what() << "\n";
    } catch (const std::exception& e) {
      ++failures;
      std::cerr << "error: " << file << ": " << e.what() << "\n";
    }
  }
  if (!reports.empty()) {
    if (opt.format == "json") text = FormatJson(reports, opt);
    if (opt.format == "csv") text = FormatCsv(reports, opt);
  }
  if (!opt.output.empty()) {
    try {
      if (!text.empty()) massprops::app::WriteFileAtomically(opt.output, text);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    }
  } else {
    std::cout << text;
  }
  return failures > 0 ? 1 : 0;
}
