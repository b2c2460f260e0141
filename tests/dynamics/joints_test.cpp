// Joints against closed forms and an independent integration: the large-amplitude physical
// pendulum (elliptic integral), the double pendulum (its own Lagrangian, integrated by odeint),
// the Lagrange top (nutation bounds and period by quadrature), a hanging chain, stops, damping,
// Coulomb friction, springs and motors, and the free joint against the free body.

#include <boost/math/special_functions/ellint_1.hpp>
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>  // its steppers' members warn as uninitialized when copied
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>

#include <gtest/gtest.h>

#include "dynamics/joints.h"
#include "dynamics/world.h"
#include "joint_bodies.h"
#include "massprops/io/mesh_io.h"
#include "massprops/mass_properties.h"

namespace {

using dynamics::Integrator;
using dynamics::Joint;
using dynamics::JointType;
using dynamics::RigidBody;
using dynamics::World;
using massprops::Matrix3;
using massprops::Vector3;

constexpr double kG = 9.81;

using testing::PlacedJoint;
using testing::SolidBox;

/// Runs n steps, calling each(step) after every one; fails the test on a failed step.
void Simulate(World& w, double h, long n, const std::function<void(long)>& each = {}) {
  for (long s = 0; s < n; ++s) {
    const dynamics::StepStatus st = w.Step(h);
    ASSERT_TRUE(st.ok) << st.message;
    if (each) each(s);
  }
}

/// Times at which x(t) crosses zero downwards, by cubic Hermite interpolation of (x, ẋ) between
/// steps.
struct Crossings {
  double t0 = 0, x0 = 0, v0 = 0;
  bool first = true;
  std::vector<double> times;
  void Add(double t, double x, double v) {
    if (!first && x0 > 0 && x <= 0) {
      const double h = t - t0;
      // Hermite on [0, 1]; Newton from the linear guess.
      double s = x0 / (x0 - x);
      for (int it = 0; it < 30; ++it) {
        const double s2 = s * s, s3 = s2 * s;
        const double p =
            (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * h * v0 + (-2 * s3 + 3 * s2) * x + (s3 - s2) * h * v;
        const double dp =
            (6 * s2 - 6 * s) * x0 + (3 * s2 - 4 * s + 1) * h * v0 + (-6 * s2 + 6 * s) * x + (3 * s2 - 2 * s) * h * v;
        s -= p / dp;
      }
      times.push_back(t0 + s * h);
    }
    first = false;
    t0 = t, x0 = x, v0 = v;
  }
};

/// The T-handle of data/meshes hinged 5 cm above its center of mass about a horizontal axis,
/// released at θ0 from hanging: period against T = 4 √(I_pivot / (m g d)) K(sin(θ0/2)).
struct MeshPendulum {
  World w;
  double period = 0;  ///< closed form
  Vector3 pivot;
  Joint joint;
  MeshPendulum(double theta0, Integrator integrator) : w(integrator) {
    const massprops::LoadedMesh loaded =
        massprops::ReadMeshFile(std::string(MASSPROPS_DATA_DIR) + "/meshes/t_handle.obj");
    const massprops::MassProperties mp = massprops::ComputeMassProperties(massprops::Triangulate(loaded.mesh), 2700.0);
    const dynamics::PlacedBody placed = dynamics::BodyFromMassProperties(mp);
    w.AddBody(placed.body);
    const double d = 0.05;
    pivot = placed.body.position + Vector3(0, 0, d);
    const Vector3 axis = Vector3(1, 0.3, 0).normalized();  // not a principal axis
    joint = PlacedJoint(w, -1, 0, pivot, axis);
    joint.position = {theta0};
    w.AddJoint(joint);
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
    const double I_pivot = axis.dot(placed.body.WorldInertia() * axis) + placed.body.mass * d * d;
    period = 4 * std::sqrt(I_pivot / (placed.body.mass * kG * d)) * boost::math::ellint_1(std::sin(theta0 / 2));
  }
  /// Mean period over n periods at step h; the largest anchor separation seen.
  double MeasuredPeriod(double h, int n, double& max_separation) {
    Crossings c;
    max_separation = 0;
    const long steps = static_cast<long>(std::ceil((n + 0.6) * period / h));
    Simulate(w, h, steps, [&](long) {
      const dynamics::JointState s = w.joint_state(0);
      c.Add(w.time(), s.position[0], s.velocity[0]);
      const Vector3 anchor = w.bodies()[0].PointPosition(w.joints()[0].child_frame.origin);
      max_separation = std::max(max_separation, (anchor - pivot).norm());
    });
    EXPECT_GE(c.times.size(), static_cast<std::size_t>(n + 1));
    if (c.times.size() < static_cast<std::size_t>(n + 1)) return 0;
    return (c.times[static_cast<std::size_t>(n)] - c.times[0]) / n;
  }
};

TEST(Joints, MeshPendulumPeriodAtLargeAmplitude) {
  const double theta0 = 2 * massprops::kPi / 3;
  {
    MeshPendulum p(theta0, Integrator::kImplicitMidpoint);
    double separation = 0;
    const double T = p.MeasuredPeriod(1e-4, 50, separation);
    std::printf("h = 0.1 ms: period error %.2e, anchor separation %.1e m\n", T / p.period - 1, separation);
    EXPECT_NEAR(T / p.period - 1, 0, 1e-6) << "T " << T << " closed form " << p.period;
    EXPECT_LE(separation, 1e-12);
  }
  {
    MeshPendulum p(theta0, Integrator::kImplicitMidpoint);
    double separation = 0;
    const double T = p.MeasuredPeriod(1e-3, 50, separation);
    std::printf("h = 1 ms: period error %.2e, anchor separation %.1e m\n", T / p.period - 1, separation);
    EXPECT_NEAR(T / p.period - 1, 0, 3e-5) << "T " << T << " closed form " << p.period;
    EXPECT_LE(separation, 1e-12);
  }
}

// Two boxes hinged end to end about parallel axes; the reference is the planar double pendulum's
// own Lagrangian (absolute angles θ1, θ2) integrated by Boost.Odeint's Runge–Kutta–Fehlberg 7(8)
// to 1e-14.
struct DoublePendulum {
  double m1 = 1.0, m2 = 0.7, L1 = 0.5, L2 = 0.4, w = 0.04;
  double I1() const { return m1 * (L1 * L1 + w * w) / 12; }  // about the hinge axis (x), at the center
  double I2() const { return m2 * (L2 * L2 + w * w) / 12; }
  double c1() const { return L1 / 2; }
  double c2() const { return L2 / 2; }
  World Make(Integrator integrator, double th1, double th2) const {
    World world(integrator);
    world.AddBody(SolidBox(m1, w, w, L1, Vector3(0, 0, -c1())));
    world.AddBody(SolidBox(m2, w, w, L2, Vector3(0, 0, -L1 - c2())));
    // One after the other: World::PlaceJoint places at the bodies as added, whatever the first
    // joint has moved.
    Joint a = PlacedJoint(world, -1, 0, Vector3::Zero(), Vector3::UnitX());
    a.position = {th1};
    world.AddJoint(a);
    Joint b = PlacedJoint(world, 0, 1, Vector3(0, 0, -L1), Vector3::UnitX());
    b.position = {th2 - th1};
    world.AddJoint(b);
    world.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
    return world;
  }
  /// (θ1, θ2, θ̇1, θ̇2) at t from rest at (th1, th2).
  std::array<double, 4> Reference(double th1, double th2, double t) const {
    const double a = I1() + m1 * c1() * c1() + m2 * L1 * L1, b = m2 * L1 * c2(), d = I2() + m2 * c2() * c2();
    const double k1 = (m1 * c1() + m2 * L1) * kG, k2 = m2 * c2() * kG;
    auto rhs = [&](const std::array<double, 4>& s, std::array<double, 4>& ds, double) {
      const double D = s[0] - s[1], cd = std::cos(D), sd = std::sin(D);
      const double r1 = -b * sd * s[3] * s[3] - k1 * std::sin(s[0]);
      const double r2 = b * sd * s[2] * s[2] - k2 * std::sin(s[1]);
      const double det = a * d - b * b * cd * cd;
      ds[0] = s[2];
      ds[1] = s[3];
      ds[2] = (d * r1 - b * cd * r2) / det;
      ds[3] = (a * r2 - b * cd * r1) / det;
    };
    namespace odeint = boost::numeric::odeint;
    std::array<double, 4> s{th1, th2, 0, 0};
    odeint::integrate_adaptive(
        odeint::make_controlled(1e-15, 1e-15, odeint::runge_kutta_fehlberg78<std::array<double, 4>>()), rhs, s, 0.0, t,
        1e-4);
    return s;
  }
  /// In the model the lower hinge's angle is relative: θ2 = q1 + q2.
  static double Error(const World& world, const std::array<double, 4>& ref) {
    const double q1 = world.joint_state(0).position[0], q2 = world.joint_state(1).position[0];
    return std::max(std::fabs(q1 - ref[0]), std::fabs(q1 + q2 - ref[1]));
  }
};

TEST(Joints, DoublePendulumOrdersAgainstAnIndependentIntegration) {
  const DoublePendulum dp;
  const double th1 = 1.2, th2 = -0.4, T = 2.0;
  const std::array<double, 4> ref = dp.Reference(th1, th2, T);
  auto error_at = [&](Integrator integrator, double h) {
    World w = dp.Make(integrator, th1, th2);
    Simulate(w, h, std::lround(T / h));
    return DoublePendulum::Error(w, ref);
  };
  if (std::getenv("JOINTS_ORDERS")) {
    for (double h : {1e-2, 5e-3, 2.5e-3, 1.25e-3, 6.25e-4, 3.125e-4, 1.5625e-4, 7.8125e-5})
      std::printf("h %g midpoint %.3e rk4 %.3e\n", h, error_at(Integrator::kImplicitMidpoint, h),
                  error_at(Integrator::kRK4, h));
  }
  const double m1 = error_at(Integrator::kImplicitMidpoint, 2e-3), m2 = error_at(Integrator::kImplicitMidpoint, 1e-3);
  const double m_order = std::log2(m1 / m2);
  std::printf("orders: midpoint %.3f, RK4 %.3f\n", m_order,
              std::log2(error_at(Integrator::kRK4, 3.125e-4) / error_at(Integrator::kRK4, 1.5625e-4)));
  EXPECT_NEAR(m_order, 2.0, 0.1) << "errors " << m1 << " " << m2;
  // RK4's h⁵ term still shows at larger steps (error ratios 28, 24, 22, 20, 18 from h = 5 ms
  // down); below 0.1 ms the reference's own accuracy (~1e-14) is reached.
  const double r1 = error_at(Integrator::kRK4, 3.125e-4), r2 = error_at(Integrator::kRK4, 1.5625e-4);
  const double r_order = std::log2(r1 / r2);
  EXPECT_NEAR(r_order, 4.0, 0.2) << "errors " << r1 << " " << r2;
  EXPECT_LT(m2, 1e-4);
  EXPECT_LT(r2, 1e-11);
}

TEST(Joints, DoublePendulumEnergyHasNoSecularDrift) {
  const DoublePendulum dp;
  World w = dp.Make(Integrator::kImplicitMidpoint, 1.2, -0.4);
  const double e0 = w.Diagnose().total_energy;
  const double scale = dp.m1 * kG * dp.L1;  // J
  double first = 0, last = 0;
  const double h = 1e-3;
  std::vector<double> windows(10, 0.0);  // the largest error in each 10 s
  Simulate(w, h, 100000, [&](long s) {
    const double err = std::fabs(w.Diagnose().total_energy - e0) / scale;
    windows[static_cast<std::size_t>(s / 10000)] = std::max(windows[static_cast<std::size_t>(s / 10000)], err);
    if (s < 10000) first = std::max(first, err);
    if (s >= 90000) last = std::max(last, err);
  });
  EXPECT_LT(first, 1e-4);
  EXPECT_LT(last, 1e-4);
  // Bounded: the last 50 s wander no further than the first 50 s (a drift would double it;
  // measured 5.0e-5 against 5.0e-5).
  const double early = *std::max_element(windows.begin(), windows.begin() + 5);
  const double late = *std::max_element(windows.begin() + 5, windows.end());
  EXPECT_LT(late, 1.5 * early) << "first 50 s " << early << ", last 50 s " << late;
}

// The heavy symmetric top on a ball joint at its tip (Goldstein §5.7): u = cos θ obeys
// u̇² = f(u) = (1 − u²)(α − βu) − (b − au)², nutating between the roots u1 < u2 of f in [−1, 1],
// with period 2 ∫ du / √f.
TEST(Joints, LagrangeTopNutatesBetweenTheRootsAtThePeriodByQuadrature) {
  const double m = 1.0, l = 0.1, I1 = 0.002, I3 = 0.004, spin = 30.0, theta0 = massprops::kPi / 3;
  const double I1p = I1 + m * l * l;
  const double u0 = std::cos(theta0);
  const double a = I3 * spin / I1p, beta = 2 * m * kG * l / I1p;
  const double b = a * u0, alpha = beta * u0;  // released with θ̇ = φ̇ = 0
  auto f = [&](double u) { return (1 - u * u) * (alpha - beta * u) - (b - a * u) * (b - a * u); };
  // f = β u³ + c2 u² + c1 u + c0: its roots by Newton from brackets.
  auto root = [&](double lo, double hi) {
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      ((f(lo) < 0) == (f(mid) < 0) ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  const double u2 = u0;  // f(u0) = 0 by the initial conditions
  ASSERT_NEAR(f(u0), 0, 1e-12);
  const double u1 = root(-1.0, u0 - 1e-9);
  const double u3 = root(1.0, 1e6);
  double quad = 0;  // (4/√β) ∫₀^{π/2} ds / √(u3 − u1 − (u2 − u1) sin² s), trapezoid over the period
  const int N = 256;
  for (int k = 0; k < N; ++k) {
    const double s = 2 * massprops::kPi * k / N;
    quad += 1.0 / std::sqrt(u3 - u1 - (u2 - u1) * std::sin(s) * std::sin(s));
  }
  const double T_nut = 4 / std::sqrt(beta) * (quad * 2 * massprops::kPi / N) / 4;
  // The same by the complete elliptic integral (a check of the quadrature).
  const double T_K = 4 / std::sqrt(beta * (u3 - u1)) * boost::math::ellint_1(std::sqrt((u2 - u1) / (u3 - u1)));
  ASSERT_NEAR(T_nut / T_K, 1, 1e-13);

  for (Integrator integrator : {Integrator::kImplicitMidpoint, Integrator::kRK4}) {
    World w(integrator);
    RigidBody top;
    top.mass = m;
    top.inertia = Vector3(I1, I1, I3);  // body z: the symmetry axis
    top.orientation = dynamics::Quaternion(Eigen::AngleAxisd(theta0, Vector3::UnitX()));
    top.position = top.orientation * Vector3(0, 0, l);  // tip at the origin
    w.AddBody(top);
    Joint ball = PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3::UnitZ(), JointType::kSpherical);
    const Vector3 spin_axis = top.orientation * Vector3::UnitZ();  // J_c's axes are the world's at t = 0
    ball.velocity = {spin * spin_axis.x(), spin * spin_axis.y(), spin * spin_axis.z()};
    w.AddJoint(ball);
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
    // The midpoint rule's error is (ω h)² / 12-like: it takes the smaller step.
    const double h = integrator == Integrator::kRK4 ? 1e-4 : 5e-5;
    std::vector<double> u{u0}, t{0};
    std::vector<double> minima, maxima, max_times;
    Simulate(w, h, std::lround(20 * T_nut / h), [&](long) {
      u.push_back((w.bodies()[0].orientation * Vector3::UnitZ()).z());
      t.push_back(w.time());
      const std::size_t n = u.size();
      if (n < 3) return;
      const double ya = u[n - 3], yb = u[n - 2], yc = u[n - 1];
      const bool is_min = yb < ya && yb <= yc, is_max = yb > ya && yb >= yc;
      if (!is_min && !is_max) return;
      // The parabola through the three samples: vertex value and time.
      const double den = ya - 2 * yb + yc;
      const double s = 0.5 * (ya - yc) / den;
      const double value = yb - 0.25 * (ya - yc) * s;
      (is_min ? minima : maxima).push_back(value);
      if (is_max) max_times.push_back(t[n - 2] + s * h);
    });
    ASSERT_GE(max_times.size(), 10u);
    double lo = 1, hi = -1;
    for (double x : minima) lo = std::min(lo, x);
    for (double x : maxima) hi = std::max(hi, x);
    std::printf("%s: u1 %.2e, u2 %.2e, period %.2e relative\n", IntegratorName(integrator), lo / u1 - 1, hi / u2 - 1,
                (max_times.back() - max_times.front()) / static_cast<double>(max_times.size() - 1) / T_nut - 1);
    EXPECT_NEAR(lo / u1, 1, 1e-6) << IntegratorName(integrator) << " lowest u " << lo << " root " << u1;
    EXPECT_NEAR(hi / u2, 1, 1e-6) << IntegratorName(integrator) << " highest u " << hi << " root " << u2;
    for (double x : minima) EXPECT_NEAR(x / u1, 1, 1e-6);
    const double period = (max_times.back() - max_times.front()) / static_cast<double>(max_times.size() - 1);
    EXPECT_NEAR(period / T_nut, 1, 1e-6) << IntegratorName(integrator) << " period " << period << " quadrature "
                                         << T_nut;
  }
}

TEST(Joints, HangingChainOfTwentyStaysStill) {
  World w;
  const double L = 0.1;
  for (int k = 0; k < 20; ++k) w.AddBody(SolidBox(0.2, 0.02, 0.03, L, Vector3(0, 0, -(k + 0.5) * L)));
  for (int k = 0; k < 20; ++k) {
    w.AddJoint(PlacedJoint(w, k - 1, k, Vector3(0, 0, -k * L), k % 2 ? Vector3::UnitX() : Vector3::UnitY()));
  }
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  double fastest = 0;
  Simulate(w, 1e-3, 10000, [&](long) {
    for (const RigidBody& b : w.bodies())
      fastest = std::max(fastest, b.velocity.norm() + b.AngularVelocity().norm() * L);
  });
  EXPECT_LT(fastest, 1e-9);
}

// A tree of more than 64 coordinates, hinges and sliders below its root, applies M⁻¹ in the
// midpoint rule by the O(n) articulated-body recursion (a dense factorization is O(n³), several a
// step): a 100-link chain of hinges alternating x and y with every third joint a slider, under
// gravity, and a free-floating tree (a free root and two arms of 40 hinges: 86 coordinates)
// spinning. Against RK4 on the dense factor over the same 0.02 s: the difference is the
// midpoint's truncation error, shrinking fourfold when h halves.
TEST(Joints, LongChainsOnTheRecursionAgreeWithTheDenseFactor) {
  const double L = 0.05;
  auto chain = [&](World& w) {
    for (int k = 0; k < 100; ++k) w.AddBody(SolidBox(0.1, 0.01, 0.01, L, Vector3(0, 0, -(k + 0.5) * L)));
    for (int k = 0; k < 100; ++k) {
      Joint j = PlacedJoint(w, k - 1, k, Vector3(0, 0, -k * L), k % 2 ? Vector3::UnitX() : Vector3::UnitY(),
                            k % 3 == 2 ? JointType::kPrismatic : JointType::kRevolute);
      j.position = {0.05 * std::sin(0.7 * k)};
      j.velocity = {0.5 * std::cos(1.3 * k)};
      w.AddJoint(j);
    }
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  };
  auto tree = [&](World& w) {
    w.AddBody(SolidBox(1.0, 0.1, 0.1, 0.1, Vector3::Zero()));
    for (int arm = 0; arm < 2; ++arm) {
      const double side = arm ? -1.0 : 1.0;
      for (int k = 0; k < 40; ++k) {
        w.AddBody(SolidBox(0.1, L, 0.01, 0.01, Vector3(side * (0.05 + (k + 0.5) * L), 0, 0)));
      }
    }
    Joint root = PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3::UnitZ(), JointType::kFree);
    root.velocity = {0.3, -0.2, 1.0, 0.1, 0.0, -0.1};
    w.AddJoint(root);
    for (int arm = 0; arm < 2; ++arm) {
      const double side = arm ? -1.0 : 1.0;
      for (int k = 0; k < 40; ++k) {
        const int body = 1 + 40 * arm + k, parent = k == 0 ? 0 : body - 1;
        Joint j = PlacedJoint(w, parent, body, Vector3(side * (0.05 + k * L), 0, 0),
                              k % 2 ? Vector3::UnitZ() : Vector3::UnitY());
        j.velocity = {0.4 * std::sin(0.8 * k + arm)};
        w.AddJoint(j);
      }
    }
  };
  for (const auto& build : {std::function<void(World&)>(chain), std::function<void(World&)>(tree)}) {
    double apart[2] = {0, 0}, moved = 0;
    for (int halving = 0; halving < 2; ++halving) {
      const double h = 1e-4 / (1 << halving);
      World mid(Integrator::kImplicitMidpoint), rk4(Integrator::kRK4);
      build(mid);
      build(rk4);
      std::vector<Vector3> start;
      for (const RigidBody& b : mid.bodies()) start.push_back(b.position);
      Simulate(mid, h, 200 << halving);
      Simulate(rk4, h, 200 << halving);
      for (std::size_t b = 0; b < mid.bodies().size(); ++b) {
        apart[halving] = std::max(apart[halving], (mid.bodies()[b].position - rk4.bodies()[b].position).norm());
        moved = std::max(moved, (mid.bodies()[b].position - start[b]).norm());
      }
    }
    EXPECT_GT(moved, 5e-3);
    EXPECT_LT(apart[0], 1e-6);
    EXPECT_LT(apart[1], apart[0] / 3) << apart[0] << " then " << apart[1] << ": not the midpoint's O(h²)";
  }
}

// A long hinge chain thrown onto its stops: the stops' impulses need columns of M⁻¹, for which a
// step on the recursion forms the dense factor. Against RK4 on the dense factor throughout: the
// same stops reached, the same joint angles to the integrators' difference.
TEST(Joints, LongChainOnItsStops) {
  const double L = 0.05;
  const int links = 80;
  auto build = [&](World& w) {
    for (int k = 0; k < links; ++k) w.AddBody(SolidBox(0.1, 0.01, 0.01, L, Vector3(0, 0, -(k + 0.5) * L)));
    for (int k = 0; k < links; ++k) {
      Joint j = PlacedJoint(w, k - 1, k, Vector3(0, 0, -k * L), Vector3::UnitX());
      j.limits.lower = -0.05;
      j.limits.upper = 0.05;
      j.velocity = {k % 2 ? 3.0 : -3.0};
      w.AddJoint(j);
    }
  };
  World mid(Integrator::kImplicitMidpoint), rk4(Integrator::kRK4);
  build(mid);
  build(rk4);
  double impulse = 0, apart = 0;
  for (int s = 0; s < 200; ++s) {
    ASSERT_TRUE(mid.Step(1e-4).ok);
    ASSERT_TRUE(rk4.Step(1e-4).ok);
    for (int k = 0; k < links; ++k) {
      impulse = std::max(impulse, std::fabs(mid.joint_state(k).limit_impulse));
      apart = std::max(apart, std::fabs(mid.joint_state(k).position[0] - rk4.joint_state(k).position[0]));
    }
  }
  EXPECT_GT(impulse, 0);
  EXPECT_LT(apart, 1e-5);  // 1.7e-6 rad
}

// A rod hinged at one end, released horizontal, swings down onto a stop at 30° from hanging,
// where gravity keeps it.
TEST(Joints, HingeStopsOnItsLimitWithoutOvershoot) {
  for (double e : {0.0, 0.5}) {
    World w;
    const double L = 0.4;
    w.AddBody(SolidBox(1.0, 0.02, 0.02, L, Vector3(0, 0, -L / 2)));
    Joint j = PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3::UnitX());
    j.limits.lower = massprops::kPi / 6;
    j.limits.upper = massprops::kPi;
    j.limits.restitution = e;
    j.position = {massprops::kPi / 2};
    w.AddJoint(j);
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
    double lowest = 10, arrival = 0, departure = 0, prev_v = 0;
    Simulate(w, 1e-3, 3000, [&](long) {
      const dynamics::JointState s = w.joint_state(0);
      lowest = std::min(lowest, s.position[0]);
      if (s.limit_impulse > 0 && arrival == 0) {
        arrival = prev_v;
        departure = s.velocity[0];
      }
      prev_v = s.velocity[0];
    });
    EXPECT_GE(lowest, j.limits.lower - 1e-6) << "restitution " << e;
    EXPECT_LT(arrival, -1.0);
    EXPECT_NEAR(departure, -e * arrival, 0.02 * std::fabs(arrival) + 1e-9) << "restitution " << e;
    if (e == 0) {
      EXPECT_NEAR(w.joint_state(0).position[0], j.limits.lower, 1e-12);
      EXPECT_LT(std::fabs(w.joint_state(0).velocity[0]), 1e-9);
    }
  }
}

TEST(Joints, DampedSliderReachesTerminalSpeed) {
  World w;
  const double m = 2.0, c = 5.0, slope = 0.3;
  w.AddBody(SolidBox(m, 0.1, 0.1, 0.1, Vector3::Zero()));
  Joint j =
      PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3(std::cos(slope), 0, -std::sin(slope)), JointType::kPrismatic);
  j.damping = c;
  w.AddJoint(j);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  Simulate(w, 1e-3, 10000);  // 25 time constants m / c
  EXPECT_NEAR(w.joint_state(0).velocity[0] / (m * kG * std::sin(slope) / c), 1, 1e-6);
}

