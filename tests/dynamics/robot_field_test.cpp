// Robot descriptions as vendors publish them (tests/robot/field/, written in the habits of the
// SolidWorks exporter and of ROS packages): what does not move a rigid body is read past with one
// note per kind, the URDF "world" link is the world frame, a collision mesh that is no solid still
// gives its hull. A pendulum hinged to the world swings at its elliptic-integral half period.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "bodies/bodies.h"
#include "bodies/robot.h"
#include "dynamics/contact.h"
#include "massprops/robot/robot_model.h"
#include "massprops/wording.h"

namespace {

using dynamics::ContactWorld;
using massprops::Matrix3;
using massprops::Vector3;

const std::string kField = std::string(MASSPROPS_DATA_DIR) + "/../tests/robot/field/";
constexpr double kG = 9.81;

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

bool AnyContains(const std::vector<std::string>& notes, const std::string& words) {
  for (const std::string& n : notes) {
    if (n.find(words) != std::string::npos) return true;
  }
  return false;
}

ContactWorld WorldWithGravity(bool ground) {
  dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  ContactWorld world(std::move(w));
  if (ground) world.AddGround({});
  return world;
}

TEST(RobotField, ControlMetadataZeroAxesAndXacroNamespaceAreReadPast) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "arm_on_world.urdf");
  ASSERT_EQ(m.links.size(), 3u);  // base_link, upper_arm, lidar_link: "world" is no link
  // One note per kind, with its count.
  EXPECT_TRUE(AnyContains(m.notes, "<transmission> (1)"));
  EXPECT_TRUE(AnyContains(m.notes, "<gazebo> (3)"));
  EXPECT_TRUE(AnyContains(m.notes, "<ros2_control> (1)"));
  int from_world = 0;
  for (const massprops::RobotJoint& j : m.joints) from_world += j.parent < 0;
  EXPECT_EQ(from_world, 1);
}

TEST(RobotField, XacroLeftUnexpandedIsRefusedNamingIt) {
  const std::string head = R"(<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
)";
  for (const auto& [body, words] : std::vector<std::pair<std::string, std::string>>{
           {R"(<xacro:include filename="$(find r)/urdf/leg.xacro"/>)", "<xacro:include> is xacro"},
           {R"(<link name="a"><inertial><mass value="${m}"/></inertial></link>)", "<mass value=\"${m}\">"}}) {
    const std::string path = Write("xacro_left.urdf", head + body + "</robot>");
    try {
      massprops::ReadRobotModel(path);
      ADD_FAILURE() << body << " was read";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("expand"), std::string::npos) << e.what();
    }
  }
}

// The bar hinged to the world (pendulum_on_world.urdf) released from horizontal: its next turning
// point comes after half the period of a pendulum of amplitude π/2,
// T/2 = 2 √(I_pivot / (m g d)) K(1/√2).
TEST(RobotField, PendulumHingedToTheWorldLinkSwingsAtItsHalfPeriod) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "pendulum_on_world.urdf");
  ASSERT_EQ(m.links.size(), 1u);
  ContactWorld world = WorldWithGravity(false);
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m);
  ASSERT_EQ(added.bodies.size(), 1u);
  const int hinge = added.joint_of.at(0);
  ASSERT_GE(hinge, 0);
  // The hinge 1 m up, the bar's center 0.25 m out along x.
  EXPECT_LT((world.world().bodies()[0].position - Vector3(0.25, 0, 1)).norm(), 1e-15);
  const double mass = 2.0, d = 0.25, i_pivot = 0.0419333333333333 + mass * d * d;
  const double k_of_inverse_sqrt2 = 1.8540746773013719;  // K(1/√2), the complete elliptic integral of the first kind
  const double half_period = 2 * std::sqrt(i_pivot / (mass * kG * d)) * k_of_inverse_sqrt2;
  const double h = 1e-4;
  double t_turn = 0, v_before = 0;
  for (int s = 0; s < 20000 && t_turn == 0; ++s) {
    const dynamics::StepStatus st = world.Step(h);
    ASSERT_TRUE(st.ok) << st.message;
    const double v = world.world().joint_state(hinge).velocity[0];
    if (s > 10 && v_before > 0 && v <= 0) t_turn = world.world().time() - h * v / (v - v_before);
    v_before = v;
  }
  ASSERT_GT(t_turn, 0);
  EXPECT_NEAR(t_turn / half_period - 1, 0, 3e-5) << t_turn << " s vs " << half_period << " s";
  EXPECT_NEAR(world.world().joint_state(hinge).position[0], massprops::kPi, 1e-3);
}

