// massprops batch (DIR | MANIFEST) -o OUT.jsonl [batch options] [the options of massprops]: every
// mesh file of a folder or manifest in child processes (runs of files; a crash ends only its
// file), one JSON line each (batch.cpp runs it).

#include <filesystem>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "arguments.h"
#include "batch.h"
#include "cli.h"
#include "commands.h"
#include "massprops/report/atomic_file.h"
#include "massprops/report/density_map.h"
#include "massprops/report/picture.h"
#include "massprops/version.h"

namespace massprops::cli {

int BatchMain(int argc, char** argv) {
  CLI::App app{
      "massprops batch: every mesh file of a folder or a manifest, in child processes that a crash or "
      "hang of one file does not take down, one JSON line each in the output (docs/datasets.md)"};
  app.set_version_flag("--version", std::string("massprops ") + kVersion);
  Arguments a;
  BatchOptions b;
  std::string shard;
  app.add_option("--jobs", b.jobs, "Child processes computing files at a time (0 = one per core)")
      ->check(app::NonNegative());
  app.add_option("--shard", shard, "i/n: only the files whose index in sorted order is i mod n (job arrays)");
  app.add_flag("--resume", b.resume, "Go on from the records already in the output (a torn last line is dropped)");
  app.add_option("--timeout", b.timeout_seconds, "Seconds a file may take before it is stopped (a timeout record)")
      ->check(app::Positive())
      ->capture_default_str();
  app.add_flag("--summary", b.summary_json, "Print the summary as JSON on stdout");
  std::string picture_format = "svg";
  app.add_option("--pictures", b.pictures,
                 "Draw each file's result into this folder (as massprops --picture): STEM.svg, or STEM-INDEX.svg "
                 "where stems repeat; each record names its picture");
  app.add_option("--picture-format", picture_format, "Pictures as svg or png")->check(CLI::IsMember({"svg", "png"}));
  AddArguments(app, a);
  if (const int status = app::ParseArguments(app, argc, argv); status >= 0) return status;
  auto bad = [](const std::string& what) {
    massprops::app::PrintError(what);
    return app::kBadArguments;
  };
  if (const auto error = CheckArguments(a, app)) return bad(*error);
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
  if (!b.pictures.empty()) {
    if (picture_format == "png" && !report::CanRasterize())
      return bad("--picture-format png: cannot draw PNG: " + report::RasterProblem());
    std::error_code ec;
    if (std::filesystem::exists(b.pictures, ec) && !std::filesystem::is_directory(b.pictures, ec)) {
      return bad("--pictures: '" + b.pictures + "' exists and is not a folder");
    }
    b.picture_extension = "." + picture_format;
  }
  b.input = a.files[0];
  b.output = a.output;
  b.quiet = a.quiet;
  b.threads_given = app.count("--threads") > 0;
  b.load = ToLoadOptions(a, app);
  if (!b.pictures.empty()) b.load.full_check = true;  // the streamed STL pass keeps no surface to draw
  if (!a.density_map.empty()) {
    try {
      b.load.part_masses = report::ReadDensityMap(a.density_map);
    } catch (const std::exception& e) {
      return bad(e.what());
    }
  }
  return cli::RunBatch(b);
}

}  // namespace massprops::cli
