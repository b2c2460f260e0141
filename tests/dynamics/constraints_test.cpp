// Loops, couplings and tendons (dynamics/constraints.h) against closed forms: coupled sliders
// falling, a parallelogram four-bar as a pendulum (elliptic period), a welded pair in free flight,
// a slider-crank's piston, a string pendulum (spatial tendon) taut and slack, a fixed tendon's
// range stopping the joints it couples; and the refusals.

#include <boost/math/special_functions/ellint_1.hpp>
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "dynamics/constraints.h"
#include "dynamics/world.h"
#include "joint_bodies.h"

namespace {

using dynamics::BodyFrame;
using dynamics::Coordinate;
using dynamics::Coupling;
using dynamics::Joint;
using dynamics::JointType;
using dynamics::Loop;
using dynamics::LoopType;
using dynamics::RigidBody;
using dynamics::Tendon;
using dynamics::World;
using massprops::Vector3;
using testing::PlacedJoint;
using testing::SolidBox;

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

void Simulate(World& w, double h, long n, const std::function<void(long)>& each = {}) {
  for (long s = 0; s < n; ++s) {
    const dynamics::StepStatus st = w.Step(h);
    ASSERT_TRUE(st.ok) << st.message;
    if (each) each(s);
  }
}

double Q(const World& w, int j) { return w.joint_state(j).position[0]; }

BodyFrame At(int body, const Vector3& origin) {
  BodyFrame f;
  f.body = body;
  f.frame.origin = origin;
  return f;
}

Coordinate JointCoordinate(int j) { return Coordinate{Coordinate::Kind::kJoint, j}; }

// Two vertical sliders, b following a with multiplier k: the pair falls as one coordinate with
// inertia m_a + k² m_b under the force −g (m_a + k m_b).
TEST(Couplings, MimicSlidersFallAsOneCoordinate) {
  for (const double k : {0.5, -2.0, 1.0}) {
    World w;
    const double ma = 1.5, mb = 0.7;
    const int a = w.AddBody(SolidBox(ma, 0.1, 0.1, 0.1, Vector3(0, 0, 0)));
    const int b = w.AddBody(SolidBox(mb, 0.1, 0.1, 0.1, Vector3(1, 0, 0)));
    const int ja = w.AddJoint(PlacedJoint(w, -1, a, Vector3(0, 0, 0), Vector3::UnitZ(), JointType::kPrismatic));
    const int jb = w.AddJoint(PlacedJoint(w, -1, b, Vector3(1, 0, 0), Vector3::UnitZ(), JointType::kPrismatic));
    Coupling c;
    c.name = "mimic";
    c.follower = JointCoordinate(jb);
    c.leader = JointCoordinate(ja);
    c.polynomial = {0, k, 0, 0, 0};
    w.AddCoupling(c);
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
    const double h = 1e-3;
    Simulate(w, h, 1000);
    const double t = w.time();
    const double expected = -kG * t * t * (ma + k * mb) / (2 * (ma + k * k * mb));
    EXPECT_NEAR(Q(w, ja), expected, 1e-9) << "k = " << k;
    EXPECT_NEAR(Q(w, jb), k * Q(w, ja), 1e-12) << "k = " << k;
    EXPECT_NEAR(w.coupling_state(0).residual, 0.0, 1e-12);
  }
}

// A quadratic coupling with an offset, y = 0.1 + 0.5 x + 2 x²: held to rounding while a spring
// swings the leader.
TEST(Couplings, PolynomialCouplingHeldToRounding) {
  World w;
  const int a = w.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3(0, 0, 0)));
  const int b = w.AddBody(SolidBox(2, 0.1, 0.1, 0.1, Vector3(1, 0, 0)));
  Joint jta = PlacedJoint(w, -1, a, Vector3(0, 0, 0), Vector3::UnitX(), JointType::kPrismatic);
  jta.stiffness = 50;
  jta.position = {0.3};
  const int ja = w.AddJoint(jta);
  Joint jtb = PlacedJoint(w, -1, b, Vector3(1, 0, 0), Vector3::UnitX(), JointType::kPrismatic);
  jtb.position = {0.1 + 0.5 * 0.3 + 2 * 0.09};
  const int jb = w.AddJoint(jtb);
  Coupling c;
  c.follower = JointCoordinate(jb);
  c.leader = JointCoordinate(ja);
  c.polynomial = {0.1, 0.5, 2, 0, 0};
  w.AddCoupling(c);
  const double e0 = w.Diagnose().total_energy;
  double worst = 0;
  Simulate(w, 1e-3, 3000, [&](long) {
    const double x = Q(w, ja);
    worst = std::max(worst, std::abs(Q(w, jb) - (0.1 + 0.5 * x + 2 * x * x)));
  });
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(std::abs(w.Diagnose().total_energy / e0 - 1), 1e-4);  // bounded, as for a chain
}