// The arm bolted to the world by the file's fixed joint: its base stays where the file puts it
// (0.5 m up), under as-written, fixed and floating bases alike for the placement; its upper arm
// swings. The base's collision mesh repeats three faces: its hull needs only the points.
TEST(RobotField, ArmBoltedToTheWorldStaysAndAMeshWithRepeatedFacesIsAHull) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "arm_on_world.urdf");
  ContactWorld world = WorldWithGravity(true);
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m);
  EXPECT_TRUE(AnyContains(added.notes, "bracket_repeated.stl")) << ::testing::PrintToString(added.notes);
  EXPECT_TRUE(AnyContains(added.notes, "link 'base_link'"));
  ASSERT_EQ(added.bodies.size(), 2u);  // the lidar welded to the base
  const Vector3 base = world.world().bodies()[0].position;
  EXPECT_NEAR(base.z(), 0.5 - 0.04 * 0.1 / 2.5, 1e-12);  // the lidar's 0.1 kg 4 cm below
  for (int s = 0; s < 500; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  EXPECT_LT((world.world().bodies()[0].position - base).norm(), 1e-12);
  EXPECT_LT(world.world().bodies()[1].position.z(), 0.55 - 0.02);  // the arm swung down from horizontal
  // The same placement with the base fixed or floating by option.
  for (const auto base_option : {dynamics::RobotOptions::Base::kFixed, dynamics::RobotOptions::Base::kFloating}) {
    ContactWorld other = WorldWithGravity(false);
    dynamics::RobotOptions options;
    options.base = base_option;
    dynamics::AddRobot(other, m, options);
    EXPECT_LT((other.world().bodies()[0].position - base).norm(), 1e-15);
  }
}

// What is drawn: each link's <visual>s in its body's frame (the lidar's STL on the base it is
// welded to, 4 cm below; the arm's box along its length). The base's visual mesh is missing from
// the package: a note, not a refusal.
TEST(RobotField, VisualsAreDrawnWhereTheirLinksAreAndAMissingOneIsANote) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "arm_on_world.urdf");
  EXPECT_TRUE(AnyContains(m.notes, "link 'base_link': visual geometry not drawn")) << ::testing::PrintToString(m.notes);
  ContactWorld world = WorldWithGravity(false);
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m);
  std::vector<std::string> notes;
  const std::vector<massprops::TriangleMesh> visuals = dynamics::VisualShapes(m, added, {}, notes);
  ASSERT_EQ(visuals.size(), 2u);
  auto world_box = [&](std::size_t k) {
    const dynamics::RigidBody& b = world.world().bodies()[static_cast<std::size_t>(added.bodies[k])];
    Eigen::AlignedBox3d box;
    for (Eigen::Index v = 0; v < visuals[k].V.rows(); ++v) {
      box.extend(b.orientation * Vector3(visuals[k].V.row(v).transpose()) + b.position);
    }
    return box;
  };
  EXPECT_EQ(visuals[0].F.rows(), 12);  // the lidar's cube alone
  const Eigen::AlignedBox3d lidar = world_box(0);
  EXPECT_LT((lidar.min() - Vector3(-0.01, -0.01, 0.45)).norm(), 1e-12);
  EXPECT_LT((lidar.max() - Vector3(0.01, 0.01, 0.47)).norm(), 1e-12);
  const Eigen::AlignedBox3d arm = world_box(1);  // horizontal at q = 0, from the shoulder 5 cm up
  EXPECT_LT((arm.min() - Vector3(0, -0.025, 0.525)).norm(), 1e-12);
  EXPECT_LT((arm.max() - Vector3(0.4, 0.025, 0.575)).norm(), 1e-12);
  // MJCF: the geoms that collide with nothing are the visuals.
  const massprops::RobotModel biped = massprops::ReadRobotModel(kField + "mjcf/scene.xml");
  std::size_t drawn = 0;
  for (const massprops::RobotLink& l : biped.links) drawn += l.visuals.size();
  EXPECT_EQ(drawn, 1u);
}

