// Jointed bodies in contact: a pendulum striking a wall rebounds with the restitution's share of
// its angular velocity (a one-degree-of-freedom impact: ω⁺ = −e ω⁻, ω⁻ from energy), a
// four-legged robot dropped limp comes to rest and, held by PD servos, stands; a two-link arm
// resting its hand on a table holds still; an impulse on one link moves its whole tree as the
// tree's mass matrix says (a free body hit beside the same body jointed to nothing).

#include <algorithm>
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "dynamics/contact.h"
#include "dynamics/joints.h"
#include "dynamics/world.h"

namespace {

using dynamics::Collider;
using dynamics::ContactOptions;
using dynamics::ContactWorld;
using dynamics::Integrator;
using dynamics::Joint;
using dynamics::JointType;
using dynamics::Material;
using dynamics::RigidBody;
using dynamics::World;
using massprops::Matrix3;
using massprops::Vector3;
namespace shape = dynamics::shape;

constexpr double kG = 9.81;

RigidBody Box(double m, const Vector3& size, const Vector3& at) {
  RigidBody b;
  b.mass = m;
  const Vector3 s2 = size.cwiseProduct(size);
  b.inertia = Vector3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()) * (m / 12.0);
  b.position = at;
  return b;
}

Collider BoxCollider(const Vector3& size, Material mat = {}) {
  return Collider{shape::Box{size / 2}, Matrix3::Identity(), Vector3::Zero(), mat};
}

ContactWorld MakeWorld(Integrator integrator = Integrator::kImplicitMidpoint, ContactOptions options = {}) {
  World w(integrator);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  return ContactWorld(std::move(w), options);
}

Joint Hinge(const ContactWorld& c, int parent, int child, const Vector3& anchor, const Vector3& axis) {
  Joint j;
  j.name = "j" + std::to_string(child);
  j.type = JointType::kRevolute;
  j.parent = parent;
  j.child = child;
  c.world().PlaceJoint(j, anchor, axis);
  return j;
}

void Simulate(ContactWorld& w, double h, long n, const std::function<void(long)>& each = {}) {
  for (long s = 0; s < n; ++s) {
    const dynamics::StepStatus st = w.Step(h);
    ASSERT_TRUE(st.ok) << st.message;
    if (each) each(s);
  }
}

// A four-legged robot: a 0.4 × 0.2 × 0.08 m body (6 kg) and four legs of two 0.2 m links
// (0.3 kg each) hinged about y at the hip and the knee, standing straight with its feet 1 cm
// above z = `lift`. Returns the body's index; `joints` receives the eight hinges.
int AddQuadruped(ContactWorld& w, double lift, std::vector<int>& joints,
                 const std::function<void(Joint&, bool knee)>& configure) {
  const Vector3 body_size(0.4, 0.2, 0.08), leg(0.04, 0.04, 0.2);
  const double leg_length = 0.2, foot = lift + 0.01;
  const double hip_z = foot + 2 * leg_length;
  const int base = w.AddBody(Box(6.0, body_size, Vector3(0, 0, hip_z + 0.04)), BoxCollider(body_size));
  for (const double sx : {0.15, -0.15}) {
    for (const double sy : {0.12, -0.12}) {
      const int thigh = w.AddBody(Box(0.3, leg, Vector3(sx, sy, hip_z - leg_length / 2)), BoxCollider(leg));
      const int shin = w.AddBody(Box(0.3, leg, Vector3(sx, sy, hip_z - 1.5 * leg_length)), BoxCollider(leg));
      Joint hip = Hinge(w, base, thigh, Vector3(sx, sy, hip_z), Vector3::UnitY());
      Joint knee = Hinge(w, thigh, shin, Vector3(sx, sy, hip_z - leg_length), Vector3::UnitY());
      for (Joint* j : {&hip, &knee}) {
        j->limits.lower = -2.0;
        j->limits.upper = 2.0;
        configure(*j, j == &knee);
      }
      joints.push_back(w.AddJoint(hip));
      joints.push_back(w.AddJoint(knee));
    }
  }
  return base;
}

