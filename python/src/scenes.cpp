// massprops.dynamics.load_scene: a scene file (or a robot file, as rbsim takes one) built by the
// scene library (scene/simulation.h) into a ContactWorld ready to step — the same bodies, joints,
// robots (placed as rbsim places them), forces and contact as `rbsim PATH`.

#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "scene/scene.h"
#include "scene/simulation.h"

namespace py = pybind11;

namespace massprops_python {
namespace {

// A .json file is a scene; any other regular file a robot description, on a ground, as rbsim runs one.
scene::Scene SceneOf(const std::string& path, const scene::RobotFileOptions& robot,
                     std::vector<std::string>& warnings) {
  if (scene::IsRobotFile(path)) return scene::RobotScene(path, robot);
  if (!robot.packages.empty()) {
    throw std::invalid_argument("packages: for a robot file; a scene's robot entry takes \"packages\"");
  }
  return scene::LoadScene(path, warnings);
}

py::dict LoadScene(const std::string& path, int threads, const py::dict& packages) {
  scene::RobotFileOptions robot;
  robot.packages = PackagesOf(packages);
  std::vector<std::string> warnings;
  std::optional<scene::Simulation> sim;
  std::string message;
  {
    py::gil_scoped_release release;
    try {
      const scene::Scene s = SceneOf(path, robot, warnings);
      sim.emplace(scene::BuildSimulation(s, warnings, threads));
    } catch (const std::exception& e) {
      message = e.what();
    }
  }
  if (!message.empty()) throw py::value_error(message);
  py::list names;
  for (const scene::SimBody& b : sim->bodies) names.append(b.name);
  py::dict out;
  out["dt"] = sim->scene.dt;
  out["duration"] = sim->scene.duration;
  out["steps"] = scene::StepCount(sim->scene);
  out["bodies"] = names;
  out["warnings"] = warnings;
  out["world"] = py::cast(std::move(sim->physics));
  return out;
}

}  // namespace

void BindScenes(py::module_& dyn) {
  dyn.def("load_scene", &LoadScene, py::arg("path"), py::arg("threads") = 1, py::arg("packages") = py::dict(),
          "A scene file (JSON) or a robot file (URDF, SDFormat, MJCF) built as `rbsim PATH` builds it: "
          "{'world': ContactWorld, 'dt', 'duration', 'steps', 'bodies' (names, in the world's order), "
          "'warnings'}. world.step(dt, steps=steps) then gives rbsim's trajectory bit for bit. "
          "ValueError names the file and the field.");
}

}  // namespace massprops_python