// An MJCF package as MuJoCo Menagerie ships one: scene.xml includes the robot (resolved from the
// main file's folder) and adds a floor, lights and a skybox; the robot's collision geoms have
// mass 0 and density 0, their bodies' <inertial>s the mass. The collision geoms still collide:
// dropped from the file's pose (its servos holding ctrl 0), the biped lands on the file's own
// floor (2 cm below z = 0) and stays on it; from its keyframe "stand" it stands, its pelvis where
// straight legs put it (MuJoCo reading the same file: ctest robot_stands_mujoco).
TEST(RobotField, MjcfSceneIncludesItsRobotAndMasslessGeomsLandOnItsFloor) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "mjcf/scene.xml");
  ASSERT_EQ(m.links.size(), 5u);
  EXPECT_TRUE(AnyContains(m.notes, "<include file=\"biped.xml\"> followed"));
  EXPECT_TRUE(AnyContains(m.notes, "<camera> (1)"));
  EXPECT_TRUE(AnyContains(m.notes, "<light> (2)"));
  ASSERT_EQ(m.grounds.size(), 1u);
  EXPECT_TRUE(m.grounds[0].normal.isApprox(Vector3::UnitZ()));
  EXPECT_DOUBLE_EQ(m.grounds[0].offset, -0.02);
  // Every collision geom is there (not the visual one), the joint ranges are limits (autolimits).
  std::size_t geoms = 0;
  for (const massprops::RobotLink& l : m.links) geoms += l.collisions.size();
  EXPECT_EQ(geoms, 7u);
  for (const massprops::RobotJoint& j : m.joints) {
    if (j.type == massprops::RobotJointType::kRevolute) {
      EXPECT_TRUE(j.lower && j.upper) << j.name;
    }
  }
  ContactWorld world = WorldWithGravity(false);
  for (const massprops::RobotGround& g : m.grounds) world.AddGround(dynamics::GroundOf(g));
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m);
  for (int s = 0; s < 2000; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  // On the floor, standing or fallen: the pelvis box (5 cm half height) no lower than on its face.
  for (std::size_t k = 0; k < added.bodies.size(); ++k) {
    const Vector3 p = world.world().bodies()[static_cast<std::size_t>(added.bodies[k])].position;
    EXPECT_GT(p.z(), -0.02) << added.body_names[k];
    EXPECT_LT(p.z(), 0.7) << added.body_names[k];
  }
  EXPECT_GT(world.world().bodies()[0].position.z(), -0.02 + 0.05 - 0.005);
  // From "stand": the feet on the floor, the pelvis 0.05 + 0.3 + 0.3 + 0.01 above its bottom.
  ContactWorld standing = WorldWithGravity(false);
  for (const massprops::RobotGround& g : m.grounds) standing.AddGround(dynamics::GroundOf(g));
  dynamics::RobotOptions stand;
  stand.keyframe = "stand";
  const dynamics::RobotInWorld biped = dynamics::AddRobot(standing, m, stand);
  for (int s = 0; s < 2000; ++s) ASSERT_TRUE(standing.Step(1e-3).ok);
  EXPECT_NEAR(standing.world().bodies()[static_cast<std::size_t>(biped.bodies[0])].position.z(), -0.02 + 0.66, 1e-3);
  for (int j : biped.joint_of) {
    if (j >= 0 && standing.world().joints()[static_cast<std::size_t>(j)].type == dynamics::JointType::kRevolute) {
      EXPECT_NEAR(standing.world().joint_state(j).position[0], 0, 1e-3);
    }
  }
}

