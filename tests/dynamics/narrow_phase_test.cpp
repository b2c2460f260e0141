// The narrow phase's pair table is whole: every pair of collider kinds — sphere, box, capsule,
// cylinder, convex hull, mesh (signed distance field), compound — has a contact routine, so no
// step can fail mid-run on a pair it cannot collide. Each pair is set overlapping in a world and
// stepped: the step succeeds and finds contact points, and the pair pushes apart.

#include <array>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynamics/contact.h"
#include "narrow_phase.h"

namespace {

using dynamics::ContactWorld;
using dynamics::Shape;
using dynamics::Vector3;
namespace shape = dynamics::shape;

// A unit-ish cube's corners and outward triangles (half size h).
void Cube(double h, std::vector<Vector3>& v, std::vector<std::array<int, 3>>& t) {
  v.clear();
  for (int i = 0; i < 8; ++i) v.emplace_back((i & 4) ? h : -h, (i & 2) ? h : -h, (i & 1) ? h : -h);
  t = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
       {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
}

std::vector<std::pair<std::string, Shape>> Kinds() {
  std::vector<Vector3> v;
  std::vector<std::array<int, 3>> t;
  Cube(0.4, v, t);
  shape::Compound compound;
  compound.parts.push_back(dynamics::Collider(shape::Sphere{0.4}, dynamics::Matrix3::Identity(), Vector3(0, 0.2, 0)));
  compound.parts.push_back(
      dynamics::Collider(shape::Box{Vector3::Constant(0.35)}, dynamics::Matrix3::Identity(), Vector3(0, -0.2, 0)));
  return {{"sphere", shape::Sphere{0.4}},
          {"box", shape::Box{Vector3::Constant(0.4)}},
          {"capsule", shape::Capsule{0.4, 0.2}},
          {"cylinder", shape::Cylinder{0.4, 0.3}},
          {"convex", shape::Convex{v, t}},
          {"mesh", dynamics::MakeMesh(v, t)},
          {"compound", compound}};
}

TEST(NarrowPhase, EveryPairOfKindsHasARoutine) {
  const auto kinds = Kinds();
  ASSERT_EQ(kinds.size(), std::variant_size_v<Shape>);
  for (const auto& [a_name, a] : kinds) {
    for (const auto& [b_name, b] : kinds) {
      ContactWorld world;
      dynamics::RigidBody body;
      body.mass = 1;
      body.inertia = Vector3::Constant(0.1);
      body.position = Vector3(-0.3, 0, 0);
      const int i = world.AddBody(body, dynamics::Collider(a));
      body.position = Vector3(0.3, 0, 0);
      const int j = world.AddBody(body, dynamics::Collider(b));
      for (int s = 0; s < 20; ++s) {
        const dynamics::StepStatus st = world.Step(1e-3);
        ASSERT_TRUE(st.ok) << a_name << " / " << b_name << ": " << st.message;
        if (s == 0) {
          EXPECT_GT(world.stats().contacts, 0) << a_name << " / " << b_name;
        }
      }
      // Pushed apart along x, not through each other.
      EXPECT_LT(world.world().bodies()[static_cast<std::size_t>(i)].position.x(), -0.3) << a_name << " / " << b_name;
      EXPECT_GT(world.world().bodies()[static_cast<std::size_t>(j)].position.x(), 0.3) << a_name << " / " << b_name;
    }
  }
}

// The table itself, as ContactWorld asks it when a body is added: every kind against every kind,
// compounds through their parts.
TEST(NarrowPhase, TheTableAnswersForEveryPairOfKinds) {
  const auto kinds = Kinds();
  for (const auto& [a_name, a] : kinds) {
    for (const auto& [b_name, b] : kinds)
      EXPECT_TRUE(dynamics::contact::SupportsPair(a, b)) << a_name << " / " << b_name;
  }
}

}  // namespace
