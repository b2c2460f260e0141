// The triangle-soup (binary STL) path: equal to the indexed path, order-independent, the same
// bits for any thread count, and its streaming closed-surface check.

#include "massprops/triangle_soup.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <numeric>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/io/mesh_io.h"
#include "massprops/mesh_topology.h"
#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::ExpectMassPropertiesNear;
using ::testing::HasSubstr;

// Binary STL bytes (little-endian) of a triangle mesh, coordinates rounded to float32.
std::string StlBytes(const TriangleMesh& m) {
  std::string s(80, ' ');
  const auto n = static_cast<std::uint32_t>(m.F.rows());
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    float rec[12] = {};
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) rec[3 + 3 * k + j] = static_cast<float>(m.V(m.F(f, k), j));
    }
    s.append(reinterpret_cast<const char*>(rec), sizeof rec);
    s.append(2, '\0');
  }
  return s;
}

SoupIntegrals Soup(const std::string& bytes, int threads = 0) {
  IntegrationOptions opt;
  opt.num_threads = threads;
  return IntegrateFloatTriangleRecords(reinterpret_cast<const unsigned char*>(bytes.data()) + 84,
                                       (static_cast<std::int64_t>(bytes.size()) - 84) / 50, 50, 12, opt);
}

TriangleMesh OffsetTorus() {
  TriangleMesh m = solids::Torus(2.0, 0.5, 60);
  std::mt19937_64 rng(4);
  m.V = testing::Transform(m.V, testing::RandomRotation(rng), Vector3(120.0, -35.5, 8.25));
  return m;
}

// m with face f appended once more at the end (and reversed after it, if asked).
TriangleMesh WithFaceAgain(const TriangleMesh& m, Eigen::Index f, bool reversed_too) {
  TriangleMesh out = m;
  out.F.conservativeResize(m.F.rows() + (reversed_too ? 2 : 1), 3);
  out.F.row(m.F.rows()) = m.F.row(f);
  if (reversed_too) out.F.row(m.F.rows() + 1) << m.F(f, 0), m.F(f, 2), m.F(f, 1);
  return out;
}

// m's faces, then all of them again.
TriangleMesh SurfaceTwice(const TriangleMesh& m) {
  TriangleMesh out;
  out.V = m.V;
  out.F.resize(2 * m.F.rows(), 3);
  out.F << m.F, m.F;
  return out;
}

TEST(TriangleSoup, EqualsTheIndexedPathOnTheSameFile) {
  const std::string path = ::testing::TempDir() + "torus.stl";
  std::ofstream(path, std::ios::binary) << StlBytes(OffsetTorus());
  const LoadedMesh indexed = ReadMeshFile(path);  // welded, float32 → double exactly
  const MassProperties a = ComputeMassProperties(Triangulate(indexed.mesh), 1.0);
  const auto soup = IntegrateBinaryStlFile(path);
  ASSERT_TRUE(soup.has_value());
  EXPECT_TRUE(soup->IsClosedCycle());
  EXPECT_EQ(soup->triangles, indexed.mesh.num_faces());
  const MassProperties b = FromIntegrals(soup->integrals, 1.0);
  ExpectMassPropertiesNear(b, a, 1e-14, 3.0);
  EXPECT_TRUE(testing::NearRel(b.surface_area, a.surface_area, 1e-14));
  EXPECT_TRUE(testing::MatrixNearRel(soup->lower, Vector3(indexed.mesh.V.colwise().minCoeff()), 0, 1));
}