// One link, three collision boxes: it collides as the three boxes (a compound), not as their
// hull. Set over a hurdle narrower than the gap between its legs and lower than them, the staple
// stands on its feet on the ground; its hull could only lie on the hurdle.
TEST(RobotField, ALinksBoxesCollideEachOnItsOwn) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "staple.urdf");
  ContactWorld world = WorldWithGravity(true);
  world.AddStatic({dynamics::shape::Box{Vector3(0.08, 0.05, 0.05)}}, Matrix3::Identity(), Vector3(0, 0, 0.05));
  dynamics::RobotOptions options;
  options.pose.translation = Vector3(0, 0, 0.005);
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m, options);
  ASSERT_EQ(added.bodies.size(), 1u);
  EXPECT_EQ(std::string(dynamics::ShapeName(dynamics::Shape(dynamics::shape::Compound{}))), "compound");
  for (int s = 0; s < 1000; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  const dynamics::RigidBody& b = world.world().bodies()[0];
  // Its center of mass 0.13667 m above its feet, the feet on the ground (within the contact's
  // slop, half a percent of its size), upright.
  EXPECT_NEAR(b.position.z(), 0.1366666666666667, 1e-3);
  EXPECT_LT(b.velocity.norm(), 1e-3);
}

TEST(RobotField, MjcfCollisionBitsDecideWhatTouches) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "mjcf/masks.xml");
  // No <inertial>s: MuJoCo's inertiafromgeom="auto" takes each body's from its geom, a solid
  // sphere of 1 kg and radius 0.1 m: I = 2/5 m r².
  ASSERT_TRUE(m.links[0].inertial.has_value());
  EXPECT_DOUBLE_EQ(m.links[0].inertial->mass, 1.0);
  EXPECT_NEAR(m.links[0].inertial->inertia(0, 0), 0.4 * 0.01, 1e-15);
  EXPECT_TRUE(AnyContains(m.notes, "inertiafromgeom"));
  ContactWorld world = WorldWithGravity(false);
  for (const massprops::RobotGround& g : m.grounds) world.AddGround(dynamics::GroundOf(g));
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m);
  ASSERT_EQ(added.bodies.size(), 6u);
  ASSERT_EQ(m.excluded.size(), 1u);
  EXPECT_TRUE(AnyContains(m.notes, "1 <contact><pair>(s) between geoms of one body (or two floors)"));
  for (int s = 0; s < 1000; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  auto z = [&](const char* name) {
    for (std::size_t k = 0; k < added.bodies.size(); ++k) {
      if (added.body_names[k] == name)
        return world.world().bodies()[static_cast<std::size_t>(added.bodies[k])].position.z();
    }
    ADD_FAILURE() << name;
    return 0.0;
  };
  EXPECT_NEAR(z("ball"), 0.1, 1e-3);
  EXPECT_LT(z("ghost"), -2.0);  // through the ball and the floor: free fall from 0.5 m for 1 s
  EXPECT_NEAR(z("other_ball"), 0.1, 1e-3);
  EXPECT_NEAR(z("lander"), 0.3, 2e-3);  // on the ball
  EXPECT_NEAR(z("third_ball"), 0.1, 1e-3);
  EXPECT_NEAR(z("dropper"), 0.1, 1e-3);  // excluded from the ball: through it, onto the floor
  EXPECT_THROW(world.ExcludePair(0, 0), std::invalid_argument);
  EXPECT_THROW(world.ExcludePair(0, 6), std::invalid_argument);
}

