#pragma once
// `rbsim PART...`: the flags of a drop (scene/drop.h), and how its resting poses are shown.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "scene/drop.h"

namespace rbsim {

// The drop's flags as given.
struct DropFlags {
  int count = 1;
  double height = 0.01;
  std::string orientation = "file", on, friction, save_scene;
  double restitution = 0, rest_speed = 0.005;
  std::uint64_t seed = 1;
  bool separate = false;
};

void DeclareDropFlags(CLI::App& app, DropFlags& f);

/// The typed options of a drop of `files`, or the first problem ("--orientation: ...").
std::string ToDropOptions(const DropFlags& f, const std::vector<std::string>& files, scene::DropOptions& out);

/// Whether any drop-only flag was given (they mean nothing for a scene or a robot).
bool AnyDropFlag(const CLI::App& app);

/// The end of a drop's summary: when the parts came to rest, the energy lost, each part's pose.
std::string RestReport(const scene::Simulation& sim, const scene::RunStats& stats);
/// The same as summary.json.
std::string RestJson(const scene::Simulation& sim, const scene::RunStats& stats);

}  // namespace rbsim