TEST(TriangleSoup, IndependentOfTriangleOrderAndThreadCount) {
  const TriangleMesh m = OffsetTorus();
  const std::string bytes = StlBytes(m);
  const SoupIntegrals one = Soup(bytes, 1);
  for (int threads : {2, 3, 0}) {
    const SoupIntegrals many = Soup(bytes, threads);
    EXPECT_TRUE(testing::SameBits(FromIntegrals(many.integrals, 2.0), FromIntegrals(one.integrals, 2.0)));
    EXPECT_EQ(many.unmatched_edge_hash, one.unmatched_edge_hash);
  }
  // Shuffled records (the first one kept, so the reference point is the same): same hash, same
  // numbers to rounding.
  TriangleMesh shuffled = m;
  std::mt19937_64 rng(8);
  std::vector<Eigen::Index> order(static_cast<std::size_t>(m.F.rows()));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin() + 1, order.end(), rng);
  for (std::size_t i = 0; i < order.size(); ++i) shuffled.F.row(static_cast<Eigen::Index>(i)) = m.F.row(order[i]);
  const SoupIntegrals s = Soup(StlBytes(shuffled));
  EXPECT_TRUE(s.IsClosedCycle());
  ExpectMassPropertiesNear(FromIntegrals(s.integrals, 1.0), FromIntegrals(one.integrals, 1.0), 1e-14, 3.0);
}

TEST(TriangleSoup, StreamingCheckFindsHolesAndFlippedFaces) {
  const TriangleMesh m = OffsetTorus();
  EXPECT_TRUE(Soup(StlBytes(m)).IsClosedCycle());
  TriangleMesh open = m;
  open.F.conservativeResize(m.F.rows() - 1, 3);
  EXPECT_FALSE(Soup(StlBytes(open)).IsClosedCycle());
  // Every single triangle of a regular grid mesh, flipped or dropped in turn, is noticed (a
  // structured mesh is where a weak hash would cancel). The hash is linear in the triangles, so
  // the contribution of each triangle is checked directly: flipping triangle f changes the sum by
  // twice its contribution, dropping it by its contribution; neither may be 0 (mod 2⁶⁴).
  TriangleMesh grid = solids::Torus(2.0, 0.5, 40);
  std::string bytes = StlBytes(grid);
  int missed = 0;
  for (Eigen::Index f = 0; f < grid.F.rows(); ++f) {
    const std::string one(bytes.data() + 84 + 50 * f, 50);
    const std::string rec = std::string(80, ' ') + std::string("\1\0\0\0", 4) + one;
    const std::uint64_t c = Soup(rec).unmatched_edge_hash;
    if (c == 0 || 2 * c == 0) ++missed;
  }
  EXPECT_EQ(missed, 0);
  for (Eigen::Index f : {Eigen::Index(0), Eigen::Index(777), m.F.rows() - 1}) {
    TriangleMesh flipped = m;
    std::swap(flipped.F(f, 1), flipped.F(f, 2));
    EXPECT_FALSE(Soup(StlBytes(flipped)).IsClosedCycle()) << f;
  }
  // Two closed boxes that share an edge: non-manifold, but a closed cycle whose integrals are
  // well defined (the sum of two solids), and the check says so.
  TriangleMesh a = Triangulate(solids::Box(Vector3(1, 1, 1)));
  TriangleMesh two;
  two.V.resize(16, 3);
  two.V << a.V, (a.V.rowwise() + Eigen::RowVector3d(1, 1, 0));
  two.F.resize(24, 3);
  two.F << a.F, (a.F.array() + 8);
  EXPECT_TRUE(Soup(StlBytes(two)).IsClosedCycle());
  const std::string path = ::testing::TempDir() + "two_boxes.stl";
  std::ofstream(path, std::ios::binary) << StlBytes(two);
  EXPECT_EQ(AnalyzeTopology(ReadMeshFile(path).mesh).non_manifold_edges, 1);  // welded view
}

// A face there twice is found by the face keys, in either orientation. A face added together with
// its reverse (a double-sided patch) and a whole second copy keep every edge matched: the cycle
// check alone passes them, with the volume unchanged or doubled.
TEST(TriangleSoup, RepeatedFacesAreFound) {
  const TriangleMesh m = OffsetTorus();
  EXPECT_FALSE(Soup(StlBytes(m)).repeated_faces);
  EXPECT_TRUE(Soup(StlBytes(WithFaceAgain(m, 321, false))).repeated_faces);
  const SoupIntegrals patch = Soup(StlBytes(WithFaceAgain(m, 321, true)));
  EXPECT_TRUE(patch.IsClosedCycle());
  EXPECT_TRUE(patch.repeated_faces);
  const SoupIntegrals c = Soup(StlBytes(SurfaceTwice(m)), 2);
  EXPECT_TRUE(c.IsClosedCycle());
  EXPECT_TRUE(c.repeated_faces);
}