// Friction per geom, mixed as MuJoCo mixes it (the larger of a pair's coefficients), each geom of a
// body with its own: pushed at v = 2 m/s on a floor of friction 0.1, a box of 0.4 stops after
// v²/(2 μ g); a body on three spheres (front 0.6, back 0.2, 2 cm below its center of mass, 0.1 m
// ahead and behind it) stops at the deceleration its shifted weight gives; a geom that states no
// friction takes MuJoCo's default, 1.
TEST(RobotField, EachGeomSlidesWithItsOwnFrictionMixedByTheLarger) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "mjcf/friction.xml");
  ASSERT_EQ(m.grounds.size(), 1u);
  EXPECT_EQ(m.grounds[0].friction, 0.1);
  EXPECT_EQ(m.links[0].collisions[0].friction, 0.4);  // from its class
  EXPECT_EQ(m.links[2].collisions[0].friction, 1.0);  // MuJoCo's default
  EXPECT_TRUE(AnyContains(m.notes, "1 geom(s) with condim 1: frictionless contact is not modelled"));
  ContactWorld world = WorldWithGravity(false);
  for (const massprops::RobotGround& g : m.grounds) world.AddGround(dynamics::GroundOf(g));
  dynamics::RobotOptions options;
  options.keyframe = "push";
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m, options);
  ASSERT_EQ(added.bodies.size(), 3u);
  const double h = 1e-3, v = 2;
  for (int s = 0; s < 800; ++s) ASSERT_TRUE(world.Step(h).ok);
  auto body = [&](int k) -> const dynamics::RigidBody& {
    return world.world().bodies()[static_cast<std::size_t>(added.bodies[static_cast<std::size_t>(k)])];
  };
  // The box: μ = max(0.4, 0.1) (the geometric mean would give 0.2 and twice the distance).
  EXPECT_NEAR(body(0).position.x(), v * v / (2 * 0.4 * kG), 3e-3);
  EXPECT_LT(body(0).velocity.norm(), 1e-6);
  // The tripod: weight on the front Nf / (m g) = (d + h μb) / (2 d + h (μb − μf)).
  const double d = 0.1, lever = 0.02, front = 0.6, back = 0.2;
  const double nf = (d + lever * back) / (2 * d + lever * (back - front));
  const double mu = front * nf + back * (1 - nf);  // 0.41667; 0.4 if the weight stayed even
  EXPECT_NEAR(body(1).position.x(), v * v / (2 * mu * kG), 3e-3);
  EXPECT_LT(body(1).velocity.norm(), 1e-6);
  EXPECT_NEAR(body(1).position.y(), 0.5, 1e-9);  // no yaw: it slid straight
  // The puck: μ = max(1, 0.1).
  EXPECT_NEAR(body(2).position.x(), v * v / (2 * 1.0 * kG), 3e-3);
  EXPECT_LT(body(2).velocity.norm(), 1e-6);
}

// <contact><pair>: a pair's geoms touch whatever their bits (a box of bits 0 and 0 paired with
// the floor lands on it; unpaired, it falls through), and each geom of a body collides with its
// own bits (two spheres of 2 and 2 touch a floor of 3 and 3).
TEST(RobotField, PairedGeomsTouchWhateverTheirBits) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "mjcf/pairs.xml");
  EXPECT_TRUE(AnyContains(m.notes, "1 <contact><pair>(s) give their own friction"))
      << ::testing::PrintToString(m.notes);
  ASSERT_EQ(m.links[0].collisions.size(), 1u);  // paired: a collision geom despite its bits
  EXPECT_EQ(m.links[1].collisions.size(), 0u);  // unpaired: drawn only
  EXPECT_EQ(m.links[1].visuals.size(), 2u);
  ContactWorld world = WorldWithGravity(false);
  for (const massprops::RobotGround& g : m.grounds) world.AddGround(dynamics::GroundOf(g));
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m);
  for (int s = 0; s < 600; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  auto z = [&](int k) {
    return world.world().bodies()[static_cast<std::size_t>(added.bodies[static_cast<std::size_t>(k)])].position.z();
  };
  EXPECT_NEAR(z(0), 0.02, 1e-3);
  EXPECT_LT(z(1), 0.2 - 0.5 * kG * 0.6 * 0.6 + 1e-6);  // free fall for 0.6 s
  EXPECT_NEAR(z(2), 0.03, 1e-3);
}

