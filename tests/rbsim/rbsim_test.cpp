// rbsim's library: scene validation (every error names the field), the simulation against the
// exact torque-free flow, body-point conversions against statics, conservation in a two-body
// scene, and the outputs' structure.

#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "dynamics/free_rigid_body.h"
#include "massprops/solids.h"
#include "massprops/text.h"
#include "outputs.h"
#include "scene/scene.h"
#include "scene/simulation.h"
#include "test_utils.h"

namespace {

using massprops::Vector3;
using massprops::testing::DataPath;
using massprops::testing::NearRel;
using nlohmann::json;
using ::testing::HasSubstr;

// Parses a scene given as JSON text (meshes relative to data/scenes), returning the warnings.
scene::Scene Parse(const std::string& text, std::vector<std::string>* warnings = nullptr) {
  std::vector<std::string> w;
  scene::Scene s = scene::ParseSceneText(text, "test.json", DataPath("scenes"), w);
  if (warnings) *warnings = w;
  return s;
}

// The error message of a scene that must be refused (at parse or at load time).
std::string ErrorOf(const std::string& text) {
  try {
    std::vector<std::string> w;
    scene::Scene s = Parse(text);
    scene::BuildSimulation(s, w);
  } catch (const scene::SceneError& e) {
    return e.what();
  }
  return "(accepted)";
}

const char* kBox = R"("solid": {"type": "box", "size": [1, 2, 3]})";

std::string OneBody(const std::string& body_fields, const std::string& top = "") {
  return "{" + top + R"("bodies": [{)" + body_fields + "}]}";
}

TEST(Scene, ErrorsNameTheFieldAndTheReason) {
  struct Case {
    std::string scene, expect;
  } cases[] = {
      {OneBody(std::string(kBox) + R"(, "densty": 3)"),
       "test.json: bodies[0]: unknown key 'densty' (did you mean 'density'?)"},
      {OneBody(kBox, R"("dtt": 0.1, )"), "unknown key 'dtt' (did you mean 'dt'?)"},
      {OneBody(std::string(kBox) + R"(, "mass": -2)"), "bodies[0].mass: must be > 0, got -2"},
      {OneBody(std::string(kBox) + R"(, "density": 0)"), "bodies[0].density: must be > 0, got 0"},
      {OneBody(std::string(kBox) + R"(, "density": 1, "mass": 2)"), "give 'density' or 'mass', not both"},
      {OneBody(R"("mesh": "no_such_part.stl")"), "bodies[0].mesh: 'no_such_part.stl' not found"},
      {OneBody(R"("name": "a")"), "bodies[0]: needs a 'mesh' (file), a 'solid' or an 'implicit' shape"},
      {OneBody(std::string(kBox) + R"(, "mesh": "../meshes/spot.obj")"), "give one of 'mesh', 'solid' and 'implicit'"},
      {OneBody(R"x("implicit": "torus(R=1)")x"), "bodies[0].implicit: shape, at character 1: torus: missing r="},
      {OneBody(R"("solid": {"type": "bx", "size": [1, 1, 1]})"), "bodies[0].solid.type: 'bx' is not one of"},
      {OneBody(R"("solid": {"type": "box"})"), "bodies[0].solid.size: is required"},
      {OneBody(R"("solid": {"type": "box", "size": [1, -1, 1]})"), "bodies[0].solid.size[1]: must be positive"},
      {OneBody(R"("solid": {"type": "torus", "major_radius": 1, "minor_radius": 2})"),
       "minor_radius: must be smaller than major_radius"},
      {OneBody(kBox, R"("dt": "0.1", )"), "test.json: dt: must be a number, not a string"},
      {OneBody(kBox, R"("dt": -0.1, )"), "dt: must be positive (got -0.1)"},
      {OneBody(kBox, R"("dt": 2, "duration": 1, )"), "dt: the step (2 s) is longer than the duration (1 s)"},
      {OneBody(kBox, R"("integrator": "rk5", )"), "integrator: 'rk5' is not one of"},
      {OneBody(kBox, R"("outputs": ["csv", "gif"], )"), "outputs[1]: unknown output 'gif'"},
      {OneBody(std::string(kBox) + R"(, "orientation": [0, 0, 0, 0])"),
       "bodies[0].orientation: the quaternion is zero"},
      {OneBody(std::string(kBox) + R"(, "orientation": [1, 0, 0])"), "a quaternion is 4 numbers"},
      {OneBody(std::string(kBox) + R"(, "velocity": [1, 2])"), "bodies[0].velocity: must be an array of 3 numbers"},
      {OneBody(std::string(kBox) + R"(, "angular_velocity_frame": "local")"),
       "'local' is not one of world, body, principal"},
      {OneBody(std::string(kBox) + R"(, "color": [2, 0, 0])"), "bodies[0].color: components are between 0 and 1"},
      {R"({"bodies": []})", "bodies: must be a non-empty array"},
      {R"({"bodies": [{"name": "a", "solid": {"type": "sphere", "radius": 1}},
                      {"name": "a", "solid": {"type": "sphere", "radius": 1}}]})",
       "bodies[1].name: 'a' is used by another body"},
      {OneBody(std::string(kBox) + R"(, "name": "crate")",
               R"("forces": [{"type": "spring", "body": "crat", "anchor": [0, 0, 0], "k": 1}], )"),
       "forces[0].body: no body is named 'crat' (did you mean 'crate'?)"},
      {OneBody(kBox, R"("forces": [{"type": "spring", "body": 3, "anchor": [0, 0, 0], "k": 1}], )"),
       "body index 3 is out of range"},
      {OneBody(kBox, R"("forces": [{"type": "spring", "body": 0, "k": 1}], )"), "forces[0].anchor: is required"},
      {OneBody(kBox, R"("forces": [{"type": "spring", "body": 0, "anchor": [0, 0, 0], "k": -1}], )"),
       "forces[0].k: must not be negative"},
      {OneBody(kBox, R"("forces": [{"type": "spring", "bodies": [0, 0], "k": 1}], )"),
       "a spring between a body and itself"},
      {OneBody(kBox, R"("forces": [{"type": "magnet"}], )"), "forces[0].type: 'magnet' is not one of"},
      {OneBody(kBox, R"("forces": [{"type": "gravity", "g": [0, 0, -9.8], "strength": 2}], )"),
       "forces[0]: unknown key 'strength'"},
      {OneBody(kBox, R"("forces": [{"type": "torque", "body": 0}], )"), "forces[0].torque: is required"},
      {OneBody(std::string(kBox) + R"(, "collision": "hul")"), "bodies[0].collision: 'hul' is not"},
      {OneBody(std::string(kBox) + R"(, "collision": {"type": "torus", "major_radius": 1, "minor_radius": 0.2})"),
       "bodies[0].collision: collides as a box, sphere, capsule or cylinder"},
      {OneBody(std::string(kBox) + R"(, "material": {"static_friction": 0.2, "kinetic_friction": 0.5})"),
       "bodies[0].material.kinetic_friction: must not exceed static_friction"},
      {OneBody(std::string(kBox) + R"(, "material": {"restitution": 1.5})"),
       "bodies[0].material.restitution: lies between 0 and 1"},
      {OneBody(std::string(kBox) + R"(, "material": {"frction": 0.5})"), "unknown key 'frction' (did you mean"},
      {OneBody(kBox, R"("ground": {"normal": [0, 0, 0]}, )"), "ground.normal: must not be the zero vector"},
      {OneBody(kBox, R"("static": [{"solid": {"type": "box", "size": [1, 1, 1]}, "collision": "none"}], )"),
       "static[0].collision: a static body that collides with nothing"},
      {OneBody(kBox, R"("static": [{"solid": {"type": "cone", "radius": 1, "height": 1}}], )"),
       "static[0]: collides as nothing"},
      {OneBody(kBox, R"("pairs": [{"bodies": ["body0", "grnd"], "material": {"friction": 1}}], )"),
       "pairs[0].bodies[1]: no body is named 'grnd'"},
      {OneBody(kBox, R"("pairs": [{"bodies": [0, "ground"]}], )"), "pairs[0].material: is required"},
  };
  for (const auto& c : cases) EXPECT_THAT(ErrorOf(c.scene), HasSubstr(c.expect)) << c.scene;
}