// A parallelogram four-bar: equal cranks hinged to the world, the coupler hinged to the first
// and closed on the second by a ball. It moves as a pendulum I q̈ = −k sin q with I = 2 I_crank +
// m_coupler l² and k = g l (m_crank + m_coupler); released at 60° its period is 4 √(I/k) K(sin 30°).
TEST(Loops, ParallelogramFourBarSwingsAtTheEllipticPeriod) {
  const double l = 1.0, d = 0.8, wdt = 0.05, mc = 1.0, mk = 0.6, q0 = kPi / 3;
  World w;
  const int c1 = w.AddBody(SolidBox(mc, wdt, wdt, l, Vector3(0, 0, -l / 2)));
  const int c2 = w.AddBody(SolidBox(mc, wdt, wdt, l, Vector3(d, 0, -l / 2)));
  const int cp = w.AddBody(SolidBox(mk, d, wdt, wdt, Vector3(d / 2, 0, -l)));
  Joint j1 = PlacedJoint(w, -1, c1, Vector3(0, 0, 0), Vector3::UnitY());
  Joint j2 = PlacedJoint(w, -1, c2, Vector3(d, 0, 0), Vector3::UnitY());
  Joint j3 = PlacedJoint(w, c1, cp, Vector3(0, 0, -l), Vector3::UnitY());
  j1.position = {q0};
  j2.position = {q0};
  j3.position = {-q0};
  const int a1 = w.AddJoint(j1);
  const int a2 = w.AddJoint(j2);
  w.AddJoint(j3);
  // The coupler's end (d/2 from its centre along its x) on the second crank's tip (l/2 below its centre).
  Loop loop;
  loop.name = "closure";
  loop.type = LoopType::kBall;
  loop.a = At(cp, Vector3(d / 2, 0, 0));
  loop.b = At(c2, Vector3(0, 0, -l / 2));
  w.AddLoop(loop);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  const double crank = mc * (wdt * wdt + l * l) / 12 + mc * l * l / 4;
  const double I = 2 * crank + mk * l * l, k = kG * l * (mc + mk);
  const double period = 4 * std::sqrt(I / k) * boost::math::ellint_1(std::sin(q0 / 2));
  const long n = 4000;
  const double h = period / n;
  const double e0 = w.Diagnose().total_energy;
  double gap = 0, energy = 0;
  auto track = [&](long) {
    gap = std::max(gap, w.loop_state(0).residual);
    energy = std::max(energy, std::abs(w.Diagnose().total_energy - e0) / std::abs(e0));
  };
  Simulate(w, h, n / 2, track);
  EXPECT_NEAR(Q(w, a1), -q0, 1e-5);
  EXPECT_NEAR(Q(w, a2), -q0, 1e-5);
  Simulate(w, h, n / 2, track);
  EXPECT_NEAR(Q(w, a1), q0, 1e-5);
  Simulate(w, h, static_cast<long>(10 / h) - n, track);  // to 10 s
  EXPECT_LT(gap, 1e-9);
  EXPECT_LT(energy, 1e-5);
  EXPECT_NEAR(Q(w, a1), Q(w, a2), 1e-9);
}