// MJCF armature (from the joint defaults): a hinged bar's small-amplitude period is
// 2π √((I_pivot + a) / (m g d)) (1 + θ0²/16 + 11 θ0⁴/3072), and the world's energy counts ½ a θ̇²:
// swung from 1 rad it stays constant, where leaving the term out would lose a quarter of the
// swing's energy at the bottom.
TEST(RobotField, ArmatureAddsToTheHingesInertiaAndItsEnergyIsCounted) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "mjcf/armature_pendulum.xml");
  ASSERT_EQ(m.joints.size(), 1u);
  EXPECT_DOUBLE_EQ(m.joints[0].armature, 0.05);
  const double mass = 2, d = 0.25, a = 0.05, i_pivot = 0.0419333333333333 + mass * d * d;
  for (const double theta0 : {0.01, 1.0}) {
    ContactWorld world = WorldWithGravity(false);
    dynamics::RobotOptions options;
    options.positions["hinge"] = theta0;
    const dynamics::RobotInWorld added = dynamics::AddRobot(world, m, options);
    const int hinge = added.joint_of.at(0);
    const double e0 = world.world().Diagnose().total_energy;
    double worst = 0, v_before = 0;
    std::vector<double> turns;  // the times θ̇ crosses zero downwards (θ at its top)
    const double h = 1e-4;
    for (int s = 0; s < 50000; ++s) {
      ASSERT_TRUE(world.Step(h).ok);
      worst = std::max(worst, std::abs(world.world().Diagnose().total_energy - e0));
      const double v = world.world().joint_state(hinge).velocity[0];
      if (s > 0 && v_before > 0 && v <= 0) turns.push_back(world.world().time() - h * v / (v - v_before));
      v_before = v;
    }
    if (theta0 == 0.01) {
      ASSERT_GE(turns.size(), 3u);
      const double period = (turns.back() - turns.front()) / static_cast<double>(turns.size() - 1);
      const double want = 2 * massprops::kPi * std::sqrt((i_pivot + a) / (mass * kG * d)) *
                          (1 + theta0 * theta0 / 16 + 11 * std::pow(theta0, 4) / 3072);
      EXPECT_NEAR(period / want - 1, 0, 3e-5) << period << " s vs " << want << " s";
    } else {
      const double swing = mass * kG * d * (1 - std::cos(theta0));
      EXPECT_LT(worst, 1e-6 * swing) << "energy drift " << worst << " J of a swing of " << swing << " J";
    }
  }
}

// A keyframe's free-joint qvel, in MuJoCo's convention (the frame's linear velocity in the world,
// its angular velocity in its own axes): the center of mass 0.1 m off the frame flies the
// parabola from v + ω × r, and the spin about the axis of symmetry stays.
TEST(RobotField, AKeyframesFreeJointVelocityThrowsTheRoot) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "mjcf/thrown.xml");
  ContactWorld world = WorldWithGravity(false);
  dynamics::RobotOptions options;
  options.keyframe = "throw";
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m, options);
  const double t = 0.5;
  for (int s = 0; s < 500; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  const dynamics::RigidBody& b = world.world().bodies()[static_cast<std::size_t>(added.bodies.front())];
  // The center of mass starts at (0.1, 0, 1) moving at v + ω × r = (1, 0.3, 2).
  const Vector3 expected(0.1 + 1 * t, 0.3 * t, 1 + 2 * t - kG * t * t / 2);
  EXPECT_LE((b.position - expected).norm(), 1e-9) << b.position.transpose();
  EXPECT_LE((b.AngularVelocity() - Vector3(0, 0, 3)).norm(), 1e-12);
}

// An actuator's ranges follow <compiler autolimits> as joints' ranges do: with it (MuJoCo 3's
// default) a ctrlrange without ctrllimited is a limit; without it, it is not, and that is noted.
TEST(RobotField, ActuatorRangesFollowAutolimitsAsJointRangesDo) {
  const auto model = [](const std::string& compiler) {
    const std::string path = (std::filesystem::temp_directory_path() / "autolimits_actuator.xml").string();
    std::ofstream(path) << "<mujoco>" << compiler << R"(<worldbody><body name="bar">
<joint name="hinge" axis="0 1 0" range="-1 1"/><inertial mass="1" diaginertia="0.1 0.1 0.01"/></body></worldbody>
<actuator><motor joint="hinge" gear="2" ctrlrange="-1 1" forcerange="-3 3"/></actuator></mujoco>)";
    return massprops::ReadRobotModel(path);
  };
  const massprops::RobotModel on = model("");
  ASSERT_EQ(on.actuators.size(), 1u);
  ASSERT_TRUE(on.actuators[0].ctrlrange.has_value());
  EXPECT_EQ(on.actuators[0].ctrlrange->second, 1.0);
  EXPECT_TRUE(on.joints[0].upper.has_value());
  const massprops::RobotModel off = model(R"(<compiler autolimits="false"/>)");
  EXPECT_FALSE(off.actuators[0].ctrlrange.has_value());
  EXPECT_FALSE(off.actuators[0].forcerange.has_value());
  EXPECT_FALSE(off.joints[0].upper.has_value());
  EXPECT_TRUE(AnyContains(off.notes, "ctrlrange is not a limit (<compiler autolimits=\"false\"> and no limited)"));
  EXPECT_TRUE(AnyContains(off.notes, "its range is not a limit"));
}

