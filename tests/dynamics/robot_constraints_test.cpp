// Robot files with couplings, loops and tendons (tests/robot/field/constraints, written as ROS
// packages and MuJoCo models write them) read and simulated against closed forms: a URDF mimic
// and an MJCF joint equality falling as one coordinate, an MJCF connect closing a parallelogram
// four-bar (its elliptic period), an MJCF tendon equality mirroring two fingers, a spatial
// tendon's string pendulum, and a mimic gripper holding a box by friction (couplings, contact and
// the finger's motor in one solve).

#include <boost/math/special_functions/ellint_1.hpp>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bodies/robot.h"
#include "dynamics/contact.h"
#include "massprops/robot/robot_model.h"

namespace {

using dynamics::ContactWorld;
using massprops::Vector3;

const std::string kDir = std::string(MASSPROPS_DATA_DIR) + "/../tests/robot/field/constraints/";
constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

struct Loaded {
  massprops::RobotModel model;
  ContactWorld world;
  dynamics::RobotInWorld added;
};

Loaded Load(const std::string& file, const std::string& keyframe = "", bool ground = false) {
  Loaded l{massprops::ReadRobotModel(kDir + file), ContactWorld(dynamics::World()), {}};
  dynamics::World w;
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  l.world = ContactWorld(std::move(w));
  if (ground) l.world.AddGround({});
  dynamics::RobotOptions options;
  options.keyframe = keyframe;
  l.added = dynamics::AddRobot(l.world, l.model, options);
  return l;
}

int JointNamed(const Loaded& l, const std::string& name) {
  for (std::size_t k = 0; k < l.model.joints.size(); ++k) {
    if (l.model.joints[k].name == name) return l.added.joint_of[k];
  }
  ADD_FAILURE() << "no joint " << name;
  return -1;
}

double Q(const Loaded& l, const std::string& name) {
  return l.world.world().joint_state(JointNamed(l, name)).position[0];
}

void Advance(Loaded& l, double h, long n) {
  for (long s = 0; s < n; ++s) {
    const dynamics::StepStatus st = l.world.Step(h);
    ASSERT_TRUE(st.ok) << st.message;
  }
}

// y = k x for two vertical sliders of masses m_x and m_y: x = −g t² (m_x + k m_y) / (2 (m_x + k² m_y)).
double Fallen(double t, double mx, double my, double k) {
  return -kG * t * t * (mx + k * my) / (2 * (mx + k * k * my));
}

TEST(RobotConstraints, UrdfMimicFallsAsOneCoordinate) {
  Loaded l = Load("mimic_sliders.urdf");
  ASSERT_EQ(l.model.couplings.size(), 1u);
  Advance(l, 1e-3, 500);
  const double t = l.world.world().time();
  EXPECT_NEAR(Q(l, "upper_slide"), Fallen(t, 1.5, 0.7, -2.0), 1e-9);
  EXPECT_NEAR(Q(l, "lower_slide"), -2.0 * Q(l, "upper_slide"), 1e-12);
}

TEST(RobotConstraints, MjcfJointAndTendonEqualities) {
  Loaded l = Load("couplings.xml", "start");
  ASSERT_EQ(l.model.couplings.size(), 2u);
  ASSERT_EQ(l.model.tendons.size(), 1u);
  Advance(l, 1e-3, 1000);
  const double t = l.world.world().time();
  EXPECT_NEAR(Q(l, "leader"), Fallen(t, 1.5, 0.7, 0.5), 1e-9);
  EXPECT_NEAR(Q(l, "follower"), 0.5 * Q(l, "leader"), 1e-12);
  // The fingers mirror each other, the driven one moved toward its target.
  EXPECT_NEAR(Q(l, "left") + Q(l, "right"), 0.0, 1e-12);
  EXPECT_GT(Q(l, "left"), 0.1);
}

TEST(RobotConstraints, MjcfConnectClosesTheFourBar) {
  Loaded l = Load("four_bar.xml", "released");
  ASSERT_EQ(l.model.loops.size(), 1u);
  const double q0 = kPi / 3, l1 = 1.0;
  const double crank = 0.08354 + 1.0 * 0.25;  // about the pivot
  const double I = 2 * crank + 0.6 * l1 * l1, k = kG * l1 * (1.0 + 0.6);
  const double period = 4 * std::sqrt(I / k) * boost::math::ellint_1(std::sin(q0 / 2));
  const long n = 4000;
  Advance(l, period / n, n / 2);
  EXPECT_NEAR(Q(l, "crank1"), -q0, 1e-5);
  EXPECT_NEAR(Q(l, "crank2"), -q0, 1e-5);
  EXPECT_NEAR(Q(l, "coupler"), q0, 1e-5);
  EXPECT_LT(l.world.world().loop_state(0).residual, 1e-9);
}

// The same four-bar as SDFormat closes it (the coupler the child of two joints): a hinge loop.
TEST(RobotConstraints, SdformatSecondParentClosesTheFourBar) {
  const massprops::RobotModel model = massprops::ReadRobotModel(kDir + "four_bar.sdf");
  ASSERT_EQ(model.loops.size(), 1u);
  ASSERT_EQ(model.joints.size(), 3u);
  dynamics::World w;
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  ContactWorld world(std::move(w));
  dynamics::RobotOptions options;
  const double q0 = kPi / 3;
  options.positions = {{"crank1", q0}, {"crank2", q0}, {"coupler", -q0}};
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, model, options);
  const double crank = 0.08354 + 1.0 * 0.25;
  const double I = 2 * crank + 0.6, k = kG * (1.0 + 0.6);
  const double period = 4 * std::sqrt(I / k) * boost::math::ellint_1(std::sin(q0 / 2));
  const long n = 4000;
  for (long s = 0; s < n / 2; ++s) ASSERT_TRUE(world.Step(period / n).ok);
  EXPECT_NEAR(world.world().joint_state(added.joint_of[0]).position[0], -q0, 1e-5);
  EXPECT_NEAR(world.world().joint_state(added.joint_of[1]).position[0], -q0, 1e-5);
  EXPECT_LT(world.world().loop_state(0).residual, 1e-9);
}