// A slider-crank: a crank of radius r turning about the world's y axis, a rod of length L from
// its pin to a piston on a slider along x; the piston's position is r cos θ + √(L² − r² sin² θ).
TEST(Loops, SliderCrankPistonFollowsTheClosedFormKinematics) {
  const double r = 0.2, L = 0.6, wdt = 0.02;
  World w;
  const int crank = w.AddBody(SolidBox(1.0, r, wdt, wdt, Vector3(r / 2, 0, 0)));
  const int rod = w.AddBody(SolidBox(0.5, L, wdt, wdt, Vector3(r + L / 2, 0, 0)));
  const int piston = w.AddBody(SolidBox(0.8, 0.05, 0.05, 0.05, Vector3(r + L, 0, 0)));
  Joint jc = PlacedJoint(w, -1, crank, Vector3(0, 0, 0), Vector3::UnitY());
  jc.velocity = {6.0};
  const int ac = w.AddJoint(jc);
  w.AddJoint(PlacedJoint(w, crank, rod, Vector3(r, 0, 0), Vector3::UnitY()));
  const int ap = w.AddJoint(PlacedJoint(w, -1, piston, Vector3(r + L, 0, 0), Vector3::UnitX(), JointType::kPrismatic));
  Loop loop;
  loop.type = LoopType::kBall;
  loop.a = At(rod, Vector3(L / 2, 0, 0));
  loop.b = At(piston, Vector3(0, 0, 0));
  w.AddLoop(loop);
  double worst = 0;
  Simulate(w, 1e-3, 2000, [&](long) {
    // A turn by θ about +y takes x toward −z: the crank pin at (r cos θ, 0, −r sin θ).
    const double th = Q(w, ac);
    const double x = r * std::cos(th) + std::sqrt(L * L - r * r * std::sin(th) * std::sin(th));
    worst = std::max(worst, std::abs(r + L + Q(w, ap) - x));
  });
  EXPECT_LT(worst, 1e-10);
  EXPECT_GT(std::abs(Q(w, ac)), 2 * kPi);  // it went round
}

// Two boxes welded and thrown with a spin: their relative pose stays fixed, their centre of mass
// follows its parabola, and the pair's angular momentum about it is conserved.
TEST(Loops, WeldedPairFliesAsOneBody) {
  World w;
  RigidBody a = SolidBox(1.0, 0.2, 0.1, 0.1, Vector3(0, 0, 0));
  RigidBody b = SolidBox(2.0, 0.1, 0.3, 0.1, Vector3(0.25, 0.05, 0));
  const Vector3 omega(0.3, 0.5, 4.0), v0(1.0, 0.0, 5.0);
  a.velocity = v0;
  b.velocity = v0 + omega.cross(b.position - a.position);
  a.angular_momentum = Vector3(a.inertia.cwiseProduct(omega));  // axes along the world's
  b.angular_momentum = Vector3(b.inertia.cwiseProduct(omega));
  const int ia = w.AddBody(a), ib = w.AddBody(b);
  Loop weld;
  weld.type = LoopType::kWeld;
  weld.a = At(ia, Vector3(0.125, 0.025, 0));
  weld.b = At(ib, Vector3(-0.125, -0.025, 0));
  w.AddLoop(weld);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  const double m = a.mass + b.mass;
  const Vector3 c0 = (a.mass * a.position + b.mass * b.position) / m;
  const Vector3 cv0 = (a.mass * a.velocity + b.mass * b.velocity) / m;
  const Vector3 offset = b.position - a.position;
  double gap = 0;
  Simulate(w, 1e-3, 1000, [&](long) { gap = std::max(gap, w.loop_state(0).residual); });
  const auto& bodies = w.bodies();
  const double t = w.time();
  const Vector3 c = (a.mass * bodies[ia].position + b.mass * bodies[ib].position) / m;
  const Vector3 expected = c0 + cv0 * t + Vector3(0, 0, -0.5 * kG * t * t);
  EXPECT_LT((c - expected).norm(), 1e-9);
  EXPECT_LT(gap, 1e-9);
  // Relative pose: b's offset in a's axes, and b's orientation relative to a's, as at the start.
  const Vector3 now = bodies[ia].orientation.conjugate() * (bodies[ib].position - bodies[ia].position);
  EXPECT_LT((now - offset).norm(), 1e-9);
  EXPECT_LT((bodies[ia].orientation.conjugate() * bodies[ib].orientation).vec().norm(), 1e-9);
}

