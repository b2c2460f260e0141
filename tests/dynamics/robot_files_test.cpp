// Robot files as publishers write them (round five): where each format places its robot, ...
// Fixtures under tests/robot/field/, in the habits of the files they stand for.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bodies/robot.h"
#include "dynamics/contact.h"
#include "massprops/robot/robot_model.h"

namespace {

using dynamics::ContactWorld;
using massprops::Vector3;

const std::string kField = std::string(MASSPROPS_DATA_DIR) + "/../tests/robot/field/";

// As rbsim and scenes add a robot given no position: set down on the file's floors (or the
// default ground) unless the file places it.
struct Added {
  ContactWorld world;
  dynamics::RobotInWorld robot;
  massprops::Placement pose;
};
Added AddAsRbsimDoes(const massprops::RobotModel& model) {
  Added out;
  std::vector<dynamics::Ground> grounds;
  for (const massprops::RobotGround& g : model.grounds) grounds.push_back(dynamics::GroundOf(g));
  if (grounds.empty()) grounds.emplace_back();
  for (const dynamics::Ground& g : grounds) out.world.AddGround(g);
  dynamics::RobotOptions options;
  options.pose = dynamics::PlaceAboveGround(model, options, grounds, dynamics::kSetDownClearance);
  out.pose = options.pose;
  out.robot = dynamics::AddRobot(out.world, model, options);
  return out;
}

Vector3 CenterOf(const Added& a, std::size_t k) {
  return a.world.world().bodies()[static_cast<std::size_t>(a.robot.bodies.at(k))].position;
}

// The control suite's pendulum: a pole hinged to the world 0.6 m above the floor, its mass a
// 1 kg sphere 0.5 m up the pole (the pole's and the hinge's geoms massless). MuJoCo starts it
// there (qpos0); so do we, over the file's own floor.
TEST(RobotFiles, MjcfHingedToTheWorldStartsWhereTheFileSays) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "control/pendulum.xml");
  EXPECT_TRUE(dynamics::PlacedByItsFile(m, {}));
  const Added a = AddAsRbsimDoes(m);
  EXPECT_TRUE(a.pose.translation.isZero(0)) << a.pose.translation.transpose();
  ASSERT_EQ(a.robot.bodies.size(), 1u);
  EXPECT_LT((CenterOf(a, 0) - Vector3(0, 0, 1.1)).norm(), 1e-12) << CenterOf(a, 0).transpose();
  // The hinge's anchor: the body's frame origin, 0.5 m below the sphere, at 0.6 m.
  const massprops::Placement link = a.robot.body_in_link[0].Inverse();
  const dynamics::RigidBody& b = a.world.world().bodies()[0];
  EXPECT_LT((b.orientation * link.translation + b.position - Vector3(0, 0, 0.6)).norm(), 1e-12);
}

// The cart-pole: rails and cart 1 m up, the pole standing on the cart (a 1 m capsule of 0.1 kg,
// its center 0.5 m above the cart's).
TEST(RobotFiles, MjcfCartOnRailsStartsOnTheRails) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "control/cartpole.xml");
  const Added a = AddAsRbsimDoes(m);
  ASSERT_EQ(a.robot.bodies.size(), 2u);
  EXPECT_LT((CenterOf(a, 0) - Vector3(0, 0, 1)).norm(), 1e-12) << CenterOf(a, 0).transpose();
  EXPECT_LT((CenterOf(a, 1) - Vector3(0, 0, 1.5)).norm(), 1e-12) << CenterOf(a, 1).transpose();
}

// SDFormat places the model by its <pose> (x y z roll pitch yaw): the crate, free, at the model's
// pose then its own; the door hinged to the world where the model puts it.
TEST(RobotFiles, SdformatModelPoseIsWhereTheModelStands) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "placed_model.sdf");
  const Added a = AddAsRbsimDoes(m);
  ASSERT_EQ(a.robot.bodies.size(), 2u);
  EXPECT_LT((CenterOf(a, 0) - Vector3(1, 2.2, 0.5)).norm(), 1e-12) << CenterOf(a, 0).transpose();
  EXPECT_LT((CenterOf(a, 1) - Vector3(0, 2.25, 1.0)).norm(), 1e-12) << CenterOf(a, 1).transpose();
}

