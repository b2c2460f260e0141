// Contact (dynamics/contact.h) against closed forms: a block sliding down and sticking on an
// incline, a sphere and a cylinder rolling, a ball bouncing, a ball with backspin, a box and a
// stack of boxes at rest, collisions in free space; energy never rises in a step (passivity),
// and free flight is the world's own integrator bit for bit.

#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "dynamics/contact.h"

namespace dynamics {
namespace {

constexpr double kG = 9.81;

Quaternion AboutY(double angle) { return Quaternion(Eigen::AngleAxisd(angle, Vector3::UnitY())); }

RigidBody BoxBody(const Vector3& half, double density, const Vector3& x, const Quaternion& q = Quaternion::Identity()) {
  RigidBody b;
  const Vector3 s = 2 * half;
  b.mass = density * s.prod();
  b.inertia = Vector3(s[1] * s[1] + s[2] * s[2], s[0] * s[0] + s[2] * s[2], s[0] * s[0] + s[1] * s[1]) * (b.mass / 12);
  b.position = x;
  b.orientation = q;
  return b;
}

RigidBody SphereBody(double r, double density, const Vector3& x) {
  RigidBody b;
  b.mass = density * 4.0 / 3 * massprops::kPi * r * r * r;
  b.inertia = Vector3::Constant(0.4 * b.mass * r * r);
  b.position = x;
  return b;
}

Material Mat(double mu_s, double mu_k, double e = 0) { return Material{mu_s, mu_k, e}; }
Collider Of(Shape s) { return Collider{std::move(s), Matrix3::Identity(), Vector3::Zero(), Material{}}; }

// Steps n times, checking after each step that the total energy did not rise by more than
// `slack` (1e-9) of it (plus what a non-conservative force could add: none here). By default the
// sweeps stop at 10⁻⁹ m/s: a tall stack's first steps, before its sweeps converge, may then gain
// ~10⁻⁸ of the energy in a step (the README's "Contact solver"): 1e-7 there (kSettledSlack).
constexpr double kSettledSlack = 1e-7;
void Simulate(ContactWorld& w, double h, int n, const std::function<void(int)>& each = nullptr, double slack = 1e-9) {
  double energy = w.world().Diagnose().total_energy;
  for (int i = 0; i < n; ++i) {
    const StepStatus s = w.Step(h);
    ASSERT_TRUE(s.ok) << s.message;
    const double now = w.world().Diagnose().total_energy;
    ASSERT_LE(now, energy + slack * std::max(1.0, std::abs(energy)))
        << "energy rose at step " << i << " by " << now - energy << " (contacts " << w.stats().contacts << ")";
    energy = now;
    if (each) each(i);
  }
}

// Gravity tilted by θ about y: the ground z = 0 is an incline of angle θ, downhill along +x.
std::unique_ptr<Force> TiltedGravity(double theta) {
  return Gravity(Vector3(kG * std::sin(theta), 0, -kG * std::cos(theta)));
}

TEST(Contact, BlockSlidesDownAnInclineAtTheKineticRate) {
  const double theta = 30 * massprops::kPi / 180, mu_s = 0.3, mu_k = 0.2;
  ContactWorld w;
  const Vector3 half(0.1, 0.05, 0.025);
  w.AddBody(BoxBody(half, 500, Vector3(0, 0, half.z())),
            Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), Mat(mu_s, mu_k)});
  w.AddGround({Vector3::UnitZ(), 0, Mat(mu_s, mu_k)});
  w.AddForce(TiltedGravity(theta));
  const double h = 1e-3;
  Simulate(w, h, 1000);
  const double a = kG * (std::sin(theta) - mu_k * std::cos(theta));
  const RigidBody& b = w.world().bodies()[0];
  EXPECT_NEAR(b.velocity.x(), a * 1.0, 0.01 * a);
  EXPECT_NEAR(b.position.x(), 0.5 * a, 0.01 * 0.5 * a);
  EXPECT_NEAR(b.position.z(), half.z(), 1e-9);  // it neither sinks nor lifts
}