// A weld's reported impulse is its whole impulse over the step, also in steps where a stop fires
// beside it: a ball welded (at its centre) to the tip of a bar resting on its stop carries the
// ball's weight, |impulse| = m g h, every step.
TEST(Loops, WeldImpulseIsTheLoadItCarriesBesideAStop) {
  World w;
  const double mb = 0.4, h = 1e-3;
  const int bar = w.AddBody(SolidBox(1.0, 0.5, 0.05, 0.05, Vector3(0.25, 0, 0)));
  const int ball = w.AddBody(SolidBox(mb, 0.1, 0.1, 0.1, Vector3(0.5, 0, 0)));
  Joint hinge = PlacedJoint(w, -1, bar, Vector3(0, 0, 0), Vector3::UnitY());
  hinge.limits.upper = 0;  // gravity turns the bar by +y: it rests on this stop
  const int j = w.AddJoint(hinge);
  Loop weld;
  weld.type = LoopType::kWeld;
  weld.a = At(bar, Vector3(0.25, 0, 0));
  weld.b = At(ball, Vector3(0, 0, 0));
  w.AddLoop(weld);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  Simulate(w, h, 200, [&](long s) {
    if (s < 10) return;
    EXPECT_LT(w.joint_state(j).limit_impulse, 0.0);  // the (upper) stop fired in this step too
    EXPECT_NEAR(w.loop_state(0).impulse, mb * kG * h, 1e-9 * mb * kG * h) << "step " << s;
  });
}

// A ball on a string of length L from a fixed point: released taut from the horizontal it
// reaches the lowest point at √(L/g) K(sin 45°) with speed √(2 g L) (the string pulls, taut, and
// never pushes: it is a range, not a rod).
TEST(Tendons, StringPendulumReachesTheBottomAtTheEllipticTime) {
  const double L = 1.0, h = 1e-3;
  World w;
  RigidBody ball = SolidBox(1.0, 0.05, 0.05, 0.05, Vector3(L, 0, 0));
  const int b = w.AddBody(ball);
  Tendon string;
  string.name = "string";
  string.path = {At(-1, Vector3(0, 0, 0)), At(b, Vector3(0, 0, 0))};
  string.limits.upper = L;
  w.AddTendon(string);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  const double expected = std::sqrt(L / kG) * boost::math::ellint_1(std::sin(kPi / 4));
  double x0 = L, t_bottom = -1, speed = 0, stretch = 0;
  Simulate(w, h, static_cast<long>(0.8 / h), [&](long) {
    const RigidBody& now = w.bodies()[b];
    stretch = std::max(stretch, now.position.norm() - L);
    if (t_bottom < 0 && now.position.x() <= 0) {
      t_bottom = w.time() - h * now.position.x() / (now.position.x() - x0);
      speed = now.velocity.norm();
    }
    x0 = now.position.x();
  });
  // Held taut through each step, at the midpoint rule's order (1 ms: 6.6e-7 s and 4e-8 m/s; a
  // stop at each step's end was first order: 1e-4 s at 0.1 ms).
  EXPECT_NEAR(t_bottom, expected, 5e-6);
  EXPECT_NEAR(speed, std::sqrt(2 * kG * L), 1e-6);
  EXPECT_LT(stretch, 1e-9);
  EXPECT_GT(w.tendon_state(0).length, L - 1e-9);  // still taut
}

