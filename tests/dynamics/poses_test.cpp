// Resting poses (dynamics/poses.h) against independent truth: the quasi-static probabilities of
// boxes, a triangular prism and a truncated cone against solid angles computed here by other means
// (the closed form of a rectangle's solid angle; directions on a Fibonacci sphere, each assigned
// to the face its ray leaves through); symmetric parts (cube, regular tetrahedron) whose every face
// is equally likely; and drops that see the dynamics (a 1×2×3 box lands on its large faces more
// often than on its small ones, and differently with restitution 0 and 0.5).

#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "dynamics/poses.h"

namespace dynamics::poses {
namespace {

using massprops::kPi;

// A convex solid given by its corners, as triangles, each turned to face away from the centroid.
struct Solid {
  std::vector<Vector3> v;
  std::vector<std::array<int, 3>> t;
};

void Outward(Solid& s) {
  Vector3 centroid = Vector3::Zero();
  for (const Vector3& x : s.v) centroid += x;
  centroid /= static_cast<double>(s.v.size());
  for (auto& tri : s.t) {
    const Vector3 &a = s.v[tri[0]], &b = s.v[tri[1]], &c = s.v[tri[2]];
    if ((b - a).cross(c - a).dot((a + b + c) / 3 - centroid) < 0) std::swap(tri[1], tri[2]);
  }
}

Solid Box(double a, double b, double c) {
  Solid s;
  for (int i = 0; i < 8; ++i)
    s.v.emplace_back((i & 1 ? 0.5 : -0.5) * a, (i & 2 ? 0.5 : -0.5) * b, (i & 4 ? 0.5 : -0.5) * c);
  s.t = {{0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
         {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}};
  Outward(s);
  return s;
}

Solid Tetrahedron(double size) {
  Solid s{{Vector3(1, 1, 1) * size, Vector3(1, -1, -1) * size, Vector3(-1, 1, -1) * size, Vector3(-1, -1, 1) * size},
          {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}};
  Outward(s);
  return s;
}

// A prism along z over the triangle (p0, p1, p2) of the xy-plane, from z = 0 to z = length.
Solid Prism(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2, double length) {
  Solid s;
  for (double z : {0.0, length})
    for (const auto& p : {p0, p1, p2}) s.v.emplace_back(p.x(), p.y(), z);
  s.t = {{0, 1, 2}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  Outward(s);
  return s;
}

// A truncated cone of n sides: radius r0 at z = 0, r1 at z = height.
Solid Frustum(double r0, double r1, double height, int n) {
  Solid s;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    s.v.emplace_back(r0 * std::cos(a), r0 * std::sin(a), 0);
    s.v.emplace_back(r1 * std::cos(a), r1 * std::sin(a), height);
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    s.t.push_back({2 * i, 2 * j, 2 * j + 1});
    s.t.push_back({2 * i, 2 * j + 1, 2 * i + 1});
    if (i >= 1 && i + 1 < n) {
      s.t.push_back({0, 2 * i, 2 * j});
      s.t.push_back({1, 2 * i + 1, 2 * j + 1});
    }
  }
  Outward(s);
  return s;
}

// Mass properties of a uniform solid, by the divergence theorem over tetrahedra from the centroid
// (independent of massprops' integrators, which the library's users call).
massprops::MassProperties MassOf(const Solid& s, double density) {
  Vector3 o = Vector3::Zero();
  for (const Vector3& x : s.v) o += x;
  o /= static_cast<double>(s.v.size());
  double volume = 0;
  Vector3 first = Vector3::Zero();
  Matrix3 second = Matrix3::Zero();
  for (const auto& tri : s.t) {
    const Vector3 a = s.v[tri[0]] - o, b = s.v[tri[1]] - o, c = s.v[tri[2]] - o;
    const double d = a.dot(b.cross(c));
    volume += d / 6;
    first += d * (a + b + c) / 24;
    const Vector3 sum = a + b + c;
    second += d * (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose()) / 120;
  }
  massprops::MassProperties mp;
  mp.volume = volume;
  mp.density = density;
  mp.mass = density * volume;
  const Vector3 com = first / volume;
  mp.center_of_mass = o + com;
  const Matrix3 about_com = density * (second - volume * com * com.transpose());
  mp.inertia_com = Matrix3::Identity() * about_com.trace() - about_com;
  return mp;
}

Part PartOf(const Solid& s, double density = 1000, Material material = {}) {
  Part p;
  p.mass_properties = MassOf(s, density);
  p.hull_vertices = s.v;
  p.hull_triangles = s.t;
  p.material = material;
  return p;
}

// Solid angle fractions by face normal: directions on a Fibonacci sphere about the center of mass,
// each given to the face through which its ray leaves the solid.
std::vector<std::pair<Vector3, double>> RayFractions(const Solid& s, const Vector3& com, int directions) {
  std::vector<Vector3> normals;
  std::vector<double> offsets;
  for (const auto& tri : s.t) {
    const Vector3 n = (s.v[tri[1]] - s.v[tri[0]]).cross(s.v[tri[2]] - s.v[tri[0]]).normalized();
    normals.push_back(n);
    offsets.push_back(n.dot(s.v[tri[0]] - com));
  }
  std::vector<std::pair<Vector3, double>> out;
  const double golden = kPi * (3 - std::sqrt(5.0));
  for (int i = 0; i < directions; ++i) {
    const double z = 1 - (2 * i + 1.0) / directions, r = std::sqrt(1 - z * z);
    const Vector3 d(r * std::cos(golden * i), r * std::sin(golden * i), z);
    double nearest = std::numeric_limits<double>::infinity();
    std::size_t hit = 0;
    for (std::size_t f = 0; f < normals.size(); ++f) {
      const double along = normals[f].dot(d);
      if (along > 0 && offsets[f] / along < nearest) nearest = offsets[f] / along, hit = f;
    }
    bool found = false;
    for (auto& [n, share] : out)
      if (n.dot(normals[hit]) > 1 - 1e-9) share += 1.0 / directions, found = true;
    if (!found) out.emplace_back(normals[hit], 1.0 / directions);
  }
  return out;
}

double FractionAlong(const std::vector<std::pair<Vector3, double>>& fractions, const Vector3& normal) {
  for (const auto& [n, share] : fractions)
    if (n.dot(normal) > 1 - 1e-9) return share;
  return 0;
}

const Pose* PoseAlong(const Estimate& e, const Vector3& normal) {
  for (const Pose& p : e.poses)
    if (p.normal.dot(normal) > 1 - 1e-9) return &p;
  return nullptr;
}

// Solid angle of an a×b rectangle seen from distance d on its axis.
double RectangleSolidAngle(double a, double b, double d) {
  return 4 * std::asin(a * b / std::sqrt((a * a + 4 * d * d) * (b * b + 4 * d * d)));
}

TEST(QuasiStatic, BoxFacesHaveTheirRectanglesSolidAngles) {
  const double a = 0.1, b = 0.2, c = 0.3;
  const Estimate e = QuasiStatic(PartOf(Box(a, b, c)));
  ASSERT_EQ(e.poses.size(), 6u);
  const double expect_z = RectangleSolidAngle(a, b, c / 2) / (4 * kPi);  // the a×b faces
  const double expect_y = RectangleSolidAngle(a, c, b / 2) / (4 * kPi);
  const double expect_x = RectangleSolidAngle(b, c, a / 2) / (4 * kPi);
  EXPECT_NEAR(PoseAlong(e, Vector3::UnitZ())->quasi_static, expect_z, 1e-14);
  EXPECT_NEAR(PoseAlong(e, -Vector3::UnitY())->quasi_static, expect_y, 1e-14);
  EXPECT_NEAR(PoseAlong(e, Vector3::UnitX())->quasi_static, expect_x, 1e-14);
  EXPECT_NEAR(2 * (expect_x + expect_y + expect_z), 1.0, 1e-14);
  // Most likely first: the b×c faces (normal ±x), whose center of mass sits lowest.
  EXPECT_NEAR(std::abs(e.poses[0].normal.x()), 1.0, 1e-15);
  // At rest on its face: the face's normal points down, the center of mass at half the thickness.
  for (const Pose& p : e.poses) {
    EXPECT_NEAR((p.rotation * p.normal - Vector3(0, 0, -1)).norm(), 0, 1e-15);
    const Vector3 com = p.rotation * Vector3::Zero() + p.translation;
    EXPECT_NEAR(com.z(), std::abs(p.normal.dot(Vector3(a, b, c))) / 2, 1e-15);
    EXPECT_EQ(p.hull_faces.size(), 2u);
  }
}

TEST(QuasiStatic, CubeAndTetrahedronAreFair) {
  for (const Pose& p : QuasiStatic(PartOf(Box(0.05, 0.05, 0.05))).poses) EXPECT_NEAR(p.quasi_static, 1.0 / 6, 1e-14);
  const Estimate t = QuasiStatic(PartOf(Tetrahedron(0.03)));
  ASSERT_EQ(t.poses.size(), 4u);
  for (const Pose& p : t.poses) EXPECT_NEAR(p.quasi_static, 0.25, 1e-14);
}

TEST(QuasiStatic, ObtusePrismTopplesOffItsShortSide) {
  // Cross-section A (0, 0), B (3, 0), C (0.5, 0.3): the center of mass projects onto side AC's
  // line beyond C, so the prism lying on AC rolls over C's edge onto side CB.
  const Eigen::Vector2d A(0, 0), B(3, 0), C(0.5, 0.3);
  const Solid s = Prism(A, B, C, 2.0);
  const Part part = PartOf(s);
  const Estimate e = QuasiStatic(part);
  const auto rays = RayFractions(s, part.mass_properties.center_of_mass, 400000);
  auto outward = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {  // of side p→q, counter-clockwise
    return Vector3(q.y() - p.y(), p.x() - q.x(), 0).normalized();
  };
  const Vector3 n_ab = outward(A, B), n_bc = outward(B, C), n_ca = outward(C, A);
  ASSERT_EQ(e.poses.size(), 4u);  // AB, BC and the two ends; CA is not a pose
  EXPECT_EQ(PoseAlong(e, n_ca), nullptr);
  EXPECT_NEAR(PoseAlong(e, n_ab)->quasi_static, FractionAlong(rays, n_ab), 2e-4);
  EXPECT_NEAR(PoseAlong(e, n_bc)->quasi_static, FractionAlong(rays, n_bc) + FractionAlong(rays, n_ca), 2e-4);
  EXPECT_NEAR(PoseAlong(e, Vector3::UnitZ())->quasi_static, FractionAlong(rays, Vector3::UnitZ()), 2e-4);
  EXPECT_GT(FractionAlong(rays, n_ca), 0.03);  // the transfer is not negligible
}

TEST(QuasiStatic, TruncatedConeFacesHaveTheirSolidAngles) {
  const Solid s = Frustum(1.0, 0.6, 0.8, 24);
  const Part part = PartOf(s);
  const Estimate e = QuasiStatic(part);
  const auto rays = RayFractions(s, part.mass_properties.center_of_mass, 400000);
  ASSERT_EQ(e.poses.size(), 26u);  // every face is stable: both ends and the 24 sides
  double total = 0;
  for (const Pose& p : e.poses) {
    EXPECT_NEAR(p.quasi_static, FractionAlong(rays, p.normal), 2e-4);
    total += p.quasi_static;
  }
  EXPECT_NEAR(total, 1.0, 1e-13);
  EXPECT_NEAR(e.poses[0].normal.z(), -1.0, 1e-15);  // the big end is the most likely
}

// Each triangle split into four at its edges' midpoints (shared, so the surface stays closed):
// faces become many coplanar triangles and edges chains of collinear pieces.
Solid Subdivided(const Solid& s) {
  Solid out{s.v, {}};
  std::map<std::pair<int, int>, int> middle;
  auto mid = [&](int a, int b) {
    const auto key = std::pair{std::min(a, b), std::max(a, b)};
    auto it = middle.find(key);
    if (it != middle.end()) return it->second;
    out.v.push_back((s.v[static_cast<std::size_t>(a)] + s.v[static_cast<std::size_t>(b)]) / 2);
    return middle[key] = static_cast<int>(out.v.size()) - 1;
  };
  for (const auto& t : s.t) {
    const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
    out.t.push_back({t[0], ab, ca});
    out.t.push_back({ab, t[1], bc});
    out.t.push_back({ca, bc, t[2]});
    out.t.push_back({ab, bc, ca});
  }
  return out;
}

TEST(QuasiStatic, TessellatedFacesAndEdgesChangeNothing) {
  // A hull as a mesh tool writes it: faces in many triangles, edges with corners along them. The
  // obtuse prism still topples over its tessellated edge onto the same face.
  const Eigen::Vector2d A(0, 0), B(3, 0), C(0.5, 0.3);
  for (const Solid& s : {Box(0.1, 0.2, 0.3), Prism(A, B, C, 2.0)}) {
    const Estimate plain = QuasiStatic(PartOf(s));
    const Solid fine = Subdivided(Subdivided(s));
    const Estimate tessellated = QuasiStatic(PartOf(fine));
    ASSERT_EQ(tessellated.poses.size(), plain.poses.size());
    for (std::size_t p = 0; p < plain.poses.size(); ++p) {
      EXPECT_NEAR((tessellated.poses[p].normal - plain.poses[p].normal).norm(), 0, 1e-12);
      EXPECT_NEAR(tessellated.poses[p].quasi_static, plain.poses[p].quasi_static, 1e-12);
      EXPECT_EQ(tessellated.poses[p].hull_faces.size(), 16 * plain.poses[p].hull_faces.size());
    }
    EXPECT_EQ(tessellated.faces.normals.size(), plain.faces.normals.size());
  }
}

TEST(QuasiStatic, FinelyFacetedConeMatchesTheDiskSolidAngle) {
  // 6000 sides: neighbouring side faces turn by 0.06°, and each one's corners lie within 10⁻⁶ of
  // the next one's plane (a construction that took every corner near a plane as the face's came
  // apart here). The ends are disks to 5·10⁻⁷: Ω = 2π (1 − d/√(d² + r²)) from the center of mass.
  const double r0 = 1.0, r1 = 0.6, h = 0.8;
  const Part part = PartOf(Frustum(r0, r1, h, 6000));
  const Estimate e = QuasiStatic(part);
  const double zc = part.mass_properties.center_of_mass.z();
  auto disk = [](double d, double r) { return 2 * kPi * (1 - d / std::sqrt(d * d + r * r)) / (4 * kPi); };
  EXPECT_NEAR(PoseAlong(e, -Vector3::UnitZ())->quasi_static, disk(zc, r0), 1e-6);
  EXPECT_NEAR(PoseAlong(e, Vector3::UnitZ())->quasi_static, disk(h - zc, r1), 1e-6);
  double total = 0;
  for (const Pose& p : e.poses) total += p.quasi_static;
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_EQ(e.faces.normals.size(), 6002u);
}

TEST(QuasiStatic, RefusesACenterOfMassOutsideTheHull) {
  Part part = PartOf(Box(1, 1, 1));
  part.mass_properties.center_of_mass = Vector3(2, 0, 0);
  EXPECT_THROW(QuasiStatic(part), std::invalid_argument);
}

TEST(Intervals, WilsonAndGoodmanAgainstPublishedValues) {
  // Wilson 95 % for 8/20 (Newcombe, Stat. Med. 17, 1998, Table I: 0.2188 to 0.6134).
  const Interval w = BinomialInterval(8, 20);
  EXPECT_NEAR(w.low, 0.2188, 5e-5);
  EXPECT_NEAR(w.high, 0.6134, 5e-5);
  // Goodman's intervals are Wilson's at z² = χ²₁(1 − α/K): wider than each binomial one.
  const std::vector<std::int64_t> counts{30, 50, 20};
  const auto sim = SimultaneousIntervals(counts);
  const double z = 2.39398;  // the normal quantile at 1 − 0.05/6
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double k = static_cast<double>(counts[i]), n = 100, a = z * z;
    EXPECT_NEAR(sim[i].low, (k + a / 2 - std::sqrt(a * (k * (n - k) / n + a / 4))) / (n + a), 1e-5);
    EXPECT_LT(sim[i].low, BinomialInterval(counts[i], 100).low);
  }
}

// Drops (simulated): small parts dropped 5 cm onto a plane.
DropOptions Drops(std::uint64_t seed, double restitution = 0) {
  DropOptions o;
  o.height = 0.05;
  o.seed = seed;
  o.ground = Material{0.5, 0.4, restitution};
  o.threads = 0;
  return o;
}

Tally DropTally(const Part& part, const DropOptions& o, std::int64_t n, Estimate* estimate = nullptr) {
  const Estimate e = QuasiStatic(part);
  if (estimate) *estimate = e;
  return Count(Drop(part, e, o, 0, n), e.poses.size());
}

TEST(Drops, CubeAndTetrahedronLandOnEveryFaceAlike) {
  for (const Solid& s : {Box(0.04, 0.04, 0.04), Tetrahedron(0.02)}) {
    const Part part = PartOf(s);
    const Tally t = DropTally(part, Drops(7), 600);
    EXPECT_EQ(t.not_settled + t.other_face, 0);
    const double fair = 1.0 / static_cast<double>(t.counts.size());
    for (const Interval& i : t.simultaneous) {
      EXPECT_LE(i.low, fair);
      EXPECT_GE(i.high, fair);
    }
  }
}

TEST(Drops, BoxLandsOnItsLargeFacesAndRestitutionMatters) {
  const Part part = PartOf(Box(0.01, 0.02, 0.03));
  Estimate e;
  const Tally still = DropTally(part, Drops(11, 0.0), 1000, &e);
  const Tally bouncy = DropTally(part, Drops(11, 0.5), 1000);
  ASSERT_EQ(still.not_settled + bouncy.not_settled, 0);
  auto by_axis = [&](const Tally& t) {  // drops per pair of faces: normal along x, y, z
    std::array<std::int64_t, 3> n{};
    for (std::size_t p = 0; p < e.poses.size(); ++p) {
      int axis = 0;
      e.poses[p].normal.cwiseAbs().maxCoeff(&axis);
      n[static_cast<std::size_t>(axis)] += t.counts[p];
    }
    return n;
  };
  const auto a = by_axis(still), b = by_axis(bouncy);
  // The 2×3 faces (normal x) against the 1×2 faces (normal z): simultaneous intervals apart.
  const auto sa = SimultaneousIntervals({a[0], a[1], a[2]});
  EXPECT_GT(sa[0].low, sa[2].high);
  // Restitution 0 against 0.5: a χ² test of homogeneity over the three pairs of faces, p < 0.001.
  double chi2 = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const double total = static_cast<double>(a[k] + b[k]);
    for (double observed : {static_cast<double>(a[k]), static_cast<double>(b[k])}) {
      const double expected = total / 2;
      chi2 += (observed - expected) * (observed - expected) / expected;
    }
  }
  EXPECT_GT(chi2, 13.82) << "x: " << a[0] << " vs " << b[0] << ", y: " << a[1] << " vs " << b[1] << ", z: " << a[2]
                         << " vs " << b[2];
}

TEST(Drops, FourTimesTheDropsHalveTheInterval) {
  const Part part = PartOf(Box(0.01, 0.02, 0.03));
  const Estimate e = QuasiStatic(part);
  const auto outcomes = Drop(part, e, Drops(3), 0, 800);
  const Tally quarter = Count({outcomes.begin(), outcomes.begin() + 200}, e.poses.size());
  const Tally all = Count(outcomes, e.poses.size());
  for (std::size_t p = 0; p < e.poses.size(); ++p) {
    const double ratio =
        (all.binomial[p].high - all.binomial[p].low) / (quarter.binomial[p].high - quarter.binomial[p].low);
    EXPECT_NEAR(ratio, 0.5, 0.12) << "pose " << p;
  }
}

TEST(Drops, SameBitsForAnyThreadCountAndBatching) {
  const Part part = PartOf(Tetrahedron(0.02));
  const Estimate e = QuasiStatic(part);
  DropOptions one = Drops(5);
  one.threads = 1;
  DropOptions two = one;
  two.threads = 2;
  const auto a = Drop(part, e, one, 0, 12);
  const auto b = Drop(part, e, two, 0, 12);
  const auto c = Drop(part, e, two, 7, 5);  // drops 7..11 alone
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].pose, b[i].pose);
    EXPECT_EQ(a[i].orientation.coeffs(), b[i].orientation.coeffs());
    EXPECT_EQ(a[i].position, b[i].position);
    if (i >= 7) {
      EXPECT_EQ(a[i].orientation.coeffs(), c[i - 7].orientation.coeffs());
    }
  }
}

TEST(Drops, OrientationsAreUniformOnTheSphereOfRotations) {
  // The rotated z axis of uniform rotations is uniform on the sphere: each octant 1/8, and the
  // mean of cos θ is 0 (and of cos² θ, 1/3).
  const int n = 80000;
  std::array<int, 8> octant{};
  double c1 = 0, c2 = 0;
  for (int k = 0; k < n; ++k) {
    const Vector3 z = DropOrientation(42, k) * Vector3::UnitZ();
    ++octant[static_cast<std::size_t>((z.x() > 0) + 2 * (z.y() > 0) + 4 * (z.z() > 0))];
    c1 += z.z() / n;
    c2 += z.z() * z.z() / n;
  }
  for (int count : octant) EXPECT_NEAR(count, n / 8.0, 5 * std::sqrt(n / 8.0));
  EXPECT_NEAR(c1, 0, 5 / std::sqrt(3.0 * n));
  EXPECT_NEAR(c2, 1.0 / 3, 5 * std::sqrt(4.0 / 45 / n));
}

}  // namespace
}  // namespace dynamics::poses