TEST(Scene, JointErrorsNameTheJointsField) {
  const std::string two = R"("bodies": [{"name": "a", "solid": {"type": "box", "size": [0.1, 0.1, 0.4]}},
                                         {"name": "b", "solid": {"type": "box", "size": [0.1, 0.1, 0.4]}}], )";
  auto scene = [&](const std::string& joints, const std::string& top = "") {
    return "{" + top + two + R"("joints": )" + joints + "}";
  };
  struct Case {
    std::string scene, expect;
  } cases[] = {
      {scene(R"([{"type": "hinge", "parent": "world", "child": "a"}])"), "joints[0].type: 'hinge' is not one of"},
      {scene(R"([{"type": "revolute", "parent": "world", "child": "c", "anchor": [0, 0, 0], "axis": [1, 0, 0]}])"),
       "joints[0].child: no body is named 'c'"},
      {scene(R"([{"type": "revolute", "parent": "wrld", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0]}])"),
       "joints[0].parent: no body is named 'wrld'"},
      {scene(R"([{"type": "revolute", "parent": "world", "child": "a", "anchor": [0, 0, 0]}])"),
       "joints[0].axis: is required for a revolute joint"},
      {scene(R"([{"type": "revolute", "parent": "world", "child": "a", "axis": [1, 0, 0]}])"),
       "joints[0].anchor: is required"},
      {scene(R"([{"type": "revolute", "parent": "world", "child": "a", "anchor": [0, 0, 0], "axis": [0, 0, 0]}])"),
       "joints[0].axis: must not be zero"},
      {scene(R"([{"type": "revolute", "parent": "a", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0]}])"),
       "joints[0].parent: a body cannot be jointed to itself"},
      {scene(R"([{"type": "revolute", "parent": "world", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0]},
                 {"type": "revolute", "parent": "b", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0]}])"),
       "joints[1].child: 'a' already hangs from joints[0]"},
      {scene(R"([{"type": "revolute", "parent": "world", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0],
                  "limits": {"lower": 1, "upper": 0}}])"),
       "joints[0].limits: lower must not exceed upper"},
      {scene(R"([{"type": "revolute", "parent": "world", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0],
                  "limits": {"lower_deg": -10, "upper_deg": 10}, "position_deg": 20}])"),
       "joints[0].position: is outside the joint's limits"},
      {scene(R"([{"type": "spherical", "parent": "world", "child": "a", "anchor": [0, 0, 0], "friction": 1}])"),
       "joints[0].friction: acts on revolute and prismatic joints, not on a spherical joint"},
      {scene(R"([{"type": "revolute", "parent": "world", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0],
                  "motor": {"mode": "position", "target": 1}}])"),
       "joints[0].motor.kp: is required"},
      {scene(R"([{"type": "revolute", "parent": "world", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0],
                  "spring": {"stiffness": 3, "rst": 0}}])"),
       "joints[0].spring: unknown key 'rst' (did you mean 'rest'?)"},
      {scene(R"([{"type": "prismatic", "parent": "world", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0],
                  "position_deg": 3}])"),
       "joints[0].position_deg: degrees are for revolute joints"},
      {scene(R"([{"type": "spherical", "parent": "world", "child": "a", "anchor": [0, 0, 0], "velocity": [1, 2]}])"),
       "joints[0].velocity: must be an array of 3 numbers"},
      {scene(
           R"([{"type": "spherical", "parent": "world", "child": "a", "anchor": [0, 0, 0], "position": [0, 0, 0, 0]}])"),
       "joints[0]: the initial quaternion must be non-zero"},
      {scene(R"([{"type": "revolute", "parent": "world", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0]}])",
             R"("integrator": "splitting", )"),
       "integrator: 'splitting' has no meaning for joints"},
      {scene(R"([{"type": "revolute", "parent": "b", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0]},
                 {"type": "revolute", "parent": "a", "child": "b", "anchor": [0, 0, 0], "axis": [1, 0, 0]}])"),
       "joints[1]: closes a loop of joints through body"},
  };
  for (const auto& c : cases) EXPECT_THAT(ErrorOf(c.scene), HasSubstr(c.expect)) << c.scene;
}

