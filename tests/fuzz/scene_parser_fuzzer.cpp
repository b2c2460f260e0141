// libFuzzer target for rbsim's scene parser: the bytes as a scene file (JSON), validated; when a
// scene of closed-form solids and implicit shapes parses, its world is built and stepped a few
// times. Any crash, sanitizer report or hang is a bug; SceneError (and nlohmann's exceptions for
// invalid JSON, which LoadScene turns into SceneError) are the expected answers to bad input.

#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "scene.h"
#include "simulation.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const nlohmann::json::exception&) {
    return 0;
  }
  std::vector<std::string> warnings;
  try {
    rbsim::Scene scene = rbsim::ParseScene(j, "fuzz.json", "/nonexistent", warnings);
    if (scene.bodies.size() > 8) return 0;
    for (const auto& b : scene.bodies) {
      if (std::holds_alternative<dynamics::ImplicitSource>(b.shape.source))
        return 0;  // Monte Carlo to 1e-4: too slow for a fuzzer
    }
    rbsim::Simulation sim = rbsim::BuildSimulation(scene, warnings, 1);
    for (int i = 0; i < 20; ++i) {
      if (!sim.physics.Step(scene.dt).ok) break;
    }
  } catch (const rbsim::SceneError&) {
  }
  return 0;
}