TEST(Contact, BlockSticksOnAnInclineWithinStaticFriction) {
  // tan 30° = 0.577 < μs = 0.7: no creep. The incline is a tilted ground plane this time.
  const double theta = 30 * massprops::kPi / 180;
  ContactWorld w;
  const Vector3 n(-std::sin(theta), 0, std::cos(theta));
  const Vector3 half(0.1, 0.05, 0.025);
  const Vector3 start = n * half.z();
  w.AddBody(BoxBody(half, 500, start, AboutY(-theta)),
            Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), Mat(0.7, 0.5)});
  w.AddGround({n, 0, Mat(0.7, 0.5)});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  Simulate(w, 1e-3, 10000);
  const RigidBody& b = w.world().bodies()[0];
  EXPECT_LT((b.position - start).norm(), 1e-6) << (b.position - start).transpose();
  EXPECT_LT(b.velocity.norm(), 1e-9);
}

TEST(Contact, SphereRollsWithoutSlipping) {
  const double theta = 20 * massprops::kPi / 180, r = 0.1;
  ContactWorld w;
  w.AddBody(SphereBody(r, 1000, Vector3(0, 0, r)),
            Collider{shape::Sphere{r}, Matrix3::Identity(), Vector3::Zero(), Mat(0.5, 0.5)});
  w.AddGround({Vector3::UnitZ(), 0, Mat(0.5, 0.5)});
  w.AddForce(TiltedGravity(theta));
  Simulate(w, 1e-3, 1000);
  const RigidBody& b = w.world().bodies()[0];
  const double a = kG * std::sin(theta) / (1 + 0.4);  // k²/r² = 2/5
  EXPECT_NEAR(b.velocity.x(), a, 1e-3 * a);
  // Rolling: the contact point does not slide (v = ω r).
  EXPECT_LT(std::abs(b.velocity.x() - b.AngularVelocity().y() * r), 1e-6);
}

TEST(Contact, CylinderRollsWithoutSlipping) {
  const double theta = 15 * massprops::kPi / 180, r = 0.05, half_length = 0.1;
  ContactWorld w;
  RigidBody b;
  b.mass = 1000 * massprops::kPi * r * r * 2 * half_length;
  const double across = b.mass * (3 * r * r + 4 * half_length * half_length) / 12;
  b.inertia = Vector3(across, across, 0.5 * b.mass * r * r);
  b.position = Vector3(0, 0, r);
  b.orientation = Quaternion(Eigen::AngleAxisd(massprops::kPi / 2, Vector3::UnitX()));  // axis along y
  w.AddBody(b, Collider{shape::Cylinder{r, half_length}, Matrix3::Identity(), Vector3::Zero(), Mat(0.5, 0.5)});
  w.AddGround({Vector3::UnitZ(), 0, Mat(0.5, 0.5)});
  w.AddForce(TiltedGravity(theta));
  Simulate(w, 1e-3, 1000);
  const RigidBody& c = w.world().bodies()[0];
  const double a = kG * std::sin(theta) / (1 + 0.5);  // k²/r² = 1/2
  EXPECT_NEAR(c.velocity.x(), a, 1e-3 * a);
  EXPECT_NEAR(c.position.z(), r, 1e-9);
}

TEST(Contact, SmallBouncesDieOutInsteadOfHoveringOverTheGround) {
  // A 1×2×3 cm box dropped flat from 0.5 mm with restitution 0.3: each bounce is slower, and once
  // slower than the resting threshold it lands. A bounce taken at a speculative contact's gap, at
  // the speed the step's kick gives, used to keep it hopping 20 µm above the ground for ever.
  const Vector3 half(0.005, 0.01, 0.015);
  ContactOptions options;
  options.sleeping = true;
  ContactWorld w(World(), options);
  w.AddBody(BoxBody(half, 1000, Vector3(0, 0, half.z() + 5e-4)),
            Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5, 0)});
  w.AddGround({Vector3::UnitZ(), 0, Mat(0.5, 0.4, 0.3)});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  int bounces = 0;
  double last_vz = 0;
  Simulate(w, 1e-3, 2000, [&](int) {
    const double vz = w.world().bodies()[0].velocity.z();
    if (last_vz < 0 && vz > 0) ++bounces;
    last_vz = vz;
  });
  EXPECT_GE(bounces, 1);  // it did bounce
  EXPECT_EQ(w.stats().sleeping, 1);
  EXPECT_NEAR(w.world().bodies()[0].position.z(), half.z(), 1e-6);
}

