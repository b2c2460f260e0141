// Robot descriptions simulated: the example quadruped (data/robots/quadruped, written by
// make_quadruped.py as URDF, SDFormat and MJCF of one robot) moves the same whichever file it is
// read from; its inertials filled from its meshes match the file massprops fill writes, bit for
// bit, and the inertials the script computed (by its own divergence-theorem sums) to rounding;
// what cannot be simulated is refused, naming the element; the thread count changes no bit.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "bodies/robot.h"
#include "dynamics/contact.h"
#include "massprops/robot/robot.h"
#include "massprops/robot/robot_model.h"

namespace {

using dynamics::ContactWorld;
using dynamics::RigidBody;
using massprops::Vector3;

const std::string kDir = std::string(MASSPROPS_DATA_DIR) + "/robots/quadruped/";

// The robot dropped from 5 cm onto the ground, its legs a little bent, for `steps` of 1 ms.
std::vector<RigidBody> Drop(const massprops::RobotModel& model, long steps = 1000, int threads = 1) {
  dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
  ContactWorld world(std::move(w));
  world.set_num_threads(threads);
  world.AddGround({});
  dynamics::RobotOptions options;
  // The base 0.47 m up: the SDFormat and MJCF files stand it 0.41 m up in their world
  // (make_quadruped.py), which the pose moves; the URDF says nothing.
  options.pose.translation = Vector3(0, 0, model.format == massprops::RobotFormat::kUrdf ? 0.47 : 0.06);
  for (const char* leg : {"front_left", "front_right", "rear_left", "rear_right"}) {
    options.positions[std::string(leg) + "_hip"] = 0.3;
    options.positions[std::string(leg) + "_knee"] = -0.6;
  }
  dynamics::AddRobot(world, model, options);
  for (long s = 0; s < steps; ++s) {
    const dynamics::StepStatus st = world.Step(1e-3);
    EXPECT_TRUE(st.ok) << st.message;
    if (!st.ok) break;
  }
  return world.world().bodies();
}

double Difference(const std::vector<RigidBody>& a, const std::vector<RigidBody>& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d = std::max(d, (a[i].position - b[i].position).norm());
    d = std::max(d, (a[i].velocity - b[i].velocity).norm());
    d = std::max(d, a[i].orientation.angularDistance(b[i].orientation));
  }
  return d;
}

TEST(Robot, ReadsTheTreeOfEachFormat) {
  for (const char* file : {"quadruped.urdf", "quadruped.sdf", "quadruped.xml"}) {
    const massprops::RobotModel m = massprops::ReadRobotModel(kDir + file);
    int revolute = 0;
    for (const massprops::RobotJoint& j : m.joints) revolute += j.type == massprops::RobotJointType::kRevolute;
    EXPECT_EQ(revolute, 8) << file;
    ASSERT_EQ(m.Roots().size(), 1u) << file;
    EXPECT_EQ(m.links[static_cast<std::size_t>(m.Roots()[0])].name, "base_link") << file;
    const auto knee = std::find_if(m.joints.begin(), m.joints.end(),
                                   [](const massprops::RobotJoint& j) { return j.name == "rear_left_knee"; });
    ASSERT_NE(knee, m.joints.end()) << file;
    EXPECT_DOUBLE_EQ(*knee->lower, -2.4) << file;
    EXPECT_DOUBLE_EQ(knee->damping, 0.05) << file;
    EXPECT_TRUE(knee->axis.isApprox(Vector3::UnitY())) << file;
    // The knee 0.2 m below the hip, the hip at the body's rear left corner.
    EXPECT_NEAR((knee->parent_to_joint.Then(knee->joint_to_child).translation - Vector3(0, 0, -0.2)).norm(), 0, 1e-15)
        << file;
  }
}

TEST(Robot, UrdfSdfAndMjcfOfOneRobotMoveTheSame) {
  const std::vector<RigidBody> urdf = Drop(massprops::ReadRobotModel(kDir + "quadruped.urdf"));
  // 13 links, 4 welded or massless lumped: 9 bodies; it fell and landed.
  ASSERT_EQ(urdf.size(), 9u);
  EXPECT_LT(urdf[0].position.z(), 0.46);
  for (const char* file : {"quadruped.sdf", "quadruped.xml"}) {
    massprops::RobotModel model = massprops::ReadRobotModel(kDir + file);
    // MJCF geoms bring MuJoCo's friction (1 where the file states none); with the URDF's material
    // instead, the same robot moves the same.
    for (massprops::RobotLink& l : model.links) {
      for (massprops::RobotGeometry& g : l.collisions) {
        if (std::string(file) == "quadruped.xml") {
          EXPECT_EQ(g.friction, 1.0) << l.name;
        }
        g.friction.reset();
      }
    }
    const std::vector<RigidBody> other = Drop(model);
    ASSERT_EQ(other.size(), urdf.size()) << file;
    EXPECT_LT(Difference(urdf, other), 1e-9) << file;
  }
}

TEST(Robot, SameBitsOnAnyThreadCount) {
  const massprops::RobotModel model = massprops::ReadRobotModel(kDir + "quadruped.urdf");
  const std::vector<RigidBody> one = Drop(model, 400, 1), four = Drop(model, 400, 4);
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].position, four[i].position) << i;
    EXPECT_EQ(one[i].angular_momentum, four[i].angular_momentum) << i;
  }
}

