// Convex polytopes for contact (src/contact/polytope.h, internal) in isolation: the faces a hull's
// triangles merge into, and the contact points of two boxes and of a sphere and a box against
// their closed forms (face-on overlap d gives the four corners of the overlap at separation −d).

#include "polytope.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynamics::contact {
namespace {

// A cube's 12 outward triangles on its 8 corners (half extent 1).
std::vector<Vector3> CubeCorners() {
  std::vector<Vector3> v;
  for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  return v;
}
std::vector<std::array<int, 3>> CubeTriangles() {
  return {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
          {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
}

TEST(Polytope, CoplanarTrianglesMergeIntoFaces) {
  const Polytope p = MakePolytope(CubeCorners(), CubeTriangles());
  EXPECT_EQ(p.vertices.size(), 8u);
  EXPECT_EQ(p.faces.size(), 6u);
  EXPECT_EQ(p.edges.size(), 12u);  // the diagonals inside faces are not edges
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    EXPECT_NEAR(p.normals[f].norm(), 1.0, 1e-15);
    EXPECT_EQ(p.faces[f].size(), 4u);
    // Outward: every corner lies on or behind the face's plane.
    const double offset = p.normals[f].dot(p.vertices[static_cast<std::size_t>(p.faces[f][0])]);
    for (const Vector3& v : p.vertices) EXPECT_LE(p.normals[f].dot(v), offset + 1e-12);
  }
  EXPECT_LT(p.centroid.norm(), 1e-15);
  const Polytope box = BoxPolytope(Vector3(1, 1, 1));
  EXPECT_EQ(box.faces.size(), 6u);
  EXPECT_EQ(box.edges.size(), 12u);
}

TEST(Polytope, RefusesWhatIsNotAClosedConvexSolid) {
  std::vector<std::array<int, 3>> open = CubeTriangles();
  open.pop_back();
  EXPECT_THROW(MakePolytope(CubeCorners(), open), std::invalid_argument);
  std::vector<Vector3> dented = CubeCorners();
  dented[7] = Vector3(0.5, 0.5, 0.5);  // a corner pushed in: not convex
  EXPECT_THROW(MakePolytope(dented, CubeTriangles()), std::invalid_argument);
}

TEST(Polytope, BoxOnBoxFaceToFace) {
  const Polytope box = BoxPolytope(Vector3(1, 1, 1));
  const shape::Box shape{Vector3(1, 1, 1)};
  const Shape s = shape;
  // Box a 0.01 into box b from above, shifted by 0.5 in x: the overlap is [−0.5, 1] × [−1, 1].
  Posed a{&s, &box, Matrix3::Identity(), Vector3(0.5, 0, 1.99), {}};
  Posed b{&s, &box, Matrix3::Identity(), Vector3::Zero(), {}};
  std::vector<ContactPoint> points;
  PolytopePolytope(box, a, box, b, 0.0, points);
  ASSERT_EQ(points.size(), 4u);
  for (const ContactPoint& c : points) {
    EXPECT_NEAR(c.separation, -0.01, 1e-12);
    EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);  // from b into a
    EXPECT_GE(c.point.x(), -0.5 - 1e-12);
    EXPECT_LE(c.point.x(), 1.0 + 1e-12);
    EXPECT_NEAR(std::abs(c.point.y()), 1.0, 1e-12);
  }
  // Apart by more than the margin: nothing.
  a.t.z() = 2.5;
  points.clear();
  PolytopePolytope(box, a, box, b, 0.1, points);
  EXPECT_TRUE(points.empty());
}

TEST(Polytope, SphereOverAFace) {
  const Polytope box = BoxPolytope(Vector3(1, 1, 1));
  const Shape s = shape::Box{Vector3(1, 1, 1)};
  const Posed b{&s, &box, Matrix3::Identity(), Vector3::Zero(), {}};
  std::vector<ContactPoint> points;
  SpherePolytope(Vector3(0.3, -0.2, 1.4), 0.5, box, b, 0.0, true, 0, points);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0].separation, 1.4 - 1.0 - 0.5, 1e-12);
  EXPECT_NEAR(points[0].normal.z(), 1.0, 1e-12);  // into the sphere
  // Over a corner: the distance to the corner decides.
  points.clear();
  const Vector3 c = Vector3(1, 1, 1) + 0.45 * Vector3(1, 1, 1).normalized();
  SpherePolytope(c, 0.5, box, b, 0.0, true, 0, points);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0].separation, 0.45 - 0.5, 1e-12);
  EXPECT_NEAR(points[0].normal.dot(Vector3(1, 1, 1).normalized()), 1.0, 1e-12);
}

}  // namespace
}  // namespace dynamics::contact