// The same across the streamed path's groups (32 768 triangles each): a face repeated far from its
// first copy, a whole second surface in the next group, and a soup whose corners are all apart
// (each triangle its own shell: the corner table grows past what shared corners need).
TEST(TriangleSoup, RepeatedFacesAndShellsAcrossGroups) {
  const TriangleMesh m = solids::Torus(2.0, 0.5, 140);  // 78 400 triangles: three groups
  ASSERT_GT(m.F.rows(), 2 * 32768);
  const SoupIntegrals once = Soup(StlBytes(m), 2);
  EXPECT_FALSE(once.repeated_faces);
  EXPECT_EQ(once.shells, 1);
  // Group 0's face 7, again in group 2, in both orientations.
  const SoupIntegrals f = Soup(StlBytes(WithFaceAgain(m, 7, true)), 2);
  EXPECT_TRUE(f.IsClosedCycle());
  EXPECT_TRUE(f.repeated_faces);
  const TriangleMesh twice = SurfaceTwice(m);
  EXPECT_TRUE(Soup(StlBytes(twice), 1).repeated_faces);
  EXPECT_TRUE(Soup(StlBytes(twice), 2).repeated_faces);
  // The same file again on this thread, on one thread and on two: each search starts afresh (the
  // search's tables are kept between buckets and searches, and only its own keys count).
  for (int threads : {1, 2, 1}) EXPECT_FALSE(Soup(StlBytes(m), threads).repeated_faces) << threads;

  TriangleMesh apart;  // 40 000 triangles, no corner shared
  const int n = 40000;
  apart.V.resize(3 * n, 3);
  apart.F.resize(n, 3);
  for (int t = 0; t < n; ++t) {
    const double x = t % 200, y = t / 200;
    apart.V.row(3 * t) << x, y, 0;
    apart.V.row(3 * t + 1) << x + 0.5, y, 0;
    apart.V.row(3 * t + 2) << x, y + 0.5, 0.25;
    apart.F.row(t) << 3 * t, 3 * t + 1, 3 * t + 2;
  }
  const SoupIntegrals a = Soup(StlBytes(apart), 2);
  EXPECT_EQ(a.shells, n);
  EXPECT_FALSE(a.repeated_faces);
  EXPECT_FALSE(a.IsClosedCycle());
}

// Meshes side by side as one soup (vertex indices offset), the second's faces reversed if asked.
TriangleMesh Together(const TriangleMesh& a, const TriangleMesh& b, bool reverse_b = false) {
  TriangleMesh out;
  out.V.resize(a.V.rows() + b.V.rows(), 3);
  out.V << a.V, b.V;
  out.F.resize(a.F.rows() + b.F.rows(), 3);
  Eigen::MatrixXi fb = b.F.array() + static_cast<int>(a.V.rows());
  if (reverse_b) fb.col(1).swap(fb.col(2));
  out.F << a.F, fb;
  return out;
}

TriangleMesh Shuffled(const TriangleMesh& m, std::uint64_t seed) {
  TriangleMesh out = m;
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Index> order(static_cast<std::size_t>(m.F.rows()));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  for (std::size_t i = 0; i < order.size(); ++i) out.F.row(static_cast<Eigen::Index>(i)) = m.F.row(order[i]);
  return out;
}