// The quadruped limp (joint damping only), its knees a little bent (straight legs would balance,
// unstably, for a while).
int AddLimpQuadruped(ContactWorld& w, double lift, std::vector<int>& joints) {
  return AddQuadruped(w, lift, joints, [](Joint& j, bool knee) {
    j.damping = 0.02;
    j.position = {knee ? -0.3 : 0.15};
  });
}

double MaxSpeed(const World& w) {
  double v = 0;
  for (const RigidBody& b : w.bodies()) v = std::max(v, b.velocity.norm() + 0.2 * b.AngularVelocity().norm());
  return v;
}

TEST(JointedContact, PendulumReboundsFromAWallPerTheRestitution) {
  for (const double e : {0.0, 0.5, 0.8}) {
    ContactWorld w = MakeWorld();
    w.AddGround({});
    // A 1 kg ball of radius 0.05 m on a massless-looking rod: hinge at z = 1, the ball's centre
    // 0.5 m below when it hangs, released from horizontal (x = +0.5).
    RigidBody ball;
    ball.mass = 1.0;
    ball.inertia = Vector3::Constant(0.4 * 0.05 * 0.05);
    ball.position = Vector3(0.5, 0, 1.0);
    Material mat;
    mat.restitution = e;
    mat.static_friction = mat.kinetic_friction = 0.0;
    const int b = w.AddBody(ball, Collider{shape::Sphere{0.05}, Matrix3::Identity(), Vector3::Zero(), mat});
    w.AddJoint(Hinge(w, -1, b, Vector3(0, 0, 1), Vector3::UnitY()));
    // The wall: its face at x = −0.05 m, the ball meets it hanging straight down.
    w.AddStatic(BoxCollider(Vector3(0.2, 0.4, 0.4), mat), Matrix3::Identity(), Vector3(-0.15, 0, 0.5));
    const double I = ball.inertia.x() + ball.mass * 0.25;
    const double omega_in = std::sqrt(2 * ball.mass * kG * 0.5 / I);  // energy at the bottom
    double fastest_back = 0, omega_before = 0;
    bool hit = false;
    Simulate(w, 1e-4, 8000, [&](long) {
      const double omega = w.world().joint_state(0).velocity[0];
      // Falling from +x it turns about +y, fastest just before the wall; after the bounce, back.
      if (!hit && w.stats().contacts > 0 && omega < 0.9 * omega_before) hit = true;
      if (!hit) omega_before = std::max(omega_before, omega);
      if (hit) fastest_back = std::max(fastest_back, -omega);
    });
    ASSERT_TRUE(hit) << "e = " << e;
    EXPECT_NEAR(omega_before, omega_in, 2e-3 * omega_in) << "e = " << e;
    // After the bounce it turns back at e ω⁻ (rising, it only slows).
    EXPECT_NEAR(fastest_back, e * omega_in, 5e-3 * omega_in + 1e-6) << "e = " << e;
  }
}