// MJCF weld (a free ball welded to a hinged rod at the reference pose: one compound pendulum) and
// a motor on a fixed tendon (each wheel turned by coef · gear · ctrl: q = coef g c t² / (2 I)).
TEST(RobotConstraints, MjcfWeldAndTendonMotor) {
  Loaded l = Load("weld_and_motor.xml", "released");
  ASSERT_EQ(l.model.loops.size(), 1u);
  ASSERT_EQ(l.model.tendons.size(), 1u);
  const double q0 = kPi / 3;
  const double I = 0.08354 + 1.0 * 0.25 + 0.0005 + 0.5 * 1.0, mgd = kG * (1.0 * 0.5 + 0.5 * 1.0);
  const double period = 4 * std::sqrt(I / mgd) * boost::math::ellint_1(std::sin(q0 / 2));
  const long n = 4000;
  Advance(l, period / n, n / 2);
  EXPECT_NEAR(Q(l, "swing"), -q0, 1e-5);
  EXPECT_LT(l.world.world().loop_state(0).residual, 1e-9);
  const double t = l.world.world().time(), force = 2 * 0.3;
  EXPECT_NEAR(Q(l, "left_spin"), 1.0 * force * t * t / (2 * 0.02), 1e-9);
  EXPECT_NEAR(Q(l, "right_spin"), -0.5 * force * t * t / (2 * 0.05), 1e-9);
}

TEST(RobotConstraints, MjcfSpatialTendonIsAString) {
  Loaded l = Load("string_pendulum.xml", "horizontal");
  ASSERT_EQ(l.model.tendons.size(), 1u);
  const double L = 0.5, h = 1e-3;
  const double bottom = std::sqrt(L / kG) * boost::math::ellint_1(std::sin(kPi / 4));
  double x0 = Q(l, "ball_x"), when = -1;
  for (long s = 0; s < static_cast<long>(0.6 / h) && when < 0; ++s) {
    ASSERT_TRUE(l.world.Step(h).ok);
    const double x = Q(l, "ball_x");
    if (x <= 0) when = l.world.world().time() - h * x / (x - x0);
    x0 = x;
    ASSERT_LT(l.world.world().tendon_state(0).length, L + 1e-9);
  }
  EXPECT_NEAR(when, bottom, 5e-6);
}

