// Mirtich's polygon path: published test polyhedra, n-gon faces integrated whole (convex and
// concave), and agreement with the triangle path on every solid to 1e-12.

#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/composition.h"
#include "massprops/mass_properties.h"
#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::ExpectMassPropertiesNear;
using ::testing::HasSubstr;
using testing::MatrixNearRel;
using testing::NearRel;

// Mirtich's `cube` (side 20, centred, quad faces): V = 8000, I = 1600000/3 · E.
TEST(PolygonPath, MirtichCube) {
  const MassProperties mp = ComputeMassProperties(solids::Box(Vector3(20, 20, 20)), 1.0);
  EXPECT_TRUE(NearRel(mp.volume, 8000.0, 1e-15));
  EXPECT_TRUE(MatrixNearRel(mp.center_of_mass, Vector3::Zero(), 1e-15, 20));
  EXPECT_TRUE(MatrixNearRel(mp.inertia_com, Matrix3::Identity() * 1600000.0 / 3.0, 1e-15, 533334));
  EXPECT_TRUE(NearRel(mp.surface_area, 2400.0, 1e-15));
}

TEST(PolygonPath, MirtichTetra) {
  const TriangleMesh tet = solids::Tetrahedron(Vector3(0, 0, 0), Vector3(5, 0, 0), Vector3(0, 4, 0), Vector3(0, 0, 3));
  const MassProperties mp = ComputeMassProperties(ToPolygonMesh(tet), 1.0);
  EXPECT_TRUE(NearRel(mp.volume, 10.0, 1e-14));
  Matrix3 want;
  want << 75.0 / 8, 5.0 / 2, 15.0 / 8, 5.0 / 2, 51.0 / 4, 3.0 / 2, 15.0 / 8, 3.0 / 2, 123.0 / 8;
  EXPECT_TRUE(MatrixNearRel(mp.inertia_com, want, 1e-14, 15.0));
}

// A prism over a regular 9-gon: the caps go through Mirtich's edge sums as 9-gons.
TEST(PolygonPath, RegularPrismWithNgonCapsUnderRigidMotions) {
  std::mt19937_64 rng(7);
  const PolygonMesh prism = solids::RegularPrism(9, 0.7, 1.9);
  const MassProperties exact = solids::RegularPrismProperties(9, 0.7, 1.9, 3.0);
  for (double distance : {0.0, 10.0, 1e4}) {
    const Matrix3 R = testing::RandomRotation(rng);
    const Vector3 t = distance * testing::RandomDirection(rng);
    PolygonMesh moved = prism;
    moved.V = testing::Transform(prism.V, R, t);
    const double tol = 1e-12 + 8 * std::numeric_limits<double>::epsilon() * distance / 0.7;
    SCOPED_TRACE(distance);
    ExpectMassPropertiesNear(ComputeMassProperties(moved, 3.0), testing::Moved(exact, R, t), tol, 1.0);
  }
}

// An L-shaped prism whose two caps are concave hexagons: the exact answer is the union of two
// boxes (composition of closed forms), which Mirtich's path must reproduce face by face.
TEST(PolygonPath, ConcaveHexagonCaps) {
  // L in the x-y plane: [0,3]×[0,1] ∪ [0,1]×[1,2], extruded over z ∈ [0, 0.5].
  const double xy[6][2] = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 2}, {0, 2}};
  PolygonMesh L;
  L.V.resize(12, 3);
  for (int k = 0; k < 6; ++k) {
    L.V.row(k) << xy[k][0], xy[k][1], 0.0;
    L.V.row(6 + k) << xy[k][0], xy[k][1], 0.5;
  }
  L.AddFace(std::vector<int>{5, 4, 3, 2, 1, 0});
  L.AddFace(std::vector<int>{6, 7, 8, 9, 10, 11});
  for (int k = 0; k < 6; ++k) L.AddFace(std::vector<int>{k, (k + 1) % 6, 6 + (k + 1) % 6, 6 + k});

  const MassProperties a =
      Transformed(solids::BoxProperties(Vector3(3, 1, 0.5), 2.0), Matrix3::Identity(), Vector3(1.5, 0.5, 0.25));
  const MassProperties b =
      Transformed(solids::BoxProperties(Vector3(1, 1, 0.5), 2.0), Matrix3::Identity(), Vector3(0.5, 1.5, 0.25));
  const MassProperties want = Combine(a, b);
  ExpectMassPropertiesNear(ComputeMassProperties(L, 2.0), want, 1e-14, 3.0);
}

// Both paths, every solid the library generates, moved off the origin: 1e-12 relative.
TEST(PolygonPath, AgreesWithTrianglePathOnEverySolid) {
  std::mt19937_64 rng(11);
  std::vector<std::pair<const char*, PolygonMesh>> meshes = {
      {"box", solids::Box(Vector3(1, 2, 3))},
      {"prism", solids::RegularPrism(12, 2.0, 0.5)},
      {"tetrahedron", ToPolygonMesh(solids::RegularTetrahedron(1.0))},
      {"octahedron", ToPolygonMesh(solids::Octahedron(2.0))},
      {"sphere", ToPolygonMesh(solids::Sphere(1.0, 24))},
      {"ellipsoid", ToPolygonMesh(solids::Ellipsoid(Vector3(1, 2, 3), 20))},
      {"cylinder", ToPolygonMesh(solids::Cylinder(1.0, 2.0, 30))},
      {"cone", ToPolygonMesh(solids::Cone(1.0, 3.0, 30))},
      {"torus", ToPolygonMesh(solids::Torus(2.0, 0.5, 24))},
      {"capsule", ToPolygonMesh(solids::Capsule(0.5, 2.0, 20))},
      {"hollow sphere", ToPolygonMesh(solids::HollowSphere(1.0, 0.9, 20))},
  };
  for (auto& [name, mesh] : meshes) {
    mesh.V = testing::Transform(mesh.V, testing::RandomRotation(rng), Vector3(3.5, -20.0, 41.0));
    const MassProperties poly = ComputeMassProperties(mesh, 1.0);
    const MassProperties tri = ComputeMassProperties(Triangulate(mesh), 1.0);
    SCOPED_TRACE(name);
    ExpectMassPropertiesNear(poly, tri, 1e-12, 3.0);
    EXPECT_TRUE(NearRel(poly.surface_area, tri.surface_area, 1e-12));
  }
}

TEST(PolygonPath, SameBitsForAnyThreadCount) {
  PolygonMesh mesh = ToPolygonMesh(solids::Torus(2.0, 0.7, 120));
  IntegrationOptions one;
  one.num_threads = 1;
  const MassProperties ref = ComputeMassProperties(mesh, 2.0, one);
  for (int threads : {2, 3, 5}) {
    IntegrationOptions opt;
    opt.num_threads = threads;
    EXPECT_TRUE(testing::SameBits(ComputeMassProperties(mesh, 2.0, opt), ref));
  }
}

TEST(PolygonPath, RejectsMalformedFaces) {
  PolygonMesh mesh = solids::Box(Vector3(1, 1, 1));
  PolygonMesh two = mesh;
  two.AddFace(std::vector<int>{0, 1});
  EXPECT_THAT([&] { ComputeMassProperties(two, 1.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("face 6 has 2 corners")));
  PolygonMesh bad_index = mesh;
  bad_index.indices[5] = 8;
  EXPECT_THAT([&] { ComputeMassProperties(bad_index, 1.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("vertex 8")));
  PolygonMesh nan = mesh;
  nan.V(4, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT([&] { ComputeMassProperties(nan, 1.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("vertex 4")));
}

}  // namespace
}  // namespace massprops
