// The triangle path (signed tetrahedra) against closed forms and published values, under rigid
// motions far from the origin, with inverted meshes, bad input, and any thread count.

#include "massprops/mass_properties.h"

#include <limits>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/principal_axes.h"
#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::ExpectMassPropertiesNear;
using ::testing::HasSubstr;
using testing::MatrixNearRel;
using testing::NearRel;

constexpr double kEps = std::numeric_limits<double>::epsilon();

TEST(TrianglePath, UnitCube) {
  const TriangleMesh cube = Triangulate(solids::Box(Vector3(1, 1, 1)));
  const MassProperties mp = ComputeMassProperties(cube, 1.0);
  EXPECT_NEAR(mp.volume, 1.0, 1e-15);
  EXPECT_NEAR(mp.surface_area, 6.0, 1e-14);
  EXPECT_TRUE(MatrixNearRel(mp.center_of_mass, Vector3::Zero(), 1e-15, 1.0));
  EXPECT_TRUE(MatrixNearRel(mp.inertia_com, Matrix3::Identity() / 6.0, 1e-15, 1.0));
}

// Mirtich's `tetra` test polyhedron: the hull of 0, (5,0,0), (0,4,0), (0,0,3).
// Reference: REFERENCE_VALUES.md (exact rationals); positive off-diagonals because the products of
// inertia are negative.
TEST(TrianglePath, MirtichTetra) {
  const TriangleMesh tet = solids::Tetrahedron(Vector3(0, 0, 0), Vector3(5, 0, 0), Vector3(0, 4, 0), Vector3(0, 0, 3));
  const MassProperties mp = ComputeMassProperties(tet, 1.0);
  EXPECT_TRUE(NearRel(mp.volume, 10.0, 1e-14));
  EXPECT_TRUE(MatrixNearRel(mp.center_of_mass, Vector3(1.25, 1.0, 0.75), 1e-14, 1.0));
  Matrix3 want;
  want << 75.0 / 8, 5.0 / 2, 15.0 / 8, 5.0 / 2, 51.0 / 4, 3.0 / 2, 15.0 / 8, 3.0 / 2, 123.0 / 8;
  EXPECT_TRUE(MatrixNearRel(mp.inertia_com, want, 1e-14, 15.0));
}

// Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia tensor", J. Math. Stat. 2004.
// Values recomputed exactly from the printed decimals (REFERENCE_VALUES.md); the paper's own
// printed values agree to 1e-7 with its b'/c' naming swapped.
TEST(TrianglePath, TononTetrahedron) {
  const TriangleMesh tet = solids::Tetrahedron(Vector3(8.3322, -11.86875, 0.93355), Vector3(0.75523, 5, 16.37072),
                                               Vector3(52.61236, 5, -5.3858), Vector3(2, 5, 3));
  const MassProperties mp = ComputeMassProperties(tet, 1.0);
  EXPECT_TRUE(NearRel(mp.volume, 1873.23336421647, 1e-12));
  EXPECT_TRUE(MatrixNearRel(mp.center_of_mass, Vector3(15.9249475, 0.7828125, 3.7296175), 1e-12, 16));
  Matrix3 want;
  want << 43520.3332854, -11996.2013932, 46343.1673814,  //
      -11996.2013932, 194711.292591, -4417.66156969,     //
      46343.1673814, -4417.66156969, 191168.764886;
  EXPECT_TRUE(MatrixNearRel(mp.inertia_com, want, 1e-11, 194711.3));
  // The paper's printed values (a, b, c, a', b', c').
  EXPECT_TRUE(NearRel(mp.inertia_com(0, 0), 43520.33257, 1e-7));
  EXPECT_TRUE(NearRel(mp.inertia_com(1, 1), 194711.28938, 1e-7));
  EXPECT_TRUE(NearRel(mp.inertia_com(2, 2), 191168.76173, 1e-7));
  EXPECT_TRUE(NearRel(-mp.inertia_com(1, 2), 4417.6615, 1e-7));
  EXPECT_TRUE(NearRel(-mp.inertia_com(0, 2), -46343.16662, 1e-7));
  EXPECT_TRUE(NearRel(-mp.inertia_com(0, 1), 11996.20119, 1e-7));
}