TEST(JointedContact, ImpulseOnALinkMovesTheTreeByItsMassMatrix) {
  // A ball strikes a ball off its centre, without gravity (friction spins it): the struck ball
  // free in a world of free bodies, unjoined in a jointed world, and on a free joint from the
  // world whose frame is away from its centre. Impulses through the coupling of a one-body tree (Φ M⁻¹ Φᵀ over its six
  // joint coordinates) are the free body's own response: the same momentum after the blow.
  enum Variant { kFreeWorld, kUnjoined, kFreeJoint };
  auto run = [](Variant variant) {
    World world(Integrator::kImplicitMidpoint);
    ContactWorld w(std::move(world));
    RigidBody struck;
    struck.mass = 2.0;
    struck.inertia = Vector3::Constant(0.4 * 2.0 * 0.1 * 0.1);
    const int box = w.AddBody(struck, Collider{shape::Sphere{0.1}, Matrix3::Identity(), Vector3::Zero(), Material{}});
    RigidBody ball;
    ball.mass = 0.5;
    ball.inertia = Vector3::Constant(0.4 * 0.5 * 0.03 * 0.03);
    ball.position = Vector3(-0.3, 0.08, 0.02);
    ball.velocity = Vector3(3, 0, 0);
    Material mat;
    mat.restitution = 0.5;
    w.AddBody(ball, Collider{shape::Sphere{0.03}, Matrix3::Identity(), Vector3::Zero(), mat});
    if (variant != kFreeWorld) {  // a pendulum far away makes the world jointed
      const int bob = w.AddBody(Box(1.0, Vector3::Constant(0.1), Vector3(5, 0, 0)));
      w.AddJoint(Hinge(w, -1, bob, Vector3(5, 0, 1), Vector3::UnitY()));
    }
    if (variant == kFreeJoint) {
      Joint free;
      free.type = JointType::kFree;
      free.parent = -1;
      free.child = box;
      w.world().PlaceJoint(free, Vector3(0.1, -0.05, 0.02), Vector3(1, 1, 0).normalized());
      w.AddJoint(free);
    }
    Simulate(w, 1e-3, 150);
    const RigidBody& b = w.world().bodies()[static_cast<std::size_t>(box)];
    return std::pair<Vector3, Vector3>(b.mass * b.velocity, b.angular_momentum);
  };
  const auto [p0, L0] = run(kFreeWorld);
  EXPECT_GT(p0.x(), 0.3);      // struck
  EXPECT_GT(L0.norm(), 1e-3);  // and turned
  for (const Variant v : {kUnjoined, kFreeJoint}) {
    const auto [p, L] = run(v);
    EXPECT_LT((p - p0).norm(), 1e-12 * p0.norm()) << v;
    // The angular momentum about the centre: to rounding for the joint at the centre; with the
    // joint's frame 12 cm away, the contact steps' first-order integration in its coordinates
    // (which carry r × m v beside I ω) turns L by ~10⁻⁵ per step while the ball moves.
    EXPECT_LT((L - L0).norm(), (v == kUnjoined ? 1e-6 : 3e-2) * L0.norm()) << v;
  }
}

TEST(JointedContact, QuadrupedDroppedLimpComesToRest) {
  ContactWorld w = MakeWorld();
  w.AddGround({});
  std::vector<int> joints;
  const int base = AddLimpQuadruped(w, 0.1, joints);
  double at_rest = -1;
  Simulate(w, 1e-3, 3000, [&](long s) {
    if (MaxSpeed(w.world()) < 1e-4) {
      if (at_rest < 0) at_rest = 1e-3 * static_cast<double>(s + 1);
    } else {
      at_rest = -1;
    }
  });
  EXPECT_GT(at_rest, 0) << "still moving at 3 s: " << MaxSpeed(w.world());
  // Folded down: the body lies on its legs or the ground, not through it.
  const double z = w.world().bodies()[static_cast<std::size_t>(base)].position.z();
  EXPECT_GT(z, 0.04 - 1e-3);
  EXPECT_LT(z, 0.5);
  for (const RigidBody& b : w.world().bodies()) EXPECT_GT(b.position.z(), 0.0);
}

