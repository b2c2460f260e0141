// Composition and transformation of mass properties against hand-derived values and against
// re-integrating the transformed meshes.

#include "massprops/composition.h"

#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::ExpectMassPropertiesNear;
using ::testing::HasSubstr;
using testing::MatrixNearRel;
using testing::NearRel;

MassProperties BoxAt(const Vector3& size, const Vector3& center, double rho) {
  return Transformed(solids::BoxProperties(size, rho), Matrix3::Identity(), center);
}

// Two unit cubes stacked along z with densities 1 and 3 (derived by hand):
// M = 4, z_c = (0.5·1 + 1.5·3)/4 = 1.25, Izz = 4/6, Ixx = Iyy = 1·(1/6 + 0.75²) + 3·(1/6 + 0.25²).
TEST(Composition, AssemblyOfTwoDensities) {
  const MassProperties mp =
      Combine(BoxAt(Vector3(1, 1, 1), Vector3(0, 0, 0.5), 1.0), BoxAt(Vector3(1, 1, 1), Vector3(0, 0, 1.5), 3.0));
  EXPECT_DOUBLE_EQ(mp.mass, 4.0);
  EXPECT_DOUBLE_EQ(mp.volume, 2.0);
  EXPECT_DOUBLE_EQ(mp.density, 2.0);
  EXPECT_TRUE(MatrixNearRel(mp.center_of_mass, Vector3(0, 0, 1.25), 1e-15, 1.0));
  const double ixx = (1.0 / 6 + 0.5625) + 3 * (1.0 / 6 + 0.0625);
  EXPECT_TRUE(MatrixNearRel(mp.inertia_com, Vector3(ixx, ixx, 4.0 / 6).asDiagonal().toDenseMatrix(), 1e-15, 2.0));
}

// trimesh's test_cube_with_tetras: the unit cube cut into 5 tetrahedra and into 6; composing
// the tetrahedra's properties must give I = E/6.
TEST(Composition, CubeFromTetrahedra) {
  const Vector3 c[8] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  const int five[5][4] = {{0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}, {1, 2, 4, 7}};
  const int six[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  auto compose = [&](const auto& tets) {
    std::vector<MassProperties> parts;
    for (const auto& t : tets) {
      parts.push_back(ComputeMassProperties(solids::Tetrahedron(c[t[0]], c[t[1]], c[t[2]], c[t[3]]), 1.0));
    }
    return Combine(parts);
  };
  for (const MassProperties& mp : {compose(five), compose(six)}) {
    EXPECT_TRUE(NearRel(mp.volume, 1.0, 1e-15));
    EXPECT_TRUE(MatrixNearRel(mp.center_of_mass, Vector3(0.5, 0.5, 0.5), 1e-15, 1.0));
    EXPECT_TRUE(MatrixNearRel(mp.inertia_com, Matrix3::Identity() / 6, 1e-15, 1.0));
  }
}

TEST(Composition, SubtractGivesTheHollowSphere) {
  const MassProperties hollow = Subtract(solids::SphereProperties(1.0, 2.0), solids::SphereProperties(0.9, 2.0));
  ExpectMassPropertiesNear(hollow, solids::HollowSphereProperties(1.0, 0.9, 2.0), 1e-14, 1.0);
  // REFERENCE_VALUES.md: R = 1, r = 0.9, ρ = 1: m = 1.13516214549711, I = 0.68614059070483.
  const MassProperties ref = solids::HollowSphereProperties(1.0, 0.9, 1.0);
  EXPECT_TRUE(NearRel(ref.mass, 1.13516214549711, 1e-13));
  EXPECT_TRUE(NearRel(ref.inertia_com(0, 0), 0.68614059070483, 1e-13));
}

// A mesh whose inner shell faces inward integrates to the hollow part through the signed sums:
// the same as subtracting the inner solid's properties.
TEST(Composition, InwardInnerShellSubtractsThroughSignedIntegrals) {
  const MassProperties mesh = ComputeMassProperties(solids::HollowSphere(1.0, 0.6, 24), 3.0);
  const MassProperties outer = ComputeMassProperties(solids::Sphere(1.0, 24), 3.0);
  const MassProperties inner = ComputeMassProperties(solids::Sphere(0.6, 24), 3.0);
  ExpectMassPropertiesNear(mesh, Subtract(outer, inner), 1e-13, 1.0);
  EXPECT_TRUE(NearRel(mesh.surface_area, outer.surface_area + inner.surface_area, 1e-13));
}

TEST(Composition, TransformedMatchesReintegration) {
  std::mt19937_64 rng(17);
  const TriangleMesh mesh = solids::Torus(2.0, 0.4, 12);
  const MassProperties mp = ComputeMassProperties(mesh, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    const Matrix3 R = testing::RandomRotation(rng);
    const Vector3 t = 5.0 * testing::RandomDirection(rng);
    TriangleMesh moved = mesh;
    moved.V = testing::Transform(mesh.V, R, t);
    ExpectMassPropertiesNear(Transformed(mp, R, t), ComputeMassProperties(moved, 1.0), 1e-13, 5.0);
  }
  Matrix3 mirror = Matrix3::Identity();
  mirror(0, 0) = -1;
  EXPECT_THAT([&] { Transformed(mp, mirror, Vector3::Zero()); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("not a rotation")));
}

TEST(Composition, ScaledMatchesReintegration) {
  const TriangleMesh tet =
      solids::Tetrahedron(Vector3(0.3, 0, 0), Vector3(5, 0.2, 0), Vector3(0, 4, 1), Vector3(1, 0, 3));
  const MassProperties mp = ComputeMassProperties(tet, 2.0);
  for (const Vector3& s : {Vector3(2, 3, 0.5), Vector3(-1, 1, 1), Vector3(1.5, 1.5, 1.5)}) {
    TriangleMesh scaled = tet;
    scaled.V = tet.V * s.asDiagonal();
    if (s.prod() < 0) scaled.F.col(1).swap(scaled.F.col(2));  // a mirror image is re-oriented
    const MassProperties want = ComputeMassProperties(scaled, 2.0);
    const MassProperties got = Scaled(mp, s);
    ExpectMassPropertiesNear(got, want, 1e-13, 5.0);
    if (s[0] == s[1] && s[1] == s[2]) {
      EXPECT_TRUE(NearRel(got.surface_area, want.surface_area, 1e-13));
    } else if (std::fabs(s[0]) != std::fabs(s[1])) {
      EXPECT_TRUE(std::isnan(got.surface_area));  // not derivable from the integrals
    }
  }
  EXPECT_THROW(Scaled(mp, Vector3(1, 0, 1)), std::invalid_argument);
}

TEST(Composition, RejectsImpossibleCombinations) {
  EXPECT_THAT([] { Combine(std::vector<MassProperties>{}); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("no parts")));
  EXPECT_THAT([] { Subtract(solids::SphereProperties(1, 1), solids::SphereProperties(2, 1)); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("not smaller")));
}

}  // namespace
}  // namespace massprops