TEST(Scene, ConstraintErrorsNameTheirField) {
  const std::string bodies = R"("bodies": [{"name": "a", "solid": {"type": "box", "size": [0.1, 0.1, 0.4]}},
                                            {"name": "b", "solid": {"type": "box", "size": [0.1, 0.1, 0.4]}, "position": [1, 0, 0]},
                                            {"name": "c", "solid": {"type": "box", "size": [0.1, 0.1, 0.1]}, "position": [1, 0, -1]}],
    "joints": [{"name": "ja", "type": "revolute", "parent": "world", "child": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0]},
               {"name": "jb", "type": "revolute", "parent": "world", "child": "b", "anchor": [1, 0, 0], "axis": [1, 0, 0]},
               {"name": "free", "type": "spherical", "parent": "b", "child": "c", "anchor": [1, 0, -1]}], )";
  auto scene = [&](const std::string& rest) { return "{" + bodies + rest + "}"; };
  struct Case {
    std::string scene, expect;
  } cases[] = {
      {scene(R"("loops": [{"type": "pin", "a": "a", "b": "b", "anchor": [0, 0, 0]}])"),
       "loops[0].type: 'pin' is not one of"},
      {scene(R"("loops": [{"type": "ball", "a": "a", "b": "d", "anchor": [0, 0, 0]}])"),
       "loops[0].b: no body is named 'd'"},
      {scene(R"("loops": [{"type": "hinge", "a": "a", "b": "b", "anchor": [0, 0, 0]}])"),
       "loops[0].axis: is required for a hinge loop"},
      {scene(R"("loops": [{"type": "ball", "a": "a", "b": "b", "axis": [1, 0, 0], "anchor": [0.5, 0, 0]}])"),
       "loops[0].axis: has no meaning for a ball loop"},
      {"{" + std::string(R"("bodies": [{"name": "a", "solid": {"type": "box", "size": [0.1, 0.1, 0.4]}}],
          "joints": [{"name": "ja", "type": "revolute", "parent": "world", "child": "a", "anchor": [0, 0, 0],
                      "axis": [1, 0, 0], "position": 0.5}],
          "loops": [{"type": "ball", "a": "a", "b": "world", "anchor": [0, 0, -0.2]}]})"),
       "loops[0]: its frames do not meet where the joints place the bodies: 0.0989616 m apart"},
      {scene(R"("couplings": [{"follower": "jb", "leader": "jx"}])"), "couplings[0].leader: no joint is named 'jx'"},
      {scene(R"("couplings": [{"follower": "jb", "leader": "jb"}])"),
       "couplings[0]: it couples a coordinate to itself"},
      {scene(R"("couplings": [{"follower": "free", "leader": "ja"}])"),
       "couplings[0].follower: 'free' is not a revolute or prismatic joint"},
      {scene(R"("couplings": [{"follower": "jb", "leader": "ja", "multiplier": 2, "polynomial": [0, 2]}])"),
       "couplings[0].polynomial: give 'multiplier' and 'offset', or 'polynomial', not both"},
      {scene(R"("tendons": [{"path": [{"body": "a", "point": [0, 0, 0]}]}])"),
       "tendons[0].path: must be an array of two points or more"},
      {scene(R"("tendons": [{"joints": [{"joint": "ja"}], "range": [1, 0]}])"),
       "tendons[0].range: its lower end is above its upper"},
      {scene(R"("tendons": [{"joints": [{"joint": "ja"}], "path": []}])"), "tendons[0]: give 'joints'"},
      {scene(R"("couplings": [{"follower": "jb", "leader": "ja"}], "integrator": "rk4")"),
       "integrator: 'rk4': loops and couplings are held by implicit-midpoint only"},
  };
  for (const auto& c : cases) EXPECT_THAT(ErrorOf(c.scene), HasSubstr(c.expect)) << c.scene;
}