// Thrown upward inside its length, the ball flies free (the string slack pulls nothing) until the
// string is taut again, which stops its fall.
TEST(Tendons, SlackStringLetsTheBallFlyUntilTaut) {
  const double L = 1.0, h = 1e-4, z0 = -0.5, up = 3.0;
  World w;
  RigidBody ball = SolidBox(1.0, 0.05, 0.05, 0.05, Vector3(0, 0, z0));
  ball.velocity = Vector3(0, 0, up);
  const int b = w.AddBody(ball);
  Tendon string;
  string.path = {At(-1, Vector3(0, 0, 0)), At(b, Vector3(0, 0, 0))};
  string.limits.upper = L;
  w.AddTendon(string);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  // Free flight until z = −L: z0 + up t − g t²/2 = −L.
  const double taut = (up + std::sqrt(up * up + 2 * kG * (z0 + L))) / kG;
  double free_error = 0, stretch = 0;
  Simulate(w, h, static_cast<long>((taut + 0.3) / h), [&](long) {
    const double t = w.time();
    const RigidBody& now = w.bodies()[b];
    if (t < taut - h) {
      free_error = std::max(free_error, std::abs(now.position.z() - (z0 + up * t - 0.5 * kG * t * t)));
      EXPECT_EQ(w.tendon_state(0).impulse, 0.0);
    }
    stretch = std::max(stretch, now.position.norm() - L);
  });
  EXPECT_LT(free_error, 1e-12);
  EXPECT_LT(stretch, 1e-9);
  EXPECT_NEAR(w.bodies()[b].position.z(), -L, 1e-9);  // hanging, stopped
  EXPECT_NEAR(w.bodies()[b].velocity.norm(), 0.0, 1e-9);
}

// Taut and moving inward, a string lets go at once: without gravity the ball flies straight at
// its speed (a rod would hold it on the circle).
TEST(Tendons, TautStringMovingInwardLetsGo) {
  World w;
  RigidBody ball = SolidBox(1.0, 0.05, 0.05, 0.05, Vector3(1, 0, 0));
  ball.velocity = Vector3(-0.5, 0.2, 0);
  const int b = w.AddBody(ball);
  Tendon string;
  string.path = {At(-1, Vector3(0, 0, 0)), At(b, Vector3(0, 0, 0))};
  string.limits.upper = 1.0;
  w.AddTendon(string);
  Simulate(w, 1e-3, 500);
  const double t = w.time();
  EXPECT_LT((w.bodies()[b].position - Vector3(1 - 0.5 * t, 0.2 * t, 0)).norm(), 1e-12);
  EXPECT_EQ(w.tendon_state(0).impulse, 0.0);
}

// A fixed tendon L = q_a + q_b with an upper end stops the two sliders it couples where L leaves
// the range: a perfectly plastic impact along (1, 1), v' = v − λ M⁻¹ (1, 1) with L̇' = 0.
TEST(Tendons, FixedTendonRangeStopsTheJointsItCouples) {
  World w;
  const double ma = 1.0, mb = 3.0, va = 1.0, vb = 0.5, upper = 0.5;
  const int a = w.AddBody(SolidBox(ma, 0.1, 0.1, 0.1, Vector3(0, 0, 0)));
  const int b = w.AddBody(SolidBox(mb, 0.1, 0.1, 0.1, Vector3(0, 1, 0)));
  Joint jta = PlacedJoint(w, -1, a, Vector3(0, 0, 0), Vector3::UnitX(), JointType::kPrismatic);
  jta.velocity = {va};
  Joint jtb = PlacedJoint(w, -1, b, Vector3(0, 1, 0), Vector3::UnitX(), JointType::kPrismatic);
  jtb.velocity = {vb};
  const int ja = w.AddJoint(jta), jb = w.AddJoint(jtb);
  Tendon t;
  t.name = "sum";
  t.joints = {{ja, 1.0}, {jb, 1.0}};
  t.limits.upper = upper;
  w.AddTendon(t);
  double longest = 0;
  Simulate(w, 1e-3, 1000, [&](long) { longest = std::max(longest, Q(w, ja) + Q(w, jb)); });
  const double lambda = (va + vb) / (1 / ma + 1 / mb);
  EXPECT_LT(longest, upper + 1e-12);
  EXPECT_NEAR(w.joint_state(ja).velocity[0], va - lambda / ma, 1e-9);
  EXPECT_NEAR(w.joint_state(jb).velocity[0], vb - lambda / mb, 1e-9);
  EXPECT_NEAR(Q(w, ja) + Q(w, jb), upper, 1e-12);
}