TEST(Robot, FilledFromItsMeshesAsMasspropsFillWritesIt) {
  massprops::RobotModelOptions fill;
  fill.fill = true;
  const massprops::RobotModel filled = massprops::ReadRobotModel(kDir + "quadruped.urdf", fill);
  // The file `massprops fill` writes, read as it is.
  const std::string written = (std::filesystem::temp_directory_path() / "robot_test_filled.urdf").string();
  {
    std::ofstream out(written);
    out << massprops::FillRobotDescription(kDir + "quadruped.urdf").document;
  }
  // (Its meshes are named relative to the robot's folder.)
  std::filesystem::copy(kDir + "meshes", std::filesystem::temp_directory_path() / "meshes",
                        std::filesystem::copy_options::overwrite_existing | std::filesystem::copy_options::recursive);
  const std::vector<RigidBody> a = Drop(filled, 300), b = Drop(massprops::ReadRobotModel(written), 300);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position, b[i].position) << i;
    EXPECT_EQ(a[i].orientation.coeffs(), b[i].orientation.coeffs()) << i;
    EXPECT_EQ(a[i].velocity, b[i].velocity) << i;
  }
  // And the inertials as the script computed them, independently: to rounding.
  const massprops::RobotModel stated = massprops::ReadRobotModel(kDir + "quadruped.urdf");
  for (std::size_t l = 0; l < stated.links.size(); ++l) {
    const auto& s = stated.links[l].inertial;
    const auto& f = filled.links[l].inertial;
    ASSERT_EQ(s.has_value(), f.has_value()) << stated.links[l].name;
    if (!s) continue;
    EXPECT_NEAR(f->mass, s->mass, 1e-13 * s->mass) << stated.links[l].name;
    EXPECT_LT((f->center_of_mass - s->center_of_mass).norm(), 1e-14) << stated.links[l].name;
    EXPECT_LT((f->inertia - s->inertia).norm(), 1e-12 * s->inertia.norm()) << stated.links[l].name;
  }
}

// A robot file written into the temporary folder.
std::string Write(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

void ExpectRefused(const std::string& path, const std::string& words) {
  try {
    massprops::ReadRobotModel(path);
    ADD_FAILURE() << path << " was read";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

const char* kTwoLinks = R"(<robot name="r"><link name="a"><inertial><mass value="1"/>
<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
<link name="b"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
)";

TEST(Robot, RefusesWhatItCannotSimulate) {
  ExpectRefused(Write("mimic.urdf", std::string(kTwoLinks) +
                                        R"(<joint name="j" type="revolute"><parent link="a"/><child link="b"/>
<mimic joint="k"/></joint></robot>)"),
                "joint 'j' <mimic>: joint=\"k\" names no joint");
  ExpectRefused(Write("xacro.urdf", R"(<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
<xacro:macro name="leg"/></robot>)"),
                "expand the file first");
  ExpectRefused(
      Write("planar.urdf", std::string(kTwoLinks) +
                               R"(<joint name="p" type="planar"><parent link="a"/><child link="b"/></joint></robot>)"),
      "joint 'p': type \"planar\"");
  ExpectRefused(Write("loop.urdf", std::string(kTwoLinks) +
                                       R"(<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
<joint name="j2" type="fixed"><parent link="a"/><child link="b"/></joint></robot>)"),
                "closed loop");
  // Several hinges in one body are read (robot_multi_hinge_mujoco); a free joint beside another is not.
  ExpectRefused(Write("two_joints.xml", R"(<mujoco><worldbody><body name="b"><inertial mass="1" diaginertia="1 1 1"/>
<freejoint name="x"/><joint name="y" type="hinge"/></body></worldbody></mujoco>)"),
                "joint 'x': a free joint below another body, or beside other joints");
  ExpectRefused(
      Write("equality.xml", R"(<mujoco><worldbody/><equality><connect body1="a" anchor="0 0 0"/></equality></mujoco>)"),
      "<equality> <connect> connect #1: body1=\"a\" names no body");
  // Couplings, loops and tendons that name what is not there, or cannot be.
  const std::string hinge_body =
      R"(<body name="b"><joint name="h" type="hinge"/><inertial mass="1" diaginertia="1 1 1"/>
<site name="s"/></body>)";
  ExpectRefused(Write("self.xml", "<mujoco><worldbody>" + hinge_body +
                                      R"(</worldbody><equality><joint joint1="h" joint2="h"/></equality></mujoco>)"),
                "<equality> <joint> joint #1: it couples a coordinate to itself");
  ExpectRefused(Write("one_site.xml",
                      "<mujoco><worldbody>" + hinge_body +
                          R"(</worldbody><tendon><spatial name="t"><site site="s"/></spatial></tendon></mujoco>)"),
                "<tendon> <spatial> spatial 't': a spatial tendon needs two sites or more");
  ExpectRefused(Write("no_tendon.xml", "<mujoco><worldbody>" + hinge_body +
                                           R"(</worldbody><equality><tendon tendon1="ghost"/></equality></mujoco>)"),
                "tendon1=\"ghost\" names no tendon");
  ExpectRefused(Write("mimic_self.urdf", std::string(kTwoLinks) +
                                             R"(<joint name="j" type="revolute"><parent link="a"/><child link="b"/>
<mimic joint="j"/></joint></robot>)"),
                "joint 'j' <mimic>: the joint mimics itself");
  ExpectRefused(
      Write("ghost.urdf", std::string(kTwoLinks) +
                              R"(<joint name="j" type="fixed"><parent link="a"/><child link="c"/></joint></robot>)"),
      "<child link=\"c\"> names no link");
}

TEST(Robot, AMasslessLinkThatMovesIsRefusedByName) {
  const std::string path = Write("massless.urdf", R"(<robot name="r"><link name="a"><inertial><mass value="1"/>
<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link><link name="b"/>
<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>)");
  ContactWorld world;
  try {
    dynamics::AddRobot(world, massprops::ReadRobotModel(path));
    ADD_FAILURE() << "added";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("link 'b' has no mass"), std::string::npos) << e.what();
  }
}

}  // namespace