// The contacts of a tree are solved as one block (its contacts' Delassus matrix, a pivoting
// step): the quadruped resting limp — its feet and body on the ground, coupled through legs held
// on their stops, which the point-by-point sweeps could not settle within their 32 a step — takes
// a few sweeps a step, and its contact impulses carry its weight each step (Σ impulses = m g h,
// the bodies at rest).
TEST(JointedContact, AQuadrupedAtRestIsSolvedAsOneBlockInAFewSweeps) {
  ContactWorld w = MakeWorld();
  w.AddGround({});
  std::vector<int> joints;
  AddLimpQuadruped(w, 0.1, joints);
  double mass = 0;
  for (const RigidBody& b : w.world().bodies()) mass += b.mass;
  const double h = 1e-3;
  long sweeps = 0, steps = 0;
  double worst = 0;
  Simulate(w, h, 3000, [&](long s) {
    if (s < 2500) return;
    sweeps += w.stats().iterations;
    ++steps;
    Vector3 total = Vector3::Zero();
    for (const dynamics::ContactReport& c : w.Contacts()) total += c.impulse;
    worst = std::max(worst, std::abs(total.z() - mass * kG * h));
  });
  ASSERT_LT(MaxSpeed(w.world()), 1e-4);
  EXPECT_LE(static_cast<double>(sweeps) / static_cast<double>(steps), 3.0);
  EXPECT_LT(worst, 1e-9 * mass * kG * h);
}

// A tree sliding as one block: two boxes hinged about the normal of an incline, one above the
// other, below static friction (tan θ = 0.9 μs) stay put; beyond it (tan θ = 1.05 μs) they slide
// together at a = g (sin θ − μk cos θ) from the first step — the pivoting step's sliding
// patches (their friction μ N against their sliding).
TEST(JointedContact, HingedBoxesOnAnInclineHoldOrSlideAtTheKineticRate) {
  Material mat;
  mat.static_friction = 0.6;
  mat.kinetic_friction = 0.4;
  for (const double ratio : {0.9, 1.05}) {
    const double theta = std::atan(ratio * mat.static_friction);
    ContactWorld w = MakeWorld();
    const Matrix3 R = Eigen::AngleAxisd(-theta, Vector3::UnitY()).toRotationMatrix();  // x up the slope
    w.AddGround(dynamics::Ground(R * Vector3::UnitZ(), 0, mat));
    const Vector3 size(0.2, 0.1, 0.05);
    auto add = [&](double x) {
      RigidBody b = Box(1.0, size, R * Vector3(x, 0, size.z() / 2));
      b.orientation = dynamics::Quaternion(R);
      return w.AddBody(b, BoxCollider(size, mat));
    };
    const int upper = add(-0.11), lower = add(0.11);
    Joint hinge = Hinge(w, upper, lower, R * Vector3(0, 0, size.z() / 2), R * Vector3::UnitZ());
    w.AddJoint(hinge);
    const Vector3 downhill = -(R * Vector3::UnitX());
    const Vector3 start = w.world().bodies()[static_cast<std::size_t>(lower)].position;
    long sweeps = 0;
    Simulate(w, 1e-3, 1000, [&](long) { sweeps += w.stats().iterations; });
    const auto& bodies = w.world().bodies();
    SCOPED_TRACE("tan θ = " + std::to_string(ratio) + " μs");
    if (ratio < 1) {
      EXPECT_LT((bodies[static_cast<std::size_t>(lower)].position - start).norm(), 1e-6);
    } else {
      const double a = kG * (std::sin(theta) - mat.kinetic_friction * std::cos(theta));
      for (const int b : {upper, lower}) {
        EXPECT_NEAR(bodies[static_cast<std::size_t>(b)].velocity.dot(downhill), a * 1.0, a * 1e-3);
        EXPECT_LT(bodies[static_cast<std::size_t>(b)].AngularVelocity().norm(), 1e-6)
            << bodies[static_cast<std::size_t>(b)].AngularVelocity().transpose();
      }
    }
    EXPECT_LE(sweeps, 3 * 1000);
  }
}