// URDF says nothing of where a free robot stands: it is set down, its lowest point 1 cm above
// the ground. A URDF bolted to its "world" link stays where the file bolts it.
TEST(RobotFiles, UrdfIsSetDownUnlessBoltedToTheWorld) {
  const massprops::RobotModel dog =
      massprops::ReadRobotModel(std::string(MASSPROPS_DATA_DIR) + "/robots/quadruped/quadruped.urdf");
  EXPECT_FALSE(dynamics::PlacedByItsFile(dog, {}));
  const Added a = AddAsRbsimDoes(dog);
  EXPECT_NEAR(a.pose.translation.z(), 0.41, 1e-12);  // legs 0.4 m below the base
  const massprops::RobotModel arm = massprops::ReadRobotModel(kField + "arm_on_world.urdf");
  EXPECT_TRUE(dynamics::PlacedByItsFile(arm, {}));
  EXPECT_TRUE(AddAsRbsimDoes(arm).pose.translation.isZero(0));
  // The same quadruped in MJCF and SDFormat stands where the file puts it: 0.41 m up.
  for (const char* file : {"quadruped.xml", "quadruped.sdf"}) {
    const Added b =
        AddAsRbsimDoes(massprops::ReadRobotModel(std::string(MASSPROPS_DATA_DIR) + "/robots/quadruped/" + file));
    EXPECT_TRUE(b.pose.translation.isZero(0)) << file;
    EXPECT_NEAR(CenterOf(b, 0).z(), CenterOf(a, 0).z(), 1e-12) << file;
  }
}

}  // namespace

namespace {

// A six-axis arm as ROS-Industrial support packages publish it: its base_link has geometry but no
// <inertial>, with massless 'base', 'flange' and 'tool0' frames welded on. ROS, Gazebo and
// PyBullet take the massless root as the world-fixed base: so do we (with a note), where the file
// puts it. Limp under gravity its arm falls in the x-z plane; the vertical first axis stays still.
TEST(RobotFiles, AMasslessRootIsTheWorldFixedBase) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "industrial/urdf/arm6.urdf");
  ASSERT_EQ(m.links.size(), 5u);  // link_1..3, flange and tool0 (welded to link_3); base_link and base: the world
  EXPECT_TRUE(dynamics::PlacedByItsFile(m, {}));
  bool noted = false;
  for (const std::string& n : m.notes) noted |= n.find("link 'base_link' has no mass") != std::string::npos;
  EXPECT_TRUE(noted);
  dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
  ContactWorld world(std::move(w));
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m);
  ASSERT_EQ(added.bodies.size(), 3u);
  const auto body = [&](int k) { return world.world().bodies()[static_cast<std::size_t>(added.bodies[k])]; };
  EXPECT_LT((body(0).position - Vector3(0, 0, 0.2)).norm(), 1e-15);
  EXPECT_LT((body(2).position - Vector3(0.1, 0, 0.6)).norm(), 1e-15);
  for (int s = 0; s < 300; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  EXPECT_LT((body(0).position - Vector3(0, 0, 0.2)).norm(), 1e-12);  // bolted down
  EXPECT_LT(std::abs(world.world().joint_state(added.joint_of[0]).position[0]), 1e-12);
  EXPECT_LT(body(2).position.z(), 0.55);  // the forearm fell
  // With --fill the base_link takes an inertial from its geometry: every link stays a link.
  massprops::RobotModelOptions fill;
  fill.fill = true;
  EXPECT_EQ(massprops::ReadRobotModel(kField + "industrial/urdf/arm6.urdf", fill).links.size(), 7u);
}

}  // namespace