// The linkages example: the four-bar's loop, the gears' coupling and the string's range held
// through 5 s, and the energy of this conservative scene kept (the string goes slack only where it
// would push: never, swinging).
TEST(Simulation, LinkagesExampleHoldsItsLoopsCouplingsAndString) {
  std::vector<std::string> w;
  scene::Scene scene = scene::LoadScene(DataPath("scenes/linkages.json"), w);
  scene::Simulation sim = scene::BuildSimulation(scene, w);
  ASSERT_EQ(sim.world().loops().size(), 1u);
  const double e0 = sim.world().Diagnose().total_energy;
  double gap = 0, gears = 0, stretch = 0, energy = 0;
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("rbsim_linkages_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  rbsim::TrajectoryWriter writer(dir.string(), {scene::OutputKind::kCsv}, true);
  scene::Run(sim, [&](const dynamics::World& world, const dynamics::Diagnostics& diag) {
    writer.Add(sim, world, diag);
    gap = std::max(gap, world.loop_state(0).residual);
    gears = std::max(gears, std::abs(world.coupling_state(0).residual));
    stretch = std::max(stretch, world.tendon_state(0).length - 0.6);
    energy = std::max(energy, std::abs(diag.total_energy - e0) / std::abs(e0));
  });
  EXPECT_LT(gap, 1e-9);
  EXPECT_LT(gears, 1e-12);
  EXPECT_LT(stretch, 1e-9);
  EXPECT_LT(energy, 1e-4);
  const dynamics::JointState wheel = sim.world().joint_state(3), pinion = sim.world().joint_state(4);
  EXPECT_NEAR(pinion.position[0], -2 * wheel.position[0], 1e-12);
  // constraints.csv: a row per loop, coupling and tendon per sample; the string's length its own.
  writer.Commit();
  std::ifstream csv(dir / "constraints.csv");
  std::string header, loop, gears_row, string_row;
  std::getline(csv, header);
  std::getline(csv, loop);
  std::getline(csv, gears_row);
  std::getline(csv, string_row);
  EXPECT_EQ(header, rbsim::kConstraintsCsvHeader);
  EXPECT_THAT(loop, HasSubstr(",closure,loop,"));
  EXPECT_THAT(gears_row, HasSubstr(",gears,coupling,0,-1,0"));  // the pinion at −1 rad, held there
  EXPECT_THAT(string_row, HasSubstr(",string,tendon,"));
  fs::remove_all(dir);
}

// The example's T-handle pendulum against the closed form T = 4 √(I/(m g d)) K(sin(θ0/2)), run
// through the scene (anchor and axis in the world, the mesh through massprops), and joints.csv.
TEST(Simulation, JointExampleMeshPendulumHasTheEllipticPeriod) {
  std::vector<std::string> w;
  scene::Scene scene = scene::LoadScene(DataPath("scenes/joints.json"), w);
  scene.duration = 6;
  scene.output_rate = 1000;
  scene::Simulation sim = scene::BuildSimulation(scene, w);
  const dynamics::RigidBody& b = sim.world().bodies()[0];
  ASSERT_EQ(sim.world().joints().size(), 4u);
  // The double pendulum starts where its angles put it: the shoulder at 1.2 rad, the elbow at
  // −1.6 rad relative (each joint placed at the scene's pose before any moved a body).
  const auto at = [](double angle, double down) {
    return Vector3(Eigen::AngleAxisd(angle, Vector3::UnitX()) * Vector3(0, 0, -down));
  };
  const Vector3 shoulder(0.4, 0, 0);
  EXPECT_LT((sim.world().bodies()[1].position - (shoulder + at(1.2, 0.25))).norm(), 1e-15);
  EXPECT_LT((sim.world().bodies()[2].position - (shoulder + at(1.2, 0.5) + at(1.2 - 1.6, 0.2))).norm(), 1e-15);
  // Hanging, the center of mass sits d = 5 cm below the pivot; released at 120°.
  const double d = 0.05, theta0 = 2 * massprops::kPi / 3;
  // (The joint has turned the body about x already: I_xx is the same.)
  const double I = b.WorldInertia()(0, 0) + b.mass * d * d;
  const double T = 4 * std::sqrt(I / (b.mass * 9.81 * d)) * std::comp_ellint_1(std::sin(theta0 / 2));
  std::vector<double> crossings;
  double q_prev = 0, t_prev = 0;
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("rbsim_joints_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  rbsim::TrajectoryWriter writer(dir.string(), {scene::OutputKind::kCsv}, true);
  scene::Run(sim, [&](const dynamics::World& world, const dynamics::Diagnostics& diag) {
    writer.Add(sim, world, diag);
    const double q = world.joint_state(0).position[0];
    if (diag.time > 0 && q_prev > 0 && q <= 0)
      crossings.push_back(t_prev + (diag.time - t_prev) * q_prev / (q_prev - q));
    q_prev = q, t_prev = diag.time;
  });
  writer.Commit();
  ASSERT_GE(crossings.size(), 3u);
  const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  EXPECT_NEAR(measured / T, 1, 2e-5) << measured << " vs " << T;
  std::ifstream csv(dir / "joints.csv");
  std::string header, first;
  std::getline(csv, header);
  std::getline(csv, first);
  EXPECT_EQ(header, rbsim::kJointsCsvHeader);
  EXPECT_THAT(first, HasSubstr("0,pivot,revolute,2.0943951023931953,"));
  fs::remove_all(dir);
}

TEST(Scene, OpenMeshIsRefusedUnlessRepairedOrAllowed) {
  // A cube with its top face missing.
  const std::string path = ::testing::TempDir() + "/open_cube.obj";
  {
    std::ofstream out(path);
    out << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
           "f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  }
  const std::string msg = ErrorOf(OneBody(R"("mesh": ")" + path + R"(")"));
  EXPECT_THAT(msg, HasSubstr("test.json: bodies[0].mesh: " + std::filesystem::path(path).lexically_normal().string()));
  EXPECT_THAT(msg, HasSubstr("boundary edges"));
  EXPECT_THAT(msg, HasSubstr("\"repair\": true"));  // the advice names scene keys, not flags
  EXPECT_THAT(msg, HasSubstr("\"allow_open\": true"));
  std::vector<std::string> w;
  EXPECT_NO_THROW(scene::BuildSimulation(Parse(OneBody(R"("mesh": ")" + path + R"(", "allow_open": true)")), w));
  EXPECT_THAT(w.at(0), HasSubstr("computed anyway"));
}

TEST(Scene, InvalidJsonNamesTheLine) {
  const std::string path = ::testing::TempDir() + "/broken.json";
  {
    std::ofstream out(path);
    out << "{\n  \"dt\": 0.01,\n  \"bodies\": [\n    {\"solid\": }\n  ]\n}\n";
  }
  std::vector<std::string> w;
  try {
    scene::LoadScene(path, w);
    FAIL() << "accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path + ": line 4: not valid JSON"));
  }
}

// A rate so low that the steps between samples overflow an integer samples the first and last
// states only (it sampled every step: llround overflowed).
TEST(Scene, AVanishingOutputRateSamplesTheFirstAndLastStatesOnly) {
  std::vector<std::string> w;
  scene::Scene s = Parse(OneBody(kBox), &w);
  s.output_rate = 1e-30;
  s.duration = 0.01;
  scene::Simulation sim = scene::BuildSimulation(s, w, 1);
  int samples = 0;
  scene::Run(sim, [&](const dynamics::World&, const dynamics::Diagnostics&) { ++samples; });
  EXPECT_EQ(samples, 2);
}

// Orientations at the edge of double precision: a quaternion whose norm overflows is normalized
// (it was called "zero"); an angle of 1e308 degrees names no rotation (its own rounding is
// 2e292 degrees) and is refused naming the field, while 4e9 degrees (rounding 5e-7) turns by its
// remainder of whole turns.
TEST(Scene, OrientationsBeyondDoublePrecisionAreStillRotations) {
  std::vector<std::string> w;
  const scene::Scene s = Parse(OneBody(std::string(kBox) + R"(, "orientation": [1e300, 1e300, 0, 0])"), &w);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_THAT(w[0], HasSubstr("norm 1.41421e+300; normalized"));
  EXPECT_NEAR(s.bodies[0].orientation.w(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(s.bodies[0].orientation.x(), std::sqrt(0.5), 1e-15);
  EXPECT_THAT(ErrorOf(OneBody(std::string(kBox) + R"(, "orientation": {"axis": [0, 0, 1], "angle_deg": 1e308})")),
              HasSubstr("bodies[0].orientation.angle_deg: 1e+308 is too large to name an angle"));
  EXPECT_THAT(ErrorOf(OneBody(std::string(kBox) + R"(, "orientation": {"axis": [0, 0, 1], "angle": 1e9})")),
              HasSubstr("bodies[0].orientation.angle: 1e+09 is too large to name an angle"));
  const scene::Scene t =
      Parse(OneBody(std::string(kBox) + R"(, "orientation": {"axis": [0, 0, 1], "angle_deg": 4e9})"), &w);
  const double turn = std::fmod(4e9, 360.0) * massprops::kPi / 180;
  EXPECT_NEAR(
      t.bodies[0].orientation.angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()))), 0,
      1e-12);
}

TEST(Scene, NonUnitQuaternionIsNormalizedWithAWarning) {
  std::vector<std::string> w;
  const scene::Scene s = Parse(OneBody(std::string(kBox) + R"(, "orientation": [2, 0, 0, 2])"), &w);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_THAT(w[0], HasSubstr("bodies[0].orientation: the quaternion has norm 2.82843; normalized"));
  EXPECT_NEAR(s.bodies[0].orientation.w(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(s.bodies[0].orientation.z(), std::sqrt(0.5), 1e-15);
}

TEST(Scene, ExampleScenesAreValid) {
  for (const char* name : {"t_handle", "heavy_top", "tumbling_spot", "hanging_spring", "two_bodies", "csg_part",
                           "box_stack", "incline_roll", "dominoes", "spot_on_table", "pile", "ring_on_peg",
                           "pile_in_bin", "joints", "quadruped", "linkages"}) {
    std::vector<std::string> w;
    EXPECT_NO_THROW(scene::BuildSimulation(scene::LoadScene(DataPath(std::string("scenes/") + name + ".json"), w), w))
        << name;
    EXPECT_TRUE(w.empty()) << name << ": " << (w.empty() ? "" : w[0]);
  }
}

// The T-handle example, run for two flips, against libdynamics' exact torque-free flow (Jacobi
// elliptic functions): ω in the principal axes and the attitude at every sample. With the
// exact-splitting integrator the run *is* the exact flow, so any frame or conversion error in the
// scene → body path shows at O(1); with the default integrator the error is O((ω dt)²).
TEST(Simulation, THandleFollowsTheExactTorqueFreeFlow) {
  // Measured: exact-splitting 4e-7 in both (the elliptic functions' rounding, step after step);
  // implicit midpoint at ω dt = 0.01: 2.5e-5 in ω, 7e-4 rad of attitude phase after 8 s.
  struct Case {
    dynamics::Integrator integrator;
    double omega_tol, angle_tol;
  };
  for (auto [integrator, omega_tol, angle_tol] : {Case{dynamics::Integrator::kExactSplitting, 2e-6, 2e-6},
                                                  Case{dynamics::Integrator::kImplicitMidpoint, 1e-4, 3e-3}}) {
    std::vector<std::string> w;
    scene::Scene scene = scene::LoadScene(DataPath("scenes/t_handle.json"), w);
    scene.duration = 8;
    scene.integrator = integrator;
    scene::Simulation sim = scene::BuildSimulation(scene, w);
    const dynamics::RigidBody& b0 = sim.world().bodies()[0];
    // The scene's ω = (10, 0.01, 0.01) in the mesh axes; the crossbar (mesh x) is the intermediate axis.
    ASSERT_TRUE(massprops::testing::MatrixNearRel(b0.BodyAngularVelocity(), Vector3(0.01, 10, -0.01), 1e-12, 10));
    const dynamics::ExactFreeRotation exact(b0.inertia, b0.BodyAngularVelocity(), b0.orientation);
    ASSERT_LT(exact.FlipInterval(), 4.0);  // two flips or more within the run
    double worst_omega = 0, worst_angle = 0;
    scene::Run(sim, [&](const dynamics::World& world, const dynamics::Diagnostics& d) {
      const scene::BodyState s = scene::StateOf(sim.bodies[0], world.bodies()[0]);
      worst_omega = std::max(worst_omega, (s.omega_principal - exact.Omega(d.time)).norm() / 10.0);
      worst_angle = std::max(worst_angle, world.bodies()[0].orientation.angularDistance(exact.Orientation(d.time)));
    });
    EXPECT_LT(worst_omega, omega_tol) << dynamics::IntegratorName(integrator);
    std::printf("%s: worst |w - w_exact|/|w| %.3g, worst attitude error %.3g rad\n",
                dynamics::IntegratorName(integrator), worst_omega, worst_angle);
    EXPECT_LT(worst_angle, angle_tol) << dynamics::IntegratorName(integrator);
  }
}

// A box hung by a corner from a damped spring settles where statics says: the corner straight
// above the center of mass, the spring stretched by m g / k. This checks the mesh-coordinate →
// body-frame conversion of force points and the scene's orientation handling.
TEST(Simulation, HangingBoxSettlesToStaticEquilibrium) {
  scene::Scene s = Parse(R"({
    "dt": 0.002, "duration": 60,
    "bodies": [{"name": "b", "solid": {"type": "box", "size": [0.2, 0.1, 0.05]}, "density": 500,
                "orientation": {"axis": [1, 2, 3], "angle_deg": 40}, "position": [0.1, 0, -0.3]}],
    "forces": [{"type": "gravity", "g": [0, 0, -9.81]},
               {"type": "spring", "body": "b", "point": [0.1, 0.05, 0.025], "anchor": [0, 0, 0],
                "k": 200, "rest_length": 0.1, "damping": 5},
               {"type": "angular_damping", "body": "b", "c": 0.01},
               {"type": "linear_damping", "c": 0.5}]})");
  std::vector<std::string> w;
  scene::Simulation sim = scene::BuildSimulation(s, w);
  scene::Run(sim, [](const dynamics::World&, const dynamics::Diagnostics&) {});
  const dynamics::RigidBody& b = sim.world().bodies()[0];
  const scene::BodyState st = scene::StateOf(sim.bodies[0], b);
  const Vector3 corner = st.position + st.orientation * Vector3(0.1, 0.05, 0.025);
  const double m = 500 * 0.2 * 0.1 * 0.05;
  EXPECT_LT(b.velocity.norm(), 1e-6);
  EXPECT_LT((corner - Vector3(0, 0, -(0.1 + m * 9.81 / 200))).norm(), 1e-6) << corner.transpose();
  EXPECT_LT((st.position.head<2>() - corner.head<2>()).norm(), 1e-6);  // COM straight below the corner
}

TEST(Simulation, SpringsHoldTheCenterOfMassUnlessAPointIsGiven) {
  // The T-handle's center of mass is 7.1 mm from its file's origin. A spring from the world point
  // where the center of mass starts, with no "point", pulls on the center of mass: nothing moves.
  // Tied at the file's origin instead, it would swing (and it does when that point is named).
  const double com_y =
      (0.08 * 0.02 * 0.02 * 0.01 - 0.02 * 0.06 * 0.02 * 0.03) / (0.08 * 0.02 * 0.02 + 0.02 * 0.06 * 0.02);
  auto run = [&](const std::string& point) {
    std::vector<std::string> w;
    scene::Simulation sim = scene::BuildSimulation(
        Parse(R"({"dt": 0.001, "duration": 0.2, "bodies": [{"name": "t", "mesh": "../meshes/t_handle.obj"}],
                  "forces": [{"type": "spring", "body": "t", "k": 500, "anchor": [0, )" +
              massprops::ExactDecimal(com_y) + R"(, 0])" + point + "}]}"),
        w);
    double moved = 0;  // largest distance of the center of mass from its start
    scene::Run(sim, [&](const dynamics::World& world, const dynamics::Diagnostics&) {
      moved = std::max(moved, (world.bodies()[0].position - Vector3(0, com_y, 0)).norm());
    });
    return moved;
  };
  EXPECT_LT(run(""), 1e-9);
  EXPECT_GT(run(R"(, "point": [0, 0, 0])"), 1e-3);  // the 7 mm stretch swings it
}

// A scene's "fluid" with "buoyancy": a ball half as dense as the water rises at a = g (ρ_f/ρ_b − 1)
// = g from rest (no drag at rest); a ball twice as dense sinks at g/2. Drag slows both after.
TEST(Simulation, AFluidsBuoyancyLiftsWhatIsLighterThanIt) {
  std::vector<std::string> w;
  scene::Simulation sim = scene::BuildSimulation(Parse(R"({"dt": 0.001, "duration": 0.01, "bodies": [
                  {"name": "cork", "solid": {"type": "sphere", "radius": 0.05}, "density": 500},
                  {"name": "stone", "solid": {"type": "sphere", "radius": 0.05}, "density": 2000, "position": [1, 0, 0]}],
                "forces": [{"type": "gravity", "g": [0, 0, -9.81]},
                           {"type": "fluid", "density": 1000, "viscosity": 0.001, "buoyancy": true}]})"),
                                                 w);
  ASSERT_TRUE(sim.physics.Step(1e-4).ok);
  const double v_cork = sim.world().bodies()[0].velocity.z(), v_stone = sim.world().bodies()[1].velocity.z();
  EXPECT_NEAR(v_cork / (9.81 * 1e-4) - 1, 0, 1e-3);  // (the drag of a speed of 1 mm/s: 3e-4 of it)
  EXPECT_NEAR(v_stone / (-0.5 * 9.81 * 1e-4) - 1, 0, 1e-3);
  EXPECT_THROW(Parse(R"({"bodies": [{"name": "b", "solid": {"type": "sphere", "radius": 0.05}}],
                         "forces": [{"type": "fluid", "wind": [1, 0, 0]}]})"),
               scene::SceneError);
}

// MJCF gravcomp (MuJoCo 3): a body compensated in full floats where it is; one compensated by half
// falls at g/2 (z = z0 − g t²/4).
TEST(Simulation, GravityCompensationHoldsUpItsShareOfTheWeight) {
  const std::string path = (std::filesystem::temp_directory_path() / "rbsim_test_gravcomp.xml").string();
  std::ofstream(path) << R"(<mujoco><worldbody>
  <body name="floater" pos="0 0 1" gravcomp="1"><freejoint/><geom type="sphere" size="0.05" mass="1"/></body>
  <body name="half" pos="1 0 1" gravcomp="0.5"><freejoint/><geom type="sphere" size="0.05" mass="2"/></body>
  </worldbody></mujoco>)";
  std::vector<std::string> w;
  scene::Simulation sim = scene::BuildSimulation(
      Parse(R"({"dt": 0.001, "duration": 0.5, "forces": [{"type": "gravity", "g": [0, 0, -9.81]}],
                "robots": [{"file": ")" +
            path + R"(", "position": [0, 0, 0]}]})"),
      w);
  for (int s = 0; s < 500; ++s) ASSERT_TRUE(sim.physics.Step(1e-3).ok);
  const auto& b = sim.world().bodies();
  EXPECT_NEAR(b[0].position.z(), 1.0, 1e-12);
  EXPECT_NEAR(b[1].position.z(), 1.0 - 9.81 * 0.25 / 4, 1e-9);
}

