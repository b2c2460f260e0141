// Uses the installed libraries the way an application would: the pipeline on a mesh of data/,
// the closed forms, a body for the dynamics. Exit 0 when every number matches its truth.
//   consumer DATA_DIR

#include <cmath>
#include <cstdio>
#include <string>

#include "dynamics/world.h"
#include "massprops/io/load.h"
#include "massprops/primitive.h"
#include "massprops/robot/robot.h"
#include "massprops/version.h"

namespace {

int failures = 0;

void Check(const char* what, double got, double want, double rel) {
  const bool ok = std::abs(got - want) <= rel * std::abs(want);
  std::printf("%s %s: %.17g (want %.17g)\n", ok ? "ok  " : "FAIL", what, got, want);
  failures += ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer DATA_DIR\n");
    return 2;
  }
  const std::string data = argv[1];
  std::printf("massprops %s\n", massprops::kVersion);

  // The T-handle: a crossbar 0.08 x 0.02 x 0.02 m on a shaft 0.02 x 0.06 x 0.02 m, in millimetres
  // read as centimetres would be wrong, so say metres; mass 1 kg given, density follows.
  massprops::LoadOptions options;
  options.unit = massprops::LengthUnit::kMetre;
  options.mass = massprops::TotalMass{1.0};
  const massprops::SolidResult r = massprops::LoadSolid(data + "/meshes/t_handle.obj", options);
  // Closed form: two boxes. Crossbar centre y = 0.01, shaft centre y = -0.03.
  const double v1 = 0.08 * 0.02 * 0.02, v2 = 0.02 * 0.06 * 0.02, v = v1 + v2;
  const double y = (v1 * 0.01 + v2 * -0.03) / v;
  const massprops::MassProperties bar =
      massprops::ClosedForm(massprops::primitive::Box{massprops::Vector3(0.08, 0.02, 0.02)}, 1.0 / v);
  const massprops::MassProperties shaft =
      massprops::ClosedForm(massprops::primitive::Box{massprops::Vector3(0.02, 0.06, 0.02)}, 1.0 / v);
  const double izz = bar.inertia_com(2, 2) + bar.mass * std::pow(0.01 - y, 2) + shaft.inertia_com(2, 2) +
                     shaft.mass * std::pow(-0.03 - y, 2);
  Check("t_handle volume", r.mp.volume, v, 1e-14);
  Check("t_handle mass", r.mp.mass, 1.0, 1e-14);
  // massprops::robot: the demo arm's base link is a 0.2 x 0.2 x 0.1 m box at 1000 kg/m^3.
  const massprops::FillResult arm = massprops::FillRobotDescription(data + "/robots/demo_arm.urdf");
  for (const massprops::LinkFill& link : arm.links) {
    if (link.name == "base_link") Check("demo_arm base_link mass", link.mp.mass, 4.0, 1e-14);
  }
  Check("t_handle com y", r.mp.center_of_mass.y(), y, 1e-13);
  Check("t_handle Izz", r.mp.inertia_com(2, 2), izz, 1e-13);
  if (!r.findings.empty()) {
    std::printf("FAIL unexpected finding: %s\n", r.findings[0].message.marked().c_str());
    ++failures;
  }

  // The glTF box goes through the assimp plugin installed beside the library (32-bit floats).
  massprops::LoadOptions gltf;
  const massprops::SolidResult box = massprops::LoadSolid(data + "/meshes/box_0.1x0.2x0.3.gltf", gltf);
  Check("gltf box mass", box.mp.mass, 6.0, 1e-6);
  Check("gltf box Ixx", box.mp.inertia_com(0, 0), 0.065, 1e-6);
  Check("gltf box com x", box.mp.center_of_mass.x(), 0.5, 1e-7);

  // A body for the dynamics: a free spin about the major axis keeps its angular velocity.
  const dynamics::PlacedBody placed = dynamics::BodyFromMassProperties(r.mp, r.principal);
  dynamics::World world;
  world.AddBody(placed.body);
  world.bodies()[0].SetAngularVelocity(placed.body.orientation * massprops::Vector3(0, 0, 3.0));
  for (int i = 0; i < 1000; ++i) world.Step(1e-3);
  Check("spin about the major axis", world.bodies()[0].BodyAngularVelocity().z(), 3.0, 1e-12);
  return failures == 0 ? 0 : 1;
}
