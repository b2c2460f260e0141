// MJCF's <option>: the medium (density, viscosity, wind: MuJoCo's fluid forces) is read; what the
// simulator sets otherwise (gravity, time step, integrator, disabled contact) is noted.

#include <cmath>
#include <string>

#include "robot/robot_internal.h"

namespace massprops::robot {

void MjcfOptions(pugi::xml_node root, RobotModel& model) {
  RobotMedium medium;
  bool fluid = false;
  for (const pugi::xml_node option : FindElements(root, "option")) {
    auto number = [&](const char* name, double& out) {
      if (const pugi::xml_attribute a = option.attribute(name)) {
        out = Numbers(a.value(), 1, std::string("<option ") + name + ">")[0];
        if (!(out >= 0) || !std::isfinite(out)) {
          throw ElementError(std::string("<option ") + name + ">: must be a finite number >= 0");
        }
        fluid = true;
      }
    };
    number("density", medium.density);
    number("viscosity", medium.viscosity);
    if (const pugi::xml_attribute w = option.attribute("wind")) {
      const auto v = Numbers(w.value(), 3, "<option wind>");
      medium.wind = Vector3(v[0], v[1], v[2]);
    }
    if (const pugi::xml_attribute g = option.attribute("gravity")) {
      const auto v = Numbers(g.value(), 3, "<option gravity>");
      if (Vector3(v[0], v[1], v[2]) != Vector3(0, 0, -9.81)) {
        model.notes.push_back("<option gravity=\"" + std::string(g.value()) +
                              "\">: the simulator's gravity is used (rbsim: 9.81 m/s² down; a scene's own)");
      }
    }
    if (option.attribute("timestep")) {
      model.notes.push_back("<option timestep>: the simulator's step is used (rbsim --dt, a scene's dt)");
    }
    if (const pugi::xml_attribute f = option.child("flag").attribute("contact");
        f && std::string(f.value()) == "disable") {
      model.notes.push_back("<option><flag contact=\"disable\">: contact is simulated here");
    }
    if (option.attribute("fluidshape")) model.notes.push_back("<option fluidshape>: not read");
  }
  for (const pugi::xml_node geom : FindElements(root, "geom")) {
    if (std::string(geom.attribute("fluidshape").value()) == "ellipsoid") {
      model.notes.push_back(
          "geom fluidshape=\"ellipsoid\": MuJoCo's ellipsoid fluid model is not simulated; the "
          "inertia-box model is used for every body");
      break;
    }
  }
  if (fluid && (medium.density > 0 || medium.viscosity > 0)) model.medium = medium;
}

}  // namespace massprops::robot
