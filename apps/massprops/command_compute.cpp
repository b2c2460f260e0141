// massprops FILE... [options]: the mass properties of each file (and of an --implicit shape),
// printed as a table, JSON, CSV or a robot file's <inertial>. This file only maps the command line
// onto the library's options and prints what massprops::report makes of the results.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "arguments.h"
#include "cli.h"
#include "commands.h"
#include "massprops/implicit.h"
#include "massprops/io/mesh_io.h"
#include "massprops/parallel.h"
#include "massprops/report/atomic_file.h"
#include "massprops/report/density_map.h"
#include "massprops/report/format.h"
#include "massprops/report/picture.h"
#include "massprops/version.h"
#include "progress.h"

namespace massprops::cli {
using namespace massprops::report;  // the formats this command prints

namespace {

// Why --picture cannot be drawn (nothing: it can).
std::optional<std::string> PictureProblem(const std::string& picture, const Arguments& a) {
  if (picture.empty()) return std::nullopt;
  if (a.files.size() + (a.implicit.empty() ? 0 : 1) != 1) {
    return "--picture draws one input; for several, massprops batch ... --pictures DIR";
  }
  try {
    report::PictureFormatOf(picture);
    report::CheckOutputPath(picture, a.files);
    if (report::PictureFormatOf(picture) == report::PictureFormat::kPng && !report::CanRasterize()) {
      return "--picture: cannot draw PNG: " + report::RasterProblem();
    }
  } catch (const std::exception& e) {
    return std::string("--picture: ") + e.what();
  }
  return std::nullopt;
}

// --about, --axes, --axes-euler as the frame the results are reported in (in each file's unit,
// the one stated or the one the file declares: scaled per result). @throws std::invalid_argument
// naming the flag.
std::optional<ReferenceFrame> ReferenceOf(const Arguments& a) {
  if (a.about.empty() && a.axes.empty() && a.axes_euler.empty()) return std::nullopt;
  ReferenceFrame f;
  for (double v : a.about) {
    if (!std::isfinite(v)) throw std::invalid_argument("--about needs three finite numbers");
  }
  for (double v : a.axes) {
    if (!std::isfinite(v)) throw std::invalid_argument("--axes needs nine finite numbers");
  }
  for (double v : a.axes_euler) {
    if (!std::isfinite(v)) throw std::invalid_argument("--axes-euler needs three finite angles");
  }
  if (!a.about.empty()) f.point = Vector3(a.about[0], a.about[1], a.about[2]);
  try {
    if (!a.axes.empty()) {
      Matrix3 r;
      r << a.axes[0], a.axes[1], a.axes[2], a.axes[3], a.axes[4], a.axes[5], a.axes[6], a.axes[7], a.axes[8];
      f.axes = RequireRotation(r);
    }
    if (!a.axes_euler.empty()) {
      const double deg = kPi / 180;
      f.axes = RotationFromEulerZYX(a.axes_euler[0] * deg, a.axes_euler[1] * deg, a.axes_euler[2] * deg);
    }
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("--axes: ") + e.what());
  }
  return f;
}

// How the results are printed. @throws std::invalid_argument naming the flag.
report::FormatOptions FormatOf(const Arguments& a) {
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
  if (!a.output_units.empty()) {
    try {
      format.units = ParseReportUnits(a.output_units);
    } catch (const std::exception& e) {
      throw std::invalid_argument(std::string("--output-units: ") + e.what());
    }
  }
  format.reference = ReferenceOf(a);
  return format;
}

bool IsRobotFormat(report::Format f) {
  return f == report::Format::kUrdf || f == report::Format::kSdf || f == report::Format::kMjcf;
}

// One input's outcome: its result, or its error (one line, worded for the command line).
struct Outcome {
  std::optional<SolidResult> result;
  std::string error;
};

template <typename Solve>
Outcome Compute(const std::string& name, bool show_progress, const Solve& solve) {
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
}

// What the formats read of a result's surface is its face sizes (the JSON counts triangles);
// the vertices and corners are let go once a file is computed, unless a picture is drawn: a
// dataset's thousand files are held until the output is written, in order.
void KeepWhatTheFormatsRead(SolidResult& r) {
  r.loaded.mesh.V = VertexMatrix();
  std::vector<std::int32_t>().swap(r.loaded.mesh.indices);
}

// Every input's outcome, in the order of the inputs. Several files are computed side by side, one
// per thread, when the library says they may be (a dataset's small files gain the cores a single
// file's stages would use); no progress line then: the lines would interleave.
std::vector<std::pair<std::string, Outcome>> ComputeAll(const Arguments& a, const LoadOptions& options,
                                                        bool keep_surfaces) {
  auto load = [&](const std::string& file, bool show_progress) {
    Outcome out = Compute(file, show_progress, [&](const ProgressCallback& progress) {
      LoadOptions o = options;
      o.progress = progress;
      return LoadSolid(file, o);
    });
    if (out.result && !keep_surfaces) KeepWhatTheFormatsRead(*out.result);
    return out;
  };
  std::vector<std::pair<std::string, Outcome>> out;
  if (a.files.size() > 1 && LoadsSideBySide(a.files, options)) {
    std::vector<Outcome> outcomes(a.files.size());
    massprops::ParallelForBlocks(static_cast<std::int64_t>(a.files.size()), options.num_threads, [&](std::int64_t i) {
      outcomes[static_cast<std::size_t>(i)] = load(a.files[static_cast<std::size_t>(i)], false);
    });
    for (std::size_t i = 0; i < a.files.size(); ++i) out.emplace_back(a.files[i], std::move(outcomes[i]));
  } else {
    for (const std::string& file : a.files) out.emplace_back(file, load(file, !a.quiet));
  }
  if (!a.implicit.empty()) {
    out.emplace_back("--implicit", Compute("--implicit", !a.quiet, [&](const ProgressCallback& progress) {
                       ImplicitOptions o;
                       o.unit = options.unit;
                       o.unit_stated = options.unit_stated;
                       o.mass = options.mass;
                       o.sampling = Sampling(a);
                       o.num_threads = options.num_threads;
                       o.progress = progress;
                       return EstimateImplicit(*implicit::ParseShape(a.implicit, ReadSdfGridFile), o);
                     }));
  }
  return out;
}

// The one result drawn (an implicit solid has no mesh: its surface drawn by marching tetrahedra).
void DrawPicture(const std::string& picture, const Arguments& a, const SolidResult& result,
                 const report::FormatOptions& format) {
  report::PictureOptions p;
  p.units = format.units;
  if (a.files.empty()) {
    SolidResult drawn = result;
    const ImplicitPtr shape = implicit::ParseShape(a.implicit, ReadSdfGridFile);
    constexpr int kResolution = 96;  // cells along the longest side
    drawn.loaded.mesh = ToPolygonMesh(implicit::Polygonize(*shape, kResolution));
    p.surface_tolerance = shape->Bounds().sizes().maxCoeff() / kResolution * MetresPerUnit(drawn.unit);
    report::WritePicture(picture, drawn, p);
  } else {
    report::WritePicture(picture, result, p);
  }
}

}  // namespace