// A box with a corner at the origin: inertia about the origin from ∫x² = m a²/3, ∫xy = m ab/4
// (trimesh's test_frame_inertia_box case). Exercises InertiaAbout and the off-diagonal sign.
TEST(TrianglePath, InertiaAboutCornerOfBox) {
  const double a = 1, b = 2, c = 3, rho = 2.5, m = rho * a * b * c;
  TriangleMesh box = Triangulate(solids::Box(Vector3(a, b, c)));
  box.V = testing::Transform(box.V, Matrix3::Identity(), Vector3(a / 2, b / 2, c / 2));
  const MassProperties mp = ComputeMassProperties(box, rho);
  Matrix3 want;
  want << m * (b * b + c * c) / 3, -m * a * b / 4, -m * a * c / 4,  //
      -m * a * b / 4, m * (a * a + c * c) / 3, -m * b * c / 4,      //
      -m * a * c / 4, -m * b * c / 4, m * (a * a + b * b) / 3;
  EXPECT_TRUE(MatrixNearRel(mp.InertiaAbout(Vector3::Zero()), want, 1e-14, want.maxCoeff()));
}

// Every exact polyhedron, moved by random rigid motions up to 1e5 from the origin, matches its
// closed form moved the same way. The tolerance is 1e-12 plus the input-rounding floor: placing a
// part of size L at distance T rounds its coordinates by up to T·ε/2, which no algorithm can undo.
struct Polyhedron {
  const char* name;
  TriangleMesh mesh;
  MassProperties exact;
  double size;
};

std::vector<Polyhedron> ExactPolyhedra() {
  return {
      {"box", Triangulate(solids::Box(Vector3(1, 2, 3))), solids::BoxProperties(Vector3(1, 2, 3), 1.0), 1.0},
      {"regular tetrahedron", solids::RegularTetrahedron(2.0), solids::RegularTetrahedronProperties(2.0, 1.0), 2.0},
      {"octahedron", solids::Octahedron(1.5), solids::OctahedronProperties(1.5, 1.0), 1.5},
      {"prism", Triangulate(solids::RegularPrism(7, 1.0, 2.0)), solids::RegularPrismProperties(7, 1.0, 2.0, 1.0), 1.0},
  };
}

TEST(TrianglePath, ExactPolyhedraUnderRigidMotionsFarFromOrigin) {
  std::mt19937_64 rng(20261122);
  for (const Polyhedron& p : ExactPolyhedra()) {
    for (double distance : {0.0, 1.0, 1e3, 1e5}) {
      for (int trial = 0; trial < 10; ++trial) {
        const Matrix3 R = testing::RandomRotation(rng);
        const Vector3 t = distance * testing::RandomDirection(rng);
        TriangleMesh moved = p.mesh;
        moved.V = testing::Transform(p.mesh.V, R, t);
        const MassProperties got = ComputeMassProperties(moved, 1.0);
        const double tol = 1e-12 + 8 * kEps * distance / p.size;
        SCOPED_TRACE(::testing::Message() << p.name << " at distance " << distance);
        ExpectMassPropertiesNear(got, testing::Moved(p.exact, R, t), tol, p.size);
        EXPECT_TRUE(NearRel(got.surface_area, p.exact.surface_area, tol));
      }
    }
  }
}

// The reason for integrating about a nearby point: about the file origin, a part 1e5 away loses
// most of its inertia to cancellation; about its bounding-box centre it keeps 10+ digits.
TEST(TrianglePath, NearbyReferencePointKeepsDigitsThatTheOriginLoses) {
  TriangleMesh box = Triangulate(solids::Box(Vector3(1, 2, 3)));
  const Vector3 t(1e5, -1e5, 1e5);  // exactly representable shift: the input is not rounded
  box.V = testing::Transform(box.V, Matrix3::Identity(), t);
  const MassProperties exact = testing::Moved(solids::BoxProperties(Vector3(1, 2, 3), 1.0), Matrix3::Identity(), t);
  const MassProperties good = ComputeMassProperties(box, 1.0);
  IntegrationOptions about_origin;
  about_origin.reference = Vector3::Zero();
  const MassProperties naive = ComputeMassProperties(box, 1.0, about_origin);
  const double scale = exact.inertia_com.maxCoeff();
  const double good_err = (good.inertia_com - exact.inertia_com).cwiseAbs().maxCoeff() / scale;
  const double naive_err = (naive.inertia_com - exact.inertia_com).cwiseAbs().maxCoeff() / scale;
  EXPECT_LT(good_err, 1e-13);
  EXPECT_GT(naive_err, 1e-6);  // documents what the default avoids
}

