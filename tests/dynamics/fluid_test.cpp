// The fluid forces (dynamics/forces.h: Fluid, MuJoCo's inertia-box model, and Buoyancy) against
// their closed forms: Stokes-like terminal velocity, the quadratic drag's tanh fall, viscous spin
// decay, a body carried off by the wind, and Archimedes' lift.

#include <cmath>

#include <gtest/gtest.h>

#include "dynamics/forces.h"
#include "dynamics/world.h"

namespace {

using dynamics::Vector3;
constexpr double kG = 9.81, kPi = 3.14159265358979323846;

dynamics::RigidBody Sphere(double m, double radius) {
  dynamics::RigidBody b;
  b.mass = m;
  b.inertia = Vector3::Constant(0.4 * m * radius * radius);
  return b;
}

// A sphere's equivalent box has half-sizes √(3/(2M)·I) = √0.6 R, r_eq the same.
double SphereREq(double radius) { return std::sqrt(0.6) * radius; }

// Viscous only: m v̇ = m g − c v with c = 6 π β r_eq: v(t) = v_T (1 − e^{−t c/m}), v_T = m g / c.
TEST(Fluid, ViscousFallReachesStokesTerminalVelocity) {
  const double m = 1, R = 0.1, beta = 0.5;
  dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
  w.AddBody(Sphere(m, R));
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  w.AddForce(dynamics::Fluid({0, beta, Vector3::Zero()}));
  const double c = 6 * kPi * beta * SphereREq(R), t = 1.0;
  for (int s = 0; s < 1000; ++s) w.Step(1e-3);
  const double expected = -(m * kG / c) * (1 - std::exp(-t * c / m));
  EXPECT_NEAR(w.bodies()[0].velocity.z() / expected - 1, 0, 1e-6) << w.bodies()[0].velocity.z();
  EXPECT_NEAR(w.bodies()[0].velocity.head<2>().norm(), 0, 1e-15);
}

// Quadratic only, a box falling flat (its 0.2 × 0.2 m face down, half-sizes 0.1, 0.1, 0.05):
// m v̇ = m g − 2 ρ r_x r_y v², v(t) = v_T tanh(g t / v_T), v_T = √(m g / (2 ρ r_x r_y)).
TEST(Fluid, QuadraticDragFallIsTheTanhOfItsTerminalSpeed) {
  const double m = 2, rho = 1.2, rx = 0.1, ry = 0.1, rz = 0.05;
  dynamics::RigidBody box;
  box.mass = m;
  box.inertia = m / 3 * Vector3(ry * ry + rz * rz, rx * rx + rz * rz, rx * rx + ry * ry);
  dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
  w.AddBody(box);
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  w.AddForce(dynamics::Fluid({rho, 0, Vector3::Zero()}));
  for (int s = 0; s < 2000; ++s) w.Step(1e-3);
  const double vt = std::sqrt(m * kG / (2 * rho * rx * ry));
  EXPECT_NEAR(w.bodies()[0].velocity.z() / (-vt * std::tanh(kG * 2.0 / vt)) - 1, 0, 1e-6);
}

// Viscous torque on a sphere spinning about any axis: I ω̇ = −8 π β r_eq³ ω.
TEST(Fluid, ViscousTorqueDecaysASpinExponentially) {
  const double m = 3, R = 0.2, beta = 0.05;
  dynamics::RigidBody ball = Sphere(m, R);
  ball.SetAngularVelocity(Vector3(1, -2, 3));
  dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
  w.AddBody(ball);
  w.AddForce(dynamics::Fluid({0, beta, Vector3::Zero()}));
  for (int s = 0; s < 500; ++s) w.Step(1e-3);
  const double k = 8 * kPi * beta * std::pow(SphereREq(R), 3) / ball.inertia.x();
  const Vector3 expected = Vector3(1, -2, 3) * std::exp(-k * 0.5);
  EXPECT_LT((w.bodies()[0].AngularVelocity() - expected).norm(), 1e-7 * expected.norm());
}

// Wind: a body at rest in a viscous medium moving at w is carried toward w: v = w (1 − e^{−t c/m});
// the quadratic term adds nothing in the directions where the relative speed is 0.
TEST(Fluid, WindCarriesABodyAlong) {
  const double m = 0.5, R = 0.05, beta = 0.2;
  const Vector3 wind(3, -1, 0);
  dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
  w.AddBody(Sphere(m, R));
  w.AddForce(dynamics::Fluid({0, beta, wind}));
  for (int s = 0; s < 300; ++s) w.Step(1e-3);
  const double c = 6 * kPi * beta * SphereREq(R);
  EXPECT_LT((w.bodies()[0].velocity - wind * (1 - std::exp(-0.3 * c / m))).norm(), 1e-8);
}

// A ball half as dense as water, released under water: it rises at a = g (ρ_f/ρ_b − 1) = g; the
// total energy with buoyancy's potential is kept.
TEST(Fluid, BuoyancyLiftsALighterBodyAtGTimesTheDensityRatioLessOne) {
  const double rho_b = 500, rho_f = 1000, R = 0.1;
  const double volume = 4.0 / 3 * kPi * R * R * R, m = rho_b * volume;
  dynamics::World w(dynamics::Integrator::kImplicitMidpoint);
  w.AddBody(Sphere(m, R));
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -kG)));
  w.AddForce(dynamics::Buoyancy(rho_f, Vector3(0, 0, -kG), 0, volume));
  const double e0 = w.Diagnose().total_energy;
  for (int s = 0; s < 100; ++s) w.Step(1e-3);
  EXPECT_NEAR(w.bodies()[0].velocity.z(), kG * (rho_f / rho_b - 1) * 0.1, 1e-12);
  EXPECT_NEAR(w.Diagnose().total_energy, e0, 1e-12);
  EXPECT_THROW(dynamics::Buoyancy(-1, Vector3(0, 0, -kG), 0, volume), std::invalid_argument);
  EXPECT_THROW(dynamics::Fluid({0, -1, Vector3::Zero()}), std::invalid_argument);
}

}  // namespace
