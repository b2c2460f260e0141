// Principal moments and axes: ordering, proper rotation, sign convention, repeated moments,
// body frame, and the physical-validity check.

#include "massprops/principal_axes.h"

#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using ::testing::HasSubstr;
using testing::MatrixNearRel;
using testing::NearRel;

// Checks the documented convention on a decomposition.
void ExpectConvention(const PrincipalInertia& p) {
  EXPECT_LE(p.moments[0], p.moments[1]);
  EXPECT_LE(p.moments[1], p.moments[2]);
  EXPECT_TRUE(MatrixNearRel(p.axes.transpose() * p.axes, Matrix3::Identity(), 1e-14, 1.0));
  EXPECT_NEAR(p.axes.determinant(), 1.0, 1e-14);
  for (int c = 0; c < 2; ++c) {
    Eigen::Index k;
    p.axes.col(c).cwiseAbs().maxCoeff(&k);
    EXPECT_GT(p.axes(k, c), 0.0) << "axis " << c + 1 << " sign";
  }
}

TEST(PrincipalAxes, DiagonalTensorIsSortedIntoAProperRotation) {
  const PrincipalInertia p = ComputePrincipalInertia(Vector3(3, 1, 2).asDiagonal());
  EXPECT_EQ(p.moments, Vector3(1, 2, 3));
  Matrix3 want;  // y, z, then y × z = x
  want << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  EXPECT_TRUE(MatrixNearRel(p.axes, want, 0.0, 1.0));
  ExpectConvention(p);
}

TEST(PrincipalAxes, RecoversRandomlyRotatedTensors) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Matrix3 R = testing::RandomRotation(rng);
    const Vector3 d(0.7, 1.9, 2.3);
    const Matrix3 I = R * d.asDiagonal() * R.transpose();
    const PrincipalInertia p = ComputePrincipalInertia(0.5 * (I + I.transpose()));
    EXPECT_TRUE(MatrixNearRel(p.moments, d, 1e-14, 2.3));
    EXPECT_TRUE(MatrixNearRel(p.axes * p.moments.asDiagonal() * p.axes.transpose(), I, 1e-14, 2.3));
    for (int c = 0; c < 3; ++c) {  // each axis is ±the true one
      EXPECT_NEAR(std::fabs(p.axes.col(c).dot(R.col(c))), 1.0, 1e-13);
    }
    ExpectConvention(p);
  }
}

TEST(PrincipalAxes, ThreeEqualMomentsGiveTheMeshAxes) {
  Matrix3 I = Matrix3::Identity() * 2.5;
  I(0, 1) = I(1, 0) = 1e-14;  // round-off in a computed sphere or cube tensor
  const PrincipalInertia p = ComputePrincipalInertia(I);
  EXPECT_EQ(p.axes, Matrix3::Identity());
  const MassProperties cube = ComputeMassProperties(solids::Box(Vector3(2, 2, 2)), 1.0);
  EXPECT_EQ(ComputePrincipalInertia(cube.inertia_com).axes, Matrix3::Identity());
}

TEST(PrincipalAxes, BodyOfRevolutionHasItsAxisAndADeterministicPair) {
  // Cylinder r = 1, h = 2 along z: Izz = m/2 is the smallest moment, Ixx = Iyy = 7m/12.
  const MassProperties cyl = ComputeMassProperties(solids::Cylinder(1.0, 2.0, 64), 1.0);
  const PrincipalInertia p = ComputePrincipalInertia(cyl.inertia_com);
  EXPECT_TRUE(MatrixNearRel(p.axes.col(0), Vector3(0, 0, 1), 1e-12, 1.0));
  EXPECT_TRUE(MatrixNearRel(p.axes.col(1), Vector3(1, 0, 0), 1e-12, 1.0));
  EXPECT_TRUE(MatrixNearRel(p.axes.col(2), Vector3(0, 1, 0), 1e-12, 1.0));
  ExpectConvention(p);

  // The same, tilted: the distinct axis follows the tilt, the pair stays perpendicular.
  std::mt19937_64 rng(5);
  const Matrix3 R = testing::RandomRotation(rng);
  const Matrix3 I = R * cyl.inertia_com * R.transpose();
  const PrincipalInertia q = ComputePrincipalInertia(0.5 * (I + I.transpose()));
  EXPECT_NEAR(std::fabs(q.axes.col(0).dot(R.col(2))), 1.0, 1e-12);
  EXPECT_TRUE(MatrixNearRel(q.axes * q.moments.asDiagonal() * q.axes.transpose(), I, 1e-13, I.cwiseAbs().maxCoeff()));
  ExpectConvention(q);
}