int ComputeMain(int argc, char** argv) {
  CLI::App app{
      "massprops: exact mass properties of the solids that mesh files bound.\n"
      "Reads OBJ, STL, PLY, OFF (own parsers) and other formats through assimp.\n"
      "Subcommands: massprops batch (DIR | MANIFEST) -o OUT.jsonl; massprops merge OUT SHARD...; "
      "massprops validate; massprops fill ROBOT -o OUT"};
  app.set_version_flag("--version", std::string("massprops ") + kVersion);
  Arguments a;
  AddArguments(app, a);
  std::string picture;
  app.add_option("--picture", picture,
                 "Draw the result into this picture (.svg or .png, by the extension): four views, the center of "
                 "mass, the principal axes, the equivalent-inertia ellipsoid, the bounding box; one input");
  if (const int status = app::ParseArguments(app, argc, argv); status >= 0) return status;
  auto bad = [](const std::string& what) {
    massprops::app::PrintError(what);
    return app::kBadArguments;
  };
  if (const auto error = CheckArguments(a, app)) return bad(*error);
  if (a.brep) {
    std::cerr << "note: --brep is the default now (CAD solids are given by their exact B-rep, the tessellation "
                 "beside it as the check); it changes nothing, and --tessellated gives the mesh's numbers\n";
  }
  if (const auto problem = PictureProblem(picture, a)) return bad(*problem);
  report::FormatOptions format;
  LoadOptions options = ToLoadOptions(a, app);
  if (!picture.empty()) options.full_check = true;  // the streamed STL pass keeps no surface to draw
  try {
    if (!a.density_map.empty()) options.part_masses = report::ReadDensityMap(a.density_map);
    format = FormatOf(a);
  } catch (const std::exception& e) {
    return bad(e.what());
  }
  const bool robot = IsRobotFormat(format.format);
  if (robot && (!a.output_units.empty() || format.reference)) {
    return bad(
        "URDF, SDF and MJCF give the inertia about the center of mass in SI; --output-units, --about and "
        "--axes are for the table, JSON and CSV");
  }
  // Messages and results in the order of the inputs, whatever order they were computed in.
  int failures = 0;
  std::vector<SolidResult> results;
  std::string text;
  for (auto& [name, o] : ComputeAll(a, options, !picture.empty())) {
    if (!o.result) {
      ++failures;
      massprops::app::PrintError(o.error);
      continue;
    }
    const SolidResult& r = *o.result;
    for (const Finding& f : r.findings) {
      std::cerr << "warning: " << massprops::app::OneLine(name) << ": " << Worded(f.message, report::CliVocabulary())
                << "\n";
    }
    if (format.format == report::Format::kTable) text += (text.empty() ? "" : "\n") + FormatTable(r, format);
    if (robot) text += FormatRobot(r, format.format);
    results.push_back(std::move(*o.result));
  }
  if (format.format == report::Format::kJson && (!results.empty() || format.json_array)) {
    text = FormatJson(results, format);  // several inputs: an array, even if some (or all) failed
  }
  if (!results.empty() && format.format == report::Format::kCsv) text = FormatCsv(results, format);
  if (!picture.empty() && !results.empty()) {
    try {
      DrawPicture(picture, a, results.front(), format);
    } catch (const std::exception& e) {
      massprops::app::PrintError(results.front().source + ": --picture: " + e.what());
      return 1;
    }
  }
  if (!a.output.empty()) {
    try {
      if (!text.empty()) report::WriteFileAtomically(a.output, text);
    } catch (const std::exception& e) {
      massprops::app::PrintError(e.what());
      return 1;
    }
  } else {
    std::cout << text;
  }
  return failures > 0 ? 1 : 0;
}

}  // namespace massprops::cli