TEST(TrianglePath, InvertedMeshGivesNegativeVolumeAndIsFlaggedInvalid) {
  TriangleMesh box = Triangulate(solids::Box(Vector3(1, 2, 3)));
  box.F.col(1).swap(box.F.col(2));
  const MassProperties mp = ComputeMassProperties(box, 1.0);
  EXPECT_NEAR(mp.volume, -6.0, 1e-14);
  EXPECT_NEAR(mp.mass, -6.0, 1e-14);
  const ValidityReport v = CheckPhysicallyValid(ComputePrincipalInertia(mp.inertia_com).moments);
  EXPECT_FALSE(v.valid);
  EXPECT_THAT(v.reason, HasSubstr("inward"));
}

TEST(TrianglePath, VolumeIntegralsShiftExactly) {
  const TriangleMesh tet = solids::Tetrahedron(Vector3(0, 0, 0), Vector3(5, 0, 0), Vector3(0, 4, 0), Vector3(0, 0, 3));
  IntegrationOptions at_a, at_b;
  at_a.reference = Vector3(1, 2, 3);
  at_b.reference = Vector3(-4, 0.5, 2);
  const VolumeIntegrals a = IntegrateTriangles(tet.V, tet.F, at_a);
  const VolumeIntegrals b = IntegrateTriangles(tet.V, tet.F, at_b);
  const VolumeIntegrals a_to_b = a.About(*at_b.reference);
  EXPECT_TRUE(NearRel(a_to_b.volume, b.volume, 1e-14));
  EXPECT_TRUE(MatrixNearRel(a_to_b.first, b.first, 1e-14, b.first.cwiseAbs().maxCoeff()));
  EXPECT_TRUE(MatrixNearRel(a_to_b.second, b.second, 1e-14, b.second.cwiseAbs().maxCoeff()));
}

TEST(TrianglePath, SameBitsForAnyThreadCount) {
  const TriangleMesh sphere = solids::Sphere(1.3, 150);  // 90k triangles: many blocks
  TriangleMesh moved = sphere;
  moved.V = testing::Transform(sphere.V, Matrix3::Identity(), Vector3(12.5, -3.25, 7.0));
  IntegrationOptions one;
  one.num_threads = 1;
  const MassProperties ref = ComputeMassProperties(moved, 7.8, one);
  for (int threads : {2, 3, 4, 8, 0}) {
    IntegrationOptions opt;
    opt.num_threads = threads;
    EXPECT_TRUE(testing::SameBits(ComputeMassProperties(moved, 7.8, opt), ref)) << threads << " threads";
  }
}

TEST(TrianglePath, RejectsNonFiniteVertexNamingIt) {
  TriangleMesh tet = solids::RegularTetrahedron(1.0);
  tet.V(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT([&] { ComputeMassProperties(tet, 1.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("vertex 2")));
  tet.V(2, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THAT([&] { ComputeMassProperties(tet, 1.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("non-finite")));
}

TEST(TrianglePath, RejectsIndexOutOfRangeNamingTheFace) {
  TriangleMesh tet = solids::RegularTetrahedron(1.0);
  tet.F(3, 2) = 99;
  EXPECT_THAT([&] { ComputeMassProperties(tet, 1.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  HasSubstr("face 3 refers to vertex 99, but the mesh has 4 vertices")));
  tet.F(3, 2) = -1;
  EXPECT_THROW(ComputeMassProperties(tet, 1.0), std::invalid_argument);
}

TEST(TrianglePath, RejectsBadDensityAndZeroVolume) {
  const TriangleMesh tet = solids::RegularTetrahedron(1.0);
  for (double rho : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    EXPECT_THAT([&] { ComputeMassProperties(tet, rho); },
                ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("density")));
  }
  TriangleMesh empty;
  EXPECT_THAT([&] { ComputeMassProperties(empty, 1.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("zero volume")));
  // A flat, doubled triangle: closed in a sense, but it bounds nothing.
  TriangleMesh flat;
  flat.V.resize(3, 3);
  flat.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  flat.F.resize(2, 3);
  flat.F << 0, 1, 2, 0, 2, 1;
  EXPECT_THAT([&] { ComputeMassProperties(flat, 1.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("zero volume")));
}

}  // namespace
}  // namespace massprops
