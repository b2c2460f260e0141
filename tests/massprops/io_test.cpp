// Mesh files: every reader path on the meshes in data/, published values for them, both
// integration paths agreeing on real meshes, and every kind of bad input named in the error.

#include "massprops/io.h"

#include <cstdio>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/composition.h"
#include "massprops/mass_properties.h"
#include "massprops/mesh_topology.h"
#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::DataPath;
using testing::ExpectMassPropertiesNear;
using testing::MatrixNearRel;
using testing::NearRel;
using ::testing::HasSubstr;

// numpy-stl's tests quote MeshLab for these two files (ρ = 1, 6 decimals, tensor convention).
// MeshLab's HalfDonut Iyy (2.701025) is 1.2e-6 below the exact value for these float32
// coordinates (2.7010262...); numpy-stl accepts it through allclose's default rtol = 1e-5. We allow
// 2e-6 absolute on the inertia (< 1e-6 relative) and keep 1e-6 on the volume and center.
TEST(RealMeshes, HalfDonutMatchesMeshLab) {
  for (const char* name : {"meshes/HalfDonut_ascii.stl", "meshes/HalfDonut_binary.stl"}) {
    SCOPED_TRACE(name);
    const LoadedMesh m = ReadMeshFile(DataPath(name));
    EXPECT_EQ(m.mesh.num_faces(), 288);
    EXPECT_EQ(m.mesh.V.rows(), 144);  // STL corners welded into shared vertices
    EXPECT_TRUE(AnalyzeTopology(m.mesh).BoundsVolume());
    const MassProperties mp = ComputeMassProperties(Triangulate(m.mesh), 1.0);
    EXPECT_NEAR(mp.volume, 2.343149, 1e-6);
    EXPECT_TRUE(MatrixNearRel(mp.center_of_mass, Vector3(1.500001, 0.209472, 1.500001), 1e-6, 1.0));
    EXPECT_TRUE(MatrixNearRel(mp.inertia_com,
                              Vector3(1.390429, 2.701025, 1.390429).asDiagonal().toDenseMatrix(),
                              2e-6, 1.0));
  }
}

TEST(RealMeshes, MoonMatchesMeshLabIncludingTheProductOfInertiaSign) {
  const LoadedMesh m = ReadMeshFile(DataPath("meshes/Moon.stl"));
  EXPECT_EQ(m.format, "stl-binary");
  const MassProperties mp = ComputeMassProperties(Triangulate(m.mesh), 1.0);
  EXPECT_NEAR(mp.volume, 0.888723, 1e-6);
  EXPECT_TRUE(MatrixNearRel(mp.center_of_mass, Vector3(0.906913, 0.170731, 1.500001), 1e-6, 1.0));
  Matrix3 meshlab;
  meshlab << 0.562097, -0.000457, 0, -0.000457, 0.656851, 0, 0, 0, 0.112465;
  EXPECT_TRUE(MatrixNearRel(mp.inertia_com, meshlab, 1e-6, 1.0));
  EXPECT_LT(mp.inertia_com(0, 1), 0.0);  // tensor entry = −∫xy: x and y are positively correlated
}

// MuJoCo's cube_cup_quad.obj: a 0.1 cube on z ∈ [0, 0.1] with an open-topped 0.08 × 0.08 × 0.09
// pocket, as planar quads. Analytic truth: the box minus the pocket (closed forms).
TEST(RealMeshes, CubeCupQuadsMatchTheAnalyticPocketedCube) {
  const LoadedMesh m = ReadMeshFile(DataPath("meshes/cube_cup_quad.obj"));
  EXPECT_FALSE(IsAllTriangles(m.mesh));
  const MeshTopology t = AnalyzeTopology(m.mesh);
  EXPECT_TRUE(t.BoundsVolume()) << t.Problems();
  const MassProperties cube = Transformed(solids::BoxProperties(Vector3(0.1, 0.1, 0.1), 1000),
                                          Matrix3::Identity(), Vector3(0, 0, 0.05));
  const MassProperties pocket = Transformed(
      solids::BoxProperties(Vector3(0.08, 0.08, 0.09), 1000), Matrix3::Identity(), Vector3(0, 0, 0.055));
  const MassProperties want = Subtract(cube, pocket);
  ExpectMassPropertiesNear(ComputeMassProperties(m.mesh, 1000), want, 1e-9, 0.1);
  ExpectMassPropertiesNear(ComputeMassProperties(Triangulate(m.mesh), 1000), want, 1e-9, 0.1);
}