TEST(Simulation, TwoBodyExampleConservesMomentaAndEnergy) {
  std::vector<std::string> w;
  scene::Simulation sim = scene::BuildSimulation(scene::LoadScene(DataPath("scenes/two_bodies.json"), w), w);
  EXPECT_TRUE(sim.conservation.energy);
  EXPECT_TRUE(sim.conservation.momentum);
  const scene::RunStats stats = scene::Run(sim, [](const dynamics::World&, const dynamics::Diagnostics&) {});
  EXPECT_LT(stats.max_drift.linear_momentum, 1e-12);
  EXPECT_LT(stats.max_drift.angular_momentum, 1e-12);
  EXPECT_LT(stats.max_drift.energy, 1e-3);  // second order, bounded (symplectic splitting)
  EXPECT_EQ(stats.steps, 10000);
  EXPECT_EQ(stats.samples, 10000 / 17 + 2);  // t = 0, every 17 steps (≈ 60 Hz), and the last step
}

// The contact examples through the scene path: the rolling ball at its closed-form rate, the
// stack standing, every domino down, Spot's hull at rest on the table.
TEST(Simulation, ContactExamples) {
  std::vector<std::string> w;
  auto run = [&](const char* name) {
    auto sim = std::make_unique<scene::Simulation>(
        scene::BuildSimulation(scene::LoadScene(DataPath(std::string("scenes/") + name + ".json"), w), w));
    EXPECT_TRUE(sim->contact) << name;
    EXPECT_FALSE(sim->conservation.energy) << name;
    const scene::RunStats stats = scene::Run(*sim, [](const dynamics::World&, const dynamics::Diagnostics&) {});
    return std::make_pair(std::move(sim), stats);
  };
  {
    auto [sim, stats] = run("incline_roll");
    const double a = 9.81 * std::sin(20 * massprops::kPi / 180) / 1.4;
    EXPECT_NEAR(sim->world().bodies()[0].velocity.norm(), a * 1.0, 1e-3 * a);
    EXPECT_LT(stats.max_penetration, 1e-12);
  }
  {
    auto [sim, stats] = run("box_stack");
    for (std::size_t i = 0; i < 10; ++i) {
      const auto& b = sim->world().bodies()[i];
      EXPECT_LT(b.velocity.norm(), 1e-4);
      EXPECT_NEAR(b.position.z(), 0.05 + 0.1 * static_cast<double>(i), 1e-3);
    }
    EXPECT_LT(stats.max_penetration, 1e-5);
  }
  {
    auto [sim, stats] = run("dominoes");
    for (const auto& b : sim->world().bodies()) EXPECT_LT(b.position.z(), 0.03);  // lying down (upright: 0.05)
  }
  {
    auto [sim, stats] = run("spot_on_table");
    const auto& b = sim->world().bodies()[0];
    EXPECT_LT(b.velocity.norm(), 1e-3);
    EXPECT_GT(b.position.z(), 0);  // on the table, not through it
  }
}