// The body frame carries the mesh so that the center of mass is the origin and the inertia is
// diagonal and ascending: recomputing from the transformed mesh shows it.
TEST(PrincipalAxes, BodyFrameDiagonalizesTheMesh) {
  std::mt19937_64 rng(9);
  TriangleMesh mesh = solids::Ellipsoid(Vector3(0.5, 1.0, 2.0), 16);
  mesh.V = testing::Transform(mesh.V, testing::RandomRotation(rng), Vector3(4, -2, 9));
  const MassProperties mp = ComputeMassProperties(mesh, 1200.0);
  const PrincipalInertia p = ComputePrincipalInertia(mp.inertia_com);
  const RigidTransform body = BodyFrameTransform(mp, p);
  TriangleMesh in_body = mesh;
  in_body.V = testing::Transform(mesh.V, body.rotation, body.translation);
  const MassProperties b = ComputeMassProperties(in_body, 1200.0);
  EXPECT_TRUE(MatrixNearRel(b.center_of_mass, Vector3::Zero(), 1e-13, 2.0));
  EXPECT_TRUE(MatrixNearRel(b.inertia_com, Matrix3(p.moments.asDiagonal()), 1e-12, p.moments[2]));
  // And the inverse is the seed notes' x = R x0 + x_c.
  const RigidTransform back = body.Inverse();
  EXPECT_TRUE(MatrixNearRel(back.rotation, p.axes, 0.0, 1.0));
  EXPECT_TRUE(MatrixNearRel(back.translation, mp.center_of_mass, 1e-14, 10.0));
}

TEST(PrincipalAxes, PhysicalValidity) {
  EXPECT_TRUE(CheckPhysicallyValid(Vector3(1, 2, 3)).valid);  // the flat-plate limit
  EXPECT_TRUE(CheckPhysicallyValid(Vector3(2, 2, 2)).valid);
  const ValidityReport tri = CheckPhysicallyValid(Vector3(1, 1, 3));
  EXPECT_FALSE(tri.valid);
  EXPECT_THAT(tri.reason, HasSubstr("triangle inequality"));
  EXPECT_FALSE(CheckPhysicallyValid(Vector3(0, 1, 1)).valid);
  EXPECT_FALSE(CheckPhysicallyValid(Vector3(-1, 2, 2)).valid);
  EXPECT_FALSE(CheckPhysicallyValid(Vector3(std::nan(""), 2, 2)).valid);
  // Every generated solid passes.
  for (const TriangleMesh& m :
       {solids::Sphere(1, 8), solids::Torus(2, 0.5, 8), solids::Cone(1, 3, 8), solids::Capsule(0.5, 2, 8)}) {
    const MassProperties mp = ComputeMassProperties(m, 1.0);
    EXPECT_TRUE(CheckPhysicallyValid(ComputePrincipalInertia(mp.inertia_com).moments).valid);
  }
}

TEST(PrincipalAxes, RejectsNonSymmetricOrNonFiniteTensors) {
  Matrix3 I = Matrix3::Identity();
  I(0, 1) = 0.5;
  EXPECT_THAT([&] { ComputePrincipalInertia(I); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("not symmetric")));
  I(0, 1) = std::nan("");
  EXPECT_THAT([&] { ComputePrincipalInertia(I); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("not finite")));
}

}  // namespace
}  // namespace massprops
