// Contact points kept from step to step (ManifoldCache, ContactOptions::reuse_distance): a kept
// manifold against the narrow phase run afresh at the moved poses, the gate's refusals, and a
// resting stack and a falling row of dominoes with and without reuse.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "dynamics/contact.h"
#include "manifold_cache.h"
#include "narrow_phase.h"
#include "polytope.h"
#include "scene/scene.h"
#include "scene/simulation.h"

namespace dynamics::contact {
namespace {

Matrix3 Turn(const Vector3& axis_angle) {
  const double angle = axis_angle.norm();
  if (angle == 0) return Matrix3::Identity();
  return Eigen::AngleAxisd(angle, axis_angle / angle).toRotationMatrix();
}

struct Pair {
  Shape shape_a = shape::Box{Vector3(0.05, 0.04, 0.03)};
  Shape shape_b = shape::Box{Vector3(0.2, 0.2, 0.05)};
  Polytope poly_a = BoxPolytope(Vector3(0.05, 0.04, 0.03));
  Polytope poly_b = BoxPolytope(Vector3(0.2, 0.2, 0.05));
  Posed a, b;
  double radius_a = Vector3(0.05, 0.04, 0.03).norm(), radius_b = Vector3(0.2, 0.2, 0.05).norm();

  // Box a resting on box b's top face (tilted about x by `tilt`: on an edge), overlapping 1 µm.
  explicit Pair(double tilt) {
    a.shape = &shape_a;
    a.polytope = &poly_a;
    b.shape = &shape_b;
    b.polytope = &poly_b;
    b.R = Turn(Vector3(0.01, -0.02, 0.3));
    b.t = Vector3(0.1, -0.2, 0.4);
    const Matrix3 tilt_a = Turn(Vector3(tilt, 0, 0));
    const Vector3 up = b.R.col(2);
    // The lowest point of a, rotated, sits 1 µm below b's top face.
    const double reach = 0.04 * std::abs(std::sin(tilt)) + 0.03 * std::cos(tilt);
    a.R = b.R * tilt_a;
    a.t = b.t + up * (0.05 + reach - 1e-6) + b.R.col(0) * 0.03;
  }
};

// Moves both shapes by a rigid motion of their own, the second by `relative` more (a turn about
// a point of b and a shift), so that b moves in a's frame by at most `relative` × (1 + radius).
void Move(Pair& p, std::mt19937& rng, double relative) {
  std::uniform_real_distribution<double> u(-1, 1);
  const Vector3 w(u(rng), u(rng), u(rng)), v(u(rng), u(rng), u(rng));
  const Matrix3 common = Turn(0.3 * w);  // the pair turned and carried as a whole
  const Vector3 shift = 0.5 * v;
  p.a.R = common * p.a.R;
  p.a.t = common * p.a.t + shift;
  p.b.R = common * p.b.R;
  p.b.t = common * p.b.t + shift;
  const Vector3 dw(u(rng), u(rng), u(rng)), dv(u(rng), u(rng), u(rng));
  const Matrix3 turn = Turn(relative / std::sqrt(3.0) * dw);
  p.b.R = turn * p.b.R;
  p.b.t = turn * (p.b.t - p.a.t) + p.a.t + relative / std::sqrt(3.0) * dv;
}

TEST(ManifoldCache, KeptPointsMatchTheNarrowPhaseAtTheMovedPoses) {
  std::mt19937 rng(7);
  for (const double tilt : {0.0, 0.2}) {  // flush faces (4 points), and on an edge (2 points)
    Pair p(tilt);
    const double margin = 1e-7, gate = 1e-10 * (p.radius_a + p.radius_b);
    std::vector<ContactPoint> found;
    Collide(p.a, p.b, ManifoldCache::WideMargin(margin, gate), found);
    ASSERT_EQ(found.size(), tilt == 0 ? 4u : 2u);
    ManifoldCache cache;
    cache.Keep(0, 1, p.a, p.b, ManifoldCache::WideMargin(margin, gate), found);
    cache.Flip();
    for (int trial = 0; trial < 200; ++trial) {
      Pair moved = p;
      moved.a.shape = &moved.shape_a;
      moved.a.polytope = &moved.poly_a;
      moved.b.shape = &moved.shape_b;
      moved.b.polytope = &moved.poly_b;
      Move(moved, rng, 0.3 * gate / (1 + p.radius_b));
      std::vector<ContactPoint> kept, fresh;
      ASSERT_TRUE(cache.Reuse(0, 1, moved.a, moved.b, p.radius_b, margin, gate, kept)) << "trial " << trial;
      Collide(moved.a, moved.b, margin, fresh);
      ASSERT_EQ(kept.size(), fresh.size());
      for (std::size_t i = 0; i < kept.size(); ++i) {
        EXPECT_EQ(kept[i].feature, fresh[i].feature);
        // The corners of a are material points: the separation is the narrow phase's to rounding
        // (the pair sits half a metre from the origin); the point is carried with a, within the gate.
        EXPECT_NEAR(kept[i].separation, fresh[i].separation, 1e-15) << "trial " << trial << " point " << i;
        EXPECT_LE((kept[i].point - fresh[i].point).norm(), gate) << "trial " << trial << " point " << i;
        EXPECT_LE((kept[i].normal - fresh[i].normal).norm(), gate / p.radius_b);
      }
    }
  }
}

TEST(ManifoldCache, RefusedBeyondTheGateOrTheMarginItWasFoundWith) {
  Pair p(0.0);
  const double margin = 1e-7, gate = 1e-10 * (p.radius_a + p.radius_b);
  std::vector<ContactPoint> found;
  Collide(p.a, p.b, ManifoldCache::WideMargin(margin, gate), found);
  ManifoldCache cache;
  cache.Keep(0, 1, p.a, p.b, ManifoldCache::WideMargin(margin, gate), found);
  cache.Flip();
  std::vector<ContactPoint> out;
  EXPECT_TRUE(cache.Reuse(0, 1, p.a, p.b, p.radius_b, margin, gate, out));
  EXPECT_FALSE(cache.Reuse(1, 0, p.a, p.b, p.radius_b, margin, gate, out));             // another pair
  EXPECT_FALSE(cache.Reuse(0, 1, p.a, p.b, p.radius_b, margin + 5 * gate, gate, out));  // a wider reach
  Pair shifted = p;
  shifted.b.t += Vector3(0, 0, 1.01 * gate);  // b slid by just over the gate
  EXPECT_FALSE(cache.Reuse(0, 1, shifted.a, shifted.b, p.radius_b, margin, gate, out));
  Pair turned = p;  // b turned about its own origin: its farthest corner moves 1.01 gates
  turned.b.R = Turn(Vector3(0, 0, 1.01 * gate / p.radius_b)) * turned.b.R;
  EXPECT_FALSE(cache.Reuse(0, 1, turned.a, turned.b, p.radius_b, margin, gate, out));
  // A pair that is not a candidate in a step is forgotten at the next (the step above reused it).
  cache.Flip();
  EXPECT_TRUE(cache.Reuse(0, 1, p.a, p.b, p.radius_b, margin, gate, out));
  cache.Flip();
  cache.Flip();
  EXPECT_FALSE(cache.Reuse(0, 1, p.a, p.b, p.radius_b, margin, gate, out));
}

struct Outcome {
  std::vector<Vector3> positions;
  long reused = 0;
};

Outcome Simulate(const std::string& name, double reuse_distance, bool exact, int steps) {
  std::vector<std::string> warnings;
  scene::Scene s = scene::LoadScene(std::string(MASSPROPS_DATA_DIR) + "/scenes/" + name, warnings);
  s.contact.reuse_distance = reuse_distance;
  s.contact.exact = exact;
  scene::Simulation sim = scene::BuildSimulation(s, warnings, 1);
  Outcome run;
  for (int i = 0; i < steps; ++i) {
    EXPECT_TRUE(sim.physics.Step(s.dt).ok);
    run.reused += sim.physics.stats().reused;
  }
  for (const auto& b : sim.world().bodies()) run.positions.push_back(b.position);
  return run;
}

// A resting stack: nearly every pair keeps its points (the narrow phase runs when the boxes'
// creep adds up to the gate), and the stack stands as it does with the narrow phase every step.
TEST(ManifoldCache, AStackKeepsItsPointsAndStandsAsWithoutThem) {
  const Outcome kept = Simulate("box_stack.json", 1e-10, false, 2000);
  const Outcome fresh = Simulate("box_stack.json", 0, false, 2000);
  const Outcome exact = Simulate("box_stack.json", 1e-10, true, 50);
  EXPECT_GT(kept.reused, 9 * 2000 * 9 / 10);  // nine box-on-box pairs
  EXPECT_EQ(fresh.reused, 0);
  EXPECT_EQ(exact.reused, 0);  // exact mode: the narrow phase every step
  // A mesh's points (samples of its distance field) are found afresh every step: Spot on a table.
  EXPECT_EQ(Simulate("spot_on_table.json", 1e-10, false, 300).reused, 0);
  for (std::size_t i = 0; i < kept.positions.size(); ++i) {
    EXPECT_LT((kept.positions[i] - fresh.positions[i]).norm(), 1e-8) << "box " << i;
  }
}

// Dominoes falling: pairs keep their points only while they rest, and the row falls as it does
// without reuse (each domino's place after 0.8 s within a micrometre).
TEST(ManifoldCache, FallingDominoesEndWhereTheyDoWithoutIt) {
  const Outcome kept = Simulate("dominoes.json", 1e-10, false, 800);
  const Outcome fresh = Simulate("dominoes.json", 0, false, 800);
  EXPECT_GT(kept.reused, 0);
  for (std::size_t i = 0; i < kept.positions.size(); ++i) {
    EXPECT_LT((kept.positions[i] - fresh.positions[i]).norm(), 1e-6) << "domino " << i;
  }
}

}  // namespace
}  // namespace dynamics::contact