// A plate on a vertical axle (no gravity torque), with a torque about the axle.
struct Axle {
  World w;
  double I = 0;
  explicit Axle(const std::function<void(Joint&)>& setup, double torque = 0) {
    w.AddBody(SolidBox(1.5, 0.3, 0.2, 0.05, Vector3(0.01, 0, 0)));  // the center 1 cm off the axle
    Joint j = PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3::UnitZ());
    setup(j);
    w.AddJoint(j);
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
    if (torque != 0) w.AddForce(dynamics::ConstantTorque(0, Vector3(0, 0, torque)));
    I = w.bodies()[0].WorldInertia()(2, 2) + 1.5 * 0.01 * 0.01;
  }
  double q() const { return w.joint_state(0).position[0]; }
  double v() const { return w.joint_state(0).velocity[0]; }
};

TEST(Joints, CoulombFrictionHoldsBelowItsTorqueAndSlipsAbove) {
  {
    Axle a([](Joint& j) { j.friction = 0.8; }, 0.79);
    Simulate(a.w, 1e-3, 2000);
    EXPECT_LT(std::fabs(a.q()), 1e-12);
    EXPECT_LT(std::fabs(a.v()), 1e-12);
    EXPECT_NEAR(a.w.joint_state(0).drive_impulse, -0.79e-3, 1e-15);
  }
  {
    Axle a([](Joint& j) { j.friction = 0.8; }, 1.1);
    Simulate(a.w, 1e-3, 2000);
    EXPECT_NEAR(a.v() / a.w.time() / ((1.1 - 0.8) / a.I), 1, 1e-6);
    // and the angle is the constant acceleration's ½ α t²
    EXPECT_NEAR(a.q() / (0.5 * (1.1 - 0.8) / a.I * a.w.time() * a.w.time()), 1, 1e-6);
  }
}

