// Assemblies (LoadOptions::parts): every part of a file on its own, the whole as their
// composition. Truth: closed forms of boxes (m = rho a b c, I = m/12 diag(b²+c², a²+c², a²+b²)),
// rotated and moved by hand (parallel axis written out here, not the library's Combine), for the
// assemblies scripts/make_assembly.py writes into data/meshes.

#include <cmath>
#include <fstream>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/io/load.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::DataPath;
using ::testing::HasSubstr;

struct Box {
  Vector3 size, center;
  double density;
  Matrix3 rotation = Matrix3::Identity();
  double Mass() const { return density * size.prod(); }
  Matrix3 Inertia() const {  // about its center, in the file's axes
    const double a = size[0], b = size[1], c = size[2], m = Mass();
    const Vector3 d(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12);
    return rotation * d.asDiagonal() * rotation.transpose();
  }
};

// Σ over the boxes with the parallel-axis term m (|d|² E − d dᵀ), d from the common center.
void ExpectWhole(const SolidResult& r, const std::vector<Box>& boxes, double tol) {
  double m = 0;
  Vector3 c = Vector3::Zero();
  for (const Box& b : boxes) {
    m += b.Mass();
    c += b.Mass() * b.center;
  }
  c /= m;
  Matrix3 I = Matrix3::Zero();
  for (const Box& b : boxes) {
    const Vector3 d = b.center - c;
    I += b.Inertia() + b.Mass() * (d.squaredNorm() * Matrix3::Identity() - d * d.transpose());
  }
  EXPECT_NEAR(r.mp.mass, m, tol * m);
  EXPECT_LT((r.mp.center_of_mass - c).norm(), tol * 0.1);
  EXPECT_LT((r.mp.inertia_com - I).norm(), tol * I.norm());
}

void ExpectBox(const SolidResult& part, const Box& b, double tol) {
  EXPECT_NEAR(part.mp.mass, b.Mass(), tol * b.Mass()) << part.part;
  EXPECT_LT((part.mp.center_of_mass - b.center).norm(), tol * b.size.norm()) << part.part;
  EXPECT_LT((part.mp.inertia_com - b.Inertia()).norm(), tol * b.Inertia().norm()) << part.part;
}

const std::vector<Box> kBracket = {{{0.10, 0.06, 0.01}, {0, 0, 0.005}, 1000},
                                   {{0.02, 0.02, 0.08}, {0.03, 0, 0.05}, 1000},
                                   {{0.01, 0.01, 0.02}, {-0.03, 0.02, 0.02}, 1000}};

TEST(Parts, ObjObjectsAreParts) {
  LoadOptions o;
  o.parts = true;
  const SolidResult r = LoadSolid(DataPath("meshes/assembly_bracket.obj"), o);
  ASSERT_EQ(r.parts.size(), 3u);
  EXPECT_EQ(r.parts[0].part, "base");
  EXPECT_EQ(r.parts[1].part, "post");  // its `g` line does not split it
  EXPECT_EQ(r.parts[2].part, "insert_brass");
  for (std::size_t i = 0; i < 3; ++i) {
    ExpectBox(r.parts[i], kBracket[i], 1e-13);
    EXPECT_EQ(r.parts[i].topology.faces, 6);
    EXPECT_TRUE(r.parts[i].topology.BoundsVolume());
  }
  ExpectWhole(r, kBracket, 1e-13);
  EXPECT_EQ(r.topology.faces, 18);
  EXPECT_EQ(r.topology.components, 3);
  // The whole equals the file computed as one solid (disjoint parts, one density), to rounding.
  const SolidResult one = LoadSolid(DataPath("meshes/assembly_bracket.obj"));
  EXPECT_TRUE(one.parts.empty());
  EXPECT_NEAR(r.mp.mass, one.mp.mass, 1e-15 * one.mp.mass);
  EXPECT_LT((r.mp.center_of_mass - one.mp.center_of_mass).norm(), 1e-16);
  EXPECT_LT((r.mp.inertia_com - one.mp.inertia_com).norm(), 1e-14 * one.mp.inertia_com.norm());
}

TEST(Parts, DensitiesAndMassesPerPart) {
  LoadOptions o;
  o.parts = true;
  o.part_masses = {{"base", Density{2700}}, {"post", Density{7850}}, {"insert_*", TotalMass{0.017}}};
  const SolidResult r = LoadSolid(DataPath("meshes/assembly_bracket.obj"), o);
  std::vector<Box> boxes = kBracket;
  boxes[0].density = 2700;
  boxes[1].density = 7850;
  boxes[2].density = 0.017 / boxes[2].size.prod();
  for (std::size_t i = 0; i < 3; ++i) ExpectBox(r.parts[i], boxes[i], 1e-13);
  ExpectWhole(r, boxes, 1e-13);
  EXPECT_TRUE(r.parts[2].mass_fixed);
  EXPECT_FALSE(r.parts[0].mass_fixed);
}

