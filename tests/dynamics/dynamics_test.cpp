// libdynamics against closed forms: projectile, springs, the torque-free symmetric and asymmetric
// tops (Jacobi elliptic solution, Dzhanibekov flip), conservation laws, orders of convergence,
// determinism, and bad input.
// Over 400 lines on purpose: one test binary per library (as everywhere in tests/), and these
// cases share the body builders and the integrator table at the top.

#include <cmath>
#include <functional>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dynamics/free_rigid_body.h"
#include "dynamics/world.h"
#include "massprops/solids.h"

namespace dynamics {
namespace {

using ::testing::HasSubstr;

RigidBody Body(const Vector3& inertia, const Vector3& omega_body, double mass = 1.0) {
  RigidBody b;
  b.mass = mass;
  b.inertia = inertia;
  b.angular_momentum = inertia.cwiseProduct(omega_body);  // q = identity: world = body
  return b;
}

// Runs a single torque-free body and returns ω in the body frame at time T.
Vector3 FreeOmega(Integrator integ, const Vector3& I, const Vector3& w0, double h, double T) {
  World w(integ);
  w.AddBody(Body(I, w0));
  const int n = static_cast<int>(std::llround(T / h));
  for (int i = 0; i < n; ++i) w.Step(h);
  return w.bodies()[0].BodyAngularVelocity();
}

TEST(ExactFreeRotation, MatchesPublishedReferenceNumbers) {
  // REFERENCE_VALUES.md: I = (1,2,3), ω0 = (0.01, 1, 0): λ = 0.577379, m = 0.99990001,
  // period 41.5092 s, flip interval 20.7546 s.
  const ExactFreeRotation r(Vector3(1, 2, 3), Vector3(0.01, 1, 0));
  EXPECT_NEAR(r.lambda(), 0.577379, 1e-6);
  EXPECT_NEAR(r.parameter_m(), 0.99990001, 1e-8);
  EXPECT_NEAR(r.Period(), 41.5092, 1e-4);
  EXPECT_NEAR(r.FlipInterval(), 20.7546, 1e-4);
  // Principia's ДжанибековEffect: I = (3,5,9), L = (0, 2, 0.01) → ω0 = L/I.
  const ExactFreeRotation p(Vector3(3, 5, 9), Vector3(0, 2.0 / 5, 0.01 / 9));
  EXPECT_NEAR(p.lambda(), 0.2177370, 1e-6);
  EXPECT_NEAR(p.Period(), 118.1109, 1e-3);
  // ω(0) reproduces the initial condition, in both regimes.
  for (const Vector3& w0 : {Vector3(0.3, 0.2, 1.0), Vector3(1.0, 0.2, 0.3), Vector3(-0.7, 0.4, -0.2)}) {
    const ExactFreeRotation e(Vector3(1, 2, 3), w0);
    EXPECT_LT((e.Omega(0) - w0).norm(), 1e-12) << w0.transpose();
  }
}

TEST(ExactFreeRotation, AttitudeAgreesWithAFineRK4AndKeepsWorldL) {
  const Vector3 I(1, 2, 3);
  const Quaternion q0 = Quaternion(Eigen::AngleAxisd(0.7, Vector3(1, 2, -1).normalized())).normalized();
  for (const Vector3& w0 : {Vector3(0.3, 0.2, 1.0), Vector3(1.0, 0.6, 0.3), Vector3(0.01, 1, 0)}) {
    const ExactFreeRotation exact(I, w0, q0);
    EXPECT_LT(exact.Orientation(0).angularDistance(q0), 1e-10) << w0.transpose();
    World w(Integrator::kRK4);
    RigidBody b = Body(I, w0);
    b.orientation = q0;
    b.angular_momentum = q0 * I.cwiseProduct(w0);
    w.AddBody(b);
    const double h = 1e-3;
    for (int i = 1; i <= 30000; ++i) {
      w.Step(h);
      if (i % 5000 == 0) {
        const Quaternion q = exact.Orientation(i * h);
        EXPECT_LT(q.angularDistance(w.bodies()[0].orientation), 1e-8) << w0.transpose() << " t=" << i * h;
        // World L = R Π is the same constant.
        EXPECT_LT((q * I.cwiseProduct(exact.Omega(i * h)) - b.angular_momentum).norm(), 1e-11);
      }
    }
  }
}

TEST(Translation, ProjectileIsExactWithVelocityVerlet) {
  for (Integrator integ : {Integrator::kImplicitMidpoint, Integrator::kSplitting, Integrator::kRK4}) {
    World w(integ);
    RigidBody b = Body(Vector3(1, 2, 3), Vector3::Zero(), 2.0);
    b.position = Vector3(1, 2, 3);
    b.velocity = Vector3(3, -1, 12);
    w.AddBody(b);
    const Vector3 g(0, 0, -9.81);
    w.AddForce(Gravity(g));
    const double h = 0.01;
    for (int i = 0; i < 200; ++i) w.Step(h);
    const double t = w.time();
    const Vector3 x = b.position + b.velocity * t + 0.5 * g * t * t;
    EXPECT_LT((w.bodies()[0].position - x).norm(), 1e-12 * x.norm()) << IntegratorName(integ);
    EXPECT_LT((w.bodies()[0].velocity - (b.velocity + g * t)).norm(), 1e-12 * 20) << IntegratorName(integ);
  }
  // Symplectic Euler's position error is exactly ½·h·g·t.
  World w(Integrator::kSymplecticEuler);
  w.AddBody(Body(Vector3(1, 1, 1), Vector3::Zero()));
  w.AddForce(Gravity(Vector3(0, 0, -10)));
  for (int i = 0; i < 100; ++i) w.Step(0.01);
  EXPECT_NEAR(w.bodies()[0].position.z() - (-0.5 * 10 * 1.0), -0.5 * 0.01 * 10 * 1.0, 1e-12);
}

TEST(Translation, UndampedSpringFollowsVerletsExactDiscreteFrequency) {
  // x'' = −ω² x, ω = √(k/m); Störmer–Verlet: cos(ω̃h) = 1 − (ωh)²/2, amplitude preserved.
  const double k = 40.0, m = 2.5, h = 0.05, x0 = 0.3;
  World w;
  RigidBody b = Body(Vector3(1, 1, 1), Vector3::Zero(), m);
  b.position = Vector3(x0, 0, 0);
  w.AddBody(b);
  w.AddForce(SpringToWorld(0, Vector3::Zero(), Vector3::Zero(), k, 0.0, 0.0));
  const double omega = std::sqrt(k / m);
  const double omega_h = std::acos(1 - 0.5 * omega * omega * h * h) / h;
  for (int i = 1; i <= 400; ++i) {
    w.Step(h);
    // The Verlet solution: x_n = x0 cos(ω̃ t_n) exactly (v0 = 0).
    ASSERT_NEAR(w.bodies()[0].position.x(), x0 * std::cos(omega_h * i * h), 1e-12) << i;
  }
  const Diagnostics d = w.Diagnose();
  EXPECT_NEAR(d.total_energy, 0.5 * k * x0 * x0, 0.5 * k * x0 * x0 * (omega * h) * (omega * h));
}

TEST(Translation, DampedSpringPeriodAndDecay) {
  // ζ = c/(2√(km)), ω_d = ω√(1−ζ²): x = e^{−ζωt}(x0 cos ω_d t + (ζω x0/ω_d) sin ω_d t).
  const double k = 10.0, m = 1.0, c = 0.4, x0 = 1.0;
  const double omega = std::sqrt(k / m), zeta = c / (2 * std::sqrt(k * m));
  const double wd = omega * std::sqrt(1 - zeta * zeta);
  auto worst_error = [&](double h) {
    World w;
    RigidBody b = Body(Vector3(1, 1, 1), Vector3::Zero(), m);
    b.position = Vector3(x0, 0, 0);
    w.AddBody(b);
    w.AddForce(SpringToWorld(0, Vector3::Zero(), Vector3::Zero(), k, 0.0, 0.0));
    w.AddForce(LinearDamping(c, 0));
    double worst = 0;
    const int n = static_cast<int>(std::llround(10.0 / h));  // 5 periods
    for (int i = 1; i <= n; ++i) {
      w.Step(h);
      const double t = i * h;
      const double x =
          std::exp(-zeta * omega * t) * (x0 * std::cos(wd * t) + zeta * omega * x0 / wd * std::sin(wd * t));
      worst = std::max(worst, std::fabs(w.bodies()[0].position.x() - x));
    }
    return worst;
  };
  const double e1 = worst_error(2e-3), e2 = worst_error(1e-3);
  EXPECT_LT(e2, 5e-4 * x0);
  // The velocity-dependent force's first half kick is implicit (its adjoint is the explicit
  // second): second order, the error quarters with the step (it halved before that fix).
  EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.15);
}

TEST(FreeRotation, SymmetricTopPrecessesAtTheClosedFormRate) {
  // I1 = I2 = I, I3 = J: body ω⊥ turns at s = (I − J)/I · ω3 (Kane & Levinson).
  const double I = 2.0, J = 0.8;
  const Vector3 w0(0.4, -0.3, 3.0);
  const double s = (I - J) / I * w0.z();
  const double T = 5.0;
  const Vector3 exact(w0.x() * std::cos(s * T) + w0.y() * std::sin(s * T),
                      -w0.x() * std::sin(s * T) + w0.y() * std::cos(s * T), w0.z());
  for (Integrator integ : {Integrator::kImplicitMidpoint, Integrator::kSplitting, Integrator::kRK4}) {
    const Vector3 got = FreeOmega(integ, Vector3(I, I, J), w0, 1e-3, T);
    EXPECT_LT((got - exact).norm(), 1e-5 * w0.norm()) << IntegratorName(integ);
  }
}

TEST(FreeRotation, AsymmetricTopFollowsTheJacobiSolutionOverManyPeriods) {
  const Vector3 I(1, 2, 3);
  for (const Vector3& w0 : {Vector3(0.3, 0.2, 1.0), Vector3(1.0, 0.6, 0.3)}) {
    const ExactFreeRotation exact(I, w0);
    const double T = 10 * exact.Period();
    World w;
    w.AddBody(Body(I, w0));
    const double h = 1e-3;
    double worst = 0;
    const int n = static_cast<int>(T / h);
    for (int i = 1; i <= n; ++i) {
      w.Step(h);
      if (i % 100 == 0) {
        worst = std::max(worst, (w.bodies()[0].BodyAngularVelocity() - exact.Omega(i * h)).norm());
      }
    }
    EXPECT_LT(worst, 2e-4 * w0.norm()) << w0.transpose();  // second order: C·h²·t
  }
}

TEST(FreeRotation, DzhanibekovFlipAtThePredictedInterval) {
  // Spun about the intermediate axis with a small perturbation: ω₂ reverses every 2K(m)/λ.
  const Vector3 I(1, 2, 3), w0(0.01, 1, 0);
  const ExactFreeRotation exact(I, w0);
  World w;
  w.AddBody(Body(I, w0));
  const double h = 1e-3;
  std::vector<double> flips;
  double prev = w0.y();
  for (int i = 1; i <= 70000; ++i) {
    w.Step(h);
    const double cur = w.bodies()[0].BodyAngularVelocity().y();
    if ((cur < 0) != (prev < 0)) flips.push_back(i * h - h * cur / (cur - prev));
    prev = cur;
  }
  ASSERT_GE(flips.size(), 3u);
  for (std::size_t k = 1; k < flips.size(); ++k) {
    EXPECT_NEAR(flips[k] - flips[k - 1], exact.FlipInterval(), 2e-3) << k;
  }
  EXPECT_NEAR(exact.FlipInterval(), 20.7546, 1e-4);
  // Near the smallest or the largest axis the spin is stable: ω keeps its sign on that axis.
  for (const auto& [axis, start] : {std::pair{0, Vector3(1, 0.01, 0.01)}, std::pair{2, Vector3(0.01, 0.01, 1)}}) {
    World s;
    s.AddBody(Body(I, start));
    for (int i = 0; i < 50000; ++i) {
      s.Step(h);
      ASSERT_GT(s.bodies()[0].BodyAngularVelocity()[axis], 0.9) << axis;
    }
  }
}

TEST(FreeRotation, ConservationLawsPerIntegrator) {
  // A tumbling body (close to the Dzhanibekov case, where errors show), 20 s at h = 0.01.
  const Vector3 I(1, 2, 3), w0(0.1, 2.0, 0.1);
  struct Case {
    Integrator integ;
    double max_energy_drift;  // relative; negative: must lose at least that much
  };
  const RigidBody start = Body(I, w0);
  const double e0 = start.RotationalEnergy();
  const double l0 = start.angular_momentum.norm();
  auto run = [&](Integrator integ) {
    World w(integ);
    w.AddBody(start);
    for (int i = 0; i < 2000; ++i) w.Step(0.01);
    return w.bodies()[0];
  };
  // Implicit midpoint: energy and |L| to rounding, world L bit for bit.
  const RigidBody mid = run(Integrator::kImplicitMidpoint);
  EXPECT_LT(std::fabs(mid.RotationalEnergy() - e0) / e0, 1e-13);
  EXPECT_LT(std::fabs(mid.angular_momentum.norm() - l0) / l0, 1e-15);
  EXPECT_EQ(mid.angular_momentum, start.angular_momentum);
  EXPECT_LT(std::fabs(mid.BodyAngularMomentum().norm() - l0) / l0, 1e-13);
  // Splitting: |L| exact, energy error bounded and small.
  const RigidBody split = run(Integrator::kSplitting);
  EXPECT_LT(std::fabs(split.BodyAngularMomentum().norm() - l0) / l0, 1e-13);
  EXPECT_LT(std::fabs(split.RotationalEnergy() - e0) / e0, 1e-2);
  // RK4: small drift at this step.
  EXPECT_LT(std::fabs(run(Integrator::kRK4).RotationalEnergy() - e0) / e0, 1e-5);
  // The textbook explicit Euler gains energy; the game-engine scheme loses it.
  EXPECT_GT(run(Integrator::kExplicitEuler).RotationalEnergy(), 1.05 * e0);
  EXPECT_GT(run(Integrator::kQuaternionEuler).RotationalEnergy(), 1.05 * e0);
  EXPECT_LT(run(Integrator::kImplicitGyroscopic).RotationalEnergy(), 0.95 * e0);
}

TEST(FreeRotation, MeasuredOrdersOfConvergence) {
  const Vector3 I(1, 2, 3), w0(0.3, 0.2, 1.0);
  const ExactFreeRotation exact(I, w0);
  const double T = 2.0;
  auto order = [&](Integrator integ, double h) {
    const double e1 = (FreeOmega(integ, I, w0, h, T) - exact.Omega(T)).norm();
    const double e2 = (FreeOmega(integ, I, w0, h / 2, T) - exact.Omega(T)).norm();
    return std::log2(e1 / e2);
  };
  EXPECT_NEAR(order(Integrator::kImplicitMidpoint, 0.02), 2.0, 0.1);
  EXPECT_NEAR(order(Integrator::kSplitting, 0.02), 2.0, 0.1);
  EXPECT_NEAR(order(Integrator::kRK4, 0.04), 4.0, 0.2);
  EXPECT_NEAR(order(Integrator::kSymplecticEuler, 0.005), 1.0, 0.1);
}

// For every integrator, 10^5 steps of a body spun near its intermediate axis (I = (1,2,3),
// ω0 = (0.01, 1, 0), h = 1e-3, 100 s: almost five flips): the worst relative error of the rotational
// energy and of world L over the run, and the order of accuracy from three step sizes.
struct IntegratorExpectation {
  Integrator integ;
  double order;        // expected observed order
  double max_energy;   // bound on the worst relative energy error over 10^5 steps
  double max_world_l;  // bound on the worst relative change of world L
};

class EveryIntegrator : public ::testing::TestWithParam<IntegratorExpectation> {};

TEST_P(EveryIntegrator, EnergyWorldMomentumAndOrder) {
  const IntegratorExpectation x = GetParam();
  const Vector3 I(1, 2, 3), w0(0.01, 1, 0);
  World w(x.integ);
  const RigidBody start = Body(I, w0);
  w.AddBody(start);
  const double e0 = start.RotationalEnergy(), l0 = start.angular_momentum.norm();
  double worst_e = 0, worst_l = 0;
  const int steps = x.order == 0 ? 10000 : 100000;  // the exact flow is costly per step
  for (int i = 0; i < steps; ++i) {
    w.Step(1e-3);
    const RigidBody& b = w.bodies()[0];
    worst_e = std::max(worst_e, std::fabs(b.RotationalEnergy() - e0) / e0);
    worst_l = std::max(worst_l, (b.angular_momentum - start.angular_momentum).norm() / l0);
  }
  RecordProperty("worst_energy_error", std::to_string(worst_e));
  RecordProperty("worst_world_L_error", std::to_string(worst_l));
  EXPECT_LE(worst_e, x.max_energy) << IntegratorName(x.integ);
  EXPECT_LE(worst_l, x.max_world_l) << IntegratorName(x.integ);
  if (x.order == 0) {  // exact flow: tiny error at any step
    const Vector3 wr(0.3, 0.2, 1.0);
    const ExactFreeRotation exact(I, wr);
    EXPECT_LT((FreeOmega(x.integ, I, wr, 0.5, 20.0) - exact.Omega(20.0)).norm(), 1e-9);
    return;
  }
  // Order from h, h/2, h/4 on a regular case (ω error at T = 2 against the Jacobi solution).
  const Vector3 wr(0.3, 0.2, 1.0);
  const ExactFreeRotation exact(I, wr);
  const double h = (x.order > 3) ? 0.04 : (x.order > 1.5 ? 0.02 : 0.004);
  double e[3];
  for (int k = 0; k < 3; ++k) e[k] = (FreeOmega(x.integ, I, wr, h / (1 << k), 2.0) - exact.Omega(2.0)).norm();
  const double p1 = std::log2(e[0] / e[1]), p2 = std::log2(e[1] / e[2]);
  EXPECT_NEAR(p1, x.order, 0.25 * x.order)
      << IntegratorName(x.integ) << " errors " << e[0] << " " << e[1] << " " << e[2];
  EXPECT_NEAR(p2, x.order, 0.25 * x.order)
      << IntegratorName(x.integ) << " errors " << e[0] << " " << e[1] << " " << e[2];
}

INSTANTIATE_TEST_SUITE_P(Integrators, EveryIntegrator,
                         ::testing::Values(
                             // The default holds energy and world L to 1e-12 (the bar).
                             IntegratorExpectation{Integrator::kImplicitMidpoint, 2, 1e-12, 1e-12},
                             IntegratorExpectation{Integrator::kSplitting, 2, 1e-3, 1e-12},
                             IntegratorExpectation{Integrator::kRK4, 4, 1e-9, 1e-9},
                             IntegratorExpectation{Integrator::kExplicitEuler, 1, 10.0, 1e-12},
                             IntegratorExpectation{Integrator::kQuaternionEuler, 1, 10.0, 1e-12},
                             IntegratorExpectation{Integrator::kSymplecticEuler, 1, 10.0, 1e-12},
                             IntegratorExpectation{Integrator::kImplicitGyroscopic, 1, 1.0, 10.0},
                             // Exact free flow: no truncation error at all; "order 0" means nothing to measure.
                             IntegratorExpectation{Integrator::kExactSplitting, 0, 1e-9, 1e-12}),
                         [](const ::testing::TestParamInfo<IntegratorExpectation>& p) {
                           std::string name = IntegratorName(p.param.integ);
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

TEST(SeedNotes, ExplicitEulerOnRDriftsWithoutReprojection) {
  // R ← R + h[ω]×R multiplies by (E + h[ω]×), whose singular values are 1 and √(1 + h²|ω|²):
  // without re-projection R stops being a rotation; with the SVD step it stays one to rounding.
  const Vector3 I0(1, 2, 3);
  const Vector3 L(0.5, 1.5, 0.2);  // world angular momentum, torque-free: constant
  Matrix3 raw = Matrix3::Identity(), projected = Matrix3::Identity();
  for (int i = 0; i < 1000; ++i) {
    auto omega = [&](const Matrix3& R) { return Vector3(R * I0.cwiseInverse().asDiagonal() * R.transpose() * L); };
    raw = ExplicitEulerRotation(raw, omega(raw), 0.01, false);
    projected = ExplicitEulerRotation(projected, omega(projected), 0.01, true);
  }
  EXPECT_GT((raw.transpose() * raw - Matrix3::Identity()).norm(), 1e-2);
  EXPECT_LT((projected.transpose() * projected - Matrix3::Identity()).norm(), 1e-14);
  EXPECT_NEAR(projected.determinant(), 1.0, 1e-14);
}

TEST(ExactSplitting, SecondOrderWithTorques) {
  // A constant body-fixed torque: exact-splitting and the default converge to the same answer,
  // and the exact-flow drift makes the splitting error smaller than the midpoint's.
  auto run = [](Integrator integ, double h) {
    World w(integ);
    w.AddBody(Body(Vector3(1, 2, 3), Vector3(0.3, 0.2, 1.0)));
    w.AddForce(PointForce(0, Vector3(0.5, 0, 0), Vector3(0, 0.2, 0), true));
    for (int i = 0; i < static_cast<int>(std::llround(4.0 / h)); ++i) w.Step(h);
    return w.bodies()[0];
  };
  const RigidBody ref = run(Integrator::kRK4, 1e-4);
  const double e1 = run(Integrator::kExactSplitting, 0.02).orientation.angularDistance(ref.orientation);
  const double e2 = run(Integrator::kExactSplitting, 0.01).orientation.angularDistance(ref.orientation);
  EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.3);
  EXPECT_LT(e1, run(Integrator::kImplicitMidpoint, 0.02).orientation.angularDistance(ref.orientation));
}

TEST(Worlds, DriftDiagnostics) {
  World w(Integrator::kExplicitEuler);
  w.AddBody(Body(Vector3(1, 2, 3), Vector3(0.1, 2, 0.1)));
  const Diagnostics d0 = w.Diagnose();
  for (int i = 0; i < 2000; ++i) w.Step(0.01);
  const Drift d = DriftSince(d0, w.Diagnose());
  EXPECT_GT(d.energy, 1e-3);  // explicit Euler gains energy
  EXPECT_LT(d.angular_momentum, 1e-15);
  EXPECT_EQ(d.linear_momentum, 0.0);
}

TEST(FreeRotation, LargeStepsNeverClampTheSpin) {
  // h·|ω| far beyond what explicit schemes survive: the implicit midpoint step (sub-stepped if
  // its solve needs it) keeps the energy and world L exact; nothing is clamped.
  for (double h : {0.1, 1.0, 10.0}) {
    World w;
    const RigidBody b = Body(Vector3(1, 2, 3), Vector3(5, 200, 3));
    w.AddBody(b);
    const StepStatus s = w.Step(h);
    EXPECT_GE(s.substeps, 1);
    EXPECT_LT(std::fabs(w.bodies()[0].RotationalEnergy() - b.RotationalEnergy()) / b.RotationalEnergy(), 1e-12) << h;
    EXPECT_EQ(w.bodies()[0].angular_momentum, b.angular_momentum);
  }
}

TEST(FreeRotation, AStepThatCannotConvergeIsReportedAndLeavesTheStateAsItWas) {
  // A spin so large that the midpoint solve fails even at h/1024: no exception from the step
  // loop, a status that says so, and the state and time exactly as before the call.
  World w;
  const RigidBody b = Body(Vector3(1, 2, 3), Vector3(3e9, -2e9, 1e9));
  w.AddBody(b);
  const StepStatus s = w.Step(1.0);
  EXPECT_FALSE(s.ok);
  EXPECT_THAT(s.message, ::testing::HasSubstr("did not converge"));
  EXPECT_EQ(w.time(), 0.0);
  EXPECT_EQ(w.bodies()[0].orientation.coeffs(), b.orientation.coeffs());
  EXPECT_EQ(w.bodies()[0].angular_momentum, b.angular_momentum);
  EXPECT_EQ(w.bodies()[0].position, b.position);
  // The same world then steps normally with a step that suits the spin.
  EXPECT_TRUE(w.Step(1e-12).ok);
}

TEST(Worlds, ADivergingStateIsReportedWithTheBodyAndQuantity) {
  // Explicit Euler on a spring far too stiff for the step: the state overflows within steps.
  for (Integrator integ : kAllIntegrators) {
    World w(integ);
    w.AddBody(Body(Vector3(1, 2, 2.5), Vector3::Zero()));
    RigidBody b = Body(Vector3(1, 2, 2.5), Vector3::Zero());
    b.position = Vector3(0, 0, -1);
    w.AddBody(b);
    w.AddForce(SpringToWorld(1, Vector3::Zero(), Vector3::Zero(), 1e12, 0, 0));
    StepStatus s;
    for (int i = 0; i < 2000 && s.ok; ++i) s = w.Step(0.5);
    if (integ == Integrator::kExplicitEuler || integ == Integrator::kQuaternionEuler) {
      ASSERT_TRUE(s.diverged) << IntegratorName(integ);
    }
    if (s.diverged) {
      EXPECT_FALSE(s.ok);
      EXPECT_EQ(s.body, 1) << IntegratorName(integ);
      EXPECT_THAT(s.message, ::testing::HasSubstr("body 1's")) << IntegratorName(integ);
      EXPECT_EQ(w.FirstNonFinite().first, 1);
    }
  }
}

TEST(Worlds, ForcesSayWhatTheyConserve) {
  World w;
  w.AddBody(Body(Vector3(1, 2, 2.5), Vector3::Zero()));
  w.AddBody(Body(Vector3(1, 2, 2.5), Vector3::Zero()));
  w.AddForce(SpringBetween(0, Vector3::Zero(), 1, Vector3::Zero(), 10, 0, 0));
  w.AddForce(LinearDamping(0.0));
  Conservation c = w.Conserves();
  EXPECT_TRUE(c.energy && c.momentum) << c.energy_broken_by << " / " << c.momentum_broken_by;
  w.AddForce(Gravity(Vector3(0, 0, -9.81)));
  w.AddForce(SpringToWorld(0, Vector3::Zero(), Vector3::Zero(), 5, 0, 0.5));
  w.AddForce(BodyFrameTorque(1, Vector3(0, 0, 1)));
  c = w.Conserves();
  EXPECT_FALSE(c.energy);
  EXPECT_FALSE(c.momentum);
  EXPECT_EQ(c.energy_broken_by, "spring damping, applied torques");
  EXPECT_EQ(c.momentum_broken_by, "gravity, springs to the world, applied torques");
}

TEST(Worlds, BodyFrameTorqueTurnsWithTheBody) {
  // A torque fixed in the body's axes: after the body has turned a quarter about z, the world
  // torque has turned with it.
  World w;
  RigidBody b = Body(Vector3(1, 2, 3), Vector3::Zero());
  b.orientation = Quaternion(Eigen::AngleAxisd(massprops::kPi / 2, Vector3::UnitZ()));
  w.AddBody(b);
  w.AddForce(BodyFrameTorque(0, Vector3(1, 0, 0)));
  w.Step(1e-3);
  const Vector3 L = w.bodies()[0].angular_momentum;  // = h τ_world to first order
  EXPECT_NEAR(L.x(), 0.0, 1e-12);
  EXPECT_NEAR(L.y(), 1e-3, 1e-9);
}

TEST(Worlds, TwoBodiesOnASpringConserveMomenta) {
  World w;
  RigidBody a = Body(Vector3(1, 2, 2.5), Vector3(0.3, 0.1, -0.2), 2.0);
  RigidBody b = Body(Vector3(0.5, 0.6, 0.9), Vector3(-1, 0.5, 0.2), 1.0);
  a.position = Vector3(-1, 0, 0);
  b.position = Vector3(1.2, 0.3, 0);
  a.velocity = Vector3(0, 0.2, 0);
  w.AddBody(a);
  w.AddBody(b);
  w.AddForce(SpringBetween(0, Vector3(0.2, 0.1, 0), 1, Vector3(-0.1, 0, 0.2), 30.0, 1.5, 0.0));
  const Diagnostics d0 = w.Diagnose();
  double worst_energy = 0;
  for (int i = 0; i < 5000; ++i) {
    w.Step(1e-3);
    worst_energy = std::max(worst_energy, std::fabs(w.Diagnose().total_energy - d0.total_energy));
  }
  const Diagnostics d1 = w.Diagnose();
  EXPECT_LT((d1.linear_momentum - d0.linear_momentum).norm(), 1e-12);
  EXPECT_LT((d1.angular_momentum - d0.angular_momentum).norm(), 1e-11);
  EXPECT_LT(worst_energy / d0.total_energy, 1e-4);  // symplectic: bounded, O(h²)
}

TEST(Worlds, SameBitsForAnyThreadCount) {
  auto run = [](int threads) {
    World w;
    w.set_num_threads(threads);
    for (int i = 0; i < 6000; ++i) {
      RigidBody b = Body(Vector3(1 + 1e-4 * i, 2, 2.5), Vector3(0.1 * (i % 7), 1, 0.3), 1.0 + i % 3);
      b.position = Vector3(i, 0, 0);
      w.AddBody(b);
    }
    w.AddForce(Gravity(Vector3(0, 0, -9.81)));
    w.AddForce(AngularDamping(0.01));
    for (int s = 0; s < 20; ++s) w.Step(0.01);
    return w.bodies();
  };
  const auto one = run(1), two = run(2);
  for (std::size_t i = 0; i < one.size(); ++i) {
    ASSERT_EQ(one[i].position, two[i].position);
    ASSERT_EQ(one[i].orientation.coeffs(), two[i].orientation.coeffs());
    ASSERT_EQ(one[i].angular_momentum, two[i].angular_momentum);
  }
}

TEST(Bodies, FromMassPropertiesOfAMesh) {
  // A 1×2×3 box turned by 30° about z: principal axes recovered, moments ascending.
  massprops::PolygonMesh box = massprops::solids::Box(Vector3(1, 2, 3));
  const Matrix3 R = Eigen::AngleAxisd(massprops::kPi / 6, Vector3::UnitZ()).toRotationMatrix();
  box.V = (box.V * R.transpose()).rowwise() + Eigen::RowVector3d(4, 5, 6);
  const RigidBody b = BodyFromMassProperties(massprops::ComputeMassProperties(box, 500.0)).body;
  EXPECT_NEAR(b.mass, 3000.0, 1e-9);
  EXPECT_LT((b.position - Vector3(4, 5, 6)).norm(), 1e-12);
  const Vector3 want = 3000.0 / 12 * Vector3(1 + 4, 1 + 9, 4 + 9);  // Izz < Ixx < Iyy
  EXPECT_LT((b.inertia - Vector3(want[0], want[1], want[2])).norm(), 1e-9);
  EXPECT_LT(
      (b.WorldInertia() - R * Vector3(want[2], want[1], want[0]).asDiagonal() * R.transpose()).cwiseAbs().maxCoeff(),
      1e-9);
  // Kinematics: v = v_c + ω × r; T = ½Mv² + ½ωᵀIω.
  RigidBody m = b;
  m.velocity = Vector3(1, 0, 0);
  m.SetAngularVelocity(Vector3(0, 0, 2));
  EXPECT_LT((m.AngularVelocity() - Vector3(0, 0, 2)).norm(), 1e-12);
  EXPECT_LT((m.PointVelocity(m.position + Vector3(0, 1, 0)) - Vector3(-1, 0, 0)).norm(), 1e-12);
  EXPECT_NEAR(m.KineticEnergy(), 0.5 * 3000 + 0.5 * 4 * m.WorldInertia()(2, 2), 1e-9);
}

TEST(Bodies, BadInputIsRefusedWithReasons) {
  World w;
  RigidBody b = Body(Vector3(1, 2, 3), Vector3::Zero());
  b.mass = -1;
  EXPECT_THAT([&] { w.AddBody(b); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("mass")));
  b = Body(Vector3(1, 1, 3), Vector3::Zero());
  EXPECT_THAT([&] { w.AddBody(b); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("triangle inequality")));
  b = Body(Vector3(1, 2, 3), Vector3::Zero());
  b.orientation.coeffs() *= 2;
  EXPECT_THAT([&] { w.AddBody(b); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("not unit")));
  b.orientation = Quaternion::Identity();
  b.velocity.x() = std::nan("");
  EXPECT_THAT([&] { w.AddBody(b); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("not finite")));
  EXPECT_THAT(
      [&] {
        w.AddForce(Gravity(Vector3(0, 0, -9.81)));
        w.AddForce(ConstantForce(3, Vector3(1, 0, 0)));
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("refers to body 3")));
  EXPECT_THAT([&] { w.Step(0.0); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("time step")));
  EXPECT_THROW(SpringToWorld(0, Vector3::Zero(), Vector3::Zero(), -1, 0, 0), std::invalid_argument);
  EXPECT_THROW(ParseIntegrator("verlet"), std::invalid_argument);
  EXPECT_EQ(ParseIntegrator("rk4"), Integrator::kRK4);
}

}  // namespace
}  // namespace dynamics

