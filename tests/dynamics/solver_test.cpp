// The velocity solve (libdynamics/src/contact/: jacobians.cpp, patches.cpp, kernels.cpp,
// solver.cpp) on hand-made rows, against closed forms: a cube resting on its four corners takes
// its weight's impulse and, sliding, exactly μk N against its sliding; two free bodies meeting
// head-on leave with their common velocity (a plastic impact conserves momentum) and, meeting off
// centre, with the impulse the effective mass 1 / (n·K n) gives.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <random>

#include "islands.h"
#include "solver.h"
#include "solver_internal.h"

namespace dynamics::contact {
namespace {

constexpr double kG = 9.81;

// A unit-mass cube (inertia 1/6) resting on the ground on its four bottom corners, after a kick of
// g h downward: the normal impulses sum to m g h (the velocity is stopped), and with a sideways
// velocity v0 beyond what μk N can stop the friction takes exactly μk N, along −v0. One solve
// from cold (no warm start): exact mode to rounding; the default's 32 sweeps leave ~10⁻⁶ m/s of
// the four redundant corners' shares, which a step's warm start then carries on removing.
struct RestingCube {
  std::vector<Row> rows;
  std::vector<Velocities> vel{{Vector3(0, 0, -kG * 1e-3), Vector3::Zero()}};
  BodyResponse response{{1.0}, {Matrix3::Identity() * 6.0}};