TEST(Joints, SpringOscillatesAtItsNaturalFrequencyAndKeepsItsEnergy) {
  const double k = 10.0;
  Axle a([&](Joint& j) {
    j.stiffness = k;
    j.rest_position = 0.1;
    j.position = {0.4};
  });
  Crossings c;
  const double e0 = a.w.Diagnose().total_energy;
  double drift = 0;
  const double h = 1e-4;
  Simulate(a.w, h, 30000, [&](long) {
    c.Add(a.w.time(), a.q() - 0.1, a.v());
    drift = std::max(drift, std::fabs(a.w.Diagnose().total_energy - e0));
  });
  ASSERT_GE(c.times.size(), 6u);
  const double T = (c.times.back() - c.times.front()) / static_cast<double>(c.times.size() - 1);
  EXPECT_NEAR(T / (2 * massprops::kPi * std::sqrt(a.I / k)), 1, 1e-6);
  EXPECT_LT(drift, 1e-12 * 0.5 * k * 0.3 * 0.3 + 1e-15);  // potential energy ½ k (q − rest)² counted
  EXPECT_TRUE(a.w.Conserves().energy);
}

// A spring too stiff for the step: its fixed-point solve contracts by about (h ω / 2)², so at
// h ω = 8 the step is halved until h ω / 2 = 1/2 (eight sub-steps; the attempts at h, h/2 and
// h/4 give up). The midpoint rule on a linear oscillator turns (x, ẋ/ω) by φ = 2 atan(h ω / 2)
// a step: after n sub-steps x = x0 cos(n φ), whatever the attempts that failed before.
TEST(Joints, AStiffSpringHalvesTheStepAndTurnsByTheMidpointRulesAngle) {
  const double omega = 800, I = Axle([](Joint&) {}).I;
  Axle a([&](Joint& j) {
    j.stiffness = I * omega * omega;
    j.rest_position = 0.1;
    j.position = {0.4};
  });
  const double h = 0.01;
  const int steps = 40, substeps = 8;
  for (int s = 0; s < steps; ++s) {
    const dynamics::StepStatus st = a.w.Step(h);
    ASSERT_TRUE(st.ok) << st.message;
    ASSERT_EQ(st.substeps, substeps) << "step " << s;
  }
  const double phi = 2 * std::atan(h / substeps * omega / 2), turned = substeps * steps * phi;
  EXPECT_NEAR(a.q() - 0.1, 0.3 * std::cos(turned), 1e-10);  // (320 solves to 1e-13, 297 rad turned)
  EXPECT_NEAR(a.v(), -0.3 * omega * std::sin(turned), 1e-7);
}

