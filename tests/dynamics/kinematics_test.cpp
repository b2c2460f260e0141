// The articulated bodies' kinematics (libdynamics/src/articulated/kinematics.cpp) against closed
// forms: where a joint configuration puts each body and how fast it then moves. A planar double
// pendulum of boxes at given angles and rates (positions, orientations, velocities, angular
// velocities and the kinetic energy ½ Σ m v² + ½ I ω² of the textbook Lagrangian); a slider
// moved along its axis; a ball joint turned by its quaternion with ω in the child's axes.

#include <cmath>

#include <gtest/gtest.h>

#include "dynamics/joints.h"
#include "dynamics/world.h"
#include "joint_bodies.h"

namespace {

using dynamics::Joint;
using dynamics::JointType;
using dynamics::RigidBody;
using dynamics::World;
using massprops::Matrix3;
using Quaternion = Eigen::Quaterniond;
using massprops::Vector3;

constexpr double kTol = 1e-12;

constexpr auto Box = testing::SolidBox;

Joint Placed(const World& w, JointType type, int parent, int child, const Vector3& anchor, const Vector3& axis) {
  return testing::PlacedJoint(w, parent, child, anchor, axis, type);
}

Matrix3 RotY(double t) { return Eigen::AngleAxisd(t, Vector3::UnitY()).toRotationMatrix(); }

void ExpectNear(const Vector3& got, const Vector3& want, const char* what) {
  EXPECT_LT((got - want).norm(), kTol * std::max(1.0, want.norm()))
      << what << ": " << got.transpose() << " against " << want.transpose();
}

// Two links hanging from the origin along −z (lengths L1, L2, centres of mass at their middles),
// hinged about y, set at angles q1 (the first against the world) and q2 (the second against the
// first) turning at q̇1, q̇2.
TEST(Kinematics, DoublePendulumPositionsVelocitiesAndKineticEnergy) {
  const double L1 = 0.7, L2 = 0.4, m1 = 2.0, m2 = 1.3, w = 0.05;
  const double q1 = 0.6, q2 = -1.1, u1 = 1.7, u2 = -2.3;
  World world;
  world.AddBody(Box(m1, w, w, L1, Vector3(0, 0, -L1 / 2)));
  world.AddBody(Box(m2, w, w, L2, Vector3(0, 0, -L1 - L2 / 2)));
  Joint shoulder = Placed(world, JointType::kRevolute, -1, 0, Vector3::Zero(), Vector3::UnitY());
  shoulder.position = {q1};
  shoulder.velocity = {u1};
  world.AddJoint(shoulder);
  Joint elbow = Placed(world, JointType::kRevolute, 0, 1, Vector3(0, 0, -L1), Vector3::UnitY());
  elbow.position = {q2};
  elbow.velocity = {u2};
  world.AddJoint(elbow);

  // R_y(θ) turns −z into (−sin θ, 0, −cos θ).
  const double phi = q1 + q2, dphi = u1 + u2, a = L1 / 2, b = L2 / 2;
  const Vector3 c1(-a * std::sin(q1), 0, -a * std::cos(q1));
  const Vector3 c2(-L1 * std::sin(q1) - b * std::sin(phi), 0, -L1 * std::cos(q1) - b * std::cos(phi));
  const Vector3 v1(-a * std::cos(q1) * u1, 0, a * std::sin(q1) * u1);
  const Vector3 v2(-L1 * std::cos(q1) * u1 - b * std::cos(phi) * dphi, 0,
                   L1 * std::sin(q1) * u1 + b * std::sin(phi) * dphi);
  const RigidBody& B1 = world.bodies()[0];
  const RigidBody& B2 = world.bodies()[1];
  ExpectNear(B1.position, c1, "first centre");
  ExpectNear(B2.position, c2, "second centre");
  EXPECT_LT((B1.orientation.toRotationMatrix() - RotY(q1)).norm(), kTol);
  EXPECT_LT((B2.orientation.toRotationMatrix() - RotY(phi)).norm(), kTol);
  ExpectNear(B1.velocity, v1, "first velocity");
  ExpectNear(B2.velocity, v2, "second velocity");
  ExpectNear(B1.AngularVelocity(), Vector3(0, u1, 0), "first angular velocity");
  ExpectNear(B2.AngularVelocity(), Vector3(0, dphi, 0), "second angular velocity");
  const double I1 = m1 * (w * w + L1 * L1) / 12, I2 = m2 * (w * w + L2 * L2) / 12;
  const double T =
      0.5 * m1 * v1.squaredNorm() + 0.5 * I1 * u1 * u1 + 0.5 * m2 * v2.squaredNorm() + 0.5 * I2 * dphi * dphi;
  // The Lagrangian's form: ½(m1 a² + I1 + m2 L1²) q̇1² + m2 L1 b cos(q2) q̇1 φ̇ + ½(m2 b² + I2) φ̇².
  const double lagrangian_T = 0.5 * (m1 * a * a + I1 + m2 * L1 * L1) * u1 * u1 +
                              m2 * L1 * b * std::cos(q2) * u1 * dphi + 0.5 * (m2 * b * b + I2) * dphi * dphi;
  EXPECT_NEAR(T, lagrangian_T, kTol * T);
  EXPECT_NEAR(world.Diagnose().kinetic_energy, T, kTol * T);
}

// A slider along a tilted axis: the body moves by q along it, at q̇, without turning.
TEST(Kinematics, SliderMovesAlongItsAxis) {
  World world;
  world.AddBody(Box(1.5, 0.1, 0.2, 0.3, Vector3(0.2, -0.1, 0.4)));
  const Vector3 axis = Vector3(1, 2, -0.5).normalized();
  Joint slider = Placed(world, JointType::kPrismatic, -1, 0, Vector3(0.2, -0.1, 0.4), axis);
  slider.position = {0.35};
  slider.velocity = {-0.8};
  world.AddJoint(slider);
  const RigidBody& b = world.bodies()[0];
  ExpectNear(b.position, Vector3(0.2, -0.1, 0.4) + 0.35 * axis, "position");
  ExpectNear(b.velocity, -0.8 * axis, "velocity");
  EXPECT_LT(b.orientation.angularDistance(Quaternion::Identity()), kTol);
  ExpectNear(b.AngularVelocity(), Vector3::Zero(), "angular velocity");
}

// A ball joint 0.3 m above a body's centre: the quaternion turns the body about the anchor, and ω
// (given in the child's joint axes, here the body's) turns its centre about the anchor.
TEST(Kinematics, BallJointTurnsAboutItsAnchor) {
  World world;
  world.AddBody(Box(0.8, 0.1, 0.1, 0.6, Vector3(0, 0, -0.3)));
  Joint ball = Placed(world, JointType::kSpherical, -1, 0, Vector3::Zero(), Vector3::UnitZ());
  const Quaternion q(Eigen::AngleAxisd(0.9, Vector3(1, -1, 0.5).normalized()));
  const Vector3 omega_child(0.4, -1.2, 2.0);
  ball.position = {q.w(), q.x(), q.y(), q.z()};
  ball.velocity = {omega_child.x(), omega_child.y(), omega_child.z()};
  world.AddJoint(ball);
  const RigidBody& b = world.bodies()[0];
  const Vector3 centre = q * Vector3(0, 0, -0.3);
  const Vector3 omega = q * omega_child;
  ExpectNear(b.position, centre, "centre");
  EXPECT_LT(b.orientation.angularDistance(q), kTol);
  ExpectNear(b.AngularVelocity(), omega, "angular velocity");
  ExpectNear(b.velocity, omega.cross(centre), "velocity");
}

}  // namespace
