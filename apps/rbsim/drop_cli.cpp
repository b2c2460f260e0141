// The definitions of drop_cli.h: a drop's flags and its resting poses, as text and JSON.

#include "drop_cli.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "massprops/text.h"

namespace rbsim {
namespace {

constexpr const char* kDropFlags[] = {"--count",    "--height",      "--orientation", "--seed",       "--on",
                                      "--friction", "--restitution", "--rest-speed",  "--save-scene", "--separate"};

// "AX,AY,AZ,DEG": an axis and an angle in degrees.
bool ParseAxisAngle(const std::string& text, scene::DropOptions& o) {
  double v[4];
  char extra;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &v[3], &extra) != 4) return false;
  o.axis = massprops::Vector3(v[0], v[1], v[2]);
  o.angle = v[3] * massprops::kPi / 180.0;
  return o.axis.allFinite() && std::isfinite(o.angle) && o.axis.norm() > 0;
}

// "MU" (both coefficients) or "MU_S,MU_K".
bool ParseFriction(const std::string& text, dynamics::Material& m) {
  double a, b;
  char extra;
  const int n = std::sscanf(text.c_str(), "%lf,%lf%c", &a, &b, &extra);
  if (n == 1) b = a;
  if ((n != 1 && n != 2) || !std::isfinite(a) || !std::isfinite(b)) return false;
  m.static_friction = a;
  m.kinetic_friction = b;
  return true;
}

std::string Num(double v, const char* format) { return massprops::FormatDouble(v, format); }

// Three decimals, and no "-0.000" for what rounds to zero.
std::string Vec(const massprops::Vector3& v) {
  const auto c = [](double x) { return Num(std::abs(x) < 5e-4 ? 0.0 : x, "%+.3f"); };
  return "(" + c(v.x()) + ", " + c(v.y()) + ", " + c(v.z()) + ")";
}

}  // namespace

void DeclareDropFlags(CLI::App& app, DropFlags& f) {
  app.add_option("--count", f.count,
                 "Parts: drop N copies of each part, as a pile (spaced so nothing starts in contact)")
      ->check(CLI::Range(1, 100000));
  app.add_option("--height", f.height, "Parts: each part's lowest point this far above what it falls on at release, m")
      ->check(massprops::app::NonNegative())
      ->capture_default_str();
  app.add_option("--orientation", f.orientation,
                 "Parts: file (or upright: as the file has it, the default), random (uniform, from --seed), or "
                 "AX,AY,AZ,DEG (turned by DEG degrees about that axis)");
  app.add_option("--seed", f.seed, "Parts: seed of --orientation random (the same seed, the same bits)");
  app.add_option("--on", f.on,
                 "Parts: drop them onto this part (a table, a bin; fixed as its file places it, read as the parts "
                 "are) instead of the ground plane");
  app.add_option("--friction", f.friction,
                 "Parts: friction of the parts, the ground and --on: MU, or MU_S,MU_K (default 0.6,0.5)");
  app.add_option("--restitution", f.restitution, "Parts: restitution of the parts, the ground and --on (default 0)")
      ->check(massprops::app::InRange(0, 1));
  app.add_option("--rest-speed", f.rest_speed,
                 "Parts: at rest when every part's fastest point is slower than this, m/s, for 0.2 s")
      ->check(massprops::app::Positive())
      ->capture_default_str();
  app.add_flag("--separate", f.separate,
               "Parts: with --parts, each part of an assembly (CAD solids, OBJ groups, glTF nodes) its own body, "
               "starting where the file places it (without: the file falls as one rigid body)");
  app.add_option("--save-scene", f.save_scene,
                 "Parts: also write the drop as a scene file (JSON) to edit and run again (the same bits)");
}

bool AnyDropFlag(const CLI::App& app) {
  for (const char* flag : kDropFlags)
    if (app.count(flag) > 0) return true;
  return false;
}

