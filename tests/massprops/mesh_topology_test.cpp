// The combinatorial checks that decide whether a mesh bounds a solid (mesh_topology.h, in the
// core): Euler's formula V − E + F = 2 − 2g on closed surfaces of known genus, holes,
// non-manifold and flipped faces, repeated faces, and how shells nest (a cavity or an overlap).

#include "massprops/mesh_topology.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <random>
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

// Meshes of 2^17 faces and more are analysed in ranges on several threads. Two tori of 90 000
// triangles (V − E + F = 0 each) with ten triangles cut out of one (ten holes of three edges),
// ten flipped in the other (three edges each traversed twice the same way), a repeated face
// (three edges used three times, unbalanced), a face with a repeated corner (an edge used four
// times, balanced); faces shuffled and vertices renumbered at random, so that edges join vertex
// ranges everywhere. Every count is the closed form's, on any number of threads.
TEST(Topology, SeveralThreadsCountWhatTheClosedFormSays) {
  const PolygonMesh two = testing::WithMovedCopy(ToPolygonMesh(solids::Torus(2.0, 0.5, 150)), Vector3(10, 0, 0));
  ASSERT_EQ(two.num_faces(), 180000);
  std::vector<std::array<std::int32_t, 3>> faces;
  for (std::int64_t f = 0; f < two.num_faces(); ++f) {
    const std::int32_t* c = two.indices.data() + two.offsets[f];
    std::array<std::int32_t, 3> face = {c[0], c[1], c[2]};
    if (f >= 90000 && f % 1000 == 500 && f < 100000) std::swap(face[1], face[2]);  // flipped
    if (f % 1000 == 7 && f < 10000) continue;                                      // cut out
    faces.push_back(face);
  }
  faces.push_back(faces[45003]);                                         // repeated
  faces.push_back({faces[60005][0], faces[60005][0], faces[60005][1]});  // a repeated corner
  std::mt19937_64 random(7);
  for (std::size_t i = faces.size() - 1; i > 0; --i) std::swap(faces[i], faces[random() % (i + 1)]);
  std::vector<std::int32_t> renumber(static_cast<std::size_t>(two.V.rows()));
  std::iota(renumber.begin(), renumber.end(), 0);
  for (std::size_t i = renumber.size() - 1; i > 0; --i) std::swap(renumber[i], renumber[random() % (i + 1)]);
  PolygonMesh mesh;
  mesh.V = two.V;
  for (const auto& face : faces) {
    mesh.AddFace(std::array<std::int32_t, 3>{renumber[static_cast<std::size_t>(face[0])],
                                             renumber[static_cast<std::size_t>(face[1])],
                                             renumber[static_cast<std::size_t>(face[2])]});
  }
  for (int threads : {1, 2, 3, 8}) {
    const MeshTopology t = AnalyzeTopology(mesh, threads);
    EXPECT_EQ(t.faces, 179992) << threads;
    EXPECT_EQ(t.vertices, 90000) << threads;
    EXPECT_EQ(t.unreferenced_vertices, 0) << threads;
    EXPECT_EQ(t.edges, 270000) << threads;
    EXPECT_EQ(t.boundary_edges, 30) << threads;
    EXPECT_EQ(t.holes, 10) << threads;
    EXPECT_EQ(t.inconsistent_edges, 30) << threads;
    EXPECT_EQ(t.non_manifold_edges, 4) << threads;
    EXPECT_EQ(t.unbalanced_edges, 3) << threads;
    EXPECT_EQ(t.degenerate_faces, 1) << threads;
    EXPECT_EQ(t.duplicate_faces, 1) << threads;
    EXPECT_EQ(t.reversed_duplicate_faces, 0) << threads;
    EXPECT_EQ(t.components, 2) << threads;
  }
}

}  // namespace
}  // namespace massprops