// A velocity motor turns an unbalanced arm about a horizontal axle: gravity's torque varies
// through the turn, the motor's impulse takes it up and the rate holds.
TEST(Joints, VelocityMotorHoldsItsRateUnderALoadBelowItsLimit) {
  for (double limit : {5.0, 0.5}) {
    World w;
    w.AddBody(SolidBox(1.0, 0.02, 0.02, 0.3, Vector3(0, 0, -0.15)));
    Joint j = PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3::UnitX());
    j.motor.mode = dynamics::JointMotor::Mode::kVelocity;
    j.motor.target = 2.0;
    j.motor.max_effort = limit;  // gravity's largest torque: 1 · 9.81 · 0.15 = 1.47 N·m
    j.velocity = {2.0};
    w.AddJoint(j);
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
    double worst = 0, largest_effort = 0;
    Simulate(w, 1e-3, 5000, [&](long) {
      worst = std::max(worst, std::fabs(w.joint_state(0).velocity[0] - 2.0));
      largest_effort = std::max(largest_effort, std::fabs(w.joint_state(0).drive_impulse) / 1e-3);
    });
    if (limit > 1.5) {
      EXPECT_LT(worst, 1e-9);
      EXPECT_NEAR(largest_effort, 1.0 * kG * 0.15, 1e-3);
    } else {
      EXPECT_GT(worst, 0.1);  // too weak: it cannot hold the rate
      EXPECT_LE(largest_effort, limit * (1 + 1e-12));
    }
  }
}

