// The narrow phase's pair table is whole: every pair of collider kinds — sphere, box, capsule,
// cylinder, convex hull, mesh (signed distance field), compound — has a contact routine, so no
// step can fail mid-run on a pair it cannot collide. Each pair is set overlapping in a world and
// stepped: the step succeeds and finds contact points, and the pair pushes apart.

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynamics/contact.h"
#include "narrow_phase.h"
#include "polytope.h"

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

// A hull against the ground through a kept scan (GroundScan: the corners near the plane at the last
// full scan, tested alone while the hull has not turned or moved enough for another to come within
// reach) finds exactly the points a full scan finds — same points, normals, separations, corners,
// in the same order — along a tumbling path that grazes, rests, lifts and jumps; and the kept
// scan is actually used on most steps.
TEST(NarrowPhase, AKeptGroundScanFindsWhatAFullScanFinds) {
  // An ellipsoid's UV tessellation (convex, 266 corners).
  const int nlat = 12, nlon = 24;
  std::vector<Vector3> v = {Vector3(0, 0, 0.3)};
  for (int i = 1; i < nlat; ++i) {
    for (int j = 0; j < nlon; ++j) {
      const double th = M_PI * i / nlat, ph = 2 * M_PI * j / nlon;
      v.emplace_back(0.5 * std::sin(th) * std::cos(ph), 0.4 * std::sin(th) * std::sin(ph), 0.3 * std::cos(th));
    }
  }
  v.emplace_back(0, 0, -0.3);
  const int south = static_cast<int>(v.size()) - 1;
  auto at = [&](int i, int j) { return 1 + (i - 1) * nlon + (j % nlon); };
  std::vector<std::array<int, 3>> t;
  for (int j = 0; j < nlon; ++j) {
    t.push_back({0, at(1, j), at(1, j + 1)});
    t.push_back({south, at(nlat - 1, j + 1), at(nlat - 1, j)});
    for (int i = 1; i + 1 < nlat; ++i) {
      t.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      t.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  const Shape hull = dynamics::MakeConvex(v, t);
  const auto& convex = std::get<shape::Convex>(hull);
  dynamics::contact::Posed a;
  a.shape = &hull;
  a.polytope = convex.polytope.get();
  dynamics::contact::GroundScan scan;
  const Vector3 n = Vector3::UnitZ();
  const dynamics::CollisionFilter ground{~0u, ~0u};
  int kept = 0;
  for (int s = 0; s < 600; ++s) {
    const double time = 1e-3 * s;
    const Vector3 axis = Vector3(std::sin(3 * time), std::cos(2 * time), 0.5).normalized();
    a.R = Eigen::AngleAxisd(4 * time + (s / 150) * 1.3, axis).toRotationMatrix();  // a jump every 150 steps
    a.t = Vector3(0.1 * time, 0, 0.28 + 0.05 * std::sin(20 * time));               // grazing, resting, lifting
    const double margin = 0.01 + 0.005 * std::sin(7 * time);
    std::vector<dynamics::contact::ContactPoint> with, without;
    dynamics::contact::CollideGround(a, n, 0.0, ground, margin, with, &scan);
    dynamics::contact::CollideGround(a, n, 0.0, ground, margin, without);
    if (scan.u != a.R.transpose() * n) ++kept;
    ASSERT_EQ(with.size(), without.size()) << "step " << s;
    for (std::size_t i = 0; i < with.size(); ++i) {
      EXPECT_EQ(with[i].point, without[i].point) << "step " << s;
      EXPECT_EQ(with[i].normal, without[i].normal);
      EXPECT_EQ(with[i].separation, without[i].separation);
      EXPECT_EQ(with[i].feature, without[i].feature);
    }
  }
  EXPECT_GT(kept, 300);
}

}  // namespace
