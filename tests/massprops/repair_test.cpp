// CGAL-backed repair and self-intersection checks on the broken meshes in data/ (their defects
// and reference volumes are documented in data/README.md and the shared SOURCES.md).

#include "massprops/repair.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/io.h"
#include "massprops/mesh_topology.h"
#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::DataPath;
using testing::NearRel;

TEST(Repair, NestedOutwardShellsBecomeAHollowPart) {
  const LoadedMesh in = ReadMeshFile(DataPath("meshes/hollow_sphere.off"));
  EXPECT_FALSE(AnalyzeShells(in.mesh).problem.empty());
  const RepairedMesh out = RepairMesh(in.mesh);
  EXPECT_TRUE(out.report.oriented_to_bound_volume);
  const ShellReport shells = AnalyzeShells(out.mesh);
  EXPECT_TRUE(shells.problem.empty()) << shells.problem;
  // +0.505952 outside, the inner 0.259048 now a cavity.
  EXPECT_NEAR(ComputeMassProperties(out.mesh, 1.0).volume, 0.505952 - 0.259048, 2e-6);
  EXPECT_NEAR(out.report.volume_after, 0.505952 - 0.259048, 2e-6);
  EXPECT_NEAR(out.report.volume_before, 0.505952 + 0.259048, 2e-6);
}

TEST(Repair, InvertedMeshIsFlipped) {
  const LoadedMesh in = ReadMeshFile(DataPath("meshes/ellipe0.003.off"));
  EXPECT_NEAR(ComputeMassProperties(in.mesh, 1.0).volume, -1.474022, 1e-6);
  const RepairedMesh out = RepairMesh(in.mesh);
  EXPECT_NEAR(ComputeMassProperties(out.mesh, 1.0).volume, 1.474022, 1e-6);
}

TEST(Repair, ShuffledOrientationsAreMadeConsistent) {
  const LoadedMesh in = ReadMeshFile(DataPath("meshes/blobby-shuffled.off"));
  EXPECT_EQ(AnalyzeTopology(in.mesh).inconsistent_edges, 3069);
  const RepairedMesh out = RepairMesh(in.mesh);
  EXPECT_TRUE(out.report.reoriented);
  const MeshTopology t = AnalyzeTopology(out.mesh);
  EXPECT_TRUE(t.BoundsVolume()) << t.Problems();
  EXPECT_EQ(t.faces, 4050);
  // Now a closed, outward surface: a positive volume that does not depend on the reference point.
  const TriangleMesh tri = Triangulate(out.mesh);
  IntegrationOptions far;
  far.reference = Vector3(10, -20, 30);
  const double v = ComputeMassProperties(tri, 1.0).volume;
  EXPECT_GT(v, 0.0);
  EXPECT_TRUE(NearRel(ComputeMassProperties(tri, 1.0, far).volume, v, 1e-9));
}

TEST(Repair, ToleranceWeldClosesCadCracks) {
  const LoadedMesh in = ReadMeshFile(DataPath("meshes/featuretype.STL"));
  const MeshTopology before = AnalyzeTopology(in.mesh);
  EXPECT_EQ(before.boundary_edges, 576);  // exact weld: false cracks (SOURCES.md)
  EXPECT_EQ(before.vertices, 2010);
  const RepairedMesh out = RepairMesh(in.mesh);
  const MeshTopology after = AnalyzeTopology(out.mesh);
  EXPECT_TRUE(after.BoundsVolume()) << after.Problems();
  EXPECT_EQ(after.vertices, 1722);  // SOURCES.md: the tolerance weld gives 1722 positions
  EXPECT_EQ(after.components, 1);
  EXPECT_EQ(out.report.welded_vertices, 288);
}

TEST(Repair, DropsDegenerateAndDuplicateFaces) {
  PolygonMesh box = ToPolygonMesh(Triangulate(solids::Box(Vector3(1, 2, 3))));
  box.AddFace(std::vector<int>{0, 1, 1});                                         // degenerate
  box.AddFace(std::vector<int>{box.indices[0], box.indices[1], box.indices[2]});  // duplicate
  const RepairedMesh out = RepairMesh(box);
  EXPECT_EQ(out.report.removed_faces, 2);
  EXPECT_TRUE(AnalyzeTopology(out.mesh).BoundsVolume());
  EXPECT_TRUE(NearRel(ComputeMassProperties(out.mesh, 1.0).volume, 6.0, 1e-14));
}

