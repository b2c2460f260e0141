#pragma once
// Drops (target massprops::scene): mesh or CAD parts dropped onto the ground, or onto a static
// part (a table, a bin), and run until they rest — `rbsim part.stl` — as a scene like any other,
// which can be written out and edited (DropSceneJson). What the parts rest on is reported by
// RestingPoses.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "massprops/io/load.h"
#include "scene/scene.h"
#include "scene/simulation.h"

namespace scene {

/// How each part starts turned (about its center of mass).
enum class DropOrientation {
  kFile,       ///< as in its file
  kRandom,     ///< uniformly random, from the seed (the same seed, the same bits)
  kAxisAngle,  ///< turned by `angle` about `axis` (world axes)
};

struct DropOptions {
  std::vector<std::string> files;  ///< the parts: mesh or CAD files
  /// How every part (and `on`) is read: unit, density or mass, repair, allow_open, threads.
  massprops::LoadOptions load;
  int count = 1;  ///< copies of each part
  /// With load.parts: each part of a file (an assembly's solids, an OBJ's groups) its own body,
  /// starting where the file places it; without: a file falls as one rigid body, the parts'
  /// composition.
  bool separate = false;
  double height = 0.01;  ///< m: each part's lowest point above what it falls on
  DropOrientation orientation = DropOrientation::kFile;
  Vector3 axis = Vector3::UnitZ();  ///< kAxisAngle
  double angle = 0;                 ///< kAxisAngle, radians
  std::uint64_t seed = 1;           ///< kRandom
  std::string on;                   ///< a part to drop onto (fixed, as its file places it), or "" for the ground
  dynamics::Material material;      ///< of the parts, the ground and `on`
  double dt = 1e-3;
  double duration = 10;  ///< s: the cap; the run ends when every part is at rest
  RestRule rest;
  /// How a part that cannot be read names the options to try (nullptr: the command line's flags).
  const massprops::Vocabulary* words = nullptr;
};

/// The scene of a drop: the scenes' gravity (9.80665 m/s² along −z), a ground plane (under `on`'s lowest point when
/// there is one), each part colliding as itself (its hull when convex, its mesh otherwise), laid out
/// side by side on a grid — in layers above `on` when they do not fit on it — so that nothing
/// starts in contact, each with its lowest point `height` above the ground or `on`'s top.
/// Reads every part once (to place it). @throws SceneError naming the file and the fault.
Scene DropScene(const DropOptions& options, std::vector<std::string>& warnings);

/// The scene as a scene file says it (docs/scenes.md), indented JSON: running it gives the same
/// bits as the drop. Mesh paths are written absolute.
std::string DropSceneJson(const Scene& scene);

/// How a part rests.
struct RestingPose {
  std::string name;
  /// The direction of gravity in the part's own (file) axes: the outward normal of the face it
  /// rests on, for a part on a face.
  Vector3 down_in_part = -Vector3::UnitZ();
  double com_height = 0;  ///< m, the center of mass above the ground plane
  double tilt = 0;        ///< radians between the part's +z and the world's +z
  /// "face" (three or more corners down, not on one line), "edge" or "corner": which of its
  /// features touches, within 1e-3 of its size of its lowest point.
  std::string support;
  /// Balanced: on the ground on an edge or a corner with its center of mass right above it (within
  /// 1e-6 of its size) — an unstable equilibrium that the slightest disturbance topples (a drop
  /// symmetric about that edge lands there and, computed exactly, stays).
  bool balanced = false;
  double speed = 0;  ///< m/s, its fastest point at the end
};

/// Each body's pose as the simulation ended.
std::vector<RestingPose> RestingPoses(const Simulation& sim);

}  // namespace scene
