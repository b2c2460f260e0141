// Drops (scene/drop.h): parts dropped until they rest, against closed forms (a cube's resting
// height, a cube on its edge falling flat), against the scene file they save (the same bits), and
// a pile of non-convex parts in a bin.

#include "scene/drop.h"

#include "massprops/io/load.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace {

using massprops::Vector3;
namespace fs = std::filesystem;

// A cube of side `side` (m) written as a CAD exporter's OBJ: a header comment, corners from 1,
// quads; its origin at a corner, so that its center of mass is off the origin.
std::string WriteCube(const std::string& name, double side) {
  const fs::path dir = fs::temp_directory_path() / "massprops_drop_test";
  fs::create_directories(dir);
  const fs::path path = dir / name;
  std::ofstream out(path);
  out << "# Exported by a CAD system\r\no cube\r\n";
  for (int k = 0; k < 8; ++k) {
    out << "v " << side * (k & 1) << " " << side * ((k >> 1) & 1) << " " << side * ((k >> 2) & 1) << "\r\n";
  }
  // Outward quads (corners k = x + 2y + 4z, numbered from 1).
  out << "f 1 3 4 2\r\nf 5 6 8 7\r\nf 1 2 6 5\r\nf 3 7 8 4\r\nf 1 5 7 3\r\nf 2 4 8 6\r\n";
  return path.string();
}

struct Dropped {
  scene::Simulation sim;
  scene::RunStats stats;
};

Dropped RunScene(const scene::Scene& s) {
  std::vector<std::string> warnings;
  Dropped d{scene::BuildSimulation(s, warnings), {}};
  d.stats = scene::Run(d.sim, [](const dynamics::World&, const dynamics::Diagnostics&) {});
  return d;
}

Dropped Drop(const scene::DropOptions& o) {
  std::vector<std::string> warnings;
  return RunScene(scene::DropScene(o, warnings));
}

TEST(Drop, CubeDroppedFlatRestsAtHalfItsSideSoon) {
  scene::DropOptions o;
  o.files = {WriteCube("cube.obj", 0.1)};
  const Dropped d = Drop(o);
  ASSERT_TRUE(d.stats.rest_time.has_value());
  // Free fall from 1 cm takes sqrt(2 h / g) = 0.045 s; it stops there (no restitution).
  EXPECT_LT(*d.stats.rest_time, 0.3);
  const auto poses = scene::RestingPoses(d.sim);
  ASSERT_EQ(poses.size(), 1U);
  EXPECT_NEAR(poses[0].com_height, 0.05, 1e-9);
  EXPECT_EQ(poses[0].support, "face");
  EXPECT_NEAR(poses[0].down_in_part.z(), -1.0, 1e-9);
  EXPECT_NEAR(poses[0].tilt, 0.0, 1e-6);
  // Dropped from where its file puts it, raised: its center of mass over the file's.
  const Vector3 p = d.sim.world().bodies()[0].position;
  EXPECT_NEAR(p.x(), 0.05, 1e-9);
  EXPECT_NEAR(p.y(), 0.05, 1e-9);
}

TEST(Drop, CubeOnItsEdgeFallsOntoAFace) {
  scene::DropOptions o;
  o.files = {WriteCube("cube.obj", 0.1)};
  o.orientation = scene::DropOrientation::kAxisAngle;
  o.axis = Vector3::UnitX();
  o.angle = massprops::kPi / 4 + 0.05;  // past the balance, so it topples one way
  o.height = 0.001;
  const Dropped d = Drop(o);
  ASSERT_TRUE(d.stats.rest_time.has_value());
  const auto poses = scene::RestingPoses(d.sim);
  EXPECT_EQ(poses[0].support, "face");
  EXPECT_NEAR(poses[0].com_height, 0.05, 1e-6);
  // A face down: gravity along one of the part's axes.
  EXPECT_NEAR(poses[0].down_in_part.cwiseAbs().maxCoeff(), 1.0, 1e-6);
  EXPECT_NEAR(std::remainder(poses[0].tilt, massprops::kPi / 2), 0.0, 1e-5);
  EXPECT_GT(poses[0].tilt, 1.0);  // it toppled onto a side face: turned 90 degrees
}

// Exactly on its edge (45°), exactly computed, it stays balanced there: said so, not called a face.
TEST(Drop, CubeBalancedOnItsEdgeIsSaidToBeBalanced) {
  scene::DropOptions o;
  o.files = {WriteCube("cube.obj", 0.1)};
  o.orientation = scene::DropOrientation::kAxisAngle;
  o.axis = Vector3::UnitX();
  o.angle = massprops::kPi / 4;
  const Dropped d = Drop(o);
  const auto poses = scene::RestingPoses(d.sim);
  EXPECT_EQ(poses[0].support, "edge");
  EXPECT_TRUE(poses[0].balanced);
  EXPECT_NEAR(poses[0].com_height, 0.05 * std::sqrt(2.0), 1e-9);
  o.angle += 0.05;
  EXPECT_FALSE(scene::RestingPoses(Drop(o).sim)[0].balanced);
}