TEST(SelfIntersections, CountsOverlapsOnly) {
  EXPECT_EQ(CountSelfIntersections(ToPolygonMesh(solids::Sphere(1.0, 12))), 0);
  // Two boxes passing through each other, as one mesh.
  const PolygonMesh both = testing::WithMovedCopy(solids::Box(Vector3(1, 1, 1)), Vector3(0.5, 0.3, 0.2));
  EXPECT_GT(CountSelfIntersections(both), 0);
}

// A prism over a five-pointed star whose corner list starts at an inner (reflex) corner: the cap's
// split into triangles overlaps itself where the star does not, which is no intersection.
PolygonMesh StarPrism(double dz) {
  PolygonMesh m;
  const int n = 10;
  m.V.resize(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    const double r = k % 2 == 0 ? 0.4 : 1.0, phi = 2.0 * 3.141592653589793 * k / n;
    m.V.row(k) << r * std::cos(phi), r * std::sin(phi), dz;
    m.V.row(n + k) << r * std::cos(phi), r * std::sin(phi), dz + 1.0;
  }
  std::vector<int> bottom, top;
  for (int k = 0; k < n; ++k) {
    bottom.push_back((n - k) % n);
    top.push_back(n + k);
    m.AddFace(std::array<int, 4>{k, (k + 1) % n, n + (k + 1) % n, n + k});
  }
  m.AddFace(bottom);
  m.AddFace(top);
  return m;
}

TEST(SelfIntersections, ANonConvexFaceIsNoIntersection) {
  const PolygonMesh star = StarPrism(0.0);
  ASSERT_TRUE(AnalyzeTopology(star).BoundsVolume());
  EXPECT_EQ(CountSelfIntersections(star), 0);
  // The same star through a shifted copy of itself.
  const PolygonMesh both = testing::WithMovedCopy(star, Vector3(0.1, 0.05, 0.5));
  EXPECT_GT(CountSelfIntersections(both), 0);
}

