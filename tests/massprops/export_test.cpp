// Robot-description inertials: the numbers in the text read back as the tensor's entries, with
// URDF/SDF's sign convention, and MJCF's quat + diaginertia rebuild the full tensor.

#include "massprops/export.h"

#include <random>
#include <regex>

#include <gtest/gtest.h>

#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::MatrixNearRel;

double Attr(const std::string& text, const std::string& name) {
  std::smatch m;
  const std::regex re(name + "=\"([^\"]+)\"");
  if (!std::regex_search(text, m, re)) ADD_FAILURE() << name << " missing in\n" << text;
  return std::stod(m[1]);
}

std::vector<double> Numbers(const std::string& s) {
  std::vector<double> out;
  std::istringstream in(s);
  for (double v; in >> v;) out.push_back(v);
  return out;
}

MassProperties TiltedTetra() {
  std::mt19937_64 rng(1);
  const TriangleMesh tet = solids::Tetrahedron(Vector3(0, 0, 0), Vector3(5, 0, 0), Vector3(0, 4, 0), Vector3(0, 0, 3));
  TriangleMesh m = tet;
  m.V = testing::Transform(tet.V, testing::RandomRotation(rng), Vector3(0.1, 0.2, 0.3));
  return ComputeMassProperties(m, 7.5);
}

TEST(Export, UrdfCarriesTheTensorEntriesExactly) {
  const MassProperties mp = TiltedTetra();
  const std::string urdf = UrdfInertial(mp);
  EXPECT_EQ(Attr(urdf, "value"), mp.mass);
  EXPECT_EQ(Attr(urdf, "ixx"), mp.inertia_com(0, 0));
  EXPECT_EQ(Attr(urdf, "ixy"), mp.inertia_com(0, 1));  // = −∫ρxy, not the product of inertia
  EXPECT_EQ(Attr(urdf, "ixz"), mp.inertia_com(0, 2));
  EXPECT_EQ(Attr(urdf, "iyy"), mp.inertia_com(1, 1));
  EXPECT_EQ(Attr(urdf, "iyz"), mp.inertia_com(1, 2));
  EXPECT_EQ(Attr(urdf, "izz"), mp.inertia_com(2, 2));
  std::smatch m;
  ASSERT_TRUE(std::regex_search(urdf, m, std::regex("xyz=\"([^\"]+)\"")));
  const auto xyz = Numbers(m[1]);
  ASSERT_EQ(xyz.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(xyz[k], mp.center_of_mass[k]);
}

TEST(Export, SdfCarriesTheTensorEntriesExactly) {
  const MassProperties mp = TiltedTetra();
  const std::string sdf = SdfInertial(mp);
  auto tag = [&](const std::string& name) {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(sdf, m, std::regex("<" + name + ">([^<]+)</" + name + ">")));
    return std::stod(m[1]);
  };
  EXPECT_EQ(tag("mass"), mp.mass);
  EXPECT_EQ(tag("ixy"), mp.inertia_com(0, 1));
  EXPECT_EQ(tag("iyz"), mp.inertia_com(1, 2));
  EXPECT_EQ(tag("izz"), mp.inertia_com(2, 2));
}

TEST(Export, MjcfQuatAndDiagonalRebuildTheTensor) {
  const MassProperties mp = TiltedTetra();
  const PrincipalInertia p = ComputePrincipalInertia(mp.inertia_com);
  const std::string mjcf = MjcfInertial(mp, p);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(mjcf, m, std::regex("quat=\"([^\"]+)\"")));
  const auto q = Numbers(m[1]);
  ASSERT_TRUE(std::regex_search(mjcf, m, std::regex("diaginertia=\"([^\"]+)\"")));
  const auto d = Numbers(m[1]);
  ASSERT_EQ(q.size(), 4u);
  ASSERT_EQ(d.size(), 3u);
  const Matrix3 R = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  const Matrix3 rebuilt = R * Vector3(d[0], d[1], d[2]).asDiagonal() * R.transpose();
  EXPECT_TRUE(MatrixNearRel(rebuilt, mp.inertia_com, 1e-14, mp.inertia_com.cwiseAbs().maxCoeff()));
  EXPECT_GE(q[0], 0.0);
  EXPECT_EQ(Attr(mjcf, "mass"), mp.mass);
}

TEST(Export, ExactDecimalRoundTrips) {
  for (double v : {0.1, 1.0 / 3.0, -2.5e-300, 6.02214076e23, 0.0}) {
    EXPECT_EQ(std::stod(ExactDecimal(v)), v);
  }
}

}  // namespace
}  // namespace massprops