// A pair's own material overrides the bodies': the ball on a frictionless incline slides at
// g sin θ instead of rolling at 5/7 of it.
TEST(Simulation, PairMaterialOverridesTheBodies) {
  std::vector<std::string> w;
  scene::Scene s = Parse(R"({"dt": 0.001, "duration": 0.5,
    "ground": {"normal": [0, 0, 1], "material": {"friction": 0.5}},
    "bodies": [{"name": "ball", "solid": {"type": "sphere", "radius": 0.05}, "position": [0, 0, 0.05],
                "material": {"friction": 0.5}}],
    "pairs": [{"bodies": ["ball", "ground"], "material": {"friction": 0}}],
    "forces": [{"type": "gravity", "g": [2, 0, -9]}]})");
  scene::Simulation sim = scene::BuildSimulation(s, w);
  scene::Run(sim, [](const dynamics::World&, const dynamics::Diagnostics&) {});
  EXPECT_NEAR(sim.world().bodies()[0].velocity.x(), 2 * 0.5, 1e-9);
  EXPECT_NEAR(sim.world().bodies()[0].AngularVelocity().norm(), 0, 1e-12);
}

TEST(Simulation, SceneFramesOfTheInitialAngularVelocity) {
  // A box turned 90° about z: ω given in its body (mesh) axes along x is world y.
  for (auto [frame, want] : {std::pair{"world", Vector3(1, 0, 0)}, std::pair{"body", Vector3(0, 1, 0)}}) {
    std::vector<std::string> w;
    scene::Simulation sim = scene::BuildSimulation(
        Parse(OneBody(std::string(kBox) + R"(, "orientation": {"axis": [0, 0, 1], "angle_deg": 90},
                      "angular_velocity": [1, 0, 0], "angular_velocity_frame": ")" +
                      frame + "\"")),
        w);
    EXPECT_TRUE(massprops::testing::MatrixNearRel(sim.world().bodies()[0].AngularVelocity(), want, 1e-15, 1)) << frame;
  }
}