namespace {

// MJCF's ref: the file draws each body at its joint's ref, where the joint starts and from which
// MuJoCo measures it; springref is the spring's rest. The slide, ref 0.2 and springref 0.3 under a
// 50 N/m spring with 2 kg, undamped: q(t) = 0.3 − 0.1 cos(5 t). (ref.xml against MuJoCo itself:
// ctest robot_ref_mujoco.)
TEST(RobotFiles, MjcfRefIsWhereTheJointStartsAndItsZeroIsMuJoCos) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "mjcf/ref.xml");
  ContactWorld world;
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m);
  const double deg = massprops::kPi / 180;
  const std::vector<std::pair<std::string, double>> starts = {
      {"shoulder", -30 * deg}, {"elbow", 60 * deg}, {"rail", 0.2}, {"twin", 10 * deg}};
  int rail = -1;
  for (const auto& [name, q] : starts) {
    std::size_t k = 0;
    while (k < m.joints.size() && m.joints[k].name != name) ++k;
    ASSERT_LT(k, m.joints.size()) << name;
    const int j = added.joint_of[k];
    EXPECT_NEAR(world.world().joint_state(j).position[0], q, 1e-15) << name;
    if (name == "rail") rail = j;
  }
  // Drawn where the file draws them: the upper arm's capsule (0.4 m, along its x) turned −30° about
  // y from (0, 0, 1); the carriage at (0.2, 0.5, 1).
  const Vector3 upper = world.world().bodies()[static_cast<std::size_t>(added.bodies[0])].position;
  EXPECT_LT((upper - Vector3(0.2 * std::cos(30 * deg), 0, 1 + 0.2 * std::sin(30 * deg))).norm(), 1e-12)
      << upper.transpose();
  const Vector3 carriage = world.world().bodies()[static_cast<std::size_t>(added.bodies[2])].position;
  EXPECT_LT((carriage - Vector3(0.2, 0.5, 1)).norm(), 1e-12) << carriage.transpose();
  for (int s = 0; s < 300; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  EXPECT_NEAR(world.world().joint_state(rail).position[0], 0.3 - 0.1 * std::cos(5 * 0.3), 1e-6);
}

}  // namespace

namespace {

// Light links on damped joints (a hand's phalanges, 1 g and 10⁻⁷ kg m², damping 0.05 N m s/rad:
// h c / I = 500 at 1 ms): the midpoint solve takes the dampers implicitly, so every 1 ms step
// converges without sub-steps, and the result is the time-converged one (the same hand at
// 0.1 ms) to 10⁻⁶ rad. (Before, the solve failed even at 1024 sub-steps; side by side with MuJoCo:
// ctest robot_light_hand_mujoco.)
TEST(RobotFiles, LightLinksOnDampedJointsStepWithoutSubsteps) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "mjcf/light_hand.xml");
  auto run = [&](double h, bool count_substeps) {
    dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
    ContactWorld world(std::move(w));
    dynamics::RobotOptions options;
    options.keyframe = "open";
    const dynamics::RobotInWorld added = dynamics::AddRobot(world, m, options);
    const long steps = std::lround(0.3 / h);
    for (long s = 0; s < steps; ++s) {
      const dynamics::StepStatus st = world.Step(h);
      EXPECT_TRUE(st.ok) << st.message;
      if (count_substeps) {
        EXPECT_EQ(st.substeps, 1) << "step " << s;  // (1: the step itself)
      }
      if (!st.ok || (count_substeps && st.substeps != 1)) break;
    }
    std::vector<double> q;
    for (const int j : added.joint_of) {
      if (j >= 0) q.push_back(world.world().joint_state(j).position[0]);
    }
    return q;
  };
  const std::vector<double> coarse = run(1e-3, true), fine = run(1e-4, false);
  ASSERT_EQ(coarse.size(), 16u);
  for (std::size_t k = 0; k < coarse.size(); ++k) EXPECT_NEAR(coarse[k], fine[k], 1e-6) << k;
}

}  // namespace