TEST(JointedContact, QuadrupedStandsOnPdServos) {
  ContactWorld w = MakeWorld();
  w.AddGround({});
  std::vector<int> joints;
  // Servos bend the legs, started straight on the ground, into a stance (hips +0.4 rad, knees
  // −0.8 rad) and hold it.
  const int base = AddQuadruped(w, 0.0, joints, [](Joint& j, bool knee) {
    j.motor.mode = dynamics::JointMotor::Mode::kPosition;
    j.motor.target = knee ? -0.8 : 0.4;
    j.motor.kp = 200;
    j.motor.kd = 5;
    j.motor.max_effort = 60;
  });
  const auto& bodies = w.world().bodies();
  double z1 = 0, worst = 0;
  Simulate(w, 1e-3, 6000, [&](long s) {
    const double z = bodies[static_cast<std::size_t>(base)].position.z();
    if (s + 1 == 1000) z1 = z;
    if (s + 1 > 1000) worst = std::max(worst, std::abs(z - z1));
  });
  // Standing: the body's height held, at about what the stance gives (hips 2 × 0.2 cos 0.4 above
  // the feet, less the sag of the servos under the weight).
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(z1, 0.3);
  EXPECT_LT(z1, 0.42);
  for (const int j : joints) EXPECT_LT(std::abs(w.world().joint_state(j).position[0]), 1.0);
}

TEST(JointedContact, ArmRestingOnATableHoldsStill) {
  // A two-link arm hinged to the world at its shoulder (z = 0.3 m), straight along +x, its elbow
  // on a stop that keeps it from bending down, its hand resting on a table: a rigid lever on a
  // pin and a support, which holds (static friction, the stop, the contact) without creeping.
  ContactWorld w = MakeWorld();
  const Vector3 link(0.3, 0.04, 0.04);
  const int upper = w.AddBody(Box(1.0, link, Vector3(0.15, 0, 0.3)), BoxCollider(link));
  const int fore = w.AddBody(Box(0.8, link, Vector3(0.45, 0, 0.3)), BoxCollider(link));
  w.AddJoint(Hinge(w, -1, upper, Vector3(0, 0, 0.3), Vector3::UnitY()));
  Joint elbow = Hinge(w, upper, fore, Vector3(0.3, 0, 0.3), Vector3::UnitY());
  elbow.limits.lower = 0;  // bending down at the elbow (the hand on the table) is stopped
  elbow.limits.upper = 2;
  w.AddJoint(elbow);
  w.AddStatic(BoxCollider(Vector3(0.3, 0.3, 0.28)), Matrix3::Identity(), Vector3(0.55, 0, 0.14 - 1e-4));
  Vector3 hand1 = Vector3::Zero();
  double drift = 0;
  const auto& bodies = w.world().bodies();
  auto hand = [&] {
    const RigidBody& b = bodies[static_cast<std::size_t>(fore)];
    return Vector3(b.position + b.Rotation() * Vector3(0.15, 0, 0));
  };
  Simulate(w, 1e-3, 6000, [&](long s) {
    if (s + 1 == 1000) hand1 = hand();
    if (s + 1 > 1000) drift = std::max(drift, (hand() - hand1).norm());
  });
  EXPECT_LT(drift, 1e-6);
  // Resting on the table top (z = 0.28 − 10⁻⁴, the hand's lower edge 2 cm below its axis).
  EXPECT_NEAR(hand1.z(), 0.28 - 1e-4 + 0.02, 2e-4);
  EXPECT_GT(w.world().joint_state(0).position[0], 0.0);  // it fell onto the table
}