// Faces that share an edge or a corner meet there only, unless they fold onto each other.
TEST(SelfIntersections, SharedEdgesAndCornersFoldedOrNot) {
  PolygonMesh m;
  m.V.resize(6, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
      0.5, 0.2, 0,                   // on the plane, the side of corner 2: folds over (0, 1, 2)
      0.5, -1, 0,                    // the other side: a flat continuation
      0.3, 0.3, 1;                   // off the plane
  PolygonMesh folded = m;
  folded.AddFace(std::array<int, 3>{0, 1, 2});
  folded.AddFace(std::array<int, 3>{1, 0, 3});
  EXPECT_EQ(CountSelfIntersections(folded), 1);
  PolygonMesh flat = m;
  flat.AddFace(std::array<int, 3>{0, 1, 2});
  flat.AddFace(std::array<int, 3>{1, 0, 4});
  EXPECT_EQ(CountSelfIntersections(flat), 0);
  PolygonMesh inside = m;  // share corner 0; the second runs inside the first from 0 to 3
  inside.AddFace(std::array<int, 3>{0, 1, 2});
  inside.AddFace(std::array<int, 3>{0, 3, 5});
  EXPECT_EQ(CountSelfIntersections(inside), 1);
  PolygonMesh outside = m;  // share corner 0 only
  outside.AddFace(std::array<int, 3>{0, 1, 2});
  outside.AddFace(std::array<int, 3>{0, 4, 5});
  EXPECT_EQ(CountSelfIntersections(outside), 0);
}

// The meshes side by side as one (their vertices renumbered).
PolygonMesh Together(const PolygonMesh& a, const PolygonMesh& b) {
  PolygonMesh out = a;
  const auto n = static_cast<std::int32_t>(a.V.rows());
  out.V.conservativeResize(n + b.V.rows(), 3);
  out.V.bottomRows(b.V.rows()) = b.V;
  for (std::int64_t f = 0; f < b.num_faces(); ++f) {
    std::vector<std::int32_t> face;
    for (int k = 0; k < b.face_size(f); ++k) face.push_back(b.indices[b.offsets[f] + k] + n);
    out.AddFace(face);
  }
  return out;
}

// The mesh with every face split into triangles (SplitPolygon), as the check splits faces of up
// to 32 corners: the second algorithm for the whole-polygon test of larger flat faces.
PolygonMesh AsTriangles(const PolygonMesh& m) { return ToPolygonMesh(Triangulate(m)); }

// A prism over a 64-gon has caps of more than 32 corners in planes of constant z, tested as whole
// polygons; every verdict matches the test of the same faces as triangles.
TEST(SelfIntersections, LargeFlatFacesAsAWholeAgreeWithTheirTriangles) {
  const PolygonMesh prism = solids::RegularPrism(64, 1.0, 0.5);  // z in [-0.25, 0.25]
  EXPECT_EQ(CountSelfIntersections(prism), 0);
  EXPECT_EQ(CountSelfIntersections(AsTriangles(prism)), 0);
  auto box_at = [](const Vector3& center, const Vector3& size) {
    PolygonMesh b = solids::Box(size);
    b.V.rowwise() += center.transpose();
    return b;
  };
  // A box through the top cap, inside the polygon: intersections.
  const PolygonMesh pierced = Together(prism, box_at(Vector3(0.2, 0.1, 0.25), Vector3(0.2, 0.2, 0.2)));
  const std::int64_t whole = CountSelfIntersections(pierced), split = CountSelfIntersections(AsTriangles(pierced));
  EXPECT_GT(whole, 0);
  EXPECT_EQ(whole, split);
  // A box across the cap's plane beside the prism: none.
  const PolygonMesh beside = Together(prism, box_at(Vector3(2.0, 0.0, 0.25), Vector3(0.2, 0.2, 0.2)));
  EXPECT_EQ(CountSelfIntersections(beside), 0);
  EXPECT_EQ(CountSelfIntersections(AsTriangles(beside)), 0);
  // A box resting on the cap (its bottom face in the cap's plane): they touch, which counts.
  const PolygonMesh resting = Together(prism, box_at(Vector3(0.0, 0.0, 0.35), Vector3(0.2, 0.2, 0.2)));
  EXPECT_GT(CountSelfIntersections(resting), 0);
  EXPECT_EQ(CountSelfIntersections(resting), CountSelfIntersections(AsTriangles(resting)));
  // A tetrahedron whose tip touches the cap inside the polygon, and one whose tip is a corner of
  // the cap (the same vertex): the first touches, the second meets it only at the shared corner.
  PolygonMesh tip = prism;
  const auto n = static_cast<std::int32_t>(tip.V.rows());
  tip.V.conservativeResize(n + 4, 3);
  tip.V.row(n) << 0.1, 0.2, 0.25;  // on the cap, inside
  tip.V.row(n + 1) << 0.0, 0.0, 0.6;
  tip.V.row(n + 2) << 0.4, 0.0, 0.6;
  tip.V.row(n + 3) << 0.0, 0.4, 0.6;
  tip.AddFace(std::array<int, 3>{n, n + 2, n + 1});
  tip.AddFace(std::array<int, 3>{n, n + 3, n + 2});
  tip.AddFace(std::array<int, 3>{n, n + 1, n + 3});
  tip.AddFace(std::array<int, 3>{n + 1, n + 2, n + 3});
  EXPECT_GT(CountSelfIntersections(tip), 0);
  EXPECT_EQ(CountSelfIntersections(tip), CountSelfIntersections(AsTriangles(tip)));
  PolygonMesh corner = tip;
  std::int32_t top_corner = -1;  // a corner of the top cap
  for (std::int32_t v = 0; v < n && top_corner < 0; ++v) {
    if (prism.V(v, 2) == 0.25) top_corner = v;
  }
  ASSERT_GE(top_corner, 0);
  for (auto& c : corner.indices) {
    if (c == n) c = top_corner;
  }
  corner.V.row(n + 1) = prism.V.row(top_corner) + Eigen::RowVector3d(-0.1, 0.0, 0.3);
  corner.V.row(n + 2) = prism.V.row(top_corner) + Eigen::RowVector3d(0.3, 0.0, 0.3);
  corner.V.row(n + 3) = prism.V.row(top_corner) + Eigen::RowVector3d(0.0, 0.3, 0.3);
  EXPECT_EQ(CountSelfIntersections(corner), 0);
  EXPECT_EQ(CountSelfIntersections(AsTriangles(corner)), 0);
}

// A prism over a 4096-gon turned into a tilted plane (its caps' corners within rounding of their
// planes, not exactly in them) is still tested cap by cap, and agrees with its triangles; the
// same pierced by a box too. A cone over a 10^5-gon (the apex a corner of 10^5 triangles, whose
// boxes all overlap) stops undecided within its budget instead of testing 5·10^9 pairs.
TEST(SelfIntersections, TiltedCapsAsAWholeAndFansWithinABudget) {
  PolygonMesh prism = solids::RegularPrism(4096, 1.0, 0.5);
  const Matrix3 tilt = Eigen::AngleAxisd(0.5236, Vector3(1, 0.3, 0).normalized()).toRotationMatrix();
  prism.V = (prism.V * tilt.transpose()).eval();
  EXPECT_EQ(CountSelfIntersections(prism), 0);
  PolygonMesh box = solids::Box(Vector3(0.2, 0.2, 0.2));
  box.V = ((box.V.rowwise() + Eigen::RowVector3d(0.2, 0.1, 0.25)) * tilt.transpose()).eval();
  const PolygonMesh pierced = Together(prism, box);
  const std::int64_t whole = CountSelfIntersections(pierced);
  EXPECT_GT(whole, 0);
  EXPECT_EQ(whole, CountSelfIntersections(AsTriangles(pierced)));

  const int n = 100000;
  PolygonMesh cone;
  cone.V.resize(n + 1, 3);
  for (int i = 0; i < n; ++i) cone.V.row(i) << std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0.0;
  cone.V.row(n) << 0, 0, 1;
  std::vector<int> base(n);
  for (int i = 0; i < n; ++i) base[static_cast<std::size_t>(i)] = n - 1 - i;
  cone.AddFace(base);
  for (int i = 0; i < n; ++i) cone.AddFace(std::array<int, 3>{i, (i + 1) % n, n});
  EXPECT_EQ(CountSelfIntersections(cone), -1);
}

// A mesh that bounds a volume once welded keeps its polygons (CGAL would split them), and its
// numbers are those of the closed form.
TEST(Repair, AClosedMeshKeepsItsPolygons) {
  PolygonMesh prism = solids::RegularPrism(1000, 1.0, 0.1);
  prism.V(5, 0) += 1e-13;  // a crack at one corner, which the weld closes
  const PolygonMesh before = prism;
  // The cracked corner, given again as a separate vertex used by one side face.
  const auto n = static_cast<std::int32_t>(prism.V.rows());
  prism.V.conservativeResize(n + 1, 3);
  prism.V.row(n) = prism.V.row(5);
  prism.V(n, 0) -= 1e-13;
  bool replaced = false;
  for (std::int64_t f = 0; f < prism.num_faces() && !replaced; ++f) {
    if (prism.face_size(f) != 4) continue;
    for (std::int64_t c = prism.offsets[f]; c < prism.offsets[f + 1]; ++c) {
      if (prism.indices[static_cast<std::size_t>(c)] == 5) {
        prism.indices[static_cast<std::size_t>(c)] = n;
        replaced = true;
      }
    }
  }
  ASSERT_TRUE(replaced);
  ASSERT_FALSE(AnalyzeTopology(prism).BoundsVolume());
  const RepairedMesh out = RepairMesh(prism);
  EXPECT_EQ(out.report.welded_vertices, 1);
  EXPECT_EQ(out.mesh.num_faces(), before.num_faces());  // 1000 quads and two 1000-gons
  EXPECT_TRUE(AnalyzeTopology(out.mesh).BoundsVolume());
  const MassProperties mp = ComputeMassProperties(out.mesh, 1.0);
  const MassProperties exact = solids::RegularPrismProperties(1000, 1.0, 0.1, 1.0);
  EXPECT_NEAR(mp.mass, exact.mass, 1e-12 * exact.mass);
  EXPECT_NEAR(mp.inertia_com(2, 2), exact.inertia_com(2, 2), 1e-12 * exact.inertia_com(2, 2));
}

}  // namespace
}  // namespace massprops