namespace {

// MuJoCo 3 habits (mujoco3.xml): <frame>s placing a body and a geom, a <replicate> of spokes,
// actuatorfrcrange, <size memory>, <extension><plugin>, option flags. Read as the same model as the
// file written out by hand in MuJoCo 2.2's terms (mujoco3_expanded.xml): the same bodies where the
// same, the same inertias (to the 8 digits of the replicate's quarter turn), the joint's
// actuatorfrcrange as the motor's forcerange; and they move the same.
TEST(RobotFiles, MuJoCo3FramesAndReplicatesReadAsTheirExpansion) {
  const massprops::RobotModel m3 = massprops::ReadRobotModel(kField + "mjcf/mujoco3.xml");
  const massprops::RobotModel m2 = massprops::ReadRobotModel(kField + "mjcf/mujoco3_expanded.xml");
  ASSERT_EQ(m3.links.size(), m2.links.size());
  ASSERT_EQ(m3.actuators.size(), 1u);
  ASSERT_TRUE(m3.actuators[0].forcerange);
  EXPECT_EQ(*m3.actuators[0].forcerange, std::make_pair(-2.0, 2.0));  // the joint's own, not its class's ±5
  for (std::size_t k = 0; k < m3.links.size(); ++k) {
    ASSERT_TRUE(m3.links[k].inertial && m2.links[k].inertial) << k;
    EXPECT_NEAR(m3.links[k].inertial->mass, m2.links[k].inertial->mass, 1e-12) << k;
    EXPECT_LT((m3.links[k].inertial->inertia - m2.links[k].inertial->inertia).norm(), 1e-9) << k;
    EXPECT_LT((m3.links[k].inertial->center_of_mass - m2.links[k].inertial->center_of_mass).norm(), 1e-9) << k;
  }
  auto run = [](const massprops::RobotModel& m) {
    dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
    ContactWorld world(std::move(w));
    for (const massprops::RobotGround& g : m.grounds) world.AddGround(dynamics::GroundOf(g));
    dynamics::AddRobot(world, m);
    for (int s = 0; s < 300; ++s) EXPECT_TRUE(world.Step(1e-3).ok);
    return world.world().bodies();
  };
  const auto a = run(m3), b = run(m2);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_LT((a[k].position - b[k].position).norm(), 1e-7) << k;
  bool replicate = false;
  for (const std::string& n : m3.notes) replicate |= n.find("<replicate>") != std::string::npos;
  EXPECT_TRUE(replicate);
  EXPECT_EQ(m3.links[1].gravity_compensation, 0.25);  // (the scene holds up a quarter of the wheel)
}

}  // namespace

namespace {

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

// The file's world as rbsim makes it: its floors and its terrains (height fields, static).
ContactWorld FileWorld(const massprops::RobotModel& m) {
  dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
  ContactWorld world(std::move(w));
  for (const massprops::RobotGround& g : m.grounds) world.AddGround(dynamics::GroundOf(g));
  for (const massprops::RobotTerrain& t : m.terrains) {
    world.AddStatic(dynamics::TerrainCollider(t), t.pose.rotation, t.pose.translation);
  }
  return world;
}

// A box on a height field that rises linearly along x (a 2 × 2 PNG, 0 and 255 across: the 1 in 4
// slope of its size), both of friction 0.1: it slides straight down the slope at
// a = g (sin θ − μ cos θ), as down the equivalent plane.
TEST(RobotFiles, ABoxSlidesDownATiltedHeightFieldAsDownThePlane) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "mjcf/hfield_slope.xml");
  ASSERT_EQ(m.terrains.size(), 1u);
  ContactWorld world = FileWorld(m);
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m);
  const Vector3 start = world.world().bodies()[static_cast<std::size_t>(added.bodies[0])].position;
  for (int s = 0; s < 500; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  const double theta = std::atan(0.25), a = 9.81 * (std::sin(theta) - 0.1 * std::cos(theta));
  const dynamics::RigidBody& box = world.world().bodies()[static_cast<std::size_t>(added.bodies[0])];
  const Vector3 down(-std::cos(theta), 0, -std::sin(theta));
  EXPECT_NEAR(box.velocity.dot(down) / (a * 0.5) - 1, 0, 1e-3) << box.velocity.transpose();
  EXPECT_LT(std::abs(box.velocity.y()), 1e-6);
  EXPECT_NEAR((box.position - start).dot(down) / (0.5 * a * 0.25) - 1, 0, 5e-3);
}

