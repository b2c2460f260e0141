// The contact step's stages on their own (internal headers in src/contact/): the worker pool,
// islands solved in parallel giving the same bits as one thread, and the mesh field's blocks.
// (The velocity solve's own tests: solver_test.cpp.)

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "dynamics/contact.h"
#include "dynamics/forces.h"
#include "islands.h"
#include "massprops/solids.h"
#include "mesh_field.h"
#include "solver.h"
#include "workers.h"

namespace dynamics::contact {
namespace {

constexpr double kDiagonalCells = 1.7320508075688772;  // a cell's diagonal, in cells

constexpr double kG = 9.81;

TEST(Workers, EveryItemRunsOnceAndErrorsReachTheCaller) {
  for (const int threads : {1, 2, 3}) {
    Workers workers(threads);
    EXPECT_EQ(workers.threads(), threads);
    for (const std::size_t n : {0u, 1u, 7u, 1000u}) {
      std::vector<std::atomic<int>> seen(n);
      workers.ForEach(n, [&](std::size_t i) { seen[i].fetch_add(1); });
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i].load(), 1) << "item " << i << " of " << n;
    }
    EXPECT_THROW(workers.ForEach(50,
                                 [](std::size_t i) {
                                   if (i == 17) throw std::runtime_error("item 17");
                                 }),
                 std::runtime_error);
    // The pool still works after an item threw.
    std::atomic<int> count{0};
    workers.ForEach(10, [&](std::size_t) { count.fetch_add(1); });
    EXPECT_EQ(count.load(), 10);
  }
}

// Sixteen separate stacks of three boxes (sixteen islands, 48 patches: the parallel solve runs)
// on 1, 2 and 3 threads: the same bits, and every stack stands.
TEST(Islands, SolvedInParallelGiveTheSameBits) {
  auto run = [](int threads) {
    ContactWorld w;
    const Vector3 half = Vector3::Constant(0.05);
    for (int s = 0; s < 16; ++s) {
      for (int k = 0; k < 3; ++k) {
        RigidBody b;
        b.mass = 1;
        b.inertia = Vector3::Constant(b.mass * 0.01 / 6);
        b.position = Vector3(0.3 * (s % 4), 0.3 * (s / 4), 0.05 + 0.1 * k);
        b.orientation = Quaternion(Eigen::AngleAxisd(0.05 * s + 0.02 * k, Vector3::UnitZ()));
        w.AddBody(b, Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), Material{0.6, 0.5, 0}});
      }
    }
    w.AddGround({Vector3::UnitZ(), 0, Material{0.6, 0.5, 0}});
    w.AddForce(Gravity(Vector3(0, 0, -kG)));
    w.set_num_threads(threads);
    for (int i = 0; i < 300; ++i) EXPECT_TRUE(w.Step(1e-3).ok);
    EXPECT_EQ(w.stats().contacts, 16 * 3 * 4);
    return w.world().bodies();
  };
  const std::vector<RigidBody> one = run(1);
  for (const int threads : {2, 3}) {
    const std::vector<RigidBody> many = run(threads);
    for (std::size_t i = 0; i < one.size(); ++i) {
      ASSERT_EQ(one[i].position, many[i].position) << "body " << i << ", " << threads << " threads";
      ASSERT_EQ(one[i].orientation.coeffs(), many[i].orientation.coeffs()) << "body " << i;
      ASSERT_EQ(one[i].velocity, many[i].velocity) << "body " << i;
    }
  }
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_NEAR(one[i].position.z(), 0.05 + 0.1 * static_cast<double>(i % 3), 1e-6) << "body " << i;
  }
}

// The field's block table (MeshField::SurelyAbove) only ever turns away points whose φ is above
// the threshold (checked against the field's own value at 60 000 points in and around its grid),
// and turns away most of those a few cells off the surface, so it is worth its lookup.
TEST(MeshFieldBlocks, SurelyAboveOnlyWherePhiIsAbove) {
  const massprops::TriangleMesh t = massprops::solids::Torus(0.035, 0.012, 32);
  std::vector<Vector3> v;
  std::vector<std::array<int, 3>> f;
  for (Eigen::Index i = 0; i < t.V.rows(); ++i) v.push_back(t.V.row(i).transpose());
  for (Eigen::Index i = 0; i < t.F.rows(); ++i) f.push_back({t.F(i, 0), t.F(i, 1), t.F(i, 2)});
  const shape::Mesh mesh = MakeMesh(std::move(v), std::move(f));
  const MeshField& field = *mesh.field;
  ASSERT_FALSE(field.block_min.empty());
  std::mt19937_64 rng(5);
  const Vector3 lo = field.origin - Vector3::Constant(2 * field.cell);
  const Vector3 span = field.cell * Vector3(field.nodes[0] + 3, field.nodes[1] + 3, field.nodes[2] + 3);
  std::uniform_real_distribution<double> u(0, 1);
  int far = 0, far_turned = 0, turned = 0;
  for (int i = 0; i < 60000; ++i) {
    const Vector3 x = lo + Vector3(u(rng), u(rng), u(rng)).cwiseProduct(span);
    const double phi = field.Distance(x, nullptr);
    for (const double threshold : {-0.004, 0.0, 0.001, 0.004}) {
      if (field.SurelyAbove(x, threshold)) {
        ++turned;
        ASSERT_GT(phi, threshold) << x.transpose();
      }
    }
    // Inside the grid, 4 cells above the threshold 0: the blocks (2 cells a side) know it.
    const Vector3 g = (x - field.origin) / field.cell;
    const bool inside = (g.array() >= 0).all() &&
                        (g.array() <= Eigen::Array3d(field.nodes[0] - 1, field.nodes[1] - 1, field.nodes[2] - 1)).all();
    if (inside && phi > 4 * kDiagonalCells * field.cell) {
      ++far;
      far_turned += field.SurelyAbove(x, 0.0) ? 1 : 0;
    }
  }
  EXPECT_GT(turned, 1000);
  ASSERT_GT(far, 1000);
  EXPECT_EQ(far_turned, far);
}

}  // namespace
}  // namespace dynamics::contact