// Both integration paths on every real mesh shipped in data/: 1e-12 relative.
TEST(RealMeshes, BothPathsAgree) {
  for (const char* name : {"meshes/spot.obj", "meshes/cube_cup_quad.obj", "meshes/Moon.stl",
                           "meshes/HalfDonut_binary.stl", "meshes/HalfDonut_ascii.stl"}) {
    SCOPED_TRACE(name);
    const LoadedMesh m = ReadMeshFile(DataPath(name));
    const TriangleMesh tri = Triangulate(m.mesh);
    const MassProperties a = ComputeMassProperties(tri, 1.0);
    const MassProperties b = ComputeMassProperties(ToPolygonMesh(tri), 1.0);
    const MassProperties c = ComputeMassProperties(m.mesh, 1.0);
    const double size = (m.mesh.V.colwise().maxCoeff() - m.mesh.V.colwise().minCoeff()).norm();
    ExpectMassPropertiesNear(a, b, 1e-12, size);
    ExpectMassPropertiesNear(a, c, 1e-12, size);
  }
}

TEST(RealMeshes, SpotIsAClosedGenusZeroShell) {
  const LoadedMesh m = ReadMeshFile(DataPath("meshes/spot.obj"));
  const MeshTopology t = AnalyzeTopology(m.mesh);
  EXPECT_EQ(t.faces, 5856);
  EXPECT_EQ(t.vertices, 2930);
  EXPECT_EQ(t.components, 1);
  EXPECT_TRUE(t.BoundsVolume());
  EXPECT_EQ(t.vertices - t.edges + t.faces, 2);  // Euler characteristic of a sphere
  // The volume does not depend on where the mesh sits (it would for an open one).
  TriangleMesh tri = Triangulate(m.mesh);
  const double v0 = ComputeMassProperties(tri, 1.0).volume;
  tri.V = testing::Transform(tri.V, Matrix3::Identity(), Vector3(250, -40, 7));
  EXPECT_TRUE(NearRel(ComputeMassProperties(tri, 1.0).volume, v0, 1e-12));
}

// ---- bad input ----