TEST(Contact, ElasticBallNeverBouncesHigherThanItFell) {
  const double r = 0.02, h0 = 0.2;
  ContactWorld w;
  w.AddBody(SphereBody(r, 1000, Vector3(0, 0, r + h0)),
            Collider{shape::Sphere{r}, Matrix3::Identity(), Vector3::Zero(), Mat(0.5, 0.5, 1.0)});
  w.AddGround({Vector3::UnitZ(), 0, Mat(0.5, 0.5, 1.0)});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  std::vector<double> apex;
  double last_vz = 0;
  for (int i = 0; i < 5000; ++i) {
    ASSERT_TRUE(w.Step(1e-3).ok);
    const RigidBody& b = w.world().bodies()[0];
    if (last_vz > 0 && b.velocity.z() <= 0) apex.push_back(b.position.z() - r);
    last_vz = b.velocity.z();
  }
  ASSERT_GE(apex.size(), 4u);
  for (double a : apex) {
    EXPECT_LE(a, h0 * (1 + 1e-9));
    EXPECT_GT(a, 0.97 * h0);  // and loses little: e = 1
  }
}

TEST(Contact, BallBouncesToEToTheTwoN) {
  const double r = 0.05, h0 = 1.0, e = 0.8;
  ContactWorld w;
  w.AddBody(SphereBody(r, 1000, Vector3(0, 0, r + h0)),
            Collider{shape::Sphere{r}, Matrix3::Identity(), Vector3::Zero(), Mat(0.5, 0.5, e)});
  w.AddGround({Vector3::UnitZ(), 0, Mat(0.5, 0.5, e)});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  std::vector<double> apex;
  double last_vz = 0;
  Simulate(w, 1e-4, 40000, [&](int) {
    const RigidBody& b = w.world().bodies()[0];
    if (last_vz > 0 && b.velocity.z() <= 0) apex.push_back(b.position.z() - r);
    last_vz = b.velocity.z();
  });
  ASSERT_GE(apex.size(), 5u);
  double previous = h0;
  for (int n = 0; n < 5; ++n) {
    EXPECT_NEAR(apex[static_cast<std::size_t>(n)] / previous, e * e, 0.01 * e * e) << "bounce " << n + 1;
    EXPECT_NEAR(apex[static_cast<std::size_t>(n)], std::pow(e, 2 * (n + 1)) * h0, 0.01 * std::pow(e, 2 * (n + 1)));
    previous = apex[static_cast<std::size_t>(n)];
  }
}

TEST(Contact, BallWithBackspinRollsAtTheClosedFormTimeAndSpeed) {
  const double r = 0.1, v0 = 3, w0 = 10, mu = 0.2;
  ContactWorld w;
  RigidBody b = SphereBody(r, 1000, Vector3(0, 0, r));
  b.velocity = Vector3(v0, 0, 0);
  b.SetAngularVelocity(Vector3(0, -w0, 0));  // backspin: rolling forward would be +v/r about y
  w.AddBody(b, Collider{shape::Sphere{r}, Matrix3::Identity(), Vector3::Zero(), Mat(mu, mu)});
  w.AddGround({Vector3::UnitZ(), 0, Mat(mu, mu)});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  const double h = 1e-4;
  double t_roll = -1;
  Simulate(w, h, 10000, [&](int i) {
    const RigidBody& s = w.world().bodies()[0];
    if (t_roll < 0 && std::abs(s.velocity.x() - s.AngularVelocity().y() * r) < 1e-9) t_roll = (i + 1) * h;
  });
  const double t_star = 2 * (v0 + r * w0) / (7 * mu * kG), v_final = (5 * v0 - 2 * r * w0) / 7;
  EXPECT_NEAR(t_roll, t_star, 0.02 * t_star);
  EXPECT_NEAR(w.world().bodies()[0].velocity.x(), v_final, 0.02 * v_final);
}

TEST(Contact, DroppedBoxComesToRest) {
  const Vector3 half(0.05, 0.05, 0.05);
  ContactWorld w;
  const Quaternion tilt(Eigen::AngleAxisd(0.3, Vector3(1, 1, 0).normalized()));
  w.AddBody(BoxBody(half, 800, Vector3(0, 0, 0.3), tilt),
            Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5)});
  w.AddGround({Vector3::UnitZ(), 0, Mat(0.6, 0.5)});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  double deepest = 0;
  Simulate(w, 1e-3, 3000, [&](int) { deepest = std::max(deepest, w.stats().max_penetration); });
  const Vector3 settled = w.world().bodies()[0].position;
  Simulate(w, 1e-3, 10000, [&](int) { deepest = std::max(deepest, w.stats().max_penetration); });
  const RigidBody& b = w.world().bodies()[0];
  EXPECT_LT(b.velocity.norm(), 1e-4);
  EXPECT_LT((b.position - settled).norm(), 1e-3);
  EXPECT_NEAR(b.position.z(), half.z(), 1e-4 * 0.1);  // face down
  EXPECT_LT(deepest, 1e-4 * 0.1);
}