namespace dynamics {
namespace {

// Velocity-dependent forces keep the kick–drift–kick integrators second order: the error at
// T = 1 s against the exact solution, at h, h/2, h/4, falls by 4 each halving.
double ObservedOrder(Integrator integrator, const std::function<double(double)>& error_at_step) {
  const double e1 = error_at_step(0.02), e2 = error_at_step(0.01), e3 = error_at_step(0.005);
  (void)integrator;
  return 0.5 * (std::log2(e1 / e2) + std::log2(e2 / e3));
}

TEST(VelocityDependentForces, LinearDampingUnderGravityIsSecondOrder) {
  // m v' = m g − c v: v(t) = v∞ + (v0 − v∞) e^{−kt}, k = c/m, v∞ = g/k; x by integration.
  const double m = 2, c = 3, k = c / m;
  const Vector3 g(0, 0, -9.81), v0(1, 2, 3), x0 = Vector3::Zero();
  for (Integrator integrator : {Integrator::kImplicitMidpoint, Integrator::kSplitting}) {
    auto error = [&](double h) {
      World w(integrator);
      RigidBody b;
      b.mass = m;
      b.velocity = v0;
      w.AddBody(b);
      w.AddForce(Gravity(g));
      w.AddForce(LinearDamping(c));
      const int n = static_cast<int>(std::lround(1.0 / h));
      for (int i = 0; i < n; ++i) EXPECT_TRUE(w.Step(h).ok);
      const double T = 1.0;
      const Vector3 vinf = g / k;
      const Vector3 v = vinf + (v0 - vinf) * std::exp(-k * T);
      const Vector3 x = x0 + vinf * T + (v0 - vinf) * (1 - std::exp(-k * T)) / k;
      return (w.bodies()[0].velocity - v).norm() + (w.bodies()[0].position - x).norm();
    };
    const double order = ObservedOrder(integrator, error);
    EXPECT_GT(order, 1.8) << IntegratorName(integrator);
    EXPECT_LT(order, 2.3) << IntegratorName(integrator);
  }
}

TEST(VelocityDependentForces, AngularDampingIsSecondOrder) {
  // A sphere (isotropic): ω(t) = ω0 e^{−ct/I} about a fixed axis.
  const double I = 0.4, c = 0.5;
  const Vector3 w0(3, -1, 2);
  for (Integrator integrator : {Integrator::kImplicitMidpoint, Integrator::kSplitting}) {
    auto error = [&](double h) {
      World w(integrator);
      RigidBody b;
      b.inertia = Vector3::Constant(I);
      b.SetAngularVelocity(w0);
      w.AddBody(b);
      w.AddForce(AngularDamping(c));
      const int n = static_cast<int>(std::lround(1.0 / h));
      for (int i = 0; i < n; ++i) EXPECT_TRUE(w.Step(h).ok);
      const double decay = std::exp(-c / I * 1.0);
      const double angle = w0.norm() * I / c * (1 - decay);
      const Quaternion q(Eigen::AngleAxisd(angle, w0.normalized()));
      return (w.bodies()[0].AngularVelocity() - w0 * decay).norm() + w.bodies()[0].orientation.angularDistance(q);
    };
    const double order = ObservedOrder(integrator, error);
    EXPECT_GT(order, 1.8) << IntegratorName(integrator);
    EXPECT_LT(order, 2.3) << IntegratorName(integrator);
  }
}

TEST(VelocityDependentForces, DampedSpringIsSecondOrder) {
  // Along a line through the anchor (rest length 0): m x'' = −k x − c x', underdamped.
  const double m = 1, k = 40, c = 2;
  const double zeta = c / (2 * std::sqrt(k * m)), w = std::sqrt(k / m), wd = w * std::sqrt(1 - zeta * zeta);
  const double x0 = 0.3, v0 = 0;
  auto exact = [&](double t) {
    const double a = x0, b = (v0 + zeta * w * x0) / wd;
    const double e = std::exp(-zeta * w * t);
    const double x = e * (a * std::cos(wd * t) + b * std::sin(wd * t));
    const double v = -zeta * w * x + e * (-a * wd * std::sin(wd * t) + b * wd * std::cos(wd * t));
    return std::pair{x, v};
  };
  for (Integrator integrator : {Integrator::kImplicitMidpoint, Integrator::kSplitting}) {
    auto error = [&](double h) {
      World world(integrator);
      RigidBody b;
      b.mass = m;
      b.position = Vector3(x0, 0, 0);
      world.AddBody(b);
      world.AddForce(SpringToWorld(0, Vector3::Zero(), Vector3::Zero(), k, 0, c));
      const int n = static_cast<int>(std::lround(1.0 / h));
      for (int i = 0; i < n; ++i) EXPECT_TRUE(world.Step(h).ok);
      const auto [x, v] = exact(1.0);
      return std::abs(world.bodies()[0].position.x() - x) + std::abs(world.bodies()[0].velocity.x() - v);
    };
    const double order = ObservedOrder(integrator, error);
    EXPECT_GT(order, 1.8) << IntegratorName(integrator);
    EXPECT_LT(order, 2.3) << IntegratorName(integrator);
  }
}

}  // namespace
}  // namespace dynamics