std::string ToDropOptions(const DropFlags& f, const std::vector<std::string>& files, scene::DropOptions& o) {
  o.files = files;
  o.count = f.count;
  o.height = f.height;
  o.seed = f.seed;
  o.separate = f.separate;
  o.on = f.on;
  o.rest.speed = f.rest_speed;
  if (f.orientation == "file" || f.orientation == "upright") {
    o.orientation = scene::DropOrientation::kFile;
  } else if (f.orientation == "random") {
    o.orientation = scene::DropOrientation::kRandom;
  } else if (ParseAxisAngle(f.orientation, o)) {
    o.orientation = scene::DropOrientation::kAxisAngle;
  } else {
    return "--orientation: expected file, upright, random or AX,AY,AZ,DEG (a non-zero axis, degrees), got '" +
           f.orientation + "'";
  }
  if (!f.friction.empty() && !ParseFriction(f.friction, o.material)) {
    return "--friction: expected MU or MU_S,MU_K (finite numbers), got '" + f.friction + "'";
  }
  o.material.restitution = f.restitution;
  if (const auto fault = dynamics::CheckMaterial(o.material)) {
    return "--friction: the " + fault->field + " " + fault->problem;
  }
  return "";
}

std::string RestReport(const scene::Simulation& sim, const scene::RunStats& stats) {
  std::ostringstream out;
  const double lost = stats.start.total_energy - stats.end.total_energy;
  if (stats.rest_time) {
    out << "  at rest at t = " << Num(*stats.rest_time, "%.3f") << " s (every part slower than "
        << Num(sim.scene.until_rest->speed, "%g") << " m/s for " << Num(sim.scene.until_rest->hold, "%g")
        << " s); energy lost " << Num(lost, "%.6g") << " J\n";
  } else {
    out << "  not at rest after " << Num(sim.world().time(), "%g")
        << " s (the cap: give a longer --duration); energy lost so far " << Num(lost, "%.6g") << " J\n";
  }
  const std::vector<scene::RestingPose> poses = scene::RestingPoses(sim);
  int width = 20;  // the names' column
  for (const scene::RestingPose& p : poses) width = std::max(width, static_cast<int>(p.name.size()));
  out << "  " << std::string("part") + std::string(static_cast<std::size_t>(width - 3), ' ')
      << "rests on  down, in the part's axes     center of mass above ground, m  tilt, deg\n";
  for (const scene::RestingPose& p : poses) {
    char line[512];
    const std::string support = p.balanced ? p.support + " (balanced: unstable)" : p.support;
    std::snprintf(line, sizeof line, "  %-*s %-9s %-28s %-31s %.2f\n", width, p.name.c_str(), support.c_str(),
                  Vec(p.down_in_part).c_str(), Num(p.com_height, "%.9g").c_str(), p.tilt * 180 / massprops::kPi);
    out << line;
  }
  return out.str();
}

std::string RestJson(const scene::Simulation& sim, const scene::RunStats& stats) {
  nlohmann::json j;
  j["at_rest"] = stats.rest_time.has_value();
  j["rest_time"] = stats.rest_time ? nlohmann::json(*stats.rest_time) : nlohmann::json(nullptr);
  j["end_time"] = sim.world().time();
  j["energy_lost"] = stats.start.total_energy - stats.end.total_energy;
  j["max_penetration"] = stats.max_penetration;
  j["parts"] = nlohmann::json::array();
  for (const scene::RestingPose& p : scene::RestingPoses(sim)) {
    j["parts"].push_back({{"name", p.name},
                          {"support", p.support},
                          {"balanced", p.balanced},
                          {"down_in_part", {p.down_in_part.x(), p.down_in_part.y(), p.down_in_part.z()}},
                          {"com_height", p.com_height},
                          {"tilt_deg", p.tilt * 180 / massprops::kPi},
                          {"speed", p.speed}});
  }
  return j.dump(2) + "\n";
}

}  // namespace rbsim