// A ball dropped on the lowest point of a bowl-shaped height field (a 21 × 21 PNG of x² + y²)
// stays there, on it (the landing's kick from the grid's diagonals leaves it rolling to and fro
// within 0.6 mm: nothing resists rolling); a size-only height field (MuJoCo fills it with zeros)
// is a flat floor at z = 0.
TEST(RobotFiles, ABallRestsAtTheBowlsLowestPointAndASizeOnlyFieldIsFlat) {
  const std::string bowl = Write("hfield_bowl_center.xml", R"(<mujoco><asset>
  <hfield name="bowl" size="0.5 0.5 0.2 0.05" file=")" + kField +
                                                               R"(mjcf/bowl.png"/>
  <hfield name="blank" size="1 1 1 0.1" nrow="8" ncol="8"/></asset>
  <worldbody><geom type="hfield" hfield="bowl"/><geom type="hfield" hfield="blank" pos="3 0 0"/>
  <body name="ball" pos="0 0 0.08"><freejoint/><geom type="sphere" size="0.03" mass="0.1"/></body>
  <body name="cube" pos="3 0.2 0.1"><freejoint/><geom type="box" size="0.05 0.05 0.05" mass="0.5"/></body>
  </worldbody></mujoco>)");
  const massprops::RobotModel m = massprops::ReadRobotModel(bowl);
  ASSERT_EQ(m.terrains.size(), 2u);
  ContactWorld world = FileWorld(m);
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m);
  for (int s = 0; s < 1500; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  const auto& b = world.world().bodies();
  const Vector3 ball = b[static_cast<std::size_t>(added.bodies[0])].position;
  const Vector3 cube = b[static_cast<std::size_t>(added.bodies[1])].position;
  EXPECT_LT(ball.head<2>().norm(), 1e-3) << ball.transpose();
  EXPECT_NEAR(ball.z(), 0.03, 1e-4);
  EXPECT_NEAR(cube.z(), 0.05, 1e-4);
  EXPECT_LT(b[static_cast<std::size_t>(added.bodies[1])].velocity.norm(), 1e-6);
}

}  // namespace

namespace {

// Falling is no reason for a joint to move: a trunk with a shoulder and an elbow (stops, damping,
// joint friction), its yaw and elbow on their stops, falls 10 s from rest (to 98 m/s) with no
// ground. Every joint stays where it was to 10⁻⁹ rad. (Before: a stop's end placed the joint on
// its limit and took the velocity from the momenta there, turning the base's growing momentum
// into joint rates; at 7.7 s the elbow was driven through its stop at 10 rad/s and the step
// failed.)
TEST(RobotFiles, AFallingRobotsJointsOnTheirStopsStayPut) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "shoulder_arm.urdf");
  dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
  ContactWorld world(std::move(w));
  dynamics::RobotOptions options;
  options.pose.rotation = Eigen::AngleAxisd(massprops::kPi / 2, Vector3::UnitX()).toRotationMatrix();
  options.positions = {{"shoulder_roll", 1.2}, {"shoulder_yaw", 1.5}, {"elbow", 0.0}};
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m, options);
  for (int s = 0; s < 10000; ++s) {
    const dynamics::StepStatus st = world.Step(1e-3);
    ASSERT_TRUE(st.ok) << "t = " << world.world().time() << ": " << st.message;
  }
  EXPECT_NEAR(world.world().bodies()[0].velocity.z(), -98.1, 1e-9);
  const std::vector<double> start = {0.0, 1.2, 1.5, 0.0};
  for (std::size_t k = 0; k < m.joints.size(); ++k) {
    const dynamics::JointState js = world.world().joint_state(added.joint_of[k]);
    EXPECT_NEAR(js.position[0], start[k], 1e-9) << m.joints[k].name;
    EXPECT_LT(std::abs(js.velocity[0]), 1e-9) << m.joints[k].name;
  }
}

}  // namespace