// A PD servo on the axle: I q̈ = kp (target − q) − kd q̇ from rest at 0, damping ratio
// ζ = kd / (2 √(kp I)); overshoot exp(−π ζ / √(1 − ζ²)) at t = π / ω_d.
TEST(Joints, PositionServoFollowsTheSecondOrderResponse) {
  const double kp = 30.0, target = 0.5, zeta = 0.3;
  double kd = 0, max_effort = 100;
  Axle probe([](Joint&) {});
  kd = zeta * 2 * std::sqrt(kp * probe.I);
  Axle a([&](Joint& j) {
    j.motor.mode = dynamics::JointMotor::Mode::kPosition;
    j.motor.target = target;
    j.motor.kp = kp;
    j.motor.kd = kd;
    j.motor.max_effort = max_effort;
  });
  double peak = 0, peak_time = 0, largest_effort = 0;
  Simulate(a.w, 1e-4, 20000, [&](long) {
    if (a.q() > peak) peak = a.q(), peak_time = a.w.time();
    largest_effort = std::max(largest_effort, std::fabs(kp * (target - a.q()) - kd * a.v()));
  });
  const double overshoot = std::exp(-massprops::kPi * zeta / std::sqrt(1 - zeta * zeta));
  const double wd = std::sqrt(kp / a.I) * std::sqrt(1 - zeta * zeta);
  EXPECT_NEAR(((peak - target) / target) / overshoot, 1, 0.01);
  EXPECT_NEAR(peak_time / (massprops::kPi / wd), 1, 0.01);
  EXPECT_LT(largest_effort, max_effort);
  EXPECT_NEAR(a.q(), target, 1e-6);
}