TEST(Contact, FinelyFacetedHullRestsFlatOnAtMostSixteenPoints) {
  // A 3000-sided prism (a cylinder's hull as a mesh tool writes it) standing on its end: 3000
  // corners touch the ground; 16 of them hold it, and it stands still.
  const int n = 3000;
  const double r = 0.05, half = 0.02;
  shape::Convex prism;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * massprops::kPi * i / n;
    prism.vertices.emplace_back(r * std::cos(a), r * std::sin(a), -half);
    prism.vertices.emplace_back(r * std::cos(a), r * std::sin(a), half);
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    prism.triangles.push_back({2 * i, 2 * j, 2 * j + 1});
    prism.triangles.push_back({2 * i, 2 * j + 1, 2 * i + 1});
    if (i >= 1 && i + 1 < n) {
      prism.triangles.push_back({0, 2 * j, 2 * i});
      prism.triangles.push_back({1, 2 * i + 1, 2 * j + 1});
    }
  }
  RigidBody b;
  b.mass = 1000 * massprops::kPi * r * r * 2 * half;
  b.inertia = b.mass * Vector3(r * r / 4 + half * half / 3, r * r / 4 + half * half / 3, r * r / 2);
  b.position = Vector3(0, 0, half);
  ContactWorld w;
  w.AddBody(b, Collider{prism, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5)});
  w.AddGround({Vector3::UnitZ(), 0, Mat(0.6, 0.5)});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  int most = 0;
  Simulate(w, 1e-3, 500, [&](int) { most = std::max(most, w.stats().contacts); });
  EXPECT_LE(most, 16);
  EXPECT_GE(most, 3);
  const RigidBody& end = w.world().bodies()[0];
  EXPECT_NEAR((end.position - b.position).norm(), 0, 1e-9);
  EXPECT_LT(end.velocity.norm() + end.AngularVelocity().norm() * r, 1e-9);
}

// Ten boxes stacked: they stand, by default (sweeps to 10⁻⁹ m/s, shock propagation when they run
// out) and in exact mode; the top box moves less than 0.01 mm in 10 s.
TEST(Contact, StackOfTenBoxesStands) {
  for (const bool exact : {false, true}) {
    SCOPED_TRACE(exact ? "exact" : "default");
    const Vector3 half(0.05, 0.05, 0.05);
    ContactOptions options;
    options.exact = exact;
    ContactWorld w(World(), options);
    for (int i = 0; i < 10; ++i) {
      w.AddBody(BoxBody(half, 500, Vector3(0, 0, half.z() * (2 * i + 1))),
                Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5)});
    }
    w.AddGround({Vector3::UnitZ(), 0, Mat(0.6, 0.5)});
    w.AddForce(Gravity(Vector3(0, 0, -kG)));
    std::vector<Vector3> start;
    for (const RigidBody& b : w.world().bodies()) start.push_back(b.position);
    double deepest = 0, top_drift = 0;
    Simulate(
        w, 1e-3, 10000,
        [&](int) {
          deepest = std::max(deepest, w.stats().max_penetration);
          top_drift = std::max(top_drift, (w.world().bodies()[9].position - start[9]).norm());
        },
        exact ? 1e-9 : kSettledSlack);
    for (std::size_t i = 0; i < start.size(); ++i) {
      const RigidBody& b = w.world().bodies()[i];
      EXPECT_LT(b.velocity.norm(), exact ? 1e-9 : 1e-5) << "box " << i;
    }
    EXPECT_LT(top_drift, 1e-5);
    EXPECT_LT(deepest, 1e-4 * 0.1);
  }
}

