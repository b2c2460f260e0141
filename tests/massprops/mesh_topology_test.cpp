// The combinatorial checks that decide whether a mesh bounds a solid (mesh_topology.h, in the
// core): Euler's formula V − E + F = 2 − 2g on closed surfaces of known genus, holes,
// non-manifold and flipped faces, repeated faces, and how shells nest (a cavity or an overlap).

#include "massprops/mesh_topology.h"

#include <algorithm>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/io/mesh_io.h"
#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::DataPath;
using ::testing::HasSubstr;

// A sphere (genus 0) and a torus (genus 1) tessellated: closed, consistently oriented, one
// component, and V − E + F = 2 − 2g; a hollow sphere is two components of genus 0 (χ = 4).
TEST(Topology, EulerCharacteristicGivesTheGenus) {
  struct Case {
    const char* name;
    TriangleMesh mesh;
    std::int64_t components, chi;
  };
  const std::vector<Case> cases = {{"sphere", solids::Sphere(1.0, 12), 1, 2},
                                   {"torus", solids::Torus(2.0, 0.5, 16), 1, 0},
                                   {"hollow sphere", solids::HollowSphere(1.0, 0.5, 10), 2, 4}};
  for (const Case& c : cases) {
    const MeshTopology t = AnalyzeTopology(ToPolygonMesh(c.mesh));
    EXPECT_TRUE(t.BoundsVolume()) << c.name << ": " << t.Problems();
    EXPECT_EQ(t.components, c.components) << c.name;
    EXPECT_EQ(t.vertices - t.edges + t.faces, c.chi) << c.name;
    EXPECT_EQ(2 * t.edges, 3 * t.faces) << c.name;  // closed triangle meshes: every edge twice
    EXPECT_EQ(t.boundary_edges + t.non_manifold_edges + t.inconsistent_edges, 0) << c.name;
  }
}

// A face repeated (same direction) and a face repeated reversed (an internal wall) are counted.
TEST(Topology, CountsRepeatedFaces) {
  PolygonMesh box = solids::Box(Vector3(1, 1, 1));
  PolygonMesh twice = box;
  twice.AddFace(std::vector<int>(box.indices.begin(), box.indices.begin() + 4));
  EXPECT_EQ(AnalyzeTopology(twice).duplicate_faces, 1);
  PolygonMesh wall = box;
  std::vector<int> reversed(box.indices.begin(), box.indices.begin() + 4);
  std::reverse(reversed.begin(), reversed.end());
  wall.AddFace(reversed);
  EXPECT_EQ(AnalyzeTopology(wall).reversed_duplicate_faces, 1);
}

TEST(Shells, NestingDecidesCavityOrOverlap) {
  // Hollow sphere with the inner shell facing inward: a valid cavity.
  const PolygonMesh hollow = ToPolygonMesh(solids::HollowSphere(1.0, 0.5, 12));
  const ShellReport good = AnalyzeShells(hollow);
  ASSERT_EQ(good.shells.size(), 2u);
  EXPECT_EQ(good.shells[0].inside_of, -1);
  EXPECT_EQ(good.shells[1].inside_of, 0);
  EXPECT_LT(good.shells[1].signed_volume, 0.0);
  EXPECT_TRUE(good.problem.empty()) << good.problem;
  // CGAL's hollow_sphere.off: both shells face outward, so the volumes overlap.
  const ShellReport bad = AnalyzeShells(ReadMeshFile(DataPath("meshes/hollow_sphere.off")).mesh);
  ASSERT_EQ(bad.shells.size(), 2u);
  EXPECT_NEAR(bad.shells[0].signed_volume, 0.505952, 1e-6);  // SOURCES.md: +0.505952, +0.259048
  EXPECT_NEAR(bad.shells[1].signed_volume, 0.259048, 1e-6);
  EXPECT_THAT(bad.problem, HasSubstr("shell 2 of 2 lies inside shell 1 and both face outward"));
  // Two disjoint boxes: an assembly, no nesting.
  const PolygonMesh two = testing::WithMovedCopy(solids::Box(Vector3(1, 1, 1)), Vector3(3, 0, 0));
  const ShellReport assembly = AnalyzeShells(two);
  EXPECT_EQ(assembly.shells.size(), 2u);
  EXPECT_EQ(assembly.shells[1].inside_of, -1);
  EXPECT_TRUE(assembly.problem.empty());
  // An inverted shell that is not inside anything.
  PolygonMesh flipped = two;
  for (std::int64_t f = 6; f < 12; ++f) {  // reverse every face of the second box
    std::reverse(flipped.indices.begin() + flipped.offsets[f], flipped.indices.begin() + flipped.offsets[f + 1]);
  }
  const ShellReport inverted = AnalyzeShells(flipped);
  EXPECT_THAT(inverted.problem, HasSubstr("faces inward but is not inside another shell"));
}

TEST(Topology, FindsHolesNonManifoldAndFlippedFaces) {
  PolygonMesh box = solids::Box(Vector3(1, 1, 1));
  PolygonMesh open = box;
  open.indices.resize(20);
  open.offsets.resize(6);  // drop the last quad
  const MeshTopology t = AnalyzeTopology(open);
  EXPECT_EQ(t.boundary_edges, 4);
  EXPECT_THAT(t.Problems(), HasSubstr("open mesh: 4 boundary edges in 1 hole"));

  PolygonMesh flipped = box;
  std::reverse(flipped.indices.begin(), flipped.indices.begin() + 4);
  EXPECT_EQ(AnalyzeTopology(flipped).inconsistent_edges, 4);

  PolygonMesh fin = box;  // a fifth face on an existing edge
  fin.V.conservativeResize(9, 3);
  fin.V.row(8) << 2, 2, 2;
  fin.AddFace(std::vector<int>{1, 3, 8});
  EXPECT_EQ(AnalyzeTopology(fin).non_manifold_edges, 1);
  EXPECT_EQ(AnalyzeTopology(fin).unbalanced_edges, 1);
  EXPECT_FALSE(AnalyzeTopology(fin).BoundsVolume());
}

}  // namespace
}  // namespace massprops
