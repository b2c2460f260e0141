// libFuzzer target for the scene parser (massprops::scene): the bytes as a scene file (JSON),
// validated; when a scene of closed-form solids and implicit shapes parses, its world is built and
// stepped a few times. Any crash, sanitizer report or hang is a bug; SceneError (invalid JSON
// included) is the expected answer to bad input.

#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene.h"
#include "scene/simulation.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> warnings;
  try {
    scene::Scene scene = scene::ParseSceneText(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json",
                                               "/nonexistent", warnings);
    if (scene.bodies.size() > 8) return 0;
    for (const auto& b : scene.bodies) {
      if (std::holds_alternative<dynamics::ImplicitSource>(b.shape.source))
        return 0;  // Monte Carlo to 1e-4: too slow for a fuzzer
    }
    scene::Simulation sim = scene::BuildSimulation(scene, warnings, 1);
    for (int i = 0; i < 20; ++i) {
      if (!sim.physics.Step(scene.dt).ok) break;
    }
  } catch (const scene::SceneError&) {
  }
  return 0;
}
