// massprops validate (commands.h): the closed-form solids tessellated ever finer, their errors
// against the closed forms.

#include "commands.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "massprops/report/atomic_file.h"
#include "massprops/text.h"
#include "massprops/validation.h"

namespace massprops::cli {
using namespace massprops::report;  // the formats this command prints
namespace {

std::string Err(double e) { return FormatDouble(e, "%9.2e"); }
std::string Order(double o) { return std::isfinite(o) ? FormatDouble(o, "%5.2f") : "    -"; }

std::string Table(const std::vector<ConvergenceRow>& rows) {
  std::ostringstream out;
  out << "closed-form solids, tessellated and integrated; errors against the closed forms\n"
         "(relative volume, center of mass / size, relative inertia norm); order = log2 of the error's\n"
         "ratio to the previous resolution's: 2 for inscribed tessellations of smooth solids, and the\n"
         "polyhedra (resolution -) are exact to rounding. 'far': turned and moved 10^5 sizes from the\n"
         "origin, where the coordinates themselves round to ~1e-11 of the size\n\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-14s %4s %9s  %-9s  %-6s  %9s %9s %9s  %5s %5s\n", "solid", "n", "triangles",
                "path", "where", "volume", "com", "inertia", "ordV", "ordI");
  out << line;
  for (const ConvergenceRow& r : rows) {
    std::snprintf(line, sizeof line, "%-14s %4s %9lld  %-9s  %-6s  %s %s %s  %s %s\n", r.solid.c_str(),
                  r.resolution > 0 ? std::to_string(r.resolution).c_str() : "-", r.triangles, r.path.c_str(),
                  r.far ? "far" : "origin", Err(r.volume_error).c_str(), Err(r.com_error).c_str(),
                  Err(r.inertia_error).c_str(), Order(r.volume_order).c_str(), Order(r.inertia_order).c_str());
    out << line;
  }
  return out.str();
}

std::string Json(const std::vector<ConvergenceRow>& rows) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
  for (const ConvergenceRow& r : rows) {
    all.push_back({{"solid", r.solid},
                   {"resolution", r.resolution > 0 ? nlohmann::ordered_json(r.resolution) : nullptr},
                   {"triangles", r.triangles},
                   {"path", r.path},
                   {"placement", r.far ? "far" : "origin"},
                   {"volume_error", r.volume_error},
                   {"com_error", r.com_error},
                   {"inertia_error", r.inertia_error},
                   {"volume_order", num(r.volume_order)},
                   {"inertia_order", num(r.inertia_order)}});
  }
  return all.dump(2) + "\n";
}

// A log-log plot of the inertia error against the triangle count (smooth solids, at the origin,
// signed tetrahedra), with the slope of second order, drawn by gnuplot into a PNG.
void Plot(const std::vector<ConvergenceRow>& rows, const std::string& path) {
  const std::string tmp = path + ".tmp.png";
  std::ostringstream script;
  script << "set terminal pngcairo size 900,650\nset output '" << tmp << "'\nset logscale xy\nset grid\n"
         << "set xlabel 'triangles'\nset ylabel 'relative error of the inertia tensor'\nset key outside right\n"
         << "set title 'massprops validate: convergence to the closed forms'\nplot ";
  std::vector<std::string> solids;
  for (const ConvergenceRow& r : rows) {
    if (r.resolution > 0 && (solids.empty() || solids.back() != r.solid)) solids.push_back(r.solid);
  }
  std::ostringstream data;
  double t0 = 0, e0 = 0;
  for (std::size_t k = 0; k < solids.size(); ++k) {
    script << (k ? ", " : "") << "'-' with linespoints title '" << solids[k] << "'";
    for (const ConvergenceRow& r : rows) {
      if (r.solid != solids[k] || r.far || r.path != "triangles") continue;
      data << r.triangles << " " << r.inertia_error << "\n";
      if (t0 == 0) t0 = static_cast<double>(r.triangles), e0 = r.inertia_error;
    }
    data << "e\n";
  }
  if (solids.empty()) throw std::runtime_error("--plot: no smooth solid to plot");
  script << ", " << e0 << " * (" << t0 << " / x) with lines dashtype 2 lc 'black' title 'slope of order 2'\n"
         << data.str();
  std::FILE* gp = ::popen("gnuplot 2>/dev/null", "w");
  if (gp == nullptr) throw std::runtime_error("--plot: cannot run gnuplot");
  const std::string s = script.str();
  std::fwrite(s.data(), 1, s.size(), gp);
  if (::pclose(gp) != 0 || !std::filesystem::exists(tmp)) {
    std::filesystem::remove(tmp);
    throw std::runtime_error("--plot: gnuplot failed (is gnuplot with the pngcairo terminal installed?)");
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

int ValidateMain(int argc, char** argv) {
  CLI::App app{
      "massprops validate: closed-form solids tessellated at a series of resolutions and placements, "
      "integrated by both paths, against their closed forms, with the observed order of convergence"};
  std::vector<std::string> solids;
  std::vector<int> resolutions = {8, 16, 32, 64, 128};
  std::string format = "table", plot, output;
  std::string known;
  for (const std::string& s : ValidationSolids()) known += (known.empty() ? "" : ",") + s;
  app.add_option("--solids", solids, "Which solids (default all: " + known + ")")->delimiter(',');
  app.add_option("--resolutions", resolutions, "Resolutions n of the smooth solids")
      ->delimiter(',')
      ->check(CLI::Range(3, 2048))
      ->capture_default_str();
  app.add_option("--format", format, "Output format")->check(CLI::IsMember({"table", "json"}))->capture_default_str();
  app.add_option("--plot", plot, "Also draw the convergence as a PNG (gnuplot)");
  app.add_option("-o,--output", output, "Write the output to this file (whole or not at all)");
  if (const int status = app::ParseArguments(app, argc, argv); status >= 0) return status;
  try {
    if (!output.empty()) report::CheckOutputPath(output, {});
    if (!plot.empty()) report::CheckOutputPath(plot, {});
  } catch (const std::exception& e) {
    massprops::app::PrintError(e.what());
    return app::kBadArguments;
  }
  ValidationOptions options;
  options.solids = solids;
  options.resolutions = resolutions;
  std::vector<ConvergenceRow> rows;
  try {
    rows = ValidateClosedForms(options);
  } catch (const std::invalid_argument& e) {
    massprops::app::PrintError(e.what());
    return app::kBadArguments;
  }
  const std::string text = format == "json" ? Json(rows) : Table(rows);
  try {
    if (!plot.empty()) Plot(rows, plot);
    if (output.empty()) {
      std::cout << text;
    } else {
      report::WriteFileAtomically(output, text);
    }
  } catch (const std::exception& e) {
    massprops::app::PrintError(e.what());
    return 1;
  }
  return 0;
}

}  // namespace massprops::cli