/// Equal to the last bit, field by field (a RigidBody has padding).
bool SameBits(const RigidBody& a, const RigidBody& b) {
  auto same = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof(x)) == 0; };
  return same(a.mass, b.mass) && same(a.inertia, b.inertia) && same(a.position, b.position) &&
         same(a.velocity, b.velocity) && same(a.orientation.coeffs(), b.orientation.coeffs()) &&
         same(a.angular_momentum, b.angular_momentum);
}

TEST(Joints, FreeJointAloneIsTheFreeBodyBitForBit) {
  auto make = [](bool joint) {
    World w;
    RigidBody b = SolidBox(2.0, 0.1, 0.2, 0.3, Vector3(0.1, 0.2, 0.3));
    b.orientation = dynamics::Quaternion(Eigen::AngleAxisd(0.4, Vector3(1, 2, 3).normalized()));
    b.SetAngularVelocity(Vector3(3, 0.01, -0.2));
    b.velocity = Vector3(0.1, 0, 1);
    w.AddBody(b);
    if (joint) {
      Joint j;
      j.type = JointType::kFree;
      j.child = 0;
      w.AddJoint(j);
    }
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
    Simulate(w, 1e-3, 2000);
    return w;
  };
  const World a = make(false), b = make(true);
  EXPECT_FALSE(b.articulated());
  const RigidBody &x = a.bodies()[0], &y = b.bodies()[0];
  EXPECT_TRUE(SameBits(x, y));
  // Its state reads the body: the origin of J_c (the center of mass here) in the world.
  const dynamics::JointState s = b.joint_state(0);
  EXPECT_NEAR((Vector3(s.position[0], s.position[1], s.position[2]) - y.position).norm(), 0, 1e-15);
}

// Fixed joints weld: a body fixed to the world stays, and one welded under a swinging hinge
// swings with it as one rigid body (the composite's period).
TEST(Joints, FixedJointsWeld) {
  World still;
  still.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3::Zero()));
  Joint weld = PlacedJoint(still, -1, 0, Vector3::Zero(), Vector3::UnitZ(), JointType::kFixed);
  still.AddJoint(weld);
  still.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  Simulate(still, 1e-3, 100);
  EXPECT_EQ(still.bodies()[0].position, Vector3::Zero());
  // Two rods welded end to end hang from a hinge: a physical pendulum of length 2L.
  World w;
  const double L = 0.3, m = 0.5;
  w.AddBody(SolidBox(m, 0.01, 0.01, L, Vector3(0, 0, -L / 2)));
  w.AddBody(SolidBox(m, 0.01, 0.01, L, Vector3(0, 0, -3 * L / 2)));
  Joint hinge = PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3::UnitX());
  hinge.position = {0.2};
  w.AddJoint(hinge);
  w.AddJoint(PlacedJoint(w, 0, 1, Vector3(0, 0, -L), Vector3::UnitX(), JointType::kFixed));
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  const double I = 2 * m * (2 * L) * (2 * L) / 3 + 2 * m * 0.01 * 0.01 / 12;  // a rod of 2L about its end
  const double T = 4 * std::sqrt(I / (2 * m * kG * L)) * boost::math::ellint_1(std::sin(0.1));
  Crossings c;
  Simulate(w, 1e-4, 40000, [&](long) { c.Add(w.time(), w.joint_state(0).position[0], w.joint_state(0).velocity[0]); });
  ASSERT_GE(c.times.size(), 3u);
  EXPECT_NEAR((c.times.back() - c.times.front()) / static_cast<double>(c.times.size() - 1) / T, 1, 1e-6);
  // The welded rod stays in line with the first.
  const Vector3 axis0 = w.bodies()[0].position.normalized(), axis1 = w.bodies()[1].position.normalized();
  EXPECT_NEAR((axis0 - axis1).norm(), 0, 1e-12);
}