// The control suite's ball on a string, in its habits: the ball falls 8 mm, the string (a spatial
// tendon limited to 0.3 m) catches it, and the cup on its sprung, damped slides comes to rest where
// its springs carry the cup and the ball, (m_cup + m_ball) g / k below its start, the ball hanging
// on the taut string below it.
TEST(RobotConstraints, ControlSuiteBallHangsOnItsString) {
  Loaded l = Load("ball_in_cup.xml");
  ASSERT_EQ(l.model.tendons.size(), 1u);
  double cup = 0, ball = 0;
  for (const massprops::RobotLink& link : l.model.links) {
    if (!link.inertial) continue;
    if (link.name == "cup") cup = link.inertial->mass;
    if (link.name == "ball") ball = link.inertial->mass;
  }
  ASSERT_GT(cup, 0);
  ASSERT_GT(ball, 0);
  Advance(l, 1e-3, 8000);
  const double sag = -(cup + ball) * kG / 20.0;
  EXPECT_NEAR(Q(l, "cup_z"), sag, 1e-4);
  // Taut: the ball 0.3 m below the cup's knot (0.6 − 0.108 + sag), to rounding.
  EXPECT_NEAR(0.2 + Q(l, "ball_z"), 0.6 - 0.108 + Q(l, "cup_z") - 0.3, 1e-9);
  EXPECT_NEAR(l.world.world().tendon_state(0).length, 0.3, 1e-12);
}

// The gripper's left finger driven closed by a velocity motor bounded at 20 N, the right one its
// mimic: a 0.2 kg box between them (friction 0.6) is squeezed by 10 N on each side and held.
TEST(RobotConstraints, MimicGripperHoldsABox) {
  massprops::RobotModel model = massprops::ReadRobotModel(kDir + "gripper.urdf");
  dynamics::World w;
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  ContactWorld world(std::move(w));
  dynamics::RobotOptions options;
  dynamics::JointMotor motor;
  motor.mode = dynamics::JointMotor::Mode::kVelocity;
  motor.target = 0.05;
  motor.max_effort = 20;
  options.motors["left_finger_joint"] = motor;
  options.positions["left_finger_joint"] = 0.039;
  options.positions["right_finger_joint"] = 0.039;
  const dynamics::RobotInWorld added = dynamics::AddRobot(world, model, options);
  dynamics::RigidBody box;
  box.mass = 0.2;
  const double side = 0.06;
  box.inertia = Vector3::Constant(box.mass * side * side / 6);
  box.position = Vector3(0, 0, 0.25);
  const int b =
      world.AddBody(box, dynamics::Collider{dynamics::shape::Box{Vector3::Constant(side / 2)},
                                            massprops::Matrix3::Identity(), Vector3::Zero(), dynamics::Material{}});
  int left = -1, right = -1;
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    if (model.joints[k].name == "left_finger_joint") left = added.joint_of[k];
    if (model.joints[k].name == "right_finger_joint") right = added.joint_of[k];
  }
  ASSERT_GE(left, 0);
  ASSERT_GE(right, 0);
  double asymmetry = 0, z_grabbed = 0;
  for (int s = 0; s < 1000; ++s) {
    if (s == 300) z_grabbed = world.world().bodies()[static_cast<std::size_t>(b)].position.z();
    const dynamics::StepStatus st = world.Step(1e-3);
    ASSERT_TRUE(st.ok) << st.message;
    const double ql = world.world().joint_state(left).position[0], qr = world.world().joint_state(right).position[0];
    asymmetry = std::max(asymmetry, std::abs(ql - qr));
  }
  EXPECT_LT(asymmetry, 1e-9);
  const dynamics::RigidBody& held = world.world().bodies()[static_cast<std::size_t>(b)];
  // It fell 2 mm (½ g t² over the 20 ms the fingers took to reach it), then held without slipping.
  EXPECT_NEAR(z_grabbed, 0.25 - 0.5 * kG * 0.02 * 0.02, 2e-4);
  EXPECT_NEAR(held.position.z(), z_grabbed, 1e-6);
  EXPECT_LT(held.velocity.norm(), 1e-6);
  EXPECT_NEAR(world.world().joint_state(left).position[0], 0.04, 1e-3);  // the fingers on its faces
}

}  // namespace
