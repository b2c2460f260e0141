// massprops.dynamics.load_scene: a scene file (or a robot file, as rbsim takes one) built by the
// scene library (scene/simulation.h) into a ContactWorld ready to step — the same bodies, joints,
// robots (placed as rbsim places them), forces and contact as `rbsim PATH`.

#include <cstdint>
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

// A scene as load_scene built it: the world ready to step and what rbsim runs it for.
struct LoadedScene {
  py::object world;  // the ContactWorld
  double dt = 0, duration = 0;
  std::int64_t steps = 0;
  std::vector<std::string> bodies, warnings;
};

LoadedScene LoadScene(const std::string& path, int threads, const py::dict& packages) {
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
  LoadedScene out;
  for (const scene::SimBody& b : sim->bodies) out.bodies.push_back(b.name);
  out.dt = sim->scene.dt;
  out.duration = sim->scene.duration;
  out.steps = scene::StepCount(sim->scene);
  out.warnings = std::move(warnings);
  out.world = py::cast(std::move(sim->physics));
  return out;
}

}  // namespace

void BindScenes(py::module_& dyn) {
  py::class_<LoadedScene>(dyn, "Scene", PlainType(),
                          "A scene file or robot file built as `rbsim PATH` builds it: its world, step and length")
      .def_readonly("world", &LoadedScene::world, "the ContactWorld, at t = 0")
      .def_readonly("dt", &LoadedScene::dt, "the scene's step, s")
      .def_readonly("duration", &LoadedScene::duration, "the scene's simulated time, s")
      .def_readonly("steps", &LoadedScene::steps, "steps rbsim takes: ceil(duration / dt)")
      .def_readonly("bodies", &LoadedScene::bodies, "the bodies' names, in the world's order")
      .def_readonly("warnings", &LoadedScene::warnings, "what building it found, one line each")
      .def(
          "run",
          [](LoadedScene& s) {
            s.world.attr("step")(s.dt, py::arg("steps") = s.steps);
            return s.world;
          },
          "Steps the world through the scene's duration as rbsim does (the same bits); returns the world")
      .def(
          "__getitem__",
          [](const LoadedScene& s, const std::string& key) -> py::object {
            if (key == "world") return s.world;
            if (key == "dt") return py::cast(s.dt);
            if (key == "duration") return py::cast(s.duration);
            if (key == "steps") return py::cast(s.steps);
            if (key == "bodies") return py::cast(s.bodies);
            if (key == "warnings") return py::cast(s.warnings);
            throw py::key_error(key);
          },
          "s['world'] and the other keys of the dict load_scene returned before 0.6 (use the attributes)");
  dyn.def("load_scene", &LoadScene, py::arg("path"), py::arg("threads") = 1, py::arg("packages") = py::dict(),
          "A scene file (JSON) or a robot file (URDF, SDFormat, MJCF) built as `rbsim PATH` builds it: a Scene "
          "(world, dt, duration, steps, bodies, warnings); scene.run() then gives rbsim's trajectory bit for bit. "
          "ValueError names the file and the field.");
}

}  // namespace massprops_python
