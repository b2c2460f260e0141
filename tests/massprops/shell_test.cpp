// Thin shells and walls against closed forms (REFERENCE_VALUES.md "Surface (shell, σ = 1)"
// table; hollow box and thick hollow sphere by subtraction of the solid closed forms).

#include <cmath>

#include <gtest/gtest.h>

#include "massprops/composition.h"
#include "massprops/shell.h"
#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::MatrixNearRel;
using testing::NearRel;

MassProperties Shell(const PolygonMesh& m, double sigma = 1.0, int threads = 0) {
  IntegrationOptions o;
  o.num_threads = threads;
  return ShellMassProperties(IntegrateSurface(m, o), sigma);
}

TEST(Shell, UnitCubeAndBox123MatchTheReferenceTable) {
  const MassProperties cube = Shell(solids::Box(Vector3(1, 1, 1)));
  EXPECT_TRUE(NearRel(cube.surface_area, 6.0, 1e-15));
  EXPECT_TRUE(NearRel(cube.mass, 6.0, 1e-15));
  EXPECT_EQ(cube.volume, 0.0);
  EXPECT_TRUE(MatrixNearRel(cube.inertia_com, Matrix3(Vector3::Constant(5.0 / 3).asDiagonal()), 1e-14, 1));
  const MassProperties box = Shell(solids::Box(Vector3(1, 2, 3)));
  EXPECT_TRUE(NearRel(box.surface_area, 22.0, 1e-15));
  EXPECT_TRUE(MatrixNearRel(
      box.inertia_com, Matrix3(Vector3(33.8333333333333, 26.3333333333333, 15.1666666666667).asDiagonal()), 1e-13, 34));
}

TEST(Shell, ClosedCylinderConvergesToTheReference) {
  // r = 1, h = 2: area 18.8495559215388, Ixx = Iyy = 18.3259571459405, Izz = 15.707963267949.
  double prev = 1;
  for (int n : {90, 180, 360}) {
    const MassProperties c = Shell(ToPolygonMesh(solids::Cylinder(1, 2, n)));
    const double err =
        std::max({std::abs(c.surface_area / 18.8495559215388 - 1), std::abs(c.inertia_com(0, 0) / 18.3259571459405 - 1),
                  std::abs(c.inertia_com(2, 2) / 15.707963267949 - 1)});
    EXPECT_LT(err, prev / 3.5) << n;  // second order: error / 4 per halving of the edge
    prev = err;
  }
  EXPECT_LT(prev, 1e-4);
}

TEST(Shell, OpenBoxWithoutItsTopAgainstHandIntegration) {
  // Unit cube centred at 0 without the +z face: area 5, COM z = (−1/2 · 1 + 0 · 4)/5 = −0.1.
  PolygonMesh box = solids::Box(Vector3(1, 1, 1));
  PolygonMesh open;
  open.V = box.V;
  for (std::int64_t f = 0; f < box.num_faces(); ++f) {
    Vector3 n = Vector3::Zero();
    for (std::int64_t k = box.offsets[f]; k < box.offsets[f + 1]; ++k)
      n += box.V.row(box.indices[static_cast<std::size_t>(k)]).transpose();
    if (n.z() > 1.5) continue;  // the four corners of the top face sum to z = 2
    open.AddFace(
        std::vector<std::int32_t>(box.indices.begin() + box.offsets[f], box.indices.begin() + box.offsets[f + 1]));
  }
  ASSERT_EQ(open.num_faces(), 5);
  const MassProperties s = Shell(open, 2.0);
  EXPECT_TRUE(NearRel(s.mass, 10.0, 1e-15));
  EXPECT_TRUE(MatrixNearRel(s.center_of_mass, Vector3(0, 0, -0.1), 1e-15, 1));
  // Izz about z through the COM: bottom 1/6, four sides 1/3 each → σ (1/6 + 4/3) = 3.
  EXPECT_TRUE(NearRel(s.inertia_com(2, 2), 3.0, 1e-14));
  // Ixx about the origin: bottom (1/12 + 1/4), sides ⊥x 2·(1/12 + 1/12), sides ⊥y 2·(1/4 + 1/12):
  // 1/3 + 1/3 + 2/3 = 4/3 → σ·4/3, then moved to the COM: − m · 0.1².
  EXPECT_TRUE(NearRel(s.inertia_com(0, 0), 2.0 * 4.0 / 3.0 - 10.0 * 0.01, 1e-14));
}