TEST(Contact, CollisionsInFreeSpaceConserveMomentum) {
  for (const bool boxes : {false, true}) {
    ContactWorld w;
    const double r = 0.1;
    RigidBody a = boxes ? BoxBody(Vector3::Constant(r), 1000, Vector3(-0.5, 0.03, 0.02))
                        : SphereBody(r, 1000, Vector3(-0.5, 0.05, 0));
    RigidBody b = boxes ? BoxBody(Vector3(0.1, 0.15, 0.05), 700, Vector3(0.5, 0, 0),
                                  Quaternion(Eigen::AngleAxisd(0.4, Vector3(0, 1, 1).normalized())))
                        : SphereBody(0.15, 700, Vector3(0.5, 0, 0));
    a.velocity = Vector3(3, 0, 0);
    a.SetAngularVelocity(Vector3(0, 2, 1));
    b.velocity = Vector3(-1, 0.2, 0);
    const Shape sa = boxes ? Shape(shape::Box{Vector3::Constant(r)}) : Shape(shape::Sphere{r});
    const Shape sb = boxes ? Shape(shape::Box{Vector3(0.1, 0.15, 0.05)}) : Shape(shape::Sphere{0.15});
    w.AddBody(a, Collider{sa, Matrix3::Identity(), Vector3::Zero(), Mat(0.4, 0.3, 0.5)});
    w.AddBody(b, Collider{sb, Matrix3::Identity(), Vector3::Zero(), Mat(0.4, 0.3, 0.5)});
    const Diagnostics start = w.world().Diagnose();
    int touched = 0;
    Simulate(w, 1e-3, 600, [&](int) { touched += w.stats().contacts > 0; });
    const Diagnostics end = w.world().Diagnose();
    EXPECT_GT(touched, 0) << (boxes ? "boxes" : "spheres");
    EXPECT_LT((end.linear_momentum - start.linear_momentum).norm(), 1e-12 * start.linear_momentum.norm());
    EXPECT_LT((end.angular_momentum - start.angular_momentum).norm(), 1e-12 * start.angular_momentum.norm() + 1e-13);
    EXPECT_LT(end.kinetic_energy, start.kinetic_energy);
  }
}

TEST(Contact, FreeFlightIsTheWorldsIntegratorBitForBit) {
  World plain;
  ContactWorld w;
  RigidBody b = BoxBody(Vector3(0.1, 0.2, 0.3), 1000, Vector3(0, 0, 5));
  b.SetAngularVelocity(Vector3(1, 2, 3));
  plain.AddBody(b);
  w.AddBody(b, Of(shape::Box{Vector3(0.1, 0.2, 0.3)}));
  w.AddGround({Vector3::UnitZ(), 0, {}});
  plain.AddForce(Gravity(Vector3(0, 0, -kG)));
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  for (int i = 0; i < 500; ++i) {  // 0.5 s: it falls 1.2 m, far from the ground
    plain.Step(1e-3);
    w.Step(1e-3);
    ASSERT_EQ(w.stats().contacts, 0);
  }
  const RigidBody& p = plain.bodies()[0];
  const RigidBody& c = w.world().bodies()[0];
  EXPECT_EQ(p.position, c.position);
  EXPECT_EQ(p.velocity, c.velocity);
  EXPECT_EQ(p.orientation.coeffs(), c.orientation.coeffs());
  EXPECT_EQ(p.angular_momentum, c.angular_momentum);
}