TEST(JointedContact, AVelocityMotorPressingALeverOntoTheGroundIsBalancedByTheContact) {
  // A 0.5 m bar (1 kg) hinged to the world about y at 5 cm above a frictionless ground, its motor
  // driving its tip down (target +1 rad/s) with at most τ: at rest on its tip, the ground's force
  // balances the motor's torque and the weight's about the hinge,
  //   Σ x_i J_z,i = (m g x_c + τ) h,
  // the tip is on the ground (within the few µm the first contact step, which solves the motor's
  // row after the contacts, lets it in), and the motor pushes at its bound. (With the motor's row
  // solved after the contacts in every step, its push went into the ground every step: the tip
  // 1.3 mm deep at τ = 2 N·m, still sinking at 12 mm/s.) With joint friction f besides the motor,
  // the joint sticks, and friction and ground share the load: the moment lies within ± f h of that.
  const double h = 1e-3, m = 1.0, pivot = 0.05, half_thickness = 0.02, length = 0.5;
  // The rest angle: the tip's lower edge on the ground, pivot − L sin θ − t cos θ = 0 (Newton).
  double rest = 0.06;
  for (int k = 0; k < 50; ++k) {
    const double f = pivot - length * std::sin(rest) - half_thickness * std::cos(rest);
    rest -= f / (-length * std::cos(rest) + half_thickness * std::sin(rest));
  }
  for (const auto& [torque, friction] :
       {std::pair{0.0, 0.0}, std::pair{2.0, 0.0}, std::pair{20.0, 0.0}, std::pair{2.0, 0.5}}) {
    SCOPED_TRACE("motor's bound " + std::to_string(torque) + " N m, friction " + std::to_string(friction));
    ContactWorld w = MakeWorld();
    Material frictionless;
    frictionless.static_friction = frictionless.kinetic_friction = 0;
    w.AddGround(dynamics::Ground(Vector3::UnitZ(), 0.0, frictionless));
    const Vector3 size(length, 2 * half_thickness, 2 * half_thickness);
    const int bar = w.AddBody(Box(m, size, Vector3(length / 2, 0, pivot)), BoxCollider(size, frictionless));
    Joint hinge = Hinge(w, -1, bar, Vector3(0, 0, pivot), Vector3::UnitY());
    if (torque > 0) {
      hinge.motor.mode = dynamics::JointMotor::Mode::kVelocity;
      hinge.motor.target = 1.0;
      hinge.motor.max_effort = torque;
    }
    hinge.friction = friction;
    const int joint = w.AddJoint(hinge);
    Simulate(w, h, 2000);
    const dynamics::JointState s = w.world().joint_state(joint);
    EXPECT_NEAR(s.position[0], rest, 2e-5);  // the tip within 10 µm of the ground
    EXPECT_LT(std::abs(s.velocity[0]), 1e-7);
    EXPECT_NEAR(s.drive_impulse, torque * h, friction * h + 1e-15);  // the friction's share
    double moment = 0;
    for (const dynamics::ContactReport& c : w.Contacts()) {
      ASSERT_EQ(c.a, bar);
      moment += c.point.x() * c.impulse.z();
    }
    const double x_c = length / 2 * std::cos(rest);  // the centre's lever arm about the hinge
    EXPECT_NEAR(moment, (m * kG * x_c + torque) * h, friction * h + 1e-6 * (m * kG * x_c + torque) * h);
    // The balance with the joint's reported impulse (the motor's and the friction's together).
    EXPECT_NEAR(moment, m * kG * x_c * h + s.drive_impulse, 1e-6 * (m * kG * x_c + torque) * h);
  }
}

