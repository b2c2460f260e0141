// massprops.dynamics.drop: parts dropped until they rest (scene/drop.h), as `rbsim PART...` drops
// them — the same scene, the same bits — with the resting poses as typed objects.

#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "massprops/io/load_schema.h"
#include "scene/drop.h"

namespace py = pybind11;

namespace massprops_python {
namespace {

// The result of a drop: the resting poses, when they came to rest, and the world as it ended.
struct DropResult {
  std::vector<scene::RestingPose> poses;
  std::optional<double> rest_time;
  double end_time = 0;
  double energy_lost = 0;
  double max_penetration = 0;
  std::vector<std::string> warnings;
  py::object world;
};

// orientation: "file", "upright", "random", or (axis, degrees).
void SetOrientation(const py::object& value, scene::DropOptions& o) {
  if (py::isinstance<py::str>(value)) {
    const std::string name = py::cast<std::string>(value);
    if (name == "file" || name == "upright") return;
    if (name == "random") {
      o.orientation = scene::DropOrientation::kRandom;
      return;
    }
    throw py::value_error("orientation must be 'file', 'upright', 'random' or (axis, degrees), not '" + name + "'");
  }
  const auto pair = py::cast<std::pair<std::array<double, 3>, double>>(value);
  o.axis = massprops::Vector3(pair.first[0], pair.first[1], pair.first[2]);
  o.angle = pair.second * massprops::kPi / 180.0;
  if (!(o.axis.norm() > 0) || !o.axis.allFinite() || !std::isfinite(o.angle)) {
    throw py::value_error("orientation: the axis must be finite and non-zero, the angle finite");
  }
  o.orientation = scene::DropOrientation::kAxisAngle;
}

// friction: μ (both coefficients) or (μs, μk); restitution e: checked as every material is.
dynamics::Material MaterialOf(const py::object& friction, double restitution) {
  dynamics::Material m;
  if (!friction.is_none()) {
    if (py::isinstance<py::float_>(friction) || py::isinstance<py::int_>(friction)) {
      m.static_friction = m.kinetic_friction = py::cast<double>(friction);
    } else {
      const auto pair = py::cast<std::pair<double, double>>(friction);
      m.static_friction = pair.first;
      m.kinetic_friction = pair.second;
    }
  }
  m.restitution = restitution;
  if (const auto fault = dynamics::CheckMaterial(m)) throw py::value_error(fault->field + " " + fault->problem);
  return m;
}

DropResult Drop(const std::vector<std::string>& paths, int count, bool separate, const std::optional<std::string>& on,
                double height, const py::object& orientation, std::uint64_t seed, const py::object& friction,
                double restitution, double rest_speed, double dt, double duration, int threads,
                const py::kwargs& options) {
  scene::DropOptions o;
  o.files = paths;
  o.count = count;
  o.separate = separate;
  o.on = on.value_or("");
  o.height = height;
  o.seed = seed;
  SetOrientation(orientation, o);
  o.material = MaterialOf(friction, restitution);
  if (!(rest_speed > 0)) throw py::value_error("rest_speed must be > 0");
  o.rest.speed = rest_speed;
  o.dt = dt;
  o.duration = duration;
  o.load = LoadOptionsFrom(options);
  if (const auto problem =
          massprops::SetLoadOption(o.load, *massprops::FindLoadOption("threads"), static_cast<std::int64_t>(threads))) {
    throw py::value_error("threads " + *problem);
  }
  o.words = &PythonWords();
  DropResult result;
  std::optional<scene::Simulation> sim;
  RunWithoutGil([&] {
    const scene::Scene s = scene::DropScene(o, result.warnings);
    sim.emplace(scene::BuildSimulation(s, result.warnings, threads));
    const scene::RunStats stats = scene::Run(*sim, [](const dynamics::World&, const dynamics::Diagnostics&) {});
    result.poses = scene::RestingPoses(*sim);
    result.rest_time = stats.rest_time;
    result.end_time = sim->world().time();
    result.energy_lost = stats.start.total_energy - stats.end.total_energy;
    result.max_penetration = stats.max_penetration;
  });
  result.world = py::cast(std::move(sim->physics));
  return result;
}

}  // namespace

void BindDrop(py::module_& dyn) {
  py::class_<scene::RestingPose>(dyn, "RestingPose", PlainType(), "How a dropped part came to rest.")
      .def_readonly("name", &scene::RestingPose::name, "the body's name: the file's stem, #k for copies")
      .def_property_readonly(
          "down_in_part",
          [](const scene::RestingPose& p) {
            return std::array<double, 3>{p.down_in_part.x(), p.down_in_part.y(), p.down_in_part.z()};
          },
          "Gravity's direction in the part's own (file) axes: the outward normal of the face it rests on")
      .def_readonly("com_height", &scene::RestingPose::com_height, "m, the center of mass above the ground plane")
      .def_property_readonly(
          "tilt_deg", [](const scene::RestingPose& p) { return p.tilt * 180 / massprops::kPi; },
          "degrees between the part's +z and the world's +z")
      .def_readonly("support", &scene::RestingPose::support, "'face', 'edge' or 'corner': what touches")
      .def_readonly("balanced", &scene::RestingPose::balanced,
                    "on an edge or corner with the center of mass right above it: an unstable equilibrium")
      .def_readonly("speed", &scene::RestingPose::speed, "m/s, its fastest point at the end")
      .def("__repr__", [](const scene::RestingPose& p) {
        return "RestingPose(" + p.name + ", " + p.support + (p.balanced ? " (balanced)" : "") +
               ", com_height=" + std::to_string(p.com_height) + ")";
      });
  py::class_<DropResult>(dyn, "DropResult", PlainType(), "The parts at rest (or at the duration's end), and the world.")
      .def_readonly("poses", &DropResult::poses, "a RestingPose per part, in the order dropped")
      .def_readonly("rest_time", &DropResult::rest_time, "s, when every part came to rest; None: not at rest")
      .def_readonly("end_time", &DropResult::end_time, "s, when the run ended (at rest plus the hold, or the cap)")
      .def_readonly("energy_lost", &DropResult::energy_lost, "J")
      .def_readonly("max_penetration", &DropResult::max_penetration, "m, the deepest overlap of the run")
      .def_readonly("warnings", &DropResult::warnings, "what loading the parts found, one line each")
      .def_readonly("world", &DropResult::world, "the ContactWorld as the run ended");
  dyn.def("drop", &Drop, py::arg("paths"), py::kw_only(), py::arg("count") = 1, py::arg("separate") = false,
          py::arg("on") = py::none(), py::arg("height") = 0.01, py::arg("orientation") = "file", py::arg("seed") = 1,
          py::arg("friction") = py::none(), py::arg("restitution") = 0.0, py::arg("rest_speed") = 0.005,
          py::arg("dt") = 1e-3, py::arg("duration") = 10.0, py::arg("threads") = 1,
          "Mesh or CAD parts dropped onto the ground (or `on` a fixed part: a table, a bin) until they rest, as "
          "`rbsim PART...` drops them (the same bits): count copies each, released `height` m above, turned as "
          "`orientation` says ('file', 'random' from `seed`, or (axis, degrees)). Load options (unit, density, "
          "mass, repair, allow_open, parts) as massprops.load; separate=True with parts=True: each part of an "
          "assembly its own body, where the file places it. Returns a DropResult (docs/scenes.md ('The `rbsim` "
          "command')).");
}

}  // namespace massprops_python
