// The block solve of an island's contacts (libdynamics/src/contact/block_solve.cpp) and its
// factor (profile_cholesky.h): the profile Cholesky solves what Eigen's dense LLT solves, banded
// or dense, regularized or not, and refuses a matrix that is not positive definite; a column of
// tilted boxes, the case the point-by-point sweeps crawl on (each sweep cut the change by ~4 %),
// is solved in a few sweeps instead of running out of them while it sways and settles, and comes
// to rest to the stopping rule with the ground carrying its weight.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dynamics/contact.h"
#include "profile_cholesky.h"

namespace dynamics {
namespace {

// A symmetric positive definite k × k matrix whose row i reaches back `band` entries (all of
// them when band ≥ k), diagonally dominant, from a fixed seed; every fifth row starts at column 0
// (a profile that is not a band).
Eigen::MatrixXd Spd(Eigen::Index k, Eigen::Index band, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(k, k);
  for (Eigen::Index i = 0; i < k; ++i) {
    for (Eigen::Index j = std::max<Eigen::Index>(0, i - band); j < i; ++j) S(i, j) = S(j, i) = u(rng);
    if (i % 5 == 4) S(i, 0) = S(0, i) = u(rng);
  }
  for (Eigen::Index i = 0; i < k; ++i) S(i, i) = S.row(i).cwiseAbs().sum() + 0.5 + std::abs(u(rng));
  return S;
}

TEST(ProfileCholesky, SolvesWhatADenseFactorSolves) {
  for (const Eigen::Index k : {1, 2, 7, 42, 96}) {
    for (const Eigen::Index band : {Eigen::Index{1}, Eigen::Index{6}, k}) {
      for (const double relative : {0.0, 1e-9, 0.25}) {
        const Eigen::MatrixXd S = Spd(k, band, static_cast<unsigned>(k * 100 + band));
        Eigen::MatrixXd regularized = S;
        regularized.diagonal() *= 1 + relative;
        const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(k, -1, 2);
        const Eigen::VectorXd expected = regularized.llt().solve(b);
        contact::ProfileCholesky factor;
        ASSERT_TRUE(factor.Compute(S, relative));
        EXPECT_EQ(factor.size(), k);
        Eigen::VectorXd x = b;
        factor.SolveInPlace(x);
        EXPECT_LE((x - expected).cwiseAbs().maxCoeff(), 1e-13 * expected.cwiseAbs().maxCoeff())
            << "k " << k << " band " << band << " relative " << relative;
        EXPECT_LE((regularized * x - b).cwiseAbs().maxCoeff(), 1e-13 * b.cwiseAbs().maxCoeff());
      }
    }
  }
}

TEST(ProfileCholesky, RefusesAMatrixThatIsNotPositiveDefinite) {
  Eigen::MatrixXd S = Spd(12, 3, 7);
  contact::ProfileCholesky factor;
  ASSERT_TRUE(factor.Compute(S));
  S(6, 6) = -1;
  EXPECT_FALSE(factor.Compute(S));
  // A semi-definite one (two equal rows): the pivot that vanishes is refused, as rounding allows.
  Eigen::MatrixXd T = Eigen::MatrixXd::Ones(3, 3);
  EXPECT_FALSE(factor.Compute(T));
  // A larger matrix after a smaller one, then a smaller one again: each solved.
  for (const Eigen::Index k : {5, 80, 3}) {
    const Eigen::MatrixXd M = Spd(k, 4, static_cast<unsigned>(k));
    ASSERT_TRUE(factor.Compute(M));
    Eigen::VectorXd x = Eigen::VectorXd::Ones(k);
    factor.SolveInPlace(x);
    EXPECT_LE((M * x - Eigen::VectorXd::Ones(k)).cwiseAbs().maxCoeff(), 1e-13);
  }
}

// Six 8 cm boxes dropped one above the other, each tilted about x as compare.py's piles tilt them
// (one of their columns): they land on edges and settle leaning on each other.
ContactWorld LeaningColumn() {
  ContactWorld w{World(), ContactOptions{}};
  const Vector3 half = Vector3::Constant(0.04);
  for (int z = 0; z < 6; ++z) {
    const int i = 21 + 36 * z;
    const double tilt = 0.3 * ((i * 7919) % 13 - 6) / 6;
    RigidBody b;
    b.mass = 500 * 8 * half.prod();
    b.inertia = Vector3::Constant(b.mass * (2 * half[0]) * (2 * half[0]) / 6);
    b.position = Vector3(0, 0, 0.06 + 0.12 * z);
    b.orientation = Quaternion(Eigen::AngleAxisd(tilt, Vector3::UnitX()));
    w.AddBody(b, Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), Material{0.6, 0.5, 0}});
  }
  w.AddGround({Vector3::UnitZ(), 0, Material{0.6, 0.5, 0}});
  w.AddForce(Gravity(Vector3(0, 0, -9.81)));
  return w;
}

TEST(BlockSolve, ALeaningColumnIsSolvedAsOneBlock) {
  ContactWorld w = LeaningColumn();
  constexpr int kMaxSweeps = 32;  // ContactOptions' default
  int capped = 0, quick = 0;
  for (int step = 0; step < 3000; ++step) {
    ASSERT_TRUE(w.Step(1e-3).ok);
    const int sweeps = w.stats().iterations;
    if (step >= 300) {  // the column has landed; it sways, then stands
      capped += sweeps >= kMaxSweeps;
      quick += sweeps <= 3;
    }
  }
  // Landed, the column sways for about a second and then stands (when exactly depends on rounding:
  // a column balanced on edges is chaotic). Its solve is one block: two sweeps, then the pivoting
  // step (at rest, the sweeps alone). The sweeps run out only in steps where a patch slides (a
  // sliding patch is swept point by point): 12 of these 2700. Before the block solve took free
  // bodies, 914 ran out of sweeps and 1764 were solved in three or fewer.
  EXPECT_LE(capped, 150) << "of the last 2700 steps";
  EXPECT_GE(quick, 2400) << "of the last 2700 steps";
  // The column stands: it is one island of six patches (boxes on boxes), and at rest to the
  // stopping rule — no point of a box moving faster than a few times 10⁻⁹ m/s.
  EXPECT_EQ(w.stats().pairs, 6);
  double mass = 0;
  for (const RigidBody& b : w.world().bodies()) {
    const double point_speed = b.velocity.norm() + 0.07 * b.AngularVelocity().norm();
    EXPECT_LT(point_speed, 1e-8) << "at " << b.position.transpose();
    EXPECT_GT(b.position.z(), 0.03);
    mass += b.mass;
  }
  // At rest, the ground carries the column's weight: its contacts' impulses over the last step
  // sum to m g h (to the momentum the step changed, < 10⁻⁶ of it here).
  Vector3 ground = Vector3::Zero();
  for (const ContactReport& c : w.Contacts()) {
    if (c.b < 0) ground += c.impulse;
  }
  EXPECT_NEAR(ground.z(), mass * 9.81 * 1e-3, 1e-6 * mass * 9.81 * 1e-3);
  EXPECT_LT(ground.head<2>().norm(), 1e-6 * mass * 9.81 * 1e-3);
}

}  // namespace
}  // namespace dynamics
