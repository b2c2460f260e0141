// massprops fill ROBOT -o OUT (commands.h): every link's inertial computed from its geometry, the
// rest of the file kept.

#include "commands.h"

#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.h"
#include "load_flags.h"
#include "massprops/report/atomic_file.h"
#include "massprops/report/density_map.h"
#include "massprops/report/format.h"
#include "massprops/robot/robot.h"
#include "massprops/text.h"

namespace massprops::cli {
using namespace massprops::report;  // the formats this command prints
namespace {

std::string Table(const std::string& file, const FillResult& r) {
  std::ostringstream out;
  std::size_t filled = 0, failed = 0, width = 4;
  for (const LinkFill& l : r.links) {
    filled += l.status == LinkStatus::kFilled;
    failed += l.status == LinkStatus::kFailed;
    width = std::max(width, l.name.size());
  }
  out << file << " (" << RobotFormatName(r.format) << "): " << r.links.size() << " links, " << filled << " filled, "
      << failed << " failed, " << r.links.size() - filled - failed << " without geometry\n";
  out << "link" << std::string(width - 4, ' ') << "  geoms    mass (kg)  center of mass (m, link frame)"
      << "         principal moments (kg m^2)\n";
  for (const LinkFill& l : r.links) {
    out << l.name << std::string(width - l.name.size(), ' ') << "  ";
    if (l.status != LinkStatus::kFilled) {
      out << "    "
          << (l.status == LinkStatus::kFailed ? "FAILED, left as it was: " + Worded(l.message, CliVocabulary())
                                              : std::string("no geometry: left as it was"))
          << "\n";
    } else {
      const Vector3& c = l.mp.center_of_mass;
      const Vector3& m = l.principal.moments;
      out << FormatDouble(l.geometries, "%5.0f") << "  " << FormatDouble(l.mp.mass, "%11.5g") << "  ["
          << FormatDouble(c[0], "% .4e") << " " << FormatDouble(c[1], "% .4e") << " " << FormatDouble(c[2], "% .4e")
          << "]  [" << FormatDouble(m[0], "%.4e") << " " << FormatDouble(m[1], "%.4e") << " "
          << FormatDouble(m[2], "%.4e") << "]\n";
    }
    for (const Advice& n : l.notes)
      out << std::string(width + 2, ' ') << "note: " << Worded(n, CliVocabulary()) << "\n";
  }
  for (const std::string& n : r.notes) out << "note: " << n << "\n";
  return out.str();
}

}  // namespace

int FillMain(int argc, char** argv) {
  CLI::App app{
      "massprops fill: a URDF, SDFormat or MJCF file with every link's <inertial> computed from its collision (or "
      "visual) geometries: meshes with their scale and pose, boxes, spheres, cylinders, capsules and ellipsoids in "
      "closed form. Everything else in the file is kept. Links that cannot be computed are named and left as they "
      "were (exit status 1)."};
  std::string input, output, density_map, from = "collision", report = "table";
  std::vector<std::string> packages;
  FillOptions o;
  bool quiet = false;
  app.add_option("robot", input, "The robot description (.urdf, .sdf, .xml)")->required();
  app.add_option("-o,--output", output, "The filled file (written whole or not at all)")->required();
  app.add_option("--density", o.density, "kg/m^3, for links without an entry in --density-map")
      ->check(CLI::PositiveNumber);
  app.add_option("--density-map", density_map,
                 "JSON or CSV: link name or glob pattern -> density (kg/m^3) or the link's mass (kg)");
  app.add_flag("--keep-mass", o.keep_mass, "Keep each link's stated mass; fill only its center of mass and inertia");
  app.add_option("--from", from, "Which geometries make the mass")->check(CLI::IsMember({"collision", "visual"}));
  app.add_option("--package", packages, "NAME=DIR: the folder of package://NAME/ (URDF) or model://NAME/ (SDF)");
  const app::LoadFlags load(app, {"repair", "allow_open", "threads"}, "The links' meshes: ");
  app.add_option("--format", report, "How the links are reported on stdout")->check(CLI::IsMember({"table", "json"}));
  app.add_flag("-q,--quiet", quiet, "No report on stdout");
  if (const int status = app::ParseArguments(app, argc, argv); status >= 0) return status;
  load.Apply(o.load);
  auto bad = [](const std::string& what) {
    massprops::app::PrintError(what);
    return app::kBadArguments;
  };
  o.from = from == "visual" ? GeometrySource::kVisual : GeometrySource::kCollision;
  for (const std::string& p : packages) {
    const auto mapping = massprops::PackageMapping(p);
    if (!mapping) return bad("--package takes NAME=DIR, got '" + p + "'");
    o.packages.push_back(*mapping);
  }
  try {
    report::CheckOutputPath(output, {input});
    if (!density_map.empty()) o.link_masses = ReadDensityMap(density_map);
  } catch (const std::exception& e) {
    return bad(e.what());
  }
  FillResult r;
  try {
    r = FillRobotDescription(input, o);
  } catch (const std::invalid_argument& e) {
    return bad(e.what());
  } catch (const std::exception& e) {
    massprops::app::PrintError(e.what());
    return 1;
  }
  try {
    report::WriteFileAtomically(output, r.document);
  } catch (const std::exception& e) {
    massprops::app::PrintError(e.what());
    return 1;
  }
  if (!quiet) std::cout << (report == "json" ? FormatFillJson(input, output, r, CliVocabulary()) : Table(input, r));
  for (const LinkFill& l : r.links) {
    if (l.status == LinkStatus::kFailed) {
      massprops::app::PrintError(input + ": link '" + l.name + "': " + Worded(l.message, CliVocabulary()) +
                                 " (left as it was)");
    }
  }
  return r.AllFilled() ? 0 : 1;
}

}  // namespace massprops::cli