TEST(Contact, BadShapesAndMaterialsAreRefused) {
  ContactWorld w;
  EXPECT_THROW(w.AddBody(RigidBody{}, Of(shape::Sphere{-1})), std::invalid_argument);
  EXPECT_THROW(w.AddGround({Vector3::Zero(), 0, {}}), std::invalid_argument);
  EXPECT_THROW(w.AddBody(RigidBody{}, Collider{shape::Sphere{1}, Matrix3::Identity(), Vector3::Zero(), Mat(0.2, 0.5)}),
               std::invalid_argument);  // kinetic above static
  const shape::Convex tetra{{Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)},
                            {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
  EXPECT_THROW(w.AddBody(RigidBody{}, Of(shape::Convex{tetra.vertices, {}})), std::invalid_argument);
  // Triangles that do not bound a convex solid (one turned inward).
  EXPECT_THROW(w.AddBody(RigidBody{}, Of(shape::Convex{tetra.vertices, {{0, 1, 2}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}})),
               std::invalid_argument);
  EXPECT_THROW(w.AddGround({Vector3::UnitZ(), 0, Mat(0.5, 0.5, 1.5)}), std::invalid_argument);
}

// A triangular prism given as a convex hull (vertices and outward triangles), dropped tilted onto
// a table (a static box): it comes to rest on one of its faces, on the table's top.
TEST(Contact, ConvexHullComesToRestOnATable) {
  const double s = 0.1, len = 0.2;
  std::vector<Vector3> v;
  for (double y : {-len / 2, len / 2}) {
    v.emplace_back(-s / 2, y, -s * std::sqrt(3.0) / 6);
    v.emplace_back(s / 2, y, -s * std::sqrt(3.0) / 6);
    v.emplace_back(0, y, s * std::sqrt(3.0) / 3);
  }
  const shape::Convex prism{v,
                            {{0, 1, 2}, {3, 5, 4}, {0, 3, 4}, {0, 4, 1}, {1, 4, 5}, {1, 5, 2}, {2, 5, 3}, {2, 3, 0}}};
  RigidBody b;
  b.mass = 1000 * (std::sqrt(3.0) / 4 * s * s) * len;
  b.inertia =
      Vector3(b.mass * (s * s / 12 + len * len / 12), b.mass * s * s / 12, b.mass * (s * s / 12 + len * len / 12));
  b.position = Vector3(0, 0, 0.3);
  b.orientation = Quaternion(Eigen::AngleAxisd(0.5, Vector3(1, 0.3, 0).normalized()));
  ContactWorld w;
  w.AddBody(b, Collider{prism, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5)});
  w.AddStatic(Collider{shape::Box{Vector3(0.5, 0.5, 0.05)}, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5)},
              Matrix3::Identity(), Vector3(0, 0, -0.05));  // top at z = 0
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  double deepest = 0;
  Simulate(w, 1e-3, 4000, [&](int) { deepest = std::max(deepest, w.stats().max_penetration); });
  const RigidBody& c = w.world().bodies()[0];
  EXPECT_LT(c.velocity.norm(), 1e-4);
  // On a rectangular face (the center of mass s √3/6 above it) or a triangular end (len / 2).
  const double z = c.position.z();
  EXPECT_TRUE(std::abs(z - s * std::sqrt(3.0) / 6) < 1e-4 || std::abs(z - len / 2) < 1e-4) << z;
  EXPECT_LT(deepest, 1e-5);
}

// A small fast ball (10 cm per step) against a 1 mm plate: stopped at the plate, not through it.
TEST(Contact, FastSmallBodiesDoNotTunnel) {
  ContactWorld w;
  RigidBody ball = SphereBody(0.01, 1000, Vector3(0, 0, 1));
  ball.velocity = Vector3(0, 0, -100);
  w.AddBody(ball, Collider{shape::Sphere{0.01}, Matrix3::Identity(), Vector3::Zero(), Mat(0.5, 0.5)});
  w.AddStatic(Of(shape::Box{Vector3(0.5, 0.5, 0.0005)}));
  Simulate(w, 1e-3, 100);
  const RigidBody& b = w.world().bodies()[0];
  EXPECT_NEAR(b.position.z(), 0.0005 + 0.01, 1e-9);
  EXPECT_EQ(b.velocity.norm(), 0.0);
}

// A sphere on a ramp that is a static box turned by θ: the closed form of the rolling sphere.
TEST(Contact, SphereRollsDownAStaticRamp) {
  const double theta = 20 * massprops::kPi / 180, r = 0.05;
  const Matrix3 R = Eigen::AngleAxisd(-theta, Vector3::UnitY()).toRotationMatrix();  // its +x rises
  const Vector3 n = R * Vector3::UnitZ();
  ContactWorld w;
  w.AddStatic(Collider{shape::Box{Vector3(2, 0.5, 0.05)}, Matrix3::Identity(), Vector3::Zero(), Mat(0.5, 0.5)}, R,
              -0.05 * n);  // top face through the origin
  w.AddBody(SphereBody(r, 1000, n * r),
            Collider{shape::Sphere{r}, Matrix3::Identity(), Vector3::Zero(), Mat(0.5, 0.5)});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  Simulate(w, 1e-3, 500);
  const RigidBody& b = w.world().bodies()[0];
  const Vector3 downhill = -(R * Vector3::UnitX());
  const double a = kG * std::sin(theta) / 1.4;
  EXPECT_NEAR(b.velocity.dot(downhill), a * 0.5, 1e-3 * a * 0.5);
  EXPECT_NEAR((b.position).dot(n), r, 1e-9);
}