TEST(Shell, ConcavePolygonFaceIsExact) {
  // An L-shaped planar face as one polygon, against its two rectangles.
  PolygonMesh l;
  l.V.resize(6, 3);
  l.V << 0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1, 3, 0, 0, 3, 0;
  l.AddFace(std::vector<int>{0, 1, 2, 3, 4, 5});
  PolygonMesh two;
  two.V.resize(8, 3);
  two.V << 0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0, 0, 1, 0, 1, 1, 0, 1, 3, 0, 0, 3, 0;
  two.AddFace(std::vector<int>{0, 1, 2, 3});
  two.AddFace(std::vector<int>{4, 5, 6, 7});
  const MassProperties a = Shell(l), b = Shell(two);
  EXPECT_TRUE(NearRel(a.surface_area, 4.0, 1e-15));
  EXPECT_TRUE(MatrixNearRel(a.center_of_mass, b.center_of_mass, 1e-15, 1));
  EXPECT_TRUE(MatrixNearRel(a.inertia_com, b.inertia_com, 1e-14, 1));
}

TEST(Shell, SameBitsForAnyThreadCountAndIndependentOfPlacement) {
  const TriangleMesh sphere = solids::Sphere(1.0, 120);  // > one block of faces
  const MassProperties one = Shell(ToPolygonMesh(sphere), 1.0, 1);
  const MassProperties four = Shell(ToPolygonMesh(sphere), 1.0, 4);
  EXPECT_TRUE(testing::SameBits(one, four));
  // Thin spherical shell r = 1: area 4π, I = 2/3 m r²; tessellation error O(1/n²).
  EXPECT_TRUE(NearRel(one.surface_area, 4 * massprops::kPi, 2e-4));
  EXPECT_TRUE(NearRel(one.inertia_com(0, 0), 8.37758040957278, 4e-4));
  // Moved 3·10⁴ away: the same numbers (integrated about the bounding-box centre).
  TriangleMesh far = sphere;
  far.V.rowwise() += Vector3(3e4, -2e4, 1e4).transpose();
  const MassProperties moved = Shell(ToPolygonMesh(far));
  EXPECT_TRUE(MatrixNearRel(moved.inertia_com, one.inertia_com, 1e-9, 8.4));
}

TEST(Wall, HollowBoxIsExact) {
  const Vector3 size(0.3, 0.2, 0.1);
  const double t = 0.01;
  const PolygonMesh wall = WallSolid(solids::Box(size), t);
  const MassProperties got = ComputeMassProperties(wall, 2700.0);
  const MassProperties want =
      Subtract(solids::BoxProperties(size, 2700.0), solids::BoxProperties(size - Vector3::Constant(2 * t), 2700.0));
  testing::ExpectMassPropertiesNear(got, want, 1e-12, 0.3);
  // The triangulated box (several triangles per face, still three planes per corner): exact too.
  const PolygonMesh tri = ToPolygonMesh(Triangulate(solids::Box(size)));
  testing::ExpectMassPropertiesNear(ComputeMassProperties(WallSolid(tri, t), 2700.0), want, 1e-12, 0.3);
}

TEST(Wall, HollowSphereConvergesToTheThickShellClosedForm) {
  const double R = 1.0, t = 0.1;
  const MassProperties want = solids::HollowSphereProperties(R, R - t, 1.0);
  double prev = 1;
  for (int n : {32, 64, 128}) {
    const MassProperties got = ComputeMassProperties(WallSolid(ToPolygonMesh(solids::Sphere(R, n)), t), 1.0);
    const double err =
        std::max(std::abs(got.mass / want.mass - 1), std::abs(got.inertia_com(0, 0) / want.inertia_com(0, 0) - 1));
    EXPECT_LT(err, prev / 3.0) << n;
    prev = err;
  }
  EXPECT_LT(prev, 5e-4);  // measured 3.1e-4 at n = 128
}

TEST(Wall, TooThickIsRefusedSayingWhy) {
  try {
    WallSolid(solids::Box(Vector3(1, 1, 0.1)), 0.06);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("thicker than the part allows"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("faces of the inner surface turn over"), std::string::npos) << e.what();
  }
  EXPECT_THROW(WallSolid(solids::Box(Vector3(1, 1, 1)), 0.0), std::invalid_argument);
  EXPECT_THROW(WallSolid(solids::Box(Vector3(1, 1, 1)), NAN), std::invalid_argument);
  EXPECT_NO_THROW(WallSolid(solids::Box(Vector3(1, 1, 0.1)), 0.04));
}

}  // namespace
}  // namespace massprops