TEST(Parts, TotalMassIsSharedByTheUnmappedParts) {
  LoadOptions o;
  o.parts = true;
  o.mass = TotalMass{1.0};
  o.part_masses = {{"post", TotalMass{0.25}}};
  const SolidResult r = LoadSolid(DataPath("meshes/assembly_bracket.obj"), o);
  EXPECT_NEAR(r.mp.mass, 1.0, 1e-15);
  EXPECT_NEAR(r.parts[1].mp.mass, 0.25, 1e-16);
  const double rho = 0.75 / (kBracket[0].size.prod() + kBracket[2].size.prod());
  EXPECT_NEAR(r.parts[0].mp.density, rho, 1e-12 * rho);
  EXPECT_NEAR(r.parts[2].mp.density, rho, 1e-12 * rho);
  std::vector<Box> boxes = kBracket;
  boxes[0].density = boxes[2].density = rho;
  boxes[1].density = 0.25 / boxes[1].size.prod();
  ExpectWhole(r, boxes, 1e-13);
}

TEST(Parts, MapEntriesMustMatchAPart) {
  LoadOptions o;
  o.parts = true;
  o.part_masses = {{"bse", Density{2700}}};
  try {
    LoadSolid(DataPath("meshes/assembly_bracket.obj"), o);
    FAIL() << "a misspelt part was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("'bse' matches no part"));
    EXPECT_THAT(e.what(), HasSubstr("'insert_brass'"));
  }
}

TEST(Parts, APartThatIsNotASolidIsNamed) {
  const std::string path = ::testing::TempDir() + "/open_part.obj";
  std::ofstream(path) << "o closed\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
                      << "o lid\nv 2 0 0\nv 3 0 0\nv 2 1 0\nv 2 0 1\nf 5 7 6\nf 5 6 8\nf 5 8 7\n";
  LoadOptions o;
  o.parts = true;
  try {
    LoadSolid(path, o);
    FAIL() << "an open part was accepted";
  } catch (const LoadError& e) {
    EXPECT_THAT(e.what(), HasSubstr("(part 'lid')"));
  }
  // Without parts, the same file is refused as a whole, as before.
  EXPECT_THROW(LoadSolid(path), LoadError);
}

TEST(Parts, FacesBeforeTheFirstNameAndRepeatedGroups) {
  const std::string path = ::testing::TempDir() + "/groups.obj";
  // Two unit tetrahedra; the first split over two `g a` runs with `g b` between: groups of one
  // name are one part wherever they are; a file with groups and no objects splits by groups.
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\n"
                      << "g a\nf 1 3 2\nf 1 2 4\ng b\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\ng a\nf 1 4 3\nf 2 3 4\n";
  LoadOptions o;
  o.parts = true;
  const SolidResult r = LoadSolid(path, o);
  ASSERT_EQ(r.parts.size(), 2u);
  EXPECT_EQ(r.parts[0].part, "a");
  EXPECT_EQ(r.parts[1].part, "b");
  EXPECT_NEAR(r.parts[0].mp.volume, 1.0 / 6, 1e-15);
  EXPECT_NEAR(r.parts[1].mp.center_of_mass[0], 5.25, 1e-14);
}

TEST(Parts, AFileWithoutNamesIsOnePart) {
  LoadOptions o;
  o.parts = true;
  const SolidResult r = LoadSolid(DataPath("meshes/t_handle.obj"), o);
  ASSERT_EQ(r.parts.size(), 1u);
  EXPECT_EQ(r.parts[0].part, "t_handle");
  EXPECT_EQ(r.mp.mass, r.parts[0].mp.mass);
}

TEST(Parts, RefusedWithModelsThatDoNotCompose) {
  LoadOptions o;
  o.parts = true;
  o.exact = true;
  EXPECT_THROW(LoadSolid(DataPath("meshes/assembly_bracket.obj"), o), std::invalid_argument);
  o.exact = false;
  o.model = ShellModel{1.0};
  EXPECT_THROW(LoadSolid(DataPath("meshes/assembly_bracket.obj"), o), std::invalid_argument);
  LoadOptions no_parts;
  no_parts.part_masses = {{"base", Density{1}}};
  EXPECT_THROW(LoadSolid(DataPath("meshes/assembly_bracket.obj"), no_parts), std::invalid_argument);
}

// glTF nodes: one cube mesh instanced by two nodes with scale, rotation and translation, under a
// parent node that moves both. Coordinates and node matrices pass through 32-bit floats.
TEST(Parts, GltfNodesAreParts) {
  if (!IsMeshFile("x.gltf")) GTEST_SKIP() << "this build reads no glTF (MASSPROPS_WITH_ASSIMP=OFF)";
  LoadOptions o;
  o.parts = true;
  const SolidResult r = LoadSolid(DataPath("meshes/assembly_nodes.gltf"), o);
  ASSERT_EQ(r.parts.size(), 2u);
  EXPECT_EQ(r.parts[0].part, "left");
  EXPECT_EQ(r.parts[1].part, "right");
  Matrix3 rz90;
  rz90 << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  const std::vector<Box> boxes = {{{0.1, 0.2, 0.3}, {0.5, 0, 1}, 1000}, {{0.1, 0.1, 0.2}, {-0.5, 0.1, 1}, 1000, rz90}};
  ExpectBox(r.parts[0], boxes[0], 1e-6);
  ExpectBox(r.parts[1], boxes[1], 1e-6);
  ExpectWhole(r, boxes, 1e-6);
}

}  // namespace
}  // namespace massprops