// Shells are counted against the welded mesh's connected components (AnalyzeTopology, a second
// algorithm on indices): one torus, two nested tori (both outward: the case an edge balance cannot
// see), two overlapping ones, and a torus with a box touching it at one corner — in file order,
// shuffled, and on several threads. Blocks are 4096 triangles, so the meshes span many blocks.
TEST(TriangleSoup, CountsShellsAsTheWeldedMeshDoes) {
  const TriangleMesh torus = solids::Torus(2.0, 0.5, 80);  // 25 600 triangles
  TriangleMesh inner = solids::Torus(2.0, 0.25, 64);
  TriangleMesh beside = torus;
  beside.V.col(0).array() += 1.0;  // overlaps the first
  TriangleMesh box = Triangulate(solids::Box(Vector3(1, 1, 1)));
  box.V.rowwise() += (torus.V.row(5) - box.V.row(0));  // one corner on a corner of the torus
  const struct {
    const char* name;
    TriangleMesh mesh;
  } cases[] = {{"one torus", torus},
               {"nested, both outward", Together(torus, inner)},
               {"nested, inner reversed", Together(torus, inner, true)},
               {"overlapping", Together(torus, beside)},
               {"touching at a corner", Together(torus, box)},
               {"three", Together(Together(torus, inner), box)}};
  for (const auto& c : cases) {
    const std::string path = ::testing::TempDir() + "shells.stl";
    std::ofstream(path, std::ios::binary) << StlBytes(c.mesh);
    const std::int64_t welded = AnalyzeTopology(ReadMeshFile(path).mesh).components;
    const std::int64_t in_order = Soup(StlBytes(c.mesh), 1).shells;
    EXPECT_EQ(Soup(StlBytes(c.mesh), 2).shells, in_order) << c.name;
    if (std::string(c.name).find("corner") == std::string::npos && std::string(c.name) != "three") {
      EXPECT_EQ(in_order, welded) << c.name;
      EXPECT_EQ(Soup(StlBytes(Shuffled(c.mesh, 3)), 2).shells, welded) << c.name;
    } else {
      // A corner where two closed fans meet may be forgotten once its first fan is closed: the
      // count may then exceed the welded one (which only sends the file to the full check), never
      // fall below it.
      EXPECT_GE(in_order, welded) << c.name;
      EXPECT_GE(Soup(StlBytes(Shuffled(c.mesh, 3)), 2).shells, welded) << c.name;
    }
  }
  EXPECT_EQ(Soup(StlBytes(torus)).shells, 1);
  EXPECT_EQ(Soup(StlBytes(Together(torus, inner))).shells, 2);
}

// A torus cut into two tubes (the faces around the major angles 0 and π removed): two open shells,
// whose open corners the frontier must not join, in file order and shuffled.
TEST(TriangleSoup, ShellsOfCutMeshes) {
  const TriangleMesh torus = solids::Torus(2.0, 0.5, 80);
  TriangleMesh cut = torus;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index f = 0; f < torus.F.rows(); ++f) {
    bool drop = false;
    for (int k = 0; k < 3; ++k) {
      const Vector3 p = torus.V.row(torus.F(f, k));
      const double phi = std::atan2(p.y(), p.x());
      drop = drop || std::abs(phi) < 1e-9 || std::abs(std::abs(phi) - massprops::kPi) < 1e-9;
    }
    if (!drop) keep.push_back(f);
  }
  cut.F.resize(static_cast<Eigen::Index>(keep.size()), 3);
  for (std::size_t i = 0; i < keep.size(); ++i) cut.F.row(static_cast<Eigen::Index>(i)) = torus.F.row(keep[i]);
  const std::string path = ::testing::TempDir() + "cut.stl";
  std::ofstream(path, std::ios::binary) << StlBytes(cut);
  EXPECT_EQ(AnalyzeTopology(ReadMeshFile(path).mesh).components, 2);
  EXPECT_EQ(Soup(StlBytes(cut), 2).shells, 2);
  EXPECT_EQ(Soup(StlBytes(Shuffled(cut, 5)), 2).shells, 2);
}

TEST(TriangleSoup, RejectsNonFiniteNamingTheTriangle) {
  std::string bytes = StlBytes(OffsetTorus());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&bytes[84 + 50 * 5000 + 12 + 4 * 7], &nan, 4);
  EXPECT_THAT([&] { Soup(bytes); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("triangle 5000")));
}

}  // namespace
}  // namespace massprops