// A floating base (free joint) carrying a hinged arm, in free space: the total momentum is
// conserved, the center of mass moves uniformly, the energy holds. And a body without a joint in an
// articulated world falls on its parabola while it spins.
TEST(Joints, FloatingBaseConservesMomentaAndAFreeBodyFallsOnItsParabola) {
  for (Integrator integrator : {Integrator::kImplicitMidpoint, Integrator::kRK4}) {
    World w(integrator);
    w.AddBody(SolidBox(3.0, 0.3, 0.2, 0.1, Vector3::Zero()));
    w.AddBody(SolidBox(0.5, 0.02, 0.02, 0.4, Vector3(0.15, 0, 0.2)));
    Joint base;
    base.name = "base";
    base.type = JointType::kFree;
    base.child = 0;
    w.PlaceJoint(base, Vector3::Zero(), Vector3::UnitZ());
    base.velocity = {0.3, -0.2, 1.0, 0.1, 0.05, -0.02};  // ω, then v, in the base's joint axes
    w.AddJoint(base);
    Joint arm = PlacedJoint(w, 0, 1, Vector3(0.15, 0, 0), Vector3::UnitY());
    arm.velocity = {2.0};
    w.AddJoint(arm);
    ASSERT_TRUE(w.articulated());
    const dynamics::Diagnostics d0 = w.Diagnose();
    auto com = [&] {
      Vector3 c = Vector3::Zero();
      double m = 0;
      for (const RigidBody& b : w.bodies()) c += b.mass * b.position, m += b.mass;
      return Vector3(c / m);
    };
    const Vector3 c0 = com();
    const Vector3 vc = d0.linear_momentum / 3.5;
    double worst_p = 0, worst_L = 0, worst_E = 0, worst_c = 0;
    Simulate(w, 1e-3, 3000, [&](long) {
      const dynamics::Diagnostics d = w.Diagnose();
      worst_p = std::max(worst_p, (d.linear_momentum - d0.linear_momentum).norm() / d0.linear_momentum.norm());
      worst_L = std::max(worst_L, (d.angular_momentum - d0.angular_momentum).norm() / d0.angular_momentum.norm());
      worst_E = std::max(worst_E, std::fabs(d.total_energy - d0.total_energy) / d0.total_energy);
      worst_c = std::max(worst_c, (com() - c0 - vc * w.time()).norm());
    });
    std::printf("%s floating base, 3 s: |p| %.1e, |L| %.1e, E %.1e, center of mass %.1e m\n",
                IntegratorName(integrator), worst_p, worst_L, worst_E, worst_c);
    // Linear momentum to rounding in both (a free joint's translation is along its parent's axes,
    // so the total force moves it directly); the rest to each integrator's order (measured: midpoint
    // 2e-8 m, 4.5e-7, 6e-8; RK4 ~1e-13).
    const bool rk4 = integrator == Integrator::kRK4;
    EXPECT_LT(worst_p, 1e-13) << IntegratorName(integrator);
    EXPECT_LT(worst_c, rk4 ? 1e-12 : 1e-7) << IntegratorName(integrator);
    EXPECT_LT(worst_L, rk4 ? 1e-11 : 2e-6) << IntegratorName(integrator);
    EXPECT_LT(worst_E, rk4 ? 1e-11 : 2e-7) << IntegratorName(integrator);
  }
  World w;
  w.AddBody(SolidBox(1, 0.1, 0.1, 0.4, Vector3(0, 0, -0.2)));
  RigidBody spinner = SolidBox(2, 0.1, 0.2, 0.3, Vector3(1, 0, 0));
  spinner.SetAngularVelocity(Vector3(3, 1, -2));
  spinner.velocity = Vector3(0.5, 0, 2);
  w.AddBody(spinner);
  Joint hinge = PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3::UnitX());
  hinge.position = {1.0};
  w.AddJoint(hinge);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  double worst = 0;
  Simulate(w, 1e-3, 1000, [&](long) {
    const double t = w.time();
    const Vector3 exact = Vector3(1, 0, 0) + t * Vector3(0.5, 0, 2) + 0.5 * t * t * Vector3(0, 0, -kG);
    worst = std::max(worst, (w.bodies()[1].position - exact).norm());
  });
  std::printf("a free body in an articulated world, 1 s: parabola to %.1e m\n", worst);
  EXPECT_LT(worst, 1e-12);  // the midpoint rule is exact for a constant force
}

TEST(Joints, SameBitsForAnyThreadCount) {
  std::vector<RigidBody> first;
  for (int threads : {1, 2, 3}) {
    World w;
    w.set_num_threads(threads);
    for (int k = 0; k < 6; ++k) w.AddBody(SolidBox(0.3, 0.03, 0.03, 0.2, Vector3(0, 0, -(k + 0.5) * 0.2)));
    for (int k = 0; k < 6; ++k) {
      Joint j = PlacedJoint(w, k - 1, k, Vector3(0, 0, -k * 0.2), k % 3 ? Vector3::UnitX() : Vector3(0, 1, 1));
      if (k == 2) j.type = JointType::kSpherical, j.velocity = {1, 2, 0.5};
      w.AddJoint(j);
    }
    w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
    Simulate(w, 1e-3, 500);
    if (first.empty()) {
      first = w.bodies();
      continue;
    }
    for (std::size_t i = 0; i < first.size(); ++i) EXPECT_TRUE(SameBits(first[i], w.bodies()[i])) << threads;
  }
}