  explicit RestingCube(const Vector3& slide, double mu) {
    vel[0].v += slide;
    for (int k = 0; k < 4; ++k) {
      Row r;
      r.a = 0;
      r.b = -1;
      r.n = Vector3::UnitZ();
      r.ra = Vector3(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, -0.5);
      r.point = r.ra;
      r.mu_s = mu;
      r.mu_k = mu;
      r.key = {0, -1000, static_cast<std::uint32_t>(k)};
      rows.push_back(r);
    }
  }
};

TEST(Solver, ACubeAtRestTakesItsWeightAndASlidingOneKineticFriction) {
  for (const bool exact : {false, true}) {
    SCOPED_TRACE(exact ? "exact" : "default");
    SolveSettings settings;
    settings.exact = exact;
    settings.max_iterations = exact ? 64 : 32;
    // At rest.
    {
      RestingCube c(Vector3::Zero(), 0.5);
      SolveScratch scratch;
      std::vector<Patch> patches;
      std::vector<int> levels;
      PreparePatches(c.rows, ContactCache{}, c.vel, c.response, 1e-6, patches, scratch);
      ASSERT_EQ(patches.size(), 1u);
      SupportLevels(1, c.rows, levels);
      SolveImpulses(c.rows, patches, c.vel, c.response, levels, {0}, settings, nullptr, scratch);
      double N = 0;
      for (const Row& r : c.rows) N += r.lambda_n;
      EXPECT_NEAR(N, kG * 1e-3, exact ? 1e-12 : 1e-5 * kG * 1e-3);
      EXPECT_LT(c.vel[0].v.norm() + c.vel[0].w.norm(), exact ? 1e-12 : 2e-6);
    }
    // Sliding at 1 m/s along (3, 4, 0)/5: μk N = 0.5 m g h stops 0.0049 m/s of it.
    {
      const Vector3 dir(0.6, 0.8, 0);
      RestingCube c(dir, 0.5);
      SolveScratch scratch;
      std::vector<Patch> patches;
      std::vector<int> levels;
      PreparePatches(c.rows, ContactCache{}, c.vel, c.response, 1e-6, patches, scratch);
      SupportLevels(1, c.rows, levels);
      SolveImpulses(c.rows, patches, c.vel, c.response, levels, {0}, settings, nullptr, scratch);
      const double tol = exact ? 1e-9 : 1e-7;
      EXPECT_NEAR(c.vel[0].v.dot(dir), 1.0 - 0.5 * kG * 1e-3, tol);
      EXPECT_NEAR(c.vel[0].v.z(), 0, tol);
      EXPECT_LT(c.vel[0].w.norm(), exact ? 1e-8 : 1e-6);  // friction at the centre of pressure: no yaw, no tilt
    }
  }
}

// Two free bodies (masses 1 and 3, inertias 0.2 and 0.5) meeting along x at a point off both
// centres: one row, target 0 (plastic). The impulse is the relative normal speed times the
// effective mass 1 / (n·K n), K = Σ (1/m) E − [r]× I⁻¹ [r]×; momentum is conserved and the
// normal velocities agree after it.
TEST(Solver, TwoBodiesMeetWithTheImpulseOfTheirEffectiveMass) {
  std::vector<Velocities> vel{{Vector3(2.0, 0.3, 0), Vector3(0, 0, 0.5)}, {Vector3(-1.0, 0, 0.2), Vector3::Zero()}};
  BodyResponse response{{1.0, 1.0 / 3.0}, {Matrix3::Identity() / 0.2, Matrix3::Identity() / 0.5}};
  Row r;
  r.a = 1;  // the body on the right; the normal points from b (the left one) into it
  r.b = 0;
  r.n = Vector3::UnitX();
  r.ra = Vector3(-0.5, 0.1, 0.05);
  r.rb = Vector3(0.5, 0.2, -0.1);
  r.point = Vector3(0.5, 0.2, -0.1);
  r.key = {1, 0, 0};
  std::vector<Row> rows{r};
  const Vector3 momentum = vel[0].v * 1.0 + vel[1].v * 3.0;
  auto normal_speed = [&] {
    const Vector3 va = vel[1].v + vel[1].w.cross(r.ra), vb = vel[0].v + vel[0].w.cross(r.rb);
    return r.n.dot(va - vb);
  };
  const double before = normal_speed();
  ASSERT_LT(before, 0);  // closing
  auto K = [&](double inv_m, double inv_i, const Vector3& x) {
    Matrix3 S;
    S << 0, -x.z(), x.y(), x.z(), 0, -x.x(), -x.y(), x.x(), 0;
    return Matrix3(inv_m * Matrix3::Identity() - S * (inv_i * Matrix3::Identity()) * S);
  };
  const double effective = 1.0 / r.n.dot((K(1.0 / 3.0, 2.0, r.ra) + K(1.0, 5.0, r.rb)) * r.n);
  SolveScratch scratch;
  std::vector<Patch> patches;
  std::vector<int> levels;
  PreparePatches(rows, ContactCache{}, vel, response, 1e-6, patches, scratch);
  SolveSettings settings;
  settings.exact = true;
  SupportLevels(2, rows, levels);
  SolveImpulses(rows, patches, vel, response, levels, {0, 0}, settings, nullptr, scratch);
  EXPECT_NEAR(rows[0].lambda_n, -before * effective, 1e-12);
  EXPECT_NEAR(normal_speed(), 0, 1e-12);
  EXPECT_LT((vel[0].v * 1.0 + vel[1].v * 3.0 - momentum).norm(), 1e-12);
}

// Coulomb's friction update on its limit (FrictionUpdate's projection, by Newton on the
// multiplier ν of x(ν) = (K + ν E)⁻¹ K t): for random responses K (SPD, 10⁻² to 10² in scale,
// condition up to 10⁴; with torsion, 3 components, and without, 2) and targets t beyond the limit
// b, the answer lies on the limit and is the point of least kinetic energy there — the optimality
// condition K (t − x) = ν x with ν ≥ 0 (Lagrange), checked as K (t − x) parallel to x and
// pointing with it — and the multiplier kept for the next update is that ν.
TEST(Solver, FrictionOnItsLimitIsTheLeastKineticEnergyThere) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 2000; ++trial) {
    const int dim = trial % 2 == 0 ? 3 : 2;
    const double scale = std::pow(10.0, 2 * u(rng));
    const Eigen::Matrix3d Q = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    const Vector3 eig(scale, scale * std::pow(10.0, 2 * (u(rng) + 1)), scale * std::pow(10.0, 1 + u(rng)));
    Matrix3 K = Q * eig.asDiagonal() * Q.transpose();
    if (dim == 2) {  // (the patch's K without torsion: its 2 × 2 block counts)
      K.row(2).setZero();
      K.col(2).setZero();
    }
    Patch p;
    p.rho = dim == 3 ? 0.01 : 0;
    const Matrix3 mass = dim == 3 ? Matrix3(K.inverse()) : [&] {
      Matrix3 m = Matrix3::Zero();
      m.topLeftCorner<2, 2>() = K.topLeftCorner<2, 2>().inverse();
      return m;
    }();
    Vector3 t(u(rng), u(rng), dim == 3 ? u(rng) : 0.0);
    const double bound = (0.05 + 0.9 * std::abs(u(rng))) * t.norm();  // t beyond it
    // FrictionUpdate's target is old − mass g: choose g so that it is t, from old = 0.
    const Vector3 g = -(K * t);
    const Vector3 x = FrictionUpdate(p, Vector3::Zero(), g, mass, K, bound);
    SCOPED_TRACE("trial " + std::to_string(trial));
    ASSERT_NEAR(x.norm(), bound, 1e-12 * bound);
    if (dim == 2) {
      EXPECT_EQ(x[2], 0.0);
    }
    const Vector3 pull = K * (t - x);  // = ν x at the optimum
    const double nu = pull.dot(x) / x.squaredNorm();
    EXPECT_GE(nu, 0.0);
    EXPECT_LE((pull - nu * x).norm(), 1e-9 * (pull.norm() + K.norm() * x.norm()));
    EXPECT_NEAR(p.nu, nu, 1e-6 * (nu + K.norm()));
  }
}

}  // namespace
}  // namespace dynamics::contact