TEST(Drop, TheSavedSceneRunsToTheSameBits) {
  scene::DropOptions o;
  o.files = {std::string(MASSPROPS_DATA_DIR) + "/meshes/t_handle.obj", WriteCube("cube.obj", 0.03)};
  o.count = 3;
  o.orientation = scene::DropOrientation::kRandom;
  o.seed = 7;
  o.duration = 0.3;
  std::vector<std::string> warnings;
  const scene::Scene direct = scene::DropScene(o, warnings);
  const scene::Scene saved = scene::ParseSceneText(scene::DropSceneJson(direct), "saved.json", "/", warnings);
  const Dropped a = RunScene(direct), b = RunScene(saved);
  ASSERT_EQ(a.sim.world().bodies().size(), 6U);
  ASSERT_EQ(b.sim.world().bodies().size(), 6U);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(a.sim.world().bodies()[k].position, b.sim.world().bodies()[k].position) << k;
    EXPECT_EQ(a.sim.world().bodies()[k].orientation.coeffs(), b.sim.world().bodies()[k].orientation.coeffs()) << k;
  }
  EXPECT_EQ(a.stats.steps, b.stats.steps);
}

TEST(Drop, RandomOrientationsFollowTheSeed) {
  scene::DropOptions o;
  o.files = {std::string(MASSPROPS_DATA_DIR) + "/meshes/t_handle.obj"};
  o.count = 4;
  o.orientation = scene::DropOrientation::kRandom;
  std::vector<std::string> warnings;
  const scene::Scene a = scene::DropScene(o, warnings), b = scene::DropScene(o, warnings);
  o.seed = 2;
  const scene::Scene c = scene::DropScene(o, warnings);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(a.bodies[k].orientation.coeffs(), b.bodies[k].orientation.coeffs());
    EXPECT_NE(a.bodies[k].orientation.coeffs(), c.bodies[k].orientation.coeffs());
    EXPECT_NEAR(a.bodies[k].orientation.norm(), 1.0, 1e-15);
  }
}

// Non-convex parts poured into a bin: every one ends inside it, at rest, none through another.
TEST(Drop, NonConvexPartsPileUpInsideABin) {
  scene::DropOptions o;
  o.files = {std::string(MASSPROPS_DATA_DIR) + "/meshes/t_handle.obj"};
  o.on = std::string(MASSPROPS_DATA_DIR) + "/meshes/bin.obj";  // 0.6 × 0.4 × 0.25 m, walls 0.02 m
  o.count = 20;
  o.orientation = scene::DropOrientation::kRandom;
  const Dropped d = Drop(o);
  ASSERT_TRUE(d.stats.rest_time.has_value());
  EXPECT_LT(d.stats.max_penetration, 5e-3);  // contact slop and impacts, far less than a part (~0.1 m)
  for (const dynamics::RigidBody& rb : d.sim.world().bodies()) {
    EXPECT_LT(std::abs(rb.position.x()), 0.28);
    EXPECT_LT(std::abs(rb.position.y()), 0.18);
    EXPECT_GT(rb.position.z(), 0.02);  // above the bin's floor
  }
  for (const scene::RestingPose& p : scene::RestingPoses(d.sim)) EXPECT_LT(p.speed, o.rest.speed);
}

// An assembly (an OBJ's groups) falls as one body of the parts' composition, or with `separate`
// as a body per part, each starting where the file puts it.
TEST(Drop, AnAssemblyFallsWholeOrPartByPart) {
  scene::DropOptions o;
  o.files = {std::string(MASSPROPS_DATA_DIR) + "/meshes/assembly_bracket.obj"};
  o.load.parts = true;
  massprops::LoadOptions whole_options;
  whole_options.parts = true;
  const massprops::SolidResult file = massprops::LoadSolid(o.files[0], whole_options);
  ASSERT_GE(file.parts.size(), 2U);
  const Dropped whole = Drop(o);
  ASSERT_EQ(whole.sim.bodies.size(), 1U);
  EXPECT_NEAR(whole.sim.bodies[0].mp.mass, file.mp.mass, 1e-15 * file.mp.mass);
  o.separate = true;
  std::vector<std::string> warnings;
  const scene::Scene apart = scene::DropScene(o, warnings);
  ASSERT_EQ(apart.bodies.size(), file.parts.size());
  double mass = 0;
  const Dropped run = RunScene(apart);
  for (std::size_t k = 0; k < file.parts.size(); ++k) {
    mass += run.sim.bodies[k].mp.mass;
    // Placed as in the file: the same offsets between the parts' centers of mass.
    const Vector3 offset = *apart.bodies[k].position - *apart.bodies[0].position;
    const Vector3 expected = file.parts[k].mp.center_of_mass - file.parts[0].mp.center_of_mass;
    EXPECT_LT((offset - expected).norm(), 1e-12) << k;
  }
  EXPECT_NEAR(mass, file.mp.mass, 1e-12 * file.mp.mass);
  EXPECT_TRUE(run.stats.rest_time.has_value());
}

TEST(Drop, BadOptionsAreNamed) {
  scene::DropOptions o;
  std::vector<std::string> warnings;
  EXPECT_THROW(scene::DropScene(o, warnings), scene::SceneError);  // no part
  o.files = {"/nonexistent/part.stl"};
  try {
    scene::DropScene(o, warnings);
    FAIL();
  } catch (const scene::SceneError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("/nonexistent/part.stl: not found"));
  }
}

}  // namespace