TEST(Simulation, ImplicitBodyHasItsClosedFormInertiaWithinTheEstimate) {
  std::vector<std::string> w;
  const scene::Simulation sim =
      scene::BuildSimulation(Parse(OneBody(R"x("implicit": "torus(R=0.2, r=0.05)", "density": 1000)x")), w);
  const massprops::MassProperties truth = massprops::solids::TorusProperties(0.2, 0.05, 1000);
  const auto& rb = sim.world().bodies()[0];
  EXPECT_NEAR(rb.mass, truth.mass, 5e-4 * truth.mass);  // tolerance 1e-4 relative standard error
  EXPECT_NEAR(rb.inertia[2], truth.inertia_com(2, 2), 5e-4 * truth.inertia_com(2, 2));
  // The display surface encloses about the same volume (marching tetrahedra, O(cell) error).
  const double v = massprops::IntegrateTriangles(sim.bodies[0].display.V, sim.bodies[0].display.F).volume;
  EXPECT_NEAR(v, truth.volume, 0.03 * truth.volume);
}

TEST(Outputs, GlbHeaderChunksAndOneKeyPerSample) {
  std::vector<std::string> w;
  scene::Scene scene = scene::LoadScene(DataPath("scenes/two_bodies.json"), w);
  scene.duration = 1;
  scene::Simulation sim = scene::BuildSimulation(scene, w);
  rbsim::Recording rec;
  const auto stats =
      scene::Run(sim, [&](const dynamics::World& world, const dynamics::Diagnostics& d) { rec.Add(sim, world, d); });
  const std::string path = ::testing::TempDir() + "/two.glb";
  rbsim::WriteGlb(path, sim, rec);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto u32 = [&](std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
  };
  ASSERT_GE(bytes.size(), 28u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(u32(4), 2u);
  EXPECT_EQ(u32(8), bytes.size());
  EXPECT_EQ(u32(16), 0x4E4F534Au);
  const std::uint32_t json_len = u32(12);
  EXPECT_EQ(json_len % 4, 0u);
  const json doc = json::parse(bytes.substr(20, json_len));
  EXPECT_EQ(u32(20 + json_len + 4), 0x004E4942u);
  EXPECT_EQ(doc["asset"]["version"], "2.0");
  EXPECT_EQ(doc["nodes"].size(), 3u);  // root + 2 bodies
  const auto& anim = doc["animations"][0];
  EXPECT_EQ(anim["channels"].size(), 4u);
  for (const auto& sampler : anim["samplers"]) {
    EXPECT_EQ(doc["accessors"][sampler["input"].get<int>()]["count"], stats.samples);
    EXPECT_EQ(doc["accessors"][sampler["output"].get<int>()]["count"], stats.samples);
  }
  // Keys are unit quaternions on one side of the double cover.
  for (const auto& q : rec.rotations[1]) EXPECT_NEAR(q.norm(), 1.0f, 1e-6f);
  for (std::size_t i = 1; i < rec.rotations[1].size(); ++i)
    EXPECT_GE(rec.rotations[1][i].dot(rec.rotations[1][i - 1]), 0.0f);
}

// The pile in the bin (data/scenes/pile_in_bin.json): 50 parts — Spot, half tori, T-handles, tori
// and boxes — each collided as its own mesh, poured into an open-topped bin that is a static mesh.
// After settling every part is inside the bin, no overlap ever exceeds half the finest field's
// cell (Spot's, 1.0 mm), the contact impulses never add kinetic energy, and the total energy rises
// in no step by more than the weight times the distance overlaps were pushed out, plus 5e-8 of it:
// a contact that turns a settling part upward lifts it in this step while gravity takes the
// kinetic energy back over the next ones (the semi-implicit step's lag; measured at most 1.7e-8
// with patch friction). A long simulation: the Release run only.
TEST(Scene, PileInABinSettlesInsideIt) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "a long simulation: run in the Release build";
#endif
  std::vector<std::string> w;
  const scene::Scene scene = scene::LoadScene(DataPath("scenes/pile_in_bin.json"), w);
  scene::Simulation sim = scene::BuildSimulation(scene, w, 2);
  ASSERT_EQ(sim.world().bodies().size(), 50u);
  double total_mass = 0;
  for (const auto& b : sim.world().bodies()) total_mass += b.mass;
  double energy = sim.world().Diagnose().total_energy;
  const double start = energy;
  double deepest = 0;
  const std::int64_t steps = scene::StepCount(scene);
  for (std::int64_t i = 0; i < steps; ++i) {
    const dynamics::StepStatus s = sim.physics.Step(scene.dt);
    ASSERT_TRUE(s.ok) << s.message;
    const dynamics::ContactStats& st = sim.physics.stats();
    deepest = std::max(deepest, st.max_penetration);
    ASSERT_GE(st.dissipated, -1e-9 * std::abs(energy)) << "step " << i;
    const double now = sim.world().Diagnose().total_energy;
    // (plus 5e-7 of the energy: what the sweeps, stopped at 10⁻⁹ m/s or after 32, may leave in a
    // step of a settling pile; measured 1.1e-7 at most)
    ASSERT_LE(now, energy + total_mass * 9.81 * st.pushed + 5e-7 * std::abs(energy))
        << "step " << i << ": rose by " << now - energy << " J, pushed " << st.pushed << " m";
    energy = now;
  }
  EXPECT_LT(deepest, 0.5e-3);
  EXPECT_LT(energy, 0.2 * start);  // settled: most of the fall is spent
  for (std::size_t i = 0; i < sim.world().bodies().size(); ++i) {
    const Vector3 x = sim.world().bodies()[i].position;
    EXPECT_LT(std::abs(x.x()), 0.28) << "part " << i;  // the bin's inner walls
    EXPECT_LT(std::abs(x.y()), 0.18) << "part " << i;
    EXPECT_GT(x.z(), 0.02) << "part " << i;  // above its bottom
    EXPECT_LT(x.z(), 0.35) << "part " << i;
    EXPECT_LT(sim.world().bodies()[i].velocity.norm(), 0.05) << "part " << i;
  }
}

}  // namespace
