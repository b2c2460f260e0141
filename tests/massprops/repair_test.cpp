// CGAL-backed repair and self-intersection checks on the broken meshes in data/ (their defects
// and reference volumes are documented in data/README.md and the shared SOURCES.md).

#include "massprops/repair/repair.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/io/geometry_steps.h"
#include "massprops/io/load.h"
#include "massprops/io/mesh_io.h"
#include "massprops/mesh_topology.h"
#include "massprops/solids.h"
#include "test_utils.h"

// The union of shells made to fail on demand, for the fallback's test, with no fault injection in
// the shipped pipeline: this program's own table of the CGAL steps, which the pipeline finds
// first (it looks in the program before any library: ENABLE_EXPORTS), is massprops::repair's with
// the union wrapped.
namespace {
bool g_fail_union = false;
const massprops::GeometrySteps* RealSteps() {
  using TableFn = const massprops::GeometrySteps* (*)();
  static const massprops::GeometrySteps* real =
      reinterpret_cast<TableFn>(::dlsym(RTLD_NEXT, "massprops_geometry_steps"))();
  return real;
}
massprops::PolygonMesh UnionOrFault(const massprops::PolygonMesh& mesh, std::int64_t& united) {
  if (g_fail_union) throw std::runtime_error("the union was made to fail (a test)");
  return RealSteps()->union_of_shells(mesh, united);
}
}  // namespace

extern "C" __attribute__((visibility("default"))) const massprops::GeometrySteps* massprops_geometry_steps() {
  static const massprops::GeometrySteps table = [] {
    massprops::GeometrySteps t = *RealSteps();
    t.union_of_shells = UnionOrFault;
    return t;
  }();
  return &table;
}

