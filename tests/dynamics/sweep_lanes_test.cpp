// One island's sweeps and shock propagation on several threads (SweepLanes): a heap of boxes
// whose contacts form one island of a few hundred patches steps to the same bits on one, two and
// three threads, and its sweeps did run on more than one. (A lane that did not wait for another's
// update of a shared body, or shock propagation that did not wait for a ground patch's update of
// the body it holds still, fails it.)

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dynamics/contact.h"

namespace dynamics {
namespace {

constexpr double kG = 9.81;

struct HeapRun {
  std::vector<RigidBody> bodies;
  int most_lanes = 0;     // over the steps
  int largest_pairs = 0;  // touching pairs in the step with the most
};

// Boxes in a 5 × 5 × 6 lattice, each tilted its own way and a little apart, dropped together onto
// the ground: they settle into one heap.
HeapRun Heap(int threads, int steps, bool exact = false) {
  ContactOptions options;
  options.exact = exact;  // rbsim 0.3's solver: point-by-point normals, shock propagation every step
  ContactWorld w(World(), options);
  const Vector3 half = Vector3::Constant(0.04);
  for (int i = 0; i < 150; ++i) {
    const int x = i % 5, y = (i / 5) % 5, z = i / 25;
    RigidBody b;
    b.mass = 500 * 8 * half.prod();
    b.inertia = Vector3::Constant(b.mass * (2 * half[0]) * (2 * half[0]) / 6);
    b.position = Vector3(0.085 * x + 0.01 * (z % 2), 0.085 * y, 0.045 + 0.085 * z);
    b.orientation = Quaternion(Eigen::AngleAxisd(0.05 * ((i * 7919) % 13 - 6), Vector3(1, 2, 3).normalized()));
    w.AddBody(b, Collider{shape::Box{half}, Matrix3::Identity(), Vector3::Zero(), Material{0.6, 0.5, 0.1}});
  }
  w.AddGround({Vector3::UnitZ(), 0, Material{0.6, 0.5, 0.1}});
  w.AddForce(Gravity(Vector3(0, 0, -kG)));
  w.set_num_threads(threads);
  HeapRun run;
  for (int s = 0; s < steps; ++s) {
    EXPECT_TRUE(w.Step(1e-3).ok);
    run.most_lanes = std::max(run.most_lanes, w.stats().lanes);
    run.largest_pairs = std::max(run.largest_pairs, w.stats().pairs);
  }
  run.bodies = w.world().bodies();
  return run;
}

TEST(SweepLanes, AHeapStepsToTheSameBitsOnOneTwoAndThreeThreads) {
  constexpr int kSteps = 60;
  const HeapRun one = Heap(1, kSteps), two = Heap(2, kSteps), three = Heap(3, kSteps);
  EXPECT_EQ(one.most_lanes, 1);
  EXPECT_EQ(two.most_lanes, 2);  // the heap is one island of more than 128 patches
  EXPECT_EQ(three.most_lanes, 3);
  EXPECT_GT(one.largest_pairs, 300);
  for (const HeapRun* other : {&two, &three}) {
    ASSERT_EQ(one.bodies.size(), other->bodies.size());
    for (std::size_t i = 0; i < one.bodies.size(); ++i) {
      EXPECT_EQ(one.bodies[i].position, other->bodies[i].position) << "body " << i;
      EXPECT_EQ(one.bodies[i].orientation.coeffs(), other->bodies[i].orientation.coeffs()) << "body " << i;
      EXPECT_EQ(one.bodies[i].velocity, other->bodies[i].velocity) << "body " << i;
      EXPECT_EQ(one.bodies[i].angular_momentum, other->bodies[i].angular_momentum) << "body " << i;
    }
  }
  // The heap did move: the bits compared are a solve's, not the starting lattice's.
  double fallen = 0;
  for (const RigidBody& b : one.bodies) fallen = std::max(fallen, b.velocity.norm());
  EXPECT_GT(fallen, 1e-3);
}

TEST(SweepLanes, ExactModeToo) {
  constexpr int kSteps = 30;
  const HeapRun one = Heap(1, kSteps, true), two = Heap(2, kSteps, true);
  EXPECT_EQ(two.most_lanes, 2);
  for (std::size_t i = 0; i < one.bodies.size(); ++i) {
    EXPECT_EQ(one.bodies[i].position, two.bodies[i].position) << "body " << i;
    EXPECT_EQ(one.bodies[i].orientation.coeffs(), two.bodies[i].orientation.coeffs()) << "body " << i;
    EXPECT_EQ(one.bodies[i].velocity, two.bodies[i].velocity) << "body " << i;
  }
}

}  // namespace
}  // namespace dynamics
