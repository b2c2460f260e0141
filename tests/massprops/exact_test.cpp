// Certified integration (exact.h) against exact rationals: polyhedra whose mass properties are
// exactly representable must come out bit for bit, far from the origin too; irrational principal
// moments must lie in their enclosures (checked against long-double eigenvalues); and the default
// path must agree with the certified one to 1e-12 on every mesh in data/ the checks accept.

#include "massprops/repair/exact.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "massprops/io/load.h"
#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::DataPath;

// Mirtich's tetra (REFERENCE_VALUES.md): volume 10, center (5/4, 1, 3/4), inertia with entries
// 75/8, 5/2, 15/8, 51/4, 3/2, 123/8 — all exact doubles, so the certified result is exactly them.
TEST(Exact, MirtichTetraBitForBit) {
  const TriangleMesh tet = solids::Tetrahedron(Vector3(0, 0, 0), Vector3(5, 0, 0), Vector3(0, 4, 0), Vector3(0, 0, 3));
  const ExactMassProperties e = ExactMassPropertiesOf(ToPolygonMesh(tet), 1.0, Density{1.0});
  EXPECT_EQ(e.mp.volume, 10.0);
  EXPECT_EQ(e.mp.center_of_mass, Vector3(1.25, 1.0, 0.75));
  Matrix3 want;
  want << 75.0 / 8, 5.0 / 2, 15.0 / 8, 5.0 / 2, 51.0 / 4, 3.0 / 2, 15.0 / 8, 3.0 / 2, 123.0 / 8;
  EXPECT_EQ(e.mp.inertia_com, want);
  // The principal moments are irrational: each enclosure holds the long-double eigenvalue.
  const Eigen::Matrix<long double, 3, 3> wl = want.cast<long double>();
  const auto ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<long double, 3, 3>>(wl).eigenvalues();
  EXPECT_EQ(e.distinct_moments, 3);
  for (int k = 0; k < 3; ++k) {
    const auto [lo, hi] = e.moments[static_cast<std::size_t>(k)];
    EXPECT_LE(static_cast<long double>(lo), ev[k] * (1 + 1e-17L));
    EXPECT_GE(static_cast<long double>(hi), ev[k] * (1 - 1e-17L));
    EXPECT_LT(hi - lo, 1e-14 * hi);
  }
}

// A 1 × 2 × 3 box moved 10^5 away by exactly representable amounts: the stored solid is exactly
// the box, so the certified inertia is exactly m(b² + c²)/12 = 6500, 5000, 2500 at density 1000
// and the center exactly the offset; a cube's three equal moments share one enclosure.
TEST(Exact, FarAwayBoxIsExactAndACubesMomentsCoincide) {
  PolygonMesh box = solids::Box(Vector3(1, 2, 3));
  const Vector3 offset(100000.5, -3.25, 7);
  box.V.rowwise() += offset.transpose();
  const ExactMassProperties e = ExactMassPropertiesOf(box, 1.0, Density{1000.0});
  EXPECT_EQ(e.mp.mass, 6000.0);
  EXPECT_EQ(e.mp.center_of_mass, offset);
  EXPECT_EQ(e.mp.inertia_com, Vector3(6500, 5000, 2500).asDiagonal().toDenseMatrix());
  EXPECT_EQ(e.moments[0].first <= 2500 && 2500 <= e.moments[0].second, true);
  EXPECT_EQ(e.moments[2].first <= 6500 && 6500 <= e.moments[2].second, true);
  // In millimetres, at a total mass of 3 kg: 1 mm = 1/1000 m exactly.
  const ExactMassProperties mm = ExactMassPropertiesOf(solids::Box(Vector3(10, 20, 30)), 0.001, TotalMass{3.0});
  EXPECT_EQ(mm.mp.mass, 3.0);
  EXPECT_EQ(mm.mp.inertia_com(0, 0), 13.0 / 40000);  // 3·(0.02² + 0.03²)/12, correctly rounded
  const ExactMassProperties cube = ExactMassPropertiesOf(solids::Box(Vector3(1, 1, 1)), 1.0, Density{1000.0});
  EXPECT_EQ(cube.distinct_moments, 1);
  EXPECT_EQ(cube.moments[0], cube.moments[2]);
  EXPECT_LE(cube.moments[0].first, 1000.0 / 6);
  EXPECT_GE(cube.moments[0].second, 1000.0 / 6);
}

// The default path against the certified one, normwise, on every mesh in data/ the checks accept.
TEST(Exact, DefaultPathWithinOneTrillionthOnTheMeshesInData) {
  const std::pair<const char*, bool> meshes[] = {{"meshes/spot.obj", false},
                                                 {"meshes/t_handle.obj", false},
                                                 {"meshes/cube_cup_quad.obj", false},
                                                 {"meshes/Moon.stl", false},
                                                 {"meshes/HalfDonut_binary.stl", false},
                                                 {"meshes/HalfDonut_ascii.stl", false},
                                                 {"meshes/box_0.1x0.2x0.3.gltf", false},
                                                 {"meshes/hollow_sphere.off", true},
                                                 {"meshes/ellipe0.003.off", true}};
  for (const auto& [name, repair] : meshes) {
    LoadOptions o;
    o.exact = true;
    o.repair = repair;
    o.unit_stated = true;
    const SolidResult r = LoadSolid(DataPath(name), o);
    ASSERT_TRUE(r.exact.has_value()) << name;
    EXPECT_LT(r.exact->inertia_difference, 1e-12) << name;
    EXPECT_LT(r.exact->com_difference, 1e-12) << name;
    for (const auto& [lo, hi] : r.exact->moments) EXPECT_LE(lo, hi) << name;
  }
}

}  // namespace
}  // namespace massprops