// A fixed tendon's spring: two sliders joined by L = q_a − q_b with stiffness k oscillate
// against each other at ω² = k (1/m_a + 1/m_b), the centre of mass still.
TEST(Tendons, FixedTendonSpringOscillatesAtTheReducedMassFrequency) {
  World w;
  const double ma = 1.0, mb = 2.0, k = 30.0;
  const int a = w.AddBody(SolidBox(ma, 0.1, 0.1, 0.1, Vector3(0, 0, 0)));
  const int b = w.AddBody(SolidBox(mb, 0.1, 0.1, 0.1, Vector3(0, 1, 0)));
  Joint jta = PlacedJoint(w, -1, a, Vector3(0, 0, 0), Vector3::UnitX(), JointType::kPrismatic);
  jta.position = {0.1};
  const int ja = w.AddJoint(jta);
  const int jb = w.AddJoint(PlacedJoint(w, -1, b, Vector3(0, 1, 0), Vector3::UnitX(), JointType::kPrismatic));
  Tendon t;
  t.joints = {{ja, 1.0}, {jb, -1.0}};
  t.stiffness = k;
  w.AddTendon(t);
  const double omega = std::sqrt(k * (1 / ma + 1 / mb));
  const double period = 2 * kPi / omega;
  const long n = 2000;
  Simulate(w, period / n, n);
  EXPECT_NEAR(Q(w, ja) - Q(w, jb), 0.1, 1e-5);
  EXPECT_NEAR(ma * Q(w, ja) + mb * Q(w, jb), ma * 0.1, 1e-12);
}

TEST(Constraints, RefusedWithTheElementNamed) {
  World w;
  const int a = w.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3(0, 0, 0)));
  const int b = w.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3(1, 0, 0)));
  const int ja = w.AddJoint(PlacedJoint(w, -1, a, Vector3(0, 0, 0), Vector3::UnitZ()));
  const int jb = w.AddJoint(PlacedJoint(w, -1, b, Vector3(1, 0, 0), Vector3::UnitZ()));
  auto refused = [&](const std::function<void()>& call, const std::string& words) {
    try {
      call();
      ADD_FAILURE() << "not refused: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  Coupling self;
  self.name = "self";
  self.follower = self.leader = JointCoordinate(ja);
  refused([&] { w.AddCoupling(self); }, "coupling 'self': it couples a coordinate to itself");
  Coupling missing;
  missing.name = "m";
  missing.follower = JointCoordinate(ja);
  missing.leader = JointCoordinate(7);
  refused([&] { w.AddCoupling(missing); }, "joint 7, does not exist");
  Coupling nan;
  nan.name = "nan";
  nan.follower = JointCoordinate(jb);
  nan.leader = JointCoordinate(ja);
  nan.polynomial[2] = std::nan("");
  refused([&] { w.AddCoupling(nan); }, "coupling 'nan': a coefficient is not finite");
  Coupling ab;
  ab.name = "ab";
  ab.follower = JointCoordinate(jb);
  ab.leader = JointCoordinate(ja);
  w.AddCoupling(ab);
  Coupling ba;
  ba.name = "ba";
  ba.follower = JointCoordinate(ja);
  ba.leader = JointCoordinate(jb);
  refused([&] { w.AddCoupling(ba); }, "coupling 'ba': it closes a cycle of couplings");
  Loop apart;
  apart.name = "apart";
  apart.a = At(a, Vector3(0, 0, 0));
  apart.b = At(b, Vector3(0, 0, 0));
  refused([&] { w.AddLoop(apart); },
          "loop 'apart': its frames do not meet where the joints place the bodies: 1 m apart");
  Tendon one;
  one.name = "one";
  one.path = {At(a, Vector3(0, 0, 0))};
  refused([&] { w.AddTendon(one); }, "tendon 'one': a spatial tendon needs two points or more");
  w.set_integrator(dynamics::Integrator::kRK4);
  refused([&] { w.Step(1e-3); }, "loops and couplings are held by the implicit-midpoint integrator only");
}

}  // namespace