namespace massprops {
namespace {

using testing::DataPath;
using testing::NearRel;
using testing::SameBits;
using testing::Transform;

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
// same pierced by a box too.
TEST(SelfIntersections, TiltedCapsAsAWhole) {
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
}

// A cone over an n-gon of unit radius in the plane z = 0, apex at height 1, turned by `tilt`. The
// base: one n-gon, a fan around its center, or a second apex below (a double cone).
enum class ConeBase { kPolygon, kFan, kApex };
PolygonMesh Cone(int n, ConeBase base, const Matrix3& tilt) {
  PolygonMesh cone;
  cone.V.resize(n + 2, 3);
  for (int i = 0; i < n; ++i)
    cone.V.row(i) << std::cos(2 * massprops::kPi * i / n), std::sin(2 * massprops::kPi * i / n), 0.0;
  cone.V.row(n) << 0, 0, 1;
  cone.V.row(n + 1) << 0, 0, base == ConeBase::kApex ? -1.0 : 0.0;
  for (int i = 0; i < n; ++i) cone.AddFace(std::array<int, 3>{i, (i + 1) % n, n});
  if (base == ConeBase::kPolygon) {
    std::vector<int> ring(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) ring[static_cast<std::size_t>(i)] = n - 1 - i;
    cone.AddFace(ring);
    cone.V.conservativeResize(n + 1, 3);
  } else {
    for (int i = 0; i < n; ++i) cone.AddFace(std::array<int, 3>{(i + 1) % n, i, n + 1});
  }
  cone.V = (cone.V * tilt.transpose()).eval();
  return cone;
}

std::int64_t Pairwise(const PolygonMesh& m) {
  SelfIntersectionOptions options;
  options.whole_groups = false;
  return CountSelfIntersections(m, options);
}

// The fan around a corner of 10^5 triangles (a cone's apex) used to make every two of their boxes
// overlap: 5·10^9 candidate pairs, and the check stopped undecided. A fan certified free of
// intersections within itself is tested as a whole: a cone in a tilted plane, over a polygon, a
// fan or a second apex, has none (it is convex), decided in well under a second.
TEST(SelfIntersections, LargeFansAsAWhole) {
  const Matrix3 tilt = Eigen::AngleAxisd(0.5236, Vector3(1, 0.3, 0).normalized()).toRotationMatrix();
  for (const ConeBase base : {ConeBase::kPolygon, ConeBase::kFan, ConeBase::kApex}) {
    const PolygonMesh cone = Cone(100000, base, tilt);
    ASSERT_TRUE(AnalyzeTopology(cone).BoundsVolume());
    EXPECT_EQ(CountSelfIntersections(cone), 0) << static_cast<int>(base);
  }
}

// Against the second algorithm (every pair of triangles) on fans of 400: what the whole-fan test
// certifies, what it refuses (a fan that winds twice, a fan folded over), and triangles that touch
// or pierce a fan.
TEST(SelfIntersections, LargeFansAgreeWithEveryPair) {
  const Matrix3 tilt = Eigen::AngleAxisd(0.5236, Vector3(1, 0.3, 0).normalized()).toRotationMatrix();
  const int n = 400;
  for (const ConeBase base : {ConeBase::kPolygon, ConeBase::kFan, ConeBase::kApex}) {
    const PolygonMesh cone = Cone(n, base, tilt);
    EXPECT_EQ(CountSelfIntersections(cone), 0);
    EXPECT_EQ(Pairwise(cone), 0);
    // A box through the side near the apex, one through the base, and one resting on the base.
    for (const Vector3& at : {Vector3(0.0, 0.1, 0.9), Vector3(0.3, 0.2, 0.0), Vector3(0.2, 0.1, -0.1)}) {
      PolygonMesh box = solids::Box(Vector3(0.2, 0.2, 0.2));
      box.V = ((box.V.rowwise() + at.transpose()) * tilt.transpose()).eval();
      const PolygonMesh both = Together(cone, box);
      const std::int64_t whole = CountSelfIntersections(both);
      EXPECT_EQ(whole, Pairwise(both)) << static_cast<int>(base) << " " << at.transpose();
      if (base != ConeBase::kApex || at.z() > 0.5) {  // the double cone holds the other two
        EXPECT_GT(whole, 0);
      }
    }
  }
  // A fan whose link winds twice around its apex (an odd n-gon visited every second corner): the
  // surface passes through itself, and the whole-fan test must not certify it.
  PolygonMesh twice;
  const int odd = 401;
  twice.V.resize(odd + 2, 3);
  for (int i = 0; i < odd; ++i) {
    const double phi = 4 * massprops::kPi * i / odd;
    twice.V.row(i) << std::cos(phi), std::sin(phi), 0.0;
  }
  twice.V.row(odd) << 0, 0, 1;
  twice.V.row(odd + 1) << 0, 0, -1;
  for (int i = 0; i < odd; ++i) {
    twice.AddFace(std::array<int, 3>{i, (i + 1) % odd, odd});
    twice.AddFace(std::array<int, 3>{(i + 1) % odd, i, odd + 1});
  }
  twice.V = (twice.V * tilt.transpose()).eval();
  const std::int64_t wound = CountSelfIntersections(twice);
  EXPECT_GT(wound, 0);
  EXPECT_EQ(wound, Pairwise(twice));
  // A double cone with two rim corners swapped: each fan folds back over itself, and the rim's
  // chords 6–8 and 7–9 cross, so the faces over them do.
  PolygonMesh folded = Cone(n, ConeBase::kApex, tilt);
  folded.V.row(7).swap(folded.V.row(8));
  const std::int64_t fold = CountSelfIntersections(folded);
  EXPECT_GT(fold, 0);
  EXPECT_EQ(fold, Pairwise(folded));
  // A sphere's poles (fans of 128 around a corner whose link is a circle of latitude) and a
  // cylinder's caps (flat fans of 128), tilted, and a box through a cap's center.
  for (const double top : {1.0, 0.5}) {
    PolygonMesh turned = ToPolygonMesh(top == 1.0 ? solids::Sphere(1.0, 64) : solids::Cylinder(1.0, 1.0, 64));
    turned.V = (turned.V * tilt.transpose()).eval();
    EXPECT_EQ(CountSelfIntersections(turned), 0);
    EXPECT_EQ(Pairwise(turned), 0);
    PolygonMesh box = solids::Box(Vector3(0.2, 0.2, 0.2));
    box.V = ((box.V.rowwise() + Eigen::RowVector3d(0.0, 0.0, top)) * tilt.transpose()).eval();
    const PolygonMesh pierced = Together(turned, box);
    const std::int64_t whole = CountSelfIntersections(pierced);
    EXPECT_GT(whole, 0);
    EXPECT_EQ(whole, Pairwise(pierced));
  }
}

// The meshes in data/ (scans, CAD exports, a quad mesh, meshes that intersect themselves): the
// whole-group check counts what every pair of triangles counts.
TEST(SelfIntersections, DataMeshesAgreeWithEveryPair) {
  std::int64_t intersecting = 0;
  for (const char* name :
       {"HalfDonut_binary.stl", "Moon.stl", "featuretype.STL", "assembly_bracket.obj", "bin.obj", "cube_cup_quad.obj",
        "spot.obj", "t_handle.obj", "blobby-shuffled.off", "ellipe0.003.off", "hollow_sphere.off"}) {
    const LoadedMesh m = ReadMeshFile(DataPath(std::string("meshes/") + name));
    const std::int64_t whole = CountSelfIntersections(m.mesh);
    EXPECT_GE(whole, 0) << name;
    EXPECT_EQ(whole, Pairwise(m.mesh)) << name;
    intersecting += whole > 0;
  }
  EXPECT_EQ(intersecting, 2);  // featuretype.STL (1216 pairs) and the bracket's touching boxes (10)
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

// Broken meshes as CAD systems export them (tests/massprops/field/make_broken.py writes them:
// ASCII STL, CR LF, %e normals), held to closed forms or to their intact twin.
std::string Field(const std::string& name) {
  return std::string(MASSPROPS_DATA_DIR) + "/../tests/massprops/field/" + name;
}

SolidResult Repaired(const std::string& name) {
  LoadOptions o;
  o.repair = true;
  o.unit = LengthUnit::kMillimetre;
  o.unit_stated = true;
  return LoadSolid(Field(name), o);
}

bool Says(const SolidResult& r, FindingKind kind, const std::string& words) {
  for (const Finding& f : r.findings) {
    if (f.kind == kind && f.message.marked().find(words) != std::string::npos) return true;
  }
  return false;
}

// A box [x0, x0 + a] × [0, b] × [0, c] mm at 1000 kg/m³: mass, center and inertia in SI.
MassProperties BoxMm(double x0, double a, double b, double c) {
  MassProperties mp = ComputeMassProperties(solids::Box(Vector3(a, b, c) * 1e-3), 1000.0);
  mp.center_of_mass += Vector3(x0 + a / 2, b / 2, c / 2) * 1e-3;
  return mp;
}

void ExpectBox(const SolidResult& r, const MassProperties& box) {
  EXPECT_NEAR(r.mp.volume, box.volume, 1e-12 * box.volume);
  EXPECT_LE((r.mp.center_of_mass - box.center_of_mass).norm(), 1e-12 * 0.03);
  EXPECT_LE((r.mp.inertia_com - box.inertia_com).norm(), 1e-12 * box.inertia_com.norm());
  EXPECT_EQ(r.relative_error_bound, 0);  // exact: nothing ambiguous was filled
}

TEST(RepairField, APlanarHoleIsFilledExactly) {
  // A cube missing one triangle of its top, and missing the whole top (a quad's two triangles).
  for (const char* name : {"cube_missing_triangle.stl", "cube_missing_quad.stl"}) {
    LoadOptions plain;
    plain.unit = LengthUnit::kMillimetre;
    plain.unit_stated = true;
    try {
      LoadSolid(Field(name), plain);
      ADD_FAILURE() << name << ": an open mesh was computed";
    } catch (const LoadError& e) {
      EXPECT_THAT(e.text(), ::testing::HasSubstr("try {repair} (it fills holes")) << name;
      EXPECT_THAT(e.text(), ::testing::HasSubstr("{winding_number} for an estimate with error bars")) << name;
    }
    const SolidResult r = Repaired(name);
    ASSERT_TRUE(r.repair) << name;
    EXPECT_EQ(r.repair->filled_holes, 1) << name;
    EXPECT_EQ(r.repair->planar_holes, 1) << name;
    EXPECT_EQ(r.repair->fill_volume_bound, 0) << name;
    EXPECT_TRUE(Says(r, FindingKind::kRepaired, "filled 1 hole (all planar, filled exactly")) << name;
    ExpectBox(r, BoxMm(0, 10, 10, 10));
  }
  EXPECT_EQ(Repaired("cube_missing_triangle.stl").repair->largest_hole, 3);
  EXPECT_EQ(Repaired("cube_missing_quad.stl").repair->largest_hole, 4);
}

TEST(RepairField, ANonPlanarHoleIsFilledWithinItsReportedBound) {
  LoadOptions plain;
  plain.unit = LengthUnit::kMillimetre;
  plain.unit_stated = true;
  const SolidResult intact = LoadSolid(Field("sphere_intact.stl"), plain);
  const SolidResult r = Repaired("sphere_with_hole.stl");
  ASSERT_TRUE(r.repair);
  EXPECT_EQ(r.repair->filled_holes, 1);
  EXPECT_EQ(r.repair->planar_holes, 0);
  EXPECT_EQ(r.repair->largest_hole, 6);
  const double bound = r.relative_error_bound;
  EXPECT_GT(bound, 1e-6);
  EXPECT_LT(bound, 1e-2);
  EXPECT_TRUE(Says(r, FindingKind::kRepaired, "none planar"));
  // The intact sphere's own triangles are one fill within the slab: ours is within the bound of it.
  EXPECT_LE(std::abs(r.mp.volume - intact.mp.volume), bound * intact.mp.volume);
  EXPECT_LE((r.mp.center_of_mass - intact.mp.center_of_mass).norm(), bound * intact.size_m);
  EXPECT_LE((r.mp.inertia_com - intact.mp.inertia_com).norm(), bound * intact.principal.moments.maxCoeff());
  EXPECT_GT(std::abs(r.mp.volume - intact.mp.volume), 0);  // not the same surface: the bound is used
}

TEST(RepairField, AFillMoreAmbiguousThanOnePercentIsRefused) {
  // The sphere less every triangle with a corner beyond x = 6 mm: a hole whose rim zigzags over
  // the mesh's rows, a slab millimetres thick under a patch of 10² mm²: no glitch to fill.
  const LoadedMesh in = ReadMeshFile(Field("sphere_intact.stl"));
  const std::string path = ::testing::TempDir() + "/sphere_cut.obj";
  {
    std::ofstream obj(path);
    obj.precision(17);
    for (Eigen::Index v = 0; v < in.mesh.V.rows(); ++v) {
      obj << "v " << in.mesh.V(v, 0) << " " << in.mesh.V(v, 1) << " " << in.mesh.V(v, 2) << "\n";
    }
    for (std::int64_t f = 0; f < in.mesh.num_faces(); ++f) {
      bool cut = false;
      std::string line = "f";
      for (std::int64_t c = in.mesh.offsets[f]; c < in.mesh.offsets[f + 1]; ++c) {
        const std::int32_t v = in.mesh.indices[static_cast<std::size_t>(c)];
        cut = cut || (in.mesh.V(v, 0) > 6 && in.mesh.V(v, 1) > 0);
        line += " " + std::to_string(v + 1);
      }
      if (!cut) obj << line << "\n";
    }
  }
  LoadOptions o;
  o.repair = true;
  o.unit = LengthUnit::kMillimetre;
  o.unit_stated = true;
  try {
    LoadSolid(path, o);
    ADD_FAILURE() << "an ambiguous fill was given as the answer";
  } catch (const LoadError& e) {
    EXPECT_THAT(e.text(), ::testing::HasSubstr("over the 1 % the repair accepts"));
    EXPECT_THAT(e.text(), ::testing::HasSubstr("{winding_number} estimates the solid with error bars"));
  }
}

// Two 64-gon prisms (radius 5 mm, 30 mm long) crossing at right angles through their centers, as
// two closed bodies: their union by CGAL's corefinement, and — when that fails — by the winding
// number with error bars, the route said. The circle's Steinmetz union, 2πr²h − 16r³/3, is
// within the polygon's own error (0.2 %) of the polyhedral one.
TEST(RepairField, InterpenetratingShellsAreUnitedAndTheFallbackEstimatesTheUnion) {
  const double r = 5, h = 30;
  const PolygonMesh z = solids::RegularPrism(64, r, h);
  Matrix3 about_x;
  about_x << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  PolygonMesh both = z;
  const auto offset = static_cast<std::int32_t>(z.V.rows());
  both.V.conservativeResize(2 * z.V.rows(), 3);
  both.V.bottomRows(z.V.rows()) = Transform(z.V, about_x, Vector3::Zero());
  for (std::int64_t f = 0; f < z.num_faces(); ++f) {
    std::vector<int> corners;
    for (std::int64_t c = z.offsets[f]; c < z.offsets[f + 1]; ++c) {
      corners.push_back(z.indices[static_cast<std::size_t>(c)] + offset);
    }
    both.AddFace(corners);
  }
  const std::string path = ::testing::TempDir() + "/crossed_cylinders.obj";
  {
    std::ofstream obj(path);
    obj.precision(17);
    for (Eigen::Index v = 0; v < both.V.rows(); ++v) {
      obj << "v " << both.V(v, 0) << " " << both.V(v, 1) << " " << both.V(v, 2) << "\n";
    }
    for (std::int64_t f = 0; f < both.num_faces(); ++f) {
      obj << "f";
      for (std::int64_t c = both.offsets[f]; c < both.offsets[f + 1]; ++c) {
        obj << " " << both.indices[static_cast<std::size_t>(c)] + 1;
      }
      obj << "\n";
    }
  }
  LoadOptions o;
  o.repair = true;
  o.unit = LengthUnit::kMillimetre;
  o.unit_stated = true;
  const SolidResult united = LoadSolid(path, o);
  ASSERT_TRUE(united.repair);
  EXPECT_EQ(united.repair->united_shells, 1);
  const double steinmetz = (2 * massprops::kPi * r * r * h - 16 * r * r * r / 3) * 1e-9;
  EXPECT_NEAR(united.mp.volume, steinmetz, 2e-3 * steinmetz);
  g_fail_union = true;
  const SolidResult estimated = LoadSolid(path, o);
  g_fail_union = false;
  ASSERT_TRUE(estimated.estimate);
  EXPECT_EQ(estimated.model, ModelKind::kWindingNumber);
  EXPECT_TRUE(Says(estimated, FindingKind::kOverlappingShells, "winding number is at least 1/2"));
  const double se = estimated.estimate->standard_error.volume;
  EXPECT_GT(se, 0);
  EXPECT_LT(se, 1e-3 * united.mp.volume);
  EXPECT_LE(std::abs(estimated.mp.volume - united.mp.volume), 5 * se);
  EXPECT_LE((estimated.mp.center_of_mass - united.mp.center_of_mass).norm(),
            5 * estimated.estimate->standard_error.center_of_mass.norm() + 1e-12);
}

// The winding-number route at its default (QMC doubled until the mass and each principal moment
// have a relative standard error under 1e-3): on a closed sphere its answer is the polyhedron's
// exact one within the error bars, and on the same sphere with a hole it bridges the hole.
TEST(RepairField, TheWindingNumberRouteMeetsItsDefaultToleranceAgainstTheExactAnswer) {
  LoadOptions plain;
  plain.unit = LengthUnit::kMillimetre;
  plain.unit_stated = true;
  const SolidResult exact = LoadSolid(Field("sphere_intact.stl"), plain);
  LoadOptions wn = plain;
  wn.model = WindingNumberModel{};
  EXPECT_EQ(std::get<WindingNumberModel>(wn.model).sampling.tolerance, 1e-3);
  for (const char* name : {"sphere_intact.stl", "sphere_with_hole.stl"}) {
    const SolidResult r = LoadSolid(Field(name), wn);
    ASSERT_TRUE(r.estimate) << name;
    EXPECT_TRUE(r.estimate->tolerance_met) << name;
    const double se = r.estimate->standard_error.volume;
    EXPECT_LE(se, 1e-3 * r.mp.volume) << name;
    EXPECT_GT(se, 0) << name;
    // The hole's fill differs from the intact surface by 5e-5 of the volume: inside the bars.
    EXPECT_LE(std::abs(r.mp.volume - exact.mp.volume), 4 * se + 1e-4 * exact.mp.volume) << name;
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(std::abs(r.estimate->principal_moments[i] - exact.principal.moments[i]),
                4 * r.estimate->principal_moments_se[i] + 2e-4 * exact.principal.moments[i])
          << name;
    }
  }
}

TEST(RepairField, ReversedRepeatsAreAnInternalWallAndSameDirectionRepeatsOneFace) {
  // Two boxes exported closed each, touching at x = 10 mm: their union, 30 × 10 × 10 mm.
  const SolidResult walls = Repaired("two_boxes_shared_face.stl");
  ASSERT_TRUE(walls.repair);
  EXPECT_EQ(walls.repair->internal_walls, 4);  // the shared face's two triangles, in each box
  EXPECT_EQ(walls.repair->repeated_faces, 0);
  EXPECT_TRUE(Says(walls, FindingKind::kRepaired, "removed 4 faces that each repeat another reversed"));
  ExpectBox(walls, BoxMm(0, 30, 10, 10));
  // Every face written twice in the same direction: one of each kept.
  const SolidResult twice = Repaired("cube_every_face_twice.stl");
  ASSERT_TRUE(twice.repair);
  EXPECT_EQ(twice.repair->repeated_faces, 12);
  EXPECT_EQ(twice.repair->internal_walls, 0);
  EXPECT_TRUE(Says(twice, FindingKind::kRepaired, "removed 12 repeated faces"));
  ExpectBox(twice, BoxMm(0, 10, 10, 10));
}

TEST(RepairField, ADoubleSidedSurfaceKeepsOneSide) {
  // Every face in a reversed pair is a surface written with both sides, not walls between
  // bodies: one side is kept and oriented outward (removing both would leave nothing).
  PolygonMesh box = ToPolygonMesh(Triangulate(solids::Box(Vector3(1, 2, 3))));
  const std::int64_t n = box.num_faces();
  for (std::int64_t f = 0; f < n; ++f) {
    const std::int32_t* c = box.indices.data() + box.offsets[f];
    box.AddFace(std::vector<int>{c[0], c[2], c[1]});
  }
  const RepairedMesh out = RepairMesh(box);
  EXPECT_EQ(out.report.internal_walls, 0);
  EXPECT_EQ(out.report.repeated_faces, n);
  EXPECT_TRUE(AnalyzeTopology(out.mesh).BoundsVolume());
  EXPECT_TRUE(NearRel(ComputeMassProperties(out.mesh, 1.0).volume, 6.0, 1e-14));
}

TEST(RepairField, AGoodMeshIsUnchangedBitForBit) {
  const LoadedMesh in = ReadMeshFile(Field("sphere_intact.stl"));
  const RepairedMesh once = RepairMesh(in.mesh);
  const RepairedMesh twice = RepairMesh(once.mesh);
  EXPECT_TRUE(twice.mesh.V == once.mesh.V);
  EXPECT_EQ(twice.mesh.indices, once.mesh.indices);
  EXPECT_EQ(twice.report.filled_holes + twice.report.removed_faces + twice.report.welded_vertices, 0);
  // Through the pipeline: a closed mesh's numbers with --repair are its numbers without, bit for bit.
  for (const char* name : {"sphere_intact.stl"}) {
    LoadOptions plain;
    plain.unit = LengthUnit::kMillimetre;
    plain.unit_stated = true;
    const SolidResult a = LoadSolid(Field(name), plain);
    const SolidResult b = Repaired(name);
    EXPECT_TRUE(SameBits(a.mp.volume, b.mp.volume)) << name;
    EXPECT_TRUE(a.mp.center_of_mass == b.mp.center_of_mass) << name;
    EXPECT_TRUE(a.mp.inertia_com == b.mp.inertia_com) << name;
  }
  const SolidResult t = Repaired("../../../data/meshes/t_handle.obj");
  LoadOptions plain;
  plain.unit = LengthUnit::kMillimetre;
  plain.unit_stated = true;
  const SolidResult u = LoadSolid(DataPath("meshes/t_handle.obj"), plain);
  EXPECT_TRUE(t.mp.inertia_com == u.mp.inertia_com);
  EXPECT_TRUE(SameBits(t.mp.volume, u.mp.volume));
}

}  // namespace
}  // namespace massprops
