// The definitions of arguments.h: the options that `massprops` and `massprops batch` share.

#include "arguments.h"

#include <cmath>
#include <map>

#include "cli.h"
#include "massprops/report/atomic_file.h"
#include "massprops/report/words.h"
#include "massprops/units.h"

namespace massprops::cli {

namespace {

// The inputs, the Monte-Carlo routes and what the solid weighs.
void AddInputArguments(CLI::App& app, Arguments& a) {
  app.add_option("files", a.files, "Mesh files");
  app.add_option("--implicit", a.implicit,
                 "Estimate a solid given in the shape syntax, e.g. 'torus(R=1, r=0.25)' "
                 "(Monte Carlo / QMC, with error bars; docs/cli.md ('Monte Carlo: implicit solids'))");
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
}

// The output format and frame.
void AddFormatArguments(CLI::App& app, Arguments& a) {
  app.add_option("--format", a.format, "Output format")
      ->check(CLI::IsMember({"table", "json", "csv", "urdf", "sdf", "mjcf"}))
      ->capture_default_str();
  app.add_option("--frame", a.frame,
                 "Also report the inertia about the file's origin (origin), or only about the "
                 "center of mass (com)")
      ->check(CLI::IsMember({"com", "origin"}))
      ->capture_default_str();
}

// The reference point and axes, the report's units.
void AddReportArguments(CLI::App& app, Arguments& a) {
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
}

// Densities per part, and the CAD files' answer.
void AddPartArguments(CLI::App& app, Arguments& a) {
  app.add_option("--density-map", a.density_map,
                 "JSON or CSV: part name or glob pattern -> density (kg/m^3) or mass (kg); first match wins; "
                 "implies --parts");
  app.add_flag("--brep", a.brep,
               "CAD files: the exact B-rep's integrals as the result; the default now, kept so that old commands "
               "run (see --tessellated)");
  app.add_flag("--tessellated", a.tessellated,
               "CAD files: the tessellation's numbers as the result, the exact B-rep's beside them (the default "
               "is the other way round)")
      ->excludes("--brep");
}

}  // namespace

void AddArguments(CLI::App& app, Arguments& a) {
  AddInputArguments(app, a);
  a.load = std::make_unique<app::LoadFlags>(
      app, std::initializer_list<std::string_view>{"density", "mass", "unit", "path", "threads", "allow_open", "repair",
                                                   "check_self_intersections", "hull", "exact", "full_check", "reader",
                                                   "parts", "deflection", "relative_deflection", "angular_deflection",
                                                   "interference_pairs"});
  AddFormatArguments(app, a);
  AddReportArguments(app, a);
  AddPartArguments(app, a);
  app.add_flag("-q,--quiet", a.quiet, "No progress line on stderr");
  app.add_option("-o,--output", a.output, "Write the output to this file (whole or not at all)");
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

LoadOptions ToLoadOptions(const Arguments& a, const CLI::App& app) {
  LoadOptions o = a.load->Options();
  if (a.shell) {
    o.model = ShellModel{a.area_density};
  } else if (a.wall > 0) {
    o.model = WallModel{a.wall};
  } else if (a.winding_number) {
    o.model =
        WindingNumberModel{WindingNumberSampling(Sampling(a), app.count("--samples") + app.count("--tolerance") > 0)};
  }
  o.parts = o.parts || !a.density_map.empty();
  o.brep = !a.tessellated;
  return o;
}

std::optional<std::string> CheckArguments(const Arguments& a, const CLI::App& app) {
  if (!std::isfinite(a.area_density) || !std::isfinite(a.wall)) return "--area-density and --wall must be finite";
  // The library's rules (FindOptionConflict), in the command line's words; a shell without its
  // density is said first, as the other flags' rules assume one.
  const auto conflict = FindOptionConflict(ToLoadOptions(a, app));
  const auto worded = [](OptionConflict c) { return report::WordedConflict(c, report::FrontEnd::kCommandLine); };
  if (conflict == OptionConflict::kShellNeedsDensity) return worded(*conflict);
  if (a.shell && app.count("--density") > 0) return "--shell takes --area-density (kg/m^2), not --density";
  if (a.files.empty() && a.implicit.empty()) return "give mesh files, or --implicit SHAPE (see --help)";
  const bool sampling_flags = app.count("--mc") + app.count("--qmc") + app.count("--samples") +
                                  app.count("--randomizations") + app.count("--seed") + app.count("--tolerance") >
                              0;
  if (sampling_flags && a.implicit.empty() && !a.winding_number) {
    return "--mc/--qmc/--samples/--randomizations/--seed/--tolerance belong to --implicit or "
           "--winding-number (exact integration needs none)";
  }
  if (a.winding_number && (a.shell || a.wall > 0)) return "--winding-number does not combine with --shell or --wall";
  if (!a.implicit.empty() && (a.shell || a.wall > 0)) {
    return "--shell and --wall describe a mesh's surface; an --implicit shape is a solid and takes neither";
  }
  if (conflict) return worded(*conflict);
  if (a.files.empty()) {  // only --implicit: the options about mesh files would be ignored
    for (const char* flag :
         {"--parts", "--density-map", "--repair", "--allow-open", "--full-check", "--check-self-intersections",
          "--path", "--reader", "--winding-number", "--hull", "--exact", "--deflection", "--relative-deflection",
          "--angular-deflection", "--brep", "--tessellated", "--interference-pairs"}) {
      if (app.count(flag) > 0)
        return std::string(flag) + " applies to mesh files; --implicit shapes take no such option";
    }
  }
  if (!a.output.empty()) {
    try {
      report::CheckOutputPath(a.output, a.files);
    } catch (const std::exception& e) {
      return std::string("-o ") + e.what();
    }
  }
  return std::nullopt;
}

}  // namespace massprops::cli