// Sleeping: a settled stack stops being stepped (its positions then stay exactly put), and a
// ball dropped on it wakes the whole island.
TEST(Contact, SleepingStackWakesWhenTouched) {
  ContactOptions options;
  options.sleeping = true;
  ContactWorld w(World(), options);
  const Vector3 half = Vector3::Constant(0.05);
  for (int i = 0; i < 3; ++i) {
    w.AddBody(BoxBody(half, 500, Vector3(0, 0, 0.05 + 0.1 * i)),
              Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5)});
  }
  w.AddGround({Vector3::UnitZ(), 0, Mat(0.6, 0.5)});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  Simulate(w, 1e-3, 1000, nullptr, kSettledSlack);
  EXPECT_EQ(w.stats().sleeping, 3);
  const Vector3 top = w.world().bodies()[2].position;
  Simulate(w, 1e-3, 1000, nullptr, kSettledSlack);
  EXPECT_EQ(w.world().bodies()[2].position, top);  // not stepped: not a bit of drift
  // A ball falls onto the stack: the island wakes, and sleeps again once all is still.
  RigidBody ball = SphereBody(0.03, 1000, Vector3(0, 0, 0.6));
  w.AddBody(ball, Collider{shape::Sphere{0.03}, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5)});
  bool woke = false;
  Simulate(
      w, 1e-3, 3000, [&](int) { woke = woke || w.stats().sleeping == 0; }, kSettledSlack);
  EXPECT_TRUE(woke);
  EXPECT_EQ(w.stats().sleeping, 4);
  EXPECT_NEAR(w.world().bodies()[3].position.z(), 0.3 + 0.03, 1e-4);  // the ball rests on the top box
}

// A cylinder standing on a box (a table) and a box resting on the cylinder: the prism the
// cylinder collides as holds both still.
TEST(Contact, CylinderOnATableUnderABox) {
  for (const bool exact : {false, true}) {
    SCOPED_TRACE(exact ? "exact" : "default");
    ContactOptions options;
    options.exact = exact;
    ContactWorld w(World(), options);
    w.AddStatic(Collider{shape::Box{Vector3(0.5, 0.5, 0.05)}, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5)},
                Matrix3::Identity(), Vector3(0, 0, -0.05));
    RigidBody c;
    c.mass = 1000 * massprops::kPi * 0.05 * 0.05 * 0.2;
    c.inertia = Vector3(c.mass * (3 * 0.05 * 0.05 + 0.04) / 12, c.mass * (3 * 0.05 * 0.05 + 0.04) / 12,
                        0.5 * c.mass * 0.05 * 0.05);
    c.position = Vector3(0, 0, 0.1);
    w.AddBody(c, Collider{shape::Cylinder{0.05, 0.1}, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5)});
    w.AddBody(BoxBody(Vector3(0.1, 0.1, 0.02), 500, Vector3(0, 0, 0.22)),
              Collider{shape::Box{Vector3(0.1, 0.1, 0.02)}, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5)});
    w.AddForce(Gravity(Vector3(0, 0, -kG)));
    Simulate(w, 1e-3, 2000, nullptr, exact ? 1e-9 : kSettledSlack);
    EXPECT_NEAR(w.world().bodies()[0].position.z(), 0.1, 1e-6);
    EXPECT_NEAR(w.world().bodies()[1].position.z(), 0.22, 1e-6);
    EXPECT_LT(w.world().bodies()[1].velocity.norm(), exact ? 1e-6 : 1e-5);
  }
}

TEST(Contact, SameBitsWhateverTheThreads) {
  auto run = [](int threads) {
    ContactWorld w;
    for (int i = 0; i < 6; ++i) {
      RigidBody b = BoxBody(Vector3::Constant(0.05), 600, Vector3(0.02 * i, 0.01 * i, 0.06 + 0.12 * i),
                            Quaternion(Eigen::AngleAxisd(0.2 * i, Vector3(0, 1, 1).normalized())));
      w.AddBody(
          b, Collider{shape::Box{Vector3::Constant(0.05)}, Matrix3::Identity(), Vector3::Zero(), Mat(0.6, 0.5, 0.2)});
    }
    w.AddGround({Vector3::UnitZ(), 0, Mat(0.6, 0.5, 0.2)});
    w.AddForce(Gravity(Vector3(0, 0, -kG)));
    w.set_num_threads(threads);
    for (int i = 0; i < 800; ++i) w.Step(1e-3);
    return w.world().bodies();
  };
  const std::vector<RigidBody> one = run(1), two = run(2);
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].position, two[i].position);
    EXPECT_EQ(one[i].orientation.coeffs(), two[i].orientation.coeffs());
  }
}

}  // namespace
}  // namespace dynamics