// MJCF actuators as MuJoCo defines them, driven by a keyframe's ctrl: a motor holds a bar level
// with gear ctrl = −m g d; a velocity actuator turns a damped wheel at kv ctrl / (kv + c); a
// general actuator with an affine bias moves its pendulum as the position servo it equals.
TEST(RobotField, MjcfActuatorsDriveTheirJointsAsMuJoCoDefinesThem) {
  const massprops::RobotModel m = massprops::ReadRobotModel(kField + "mjcf/actuators.xml");
  ASSERT_EQ(m.actuators.size(), 4u);
  ASSERT_EQ(m.keyframes.size(), 1u);
  ContactWorld world = WorldWithGravity(false);
  dynamics::RobotOptions options;
  options.keyframe = "start";
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, m, options);
  auto state = [&](std::size_t joint) { return world.world().joint_state(added.joint_of.at(joint)); };
  for (int s = 0; s < 3000; ++s) ASSERT_TRUE(world.Step(1e-3).ok);
  EXPECT_NEAR(state(0).position[0], 0, 1e-9);  // held level
  EXPECT_NEAR(state(1).velocity[0], 50 * 2 / (50 + 0.5), 1e-6);
  // (to rounding: the two pendulums hang at different places, so their sums round differently)
  EXPECT_NEAR(state(2).position[0], state(3).position[0], 1e-12);
  EXPECT_NEAR(state(2).velocity[0], state(3).velocity[0], 1e-12);
  EXPECT_GT(state(2).position[0], 0.1);  // it moved toward 0.5 rad, against gravity
  // Without the keyframe, ctrl is 0: the motor is limp and the bar falls.
  ContactWorld limp = WorldWithGravity(false);
  const dynamics::RobotInWorld limp_added = dynamics::AddRobot(limp, m);
  for (int s = 0; s < 300; ++s) ASSERT_TRUE(limp.Step(1e-3).ok);
  EXPECT_GT(limp.world().joint_state(limp_added.joint_of.at(0)).position[0], 0.1);
  // A keyframe the file has not is refused, naming those it has.
  dynamics::RobotOptions missing;
  missing.keyframe = "home";
  ContactWorld other = WorldWithGravity(false);
  try {
    dynamics::AddRobot(other, m, missing);
    ADD_FAILURE() << "added";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no keyframe named 'home' (it has: start)"), std::string::npos) << e.what();
  }
}