TEST(JointedContact, ABoxRestsOnALeverThatItsJointsFrictionHolds) {
  // A horizontal 0.5 m bar (1 kg) hinged to the world about y, its joint's Coulomb friction 5 N·m
  // above the 2.45 N·m its weight and the 1.80 N·m of a 0.4 kg box set down (touching, at rest) on
  // its far end: the joint sticks, the bar stays where it is (but for the few µrad of the first
  // contact step, which solves the friction's row after the contacts) and the box rests on it, the
  // contacts carrying the box's weight, Σ J_z = m g h. (With the friction's row after the contacts
  // in every step, the contacts saw a free joint: the bar gave way under the box, 0.04 rad in
  // 1.5 s, the box sliding off it at 2.4 cm/s.)
  const double h = 1e-3, length = 0.5, box_mass = 0.4;
  ContactWorld w = MakeWorld();
  const Vector3 bar_size(length, 0.04, 0.04), box_size(0.06, 0.06, 0.06);
  const int bar = w.AddBody(Box(1.0, bar_size, Vector3(length / 2, 0, 0.5)), BoxCollider(bar_size));
  Joint hinge = Hinge(w, -1, bar, Vector3(0, 0, 0.5), Vector3::UnitY());
  hinge.friction = 5.0;
  const int joint = w.AddJoint(hinge);
  const int box =
      w.AddBody(Box(box_mass, box_size, Vector3(length - 0.04, 0, 0.5 + 0.02 + 0.03)), BoxCollider(box_size));
  Simulate(w, h, 1500);
  const dynamics::JointState s = w.world().joint_state(joint);
  EXPECT_LT(std::abs(s.position[0]), 1e-5);
  EXPECT_LT(std::abs(s.velocity[0]), 1e-9);
  const RigidBody& b = w.world().bodies()[static_cast<std::size_t>(box)];
  EXPECT_NEAR(b.position.z(), 0.5 + 0.02 + 0.03, 1e-5);  // on the bar, not in it
  EXPECT_LT(b.velocity.norm(), 1e-7);
  double carried = 0;
  for (const dynamics::ContactReport& c : w.Contacts()) {
    if (c.a == box) carried += c.impulse.z();
    if (c.b == box) carried -= c.impulse.z();
  }
  EXPECT_NEAR(carried, box_mass * kG * h, 1e-6 * box_mass * kG * h);
}

TEST(JointedContact, AWeakMotorsLinkStrikesABallWithItsOwnInertia) {
  // A 0.5 m bar (1 kg, I = 0.0835 kg·m² about its hinge) turning about z at ω0 = 1 rad/s, its
  // velocity motor holding that rate with at most 0.01 N·m, strikes a free 1 kg ball (no gravity,
  // no friction, e = 0) at r = 0.45 m: the impact is the bar's inertia against the ball's,
  //   v = I ω0 r / (I + m r²) = 0.131 m/s,
  // not the motor's target rate (0.45 m/s, as if the bar were held rigid: the motor cannot).
  const double h = 1e-3, length = 0.5, r = 0.45, ball = 1.0, radius = 0.03;
  World free_space;
  ContactWorld w(std::move(free_space));
  Material frictionless;
  frictionless.static_friction = frictionless.kinetic_friction = 0;
  const Vector3 size(length, 0.04, 0.04);
  const int bar = w.AddBody(Box(1.0, size, Vector3(length / 2, 0, 0)), BoxCollider(size, frictionless));
  RigidBody b;
  b.mass = ball;
  b.inertia = Vector3::Constant(0.4 * ball * radius * radius);
  b.position = Vector3(r, 0.02 + radius + 0.002, 0);  // 2 mm ahead of the bar's face
  const int sphere = w.AddBody(b, Collider{shape::Sphere{radius}, Matrix3::Identity(), Vector3::Zero(), frictionless});
  Joint hinge = Hinge(w, -1, bar, Vector3::Zero(), Vector3::UnitZ());
  hinge.motor.mode = dynamics::JointMotor::Mode::kVelocity;
  hinge.motor.target = 1.0;
  hinge.motor.max_effort = 0.01;
  hinge.velocity = {1.0};
  w.AddJoint(hinge);
  const double inertia = 1.0 * (length * length + 0.04 * 0.04) / 12 + 1.0 * (length / 2) * (length / 2);
  const double expected = inertia * 1.0 * r / (inertia + ball * r * r);
  // The ball's velocity and the bar's at the ball, five steps after the first contact (the motor's
  // 0.01 N·m adds 8·10⁻⁵ m/s by then): they move together.
  long first = -1;
  double struck = 0, tip = 0;
  const auto& bodies = w.world().bodies();
  Simulate(w, h, 40, [&](long k) {
    if (first < 0 && !w.Contacts().empty()) first = k;
    if (first < 0 || k != first + 5) return;
    struck = bodies[static_cast<std::size_t>(sphere)].velocity.y();
    tip = bodies[static_cast<std::size_t>(bar)].AngularVelocity().z() * r;
  });
  ASSERT_GE(first, 0) << "no impact";
  EXPECT_NEAR(struck, expected, 2e-3 * expected);
  EXPECT_NEAR(tip, struck, 1e-3 * expected);
}