class BadFiles : public ::testing::Test {
 protected:
  std::string Write(const std::string& name, const std::string& bytes) {
    const std::string path = ::testing::TempDir() + name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  static std::string BinaryStl(std::uint32_t declared, int records) {
    std::string s(80, ' ');
    s.append(reinterpret_cast<const char*>(&declared), 4);
    s.append(std::string(50 * records, '\0'));
    return s;
  }
};

TEST_F(BadFiles, MissingEmptyAndUnknownFormat) {
  EXPECT_THAT([] { ReadMeshFile("/nonexistent/part.stl"); },
              ::testing::ThrowsMessage<MeshFileError>(HasSubstr("/nonexistent/part.stl: cannot open")));
  const std::string empty = Write("empty.obj", "");
  EXPECT_THAT([&] { ReadMeshFile(empty); },
              ::testing::ThrowsMessage<MeshFileError>(HasSubstr("empty.obj: the file is empty")));
  const std::string step = Write("part.step", "ISO-10303-21;");
  EXPECT_THAT([&] { ReadMeshFile(step); },
              ::testing::ThrowsMessage<MeshFileError>(HasSubstr("unknown mesh format 'step'")));
}

TEST_F(BadFiles, TruncatedBinaryStl) {
  const std::string path = Write("truncated.stl", BinaryStl(10, 7));
  EXPECT_THAT([&] { ReadMeshFile(path); },
              ::testing::ThrowsMessage<MeshFileError>(
                  HasSubstr("header says 10 triangles, which need 584 bytes, but the file has 434")));
}

TEST_F(BadFiles, BinaryStlWithSolidHeaderAndTrailingByteIsStillBinary) {
  // The shipped HalfDonut_binary.stl starts with "solid" and has one byte after its records.
  const LoadedMesh m = ReadMeshFile(DataPath("meshes/HalfDonut_binary.stl"));
  EXPECT_EQ(m.format, "stl-binary");
  EXPECT_EQ(m.mesh.num_faces(), 288);
}

TEST_F(BadFiles, AsciiStlGarbageAndNonFinite) {
  const std::string garbage =
      Write("garbage.stl", "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 zero\n");
  EXPECT_THAT([&] { ReadMeshFile(garbage); },
              ::testing::ThrowsMessage<MeshFileError>(HasSubstr("line 4: expected a number")));
  const std::string two =
      Write("two.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"
                       "endfacet\nendsolid x\n");
  EXPECT_THAT([&] { ReadMeshFile(two); },
              ::testing::ThrowsMessage<MeshFileError>(HasSubstr("a facet has 2 vertices")));
  const std::string nan =
      Write("nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nan\nvertex 1 0 0\n"
                       "vertex 0 1 0\nendloop\nendfacet\nendsolid x\n");
  EXPECT_THAT([&] { ReadMeshFile(nan); },
              ::testing::ThrowsMessage<MeshFileError>(HasSubstr("non-finite")));
}

TEST_F(BadFiles, ObjFaults) {
  const std::string range = Write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  EXPECT_THAT([&] { ReadMeshFile(range); },
              ::testing::ThrowsMessage<MeshFileError>(
                  HasSubstr("range.obj: line 4: face index 4 is out of range (3 vertices so far)")));
  const std::string inf = Write("inf.obj", "v 0 0 0\nv 1 inf 0\n");
  EXPECT_THAT([&] { ReadMeshFile(inf); },
              ::testing::ThrowsMessage<MeshFileError>(HasSubstr("line 2: non-finite coordinate")));
  const std::string text = Write("text.obj", "v 0 0 zero\n");
  EXPECT_THAT([&] { ReadMeshFile(text); },
              ::testing::ThrowsMessage<MeshFileError>(HasSubstr("expected a coordinate, got 'zero'")));
  const std::string nofaces = Write("nofaces.obj", "v 0 0 0\n# nothing else\n");
  EXPECT_THAT([&] { ReadMeshFile(nofaces); },
              ::testing::ThrowsMessage<MeshFileError>(HasSubstr("no faces")));
}

TEST_F(BadFiles, ObjSyntaxThatIsValid) {
  // Negative (relative) indices, v/vt/vn corners, CRLF, a continued line, comments, groups.
  const std::string path = Write(
      "valid.obj",
      "# tetrahedron\r\no tet\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nv 0 0 1\r\nvt 0 0\r\nvn 0 0 1\r\n"
      "g a\r\nf 1/1/1 3/1/1 2/1/1\r\nf 1//1 2//1 \\\r\n 4//1\r\nf -4 -1 -2\r\nf 2 3 4 # last\r\n");
  const LoadedMesh m = ReadMeshFile(path);
  EXPECT_EQ(m.mesh.num_faces(), 4);
  EXPECT_TRUE(AnalyzeTopology(m.mesh).BoundsVolume());
  EXPECT_TRUE(NearRel(ComputeMassProperties(m.mesh, 1.0).volume, 1.0 / 6, 1e-15));
}

TEST(Topology, FindsHolesNonManifoldAndFlippedFaces) {
  PolygonMesh box = solids::Box(Vector3(1, 1, 1));
  PolygonMesh open = box;
  open.indices.resize(20);
  open.offsets.resize(6);  // drop the last quad
  const MeshTopology t = AnalyzeTopology(open);
  EXPECT_EQ(t.boundary_edges, 4);
  EXPECT_THAT(t.Problems(), HasSubstr("open mesh: 4 boundary edges"));

  PolygonMesh flipped = box;
  std::reverse(flipped.indices.begin(), flipped.indices.begin() + 4);
  EXPECT_EQ(AnalyzeTopology(flipped).inconsistent_edges, 4);

  PolygonMesh fin = box;  // a fifth face on an existing edge
  fin.V.conservativeResize(9, 3);
  fin.V.row(8) << 2, 2, 2;
  fin.AddFace(std::vector<int>{1, 3, 8});
  EXPECT_EQ(AnalyzeTopology(fin).non_manifold_edges, 1);
}

}  // namespace
}  // namespace massprops