TEST(Joints, BadJointsAreRefusedNamingTheJointAndTheFault) {
  World w;
  w.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3::Zero()));
  w.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3(0, 0, 1)));
  auto refused = [&](const std::function<void(Joint&)>& edit, const std::string& words) {
    Joint j = PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3::UnitX());
    j.name = "elbow";
    edit(j);
    try {
      w.AddJoint(j);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("joint 'elbow'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused([](Joint& j) { j.child = 5; }, "child body 5 does not exist");
  refused([](Joint& j) { j.parent = 0; }, "jointed to itself");
  refused([](Joint& j) { j.axis = Vector3::Zero(); }, "axis");
  refused([](Joint& j) { j.limits.lower = 1, j.limits.upper = 0; }, "lower <= upper");
  refused([](Joint& j) { j.limits.restitution = 2; }, "restitution");
  refused([](Joint& j) { j.damping = -1; }, "damping");
  refused([](Joint& j) { j.motor.max_effort = 0; }, "max effort");
  refused([](Joint& j) { j.position = {1, 2}; }, "position has 1 numbers");
  refused([](Joint& j) { j.limits.upper = 0.5, j.position = {1.0}; }, "outside its limits");
  refused([](Joint& j) { j.type = JointType::kSpherical, j.stiffness = 1; }, "not on a spherical joint");
  w.AddJoint(PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3::UnitX()));
  refused([](Joint&) {}, "already hangs from joint");
  // A loop: 1 hangs from 0 ... and 0 from 1 cannot be added (0 already has a parent); a loop
  // among bodies without the world:
  World loop;
  loop.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3::Zero()));
  loop.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3(0, 0, 1)));
  loop.AddJoint(PlacedJoint(loop, 0, 1, Vector3::Zero(), Vector3::UnitX()));
  EXPECT_THROW(loop.AddJoint(PlacedJoint(loop, 1, 0, Vector3::Zero(), Vector3::UnitX())), std::invalid_argument);
  EXPECT_EQ(loop.joints().size(), 1u);
  // A longer one, closed by its fourth joint (placement waits for a read: the loop is found when
  // the joint is added all the same), named; the world then steps the joints it took.
  loop.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3(0, 0, 2)));
  loop.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3(0, 0, 3)));
  loop.AddJoint(PlacedJoint(loop, 1, 2, Vector3(0, 0, 1.5), Vector3::UnitX()));
  loop.AddJoint(PlacedJoint(loop, 2, 3, Vector3(0, 0, 2.5), Vector3::UnitY()));
  Joint closing = PlacedJoint(loop, 3, 0, Vector3(0, 0, 0.5), Vector3::UnitX());
  closing.name = "closing";
  try {
    loop.AddJoint(closing);
    ADD_FAILURE() << "a loop of joints was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'closing': closes a loop of joints through body 0"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(loop.joints().size(), 3u);
  EXPECT_TRUE(loop.Step(1e-3).ok);
  // Integrators that step free bodies only refuse.
  w.set_integrator(Integrator::kExactSplitting);
  try {
    w.Step(1e-3);
    ADD_FAILURE() << "exact splitting stepped joints";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no meaning for joints"), std::string::npos) << e.what();
  }
}

// Bodies are placed by their joints when next read or stepped, not at every AddJoint (a chain of
// n links took O(n²) to build): a world read after every joint and one read only at the end hold
// the same bits, placed and stepped. A free joint given its position and not its velocity takes
// its body's velocity through the joint and back at every placement: there, the same to rounding
// (10⁻¹², grown to ~3·10⁻¹² m/s in 50 steps).
TEST(Joints, PlacementWhenReadIsPlacementAtEveryJoint) {
  for (const bool with_free : {false, true}) {
    auto build = [&](World& w, bool read_each) {
      const double L = 0.1;
      for (int k = 0; k < 40; ++k) {
        RigidBody b = SolidBox(0.2, 0.02, 0.02, L, Vector3(0.01 * k, 0, -(k + 0.5) * L));
        b.velocity = Vector3(0.1 * std::sin(k), 0.2, -0.1 * std::cos(k));
        w.AddBody(b);
      }
      const JointType types[] = {JointType::kRevolute, JointType::kPrismatic, JointType::kSpherical,
                                 with_free ? JointType::kFree : JointType::kRevolute, JointType::kFixed};
      for (int k = 0; k < 40; ++k) {
        const JointType type = types[k % 5];
        Joint j = PlacedJoint(w, k == 0 ? -1 : (k % 7 == 3 ? k - 3 : k - 1), k, Vector3(0.01 * k, 0, -k * L),
                              k % 2 ? Vector3::UnitX() : Vector3::UnitY(), type);
        if (type == JointType::kRevolute || type == JointType::kPrismatic) j.position = {0.05 * std::sin(0.7 * k)};
        if (type == JointType::kFree) j.position = {0.01, 0.0, -0.02, 1.0, 0.0, 0.0, 0.0};  // no velocity given
        w.AddJoint(j);
        if (read_each) {
          EXPECT_TRUE(w.bodies()[static_cast<std::size_t>(k)].position.allFinite());
        }
      }
      w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
    };
    World each(Integrator::kImplicitMidpoint), once(Integrator::kImplicitMidpoint);
    build(each, true);
    build(once, false);
    auto same = [&](const char* when, double rounding) {
      const double tolerance = with_free ? rounding : 0.0;
      for (std::size_t b = 0; b < each.bodies().size(); ++b) {
        const RigidBody &x = each.bodies()[b], &y = once.bodies()[b];
        EXPECT_LE((x.position - y.position).norm(), tolerance) << when << ", body " << b;
        EXPECT_LE((x.velocity - y.velocity).norm(), tolerance) << when << ", body " << b;
        EXPECT_LE((x.orientation.coeffs() - y.orientation.coeffs()).norm(), tolerance) << when << ", body " << b;
        EXPECT_LE((x.angular_momentum - y.angular_momentum).norm(), tolerance) << when << ", body " << b;
      }
    };
    same("placed", 1e-12);
    // Placed: each child where its joint's position puts it (a revolute joint's child turned about
    // its axis by the angle given, from where it was added).
    EXPECT_GT((once.bodies()[1].position - once.body_as_added(1).position).norm(), 1e-4);
    Simulate(each, 1e-3, 50);
    Simulate(once, 1e-3, 50);
    same("after 50 steps", 1e-9);
  }
  // A lone body's free joint from the world, given a position, then another body added before
  // anything is read: the first is placed all the same (and the world stays one of free bodies).
  World w;
  w.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3::Zero()));
  Joint free = PlacedJoint(w, -1, 0, Vector3::Zero(), Vector3::UnitZ(), JointType::kFree);
  free.position = {1.0, 2.0, 3.0, 1.0, 0.0, 0.0, 0.0};
  w.AddJoint(free);
  w.AddBody(SolidBox(1, 0.1, 0.1, 0.1, Vector3(5, 0, 0)));
  EXPECT_FALSE(w.articulated());
  EXPECT_LT((w.bodies()[0].position - Vector3(1, 2, 3)).norm(), 1e-12);
  EXPECT_EQ(w.bodies()[1].position, Vector3(5, 0, 0));
}

TEST(Joints, ConservationIsReportedFromTheJoints) {
  Axle damped([](Joint& j) { j.damping = 0.1; });
  EXPECT_FALSE(damped.w.Conserves().energy);
  EXPECT_NE(damped.w.Conserves().energy_broken_by.find("joint damping"), std::string::npos);
  EXPECT_NE(damped.w.Conserves().momentum_broken_by.find("joints to the world"), std::string::npos);
}

}  // namespace

#pragma GCC diagnostic pop