TEST(JointedContact, SelfCollisionIsSwitchable) {
  // A bar welded to the world, a second bar hinged about z at its end, swung round at 3 rad/s
  // without gravity, and a ball welded to the second bar's far end: after half a turn the ball
  // (two joints from the first bar, so not its neighbour) reaches the first bar. With
  // self-collision it stops there; without, it passes through and the hinge turns on.
  for (const bool self : {false, true}) {
    ContactOptions options;
    options.self_collision = self;
    ContactWorld w(World(Integrator::kImplicitMidpoint), options);
    const Vector3 bar(0.4, 0.1, 0.1);
    const int a = w.AddBody(Box(1.0, bar, Vector3(0, 0, 0)), BoxCollider(bar));
    const int b = w.AddBody(Box(1.0, bar, Vector3(0.45, 0, 0)), BoxCollider(bar));
    RigidBody ball;
    ball.mass = 0.5;
    ball.inertia = Vector3::Constant(0.4 * 0.5 * 0.05 * 0.05);
    ball.position = Vector3(0.7, 0, 0);
    const int c = w.AddBody(ball, Collider{shape::Sphere{0.05}, Matrix3::Identity(), Vector3::Zero(), Material{}});
    Joint weld;
    weld.type = JointType::kFixed;
    weld.parent = -1;
    weld.child = a;
    w.world().PlaceJoint(weld, Vector3::Zero(), Vector3::UnitZ());
    w.AddJoint(weld);
    Joint hinge = Hinge(w, a, b, Vector3(0.25, 0, 0), Vector3::UnitZ());
    hinge.velocity = {3.0};
    const int h = w.AddJoint(hinge);
    Joint hand;
    hand.type = JointType::kFixed;
    hand.parent = b;
    hand.child = c;
    w.world().PlaceJoint(hand, ball.position, Vector3::UnitZ());
    w.AddJoint(hand);
    double turned = 0;
    Simulate(w, 1e-3, 1500, [&](long) { turned = std::max(turned, w.world().joint_state(h).position[0]); });
    if (self) {
      // The ball (0.45 m from the hinge) meets the bar's end face (x = -0.2 ... its corner) before
      // half a turn: it never gets past pi.
      EXPECT_LT(turned, massprops::kPi);
      EXPECT_GT(turned, 2.5);
    } else {
      EXPECT_GT(turned, 4.0);  // through the bar and on
    }
  }
}

TEST(JointedContact, ABoxDroppedOnALimpRobotDoesNotSinkIntoIt) {
  // An 8 kg box falls 0.5 m onto the limp quadruped, whose legs fold onto their stops under it:
  // the legs pressed on their stops hold rigid against the ground, and nothing sinks into
  // anything by more than the contacts' slop and a step's worth of motion.
  ContactWorld w = MakeWorld();
  w.AddGround({});
  std::vector<int> joints;
  AddLimpQuadruped(w, 0.0, joints);
  const Vector3 size = Vector3::Constant(0.2);
  w.AddBody(Box(8.0, size, Vector3(0, 0, 1.0)), BoxCollider(size));
  double deepest = 0;
  Simulate(w, 1e-3, 2000, [&](long) { deepest = std::max(deepest, w.stats().max_penetration); });
  EXPECT_LT(deepest, 2e-3);
  for (const RigidBody& b : w.world().bodies()) EXPECT_GT(b.position.z(), 0.0);
}

}  // namespace