// package:// as ROS tools find packages: a package whose folder is not named as the package (a
// vendor's arm_description folder holding acme_arm_description), found below ROS_PACKAGE_PATH by
// its package.xml, or at AMENT_PREFIX_PATH's share/NAME; not found, the error says where it looked.
TEST(RobotField, PackagesAreFoundAsRosToolsFindThem) {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / ("massprops_ros_" + std::to_string(::getpid()));
  const fs::path package = root / "ws" / "src" / "vendor" / "arm_description";
  const fs::path installed = root / "install" / "share" / "acme_arm_description";
  const std::string tetrahedron = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  for (const fs::path& p : {package, installed}) {
    fs::create_directories(p / "meshes");
    std::ofstream(p / "meshes" / "link.obj") << tetrahedron;
    std::ofstream(p / "package.xml") << "<?xml version=\"1.0\"?>\n<package format=\"3\">\n  "
                                        "<name>acme_arm_description</name>\n  <version>1.0.0</version>\n</package>\n";
  }
  fs::create_directories(root / "ws" / "src" / "other_pkg");
  std::ofstream(root / "ws" / "src" / "other_pkg" / "package.xml") << "<package><name>other_pkg</name></package>";
  const fs::path urdf = root / "robot.urdf";
  std::ofstream(urdf) << R"(<robot name="r"><link name="a"><collision><geometry>
<mesh filename="package://acme_arm_description/meshes/link.obj"/></geometry></collision></link></robot>)";
  massprops::RobotModelOptions fill;
  fill.fill = true;
  auto mesh_path = [&] {
    const massprops::RobotModel m = massprops::ReadRobotModel(urdf.string(), fill);
    return std::get<massprops::RobotMesh>(m.links[0].collisions.at(0).shape).path;
  };
  unsetenv("ROS_PACKAGE_PATH");
  unsetenv("AMENT_PREFIX_PATH");
  try {
    mesh_path();
    ADD_FAILURE() << "found without a path";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("the package 'acme_arm_description' is not found in the description's "
                                         "folders, ROS_PACKAGE_PATH and AMENT_PREFIX_PATH"),
              std::string::npos)
        << e.what();
  }
  setenv("ROS_PACKAGE_PATH", (root / "nowhere").string().append(":").append((root / "ws" / "src").string()).c_str(), 1);
  EXPECT_EQ(fs::path(mesh_path()), package / "meshes" / "link.obj");
  unsetenv("ROS_PACKAGE_PATH");
  setenv("AMENT_PREFIX_PATH", (root / "install").string().c_str(), 1);
  EXPECT_EQ(fs::path(mesh_path()), installed / "meshes" / "link.obj");
  unsetenv("AMENT_PREFIX_PATH");
  fs::remove_all(root);
}

// A collision mesh that cannot be read at all is named by its link and geometry, and the file by
// its path, once.
TEST(RobotField, AnUnreadableCollisionMeshIsNamedByItsLink) {
  const std::string path = Write("unreadable_mesh.urdf", R"(<robot name="r"><link name="a"><inertial>
<mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
<collision><geometry><mesh filename=")" + kField + R"(package.xml"/></geometry></collision></link></robot>)");
  ContactWorld world;
  try {
    dynamics::AddRobot(world, massprops::ReadRobotModel(path));
    ADD_FAILURE() << "added";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("link 'a' collision #1: "), std::string::npos) << what;
    EXPECT_NE(what.find("package.xml"), std::string::npos) << what;
    EXPECT_EQ(what.find(path), std::string::npos) << what;  // the robot file is named by the caller
  }
}

// A body made from a CAD file (rbsim's scenes, BodyBuilder): its mass properties are the exact
// B-rep's, its display and collision mesh the tessellation, both in the file's own unit (inches
// here, with no unit stated).
TEST(RobotField, ACadBodyTakesTheBrepsInertiaAndTheFilesUnit) {
  dynamics::BodyBuilder builder(massprops::ApiVocabulary());
  dynamics::BodyShape shape;
  shape.source = dynamics::MeshSource{kField + "../../cad/field/block_ap203.stp", false, false};
  std::vector<dynamics::BodyWarning> warnings;
  const dynamics::BuiltShape built = builder.Load(shape, warnings);
  const double in = 0.0254, m = 1000 * 6 * in * in * in;
  EXPECT_NEAR(built.mp.volume, 6 * in * in * in, 1e-12 * built.mp.volume);
  EXPECT_NEAR(built.mp.inertia_com(0, 0), m * (4 + 9) * in * in / 12, 1e-12 * m * in * in);
  const Vector3 extent = built.display.V.colwise().maxCoeff() - built.display.V.colwise().minCoeff();
  EXPECT_LT((extent - Vector3(1, 2, 3) * in).norm(), 1e-12) << extent.transpose();
}

TEST(RobotField, AWorldLinkCannotBeAChild) {
  const std::string path = Write("world_child.urdf", R"(<robot name="r"><link name="world"/>
<link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
<joint name="j" type="fixed"><parent link="a"/><child link="world"/></joint></robot>)");
  try {
    massprops::ReadRobotModel(path);
    ADD_FAILURE() << "read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'j': <child link=\"world\">"), std::string::npos) << e.what();
  }
}

}  // namespace
