// massprops::robot against independent values: the demo arm of data/robots in URDF, SDFormat
// and MJCF. Primitives: closed forms written out here (not the library's), rotated and composed
// by hand. Meshes: the mesh file's vertices scaled, rotated and moved here, then integrated as a
// new mesh — a second path to the fill's (integrate once, then scale and move the integrals).

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "massprops/io/load.h"
#include "massprops/io/mesh_io.h"
#include "massprops/robot/robot.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::DataPath;
using ::testing::HasSubstr;

struct Body {  // mass, center of mass and inertia about it, in the link frame
  double m = 0;
  Vector3 c = Vector3::Zero();
  Matrix3 I = Matrix3::Zero();
};

Body Placed(double m, const Vector3& diag, const Matrix3& R, const Vector3& t) {
  return {m, t, R * diag.asDiagonal() * R.transpose()};
}

Body Sum(const std::vector<Body>& parts) {
  Body s;
  for (const Body& p : parts) {
    s.m += p.m;
    s.c += p.m * p.c;
  }
  s.c /= s.m;
  for (const Body& p : parts) {
    const Vector3 d = p.c - s.c;
    s.I += p.I + p.m * (d.squaredNorm() * Matrix3::Identity() - d * d.transpose());
  }
  return s;
}

Body Box(double rho, const Vector3& size, const Matrix3& R, const Vector3& t) {
  const double a = size[0], b = size[1], c = size[2], m = rho * a * b * c;
  return Placed(m, Vector3(b * b + c * c, a * a + c * c, a * a + b * b) * (m / 12), R, t);
}
Body Cylinder(double rho, double r, double h, const Matrix3& R, const Vector3& t) {
  const double m = rho * massprops::kPi * r * r * h;
  return Placed(m, Vector3(m * (3 * r * r + h * h) / 12, m * (3 * r * r + h * h) / 12, m * r * r / 2), R, t);
}
Body Sphere(double rho, double r, const Vector3& t) {
  const double m = rho * 4.0 / 3 * massprops::kPi * r * r * r;
  return Placed(m, Vector3::Constant(0.4 * m * r * r), Matrix3::Identity(), t);
}
// Cylinder part of length L between two hemispheres (each a hemisphere's 2/5 m r² about its flat
// face, moved to the capsule's center).
Body Capsule(double rho, double r, double L, const Matrix3& R, const Vector3& t) {
  const double mc = rho * massprops::kPi * r * r * L, ms = rho * 4.0 / 3 * massprops::kPi * r * r * r;
  const double across = mc * (L * L / 12 + r * r / 4) + ms * (0.4 * r * r + L * L / 4 + 3 * L * r / 8);
  return Placed(mc + ms, Vector3(across, across, mc * r * r / 2 + ms * 0.4 * r * r), R, t);
}
Body Ellipsoid(double rho, const Vector3& s, const Matrix3& R, const Vector3& t) {
  const double m = rho * 4.0 / 3 * massprops::kPi * s.prod();
  return Placed(m, Vector3(s[1] * s[1] + s[2] * s[2], s[0] * s[0] + s[2] * s[2], s[0] * s[0] + s[1] * s[1]) * (m / 5),
                R, t);
}

// The mesh file moved vertex by vertex (x ↦ R diag(s) x + t) and integrated as it then is.
Body Mesh(const std::string& file, double rho, const Vector3& s, const Matrix3& R, const Vector3& t) {
  LoadedMesh mesh = ReadMeshFile(file);
  for (Eigen::Index v = 0; v < mesh.mesh.V.rows(); ++v) {
    const Vector3 x = mesh.mesh.V.row(v).transpose();
    mesh.mesh.V.row(v) = (R * s.cwiseProduct(x) + t).transpose();
  }
  LoadOptions o;
  o.mass = Density{rho};
  o.unit_stated = true;
  const SolidResult r = SolveMesh(std::move(mesh), file, o);
  return {r.mp.mass, r.mp.center_of_mass, r.mp.inertia_com};
}

Matrix3 Rpy(double r, double p, double y) {
  return (Eigen::AngleAxisd(y, Vector3::UnitZ()) * Eigen::AngleAxisd(p, Vector3::UnitY()) *
          Eigen::AngleAxisd(r, Vector3::UnitX()))
      .toRotationMatrix();
}
const Matrix3 kI = Matrix3::Identity();

const LinkFill& Find(const FillResult& r, const std::string& name) {
  for (const LinkFill& l : r.links) {
    if (l.name == name) return l;
  }
  throw std::runtime_error("no link " + name);
}

void Expect(const FillResult& r, const std::string& name, const Body& want, double tol = 1e-12) {
  const LinkFill& l = Find(r, name);
  ASSERT_EQ(l.status, LinkStatus::kFilled) << name << ": " << l.message.marked();
  EXPECT_NEAR(l.mp.mass, want.m, tol * want.m) << name;
  EXPECT_LT((l.mp.center_of_mass - want.c).norm(), tol * std::max(1e-2, want.c.norm())) << name;
  EXPECT_LT((l.mp.inertia_com - want.I).norm(), tol * want.I.norm()) << name << "\n"
                                                                     << l.mp.inertia_com << "\n"
                                                                     << want.I;
}

// The links the three files share: base, T-handle, hand and plate (URDF/SDF placements).
void ExpectCommon(const FillResult& r) {
  const std::string handle = DataPath("robots/meshes/t_handle.obj"), spot = DataPath("meshes/spot.obj");
  Expect(r, "base_link", Box(1000, {0.2, 0.2, 0.1}, Rpy(0, 0, 0.3), {0, 0, 0.05}));
  Expect(r, "upper_arm", Mesh(handle, 1000, {2, 1, 0.5}, Rpy(0.5, -0.2, 1.0), {0.01, 0.02, 0.3}));
  Expect(r, "hand", Mesh(spot, 1000, {0.1, 0.1, 0.1}, Rpy(massprops::kPi / 2, 0, 0), {0, 0, 0.05}));
}

TEST(Fill, Urdf) {
  const FillResult r = FillRobotDescription(DataPath("robots/demo_arm.urdf"));
  EXPECT_EQ(r.format, RobotFormat::kUrdf);
  EXPECT_TRUE(r.AllFilled());
  // The "world" link is the world frame, no link to fill (it stays in the file as it was).
  EXPECT_TRUE(std::none_of(r.links.begin(), r.links.end(), [](const LinkFill& l) { return l.name == "world"; }));
  ExpectCommon(r);
  Expect(r, "forearm", Sum({Cylinder(1000, 0.03, 0.25, kI, {0, 0, 0.125}), Sphere(1000, 0.04, {0, 0, 0.3})}));
  Expect(r, "tag_plate", Box(1000, {0.1, 0.1, 1e-9}, Rpy(0.3, 0.4, 0.5), {0.02, 0, 0}), 1e-9);
  // The old guess is gone, the new inertial is where the old one was, and the world link (no
  // geometry) has none.
  EXPECT_THAT(r.document, Not(HasSubstr("ixx=\"0.01\"")));
  EXPECT_THAT(r.document, HasSubstr("<!-- a guess from the CAD export, to be replaced -->\n    <inertial>"));
  EXPECT_THAT(r.document, HasSubstr("<link name=\"world\"/>"));
}

TEST(Fill, Sdf) {
  const FillResult r = FillRobotDescription(DataPath("robots/demo_arm.sdf"));
  EXPECT_EQ(r.format, RobotFormat::kSdf);
  EXPECT_TRUE(r.AllFilled());
  ExpectCommon(r);  // the T-handle's pose in degrees: the same rotation to rounding
  Expect(r, "forearm", Sum({Cylinder(1000, 0.03, 0.25, kI, {0, 0, 0.125}), Sphere(1000, 0.04, {0, 0, 0.3})}));
  Expect(r, "sensor",
         Sum({Capsule(1000, 0.02, 0.06, Rpy(0, massprops::kPi / 2, 0), Vector3::Zero()),
              Ellipsoid(1000, {0.01, 0.02, 0.03}, kI, {0.07, 0, 0})}));
  Expect(r, "tag_plate", Box(1000, {0.1, 0.1, 1e-9}, Rpy(0.3, 0.4, 0.5), {0.02, 0, 0}), 1e-9);
}

TEST(Fill, Mjcf) {
  const FillResult r = FillRobotDescription(DataPath("robots/demo_arm.xml"));
  EXPECT_EQ(r.format, RobotFormat::kMjcf);
  EXPECT_TRUE(r.AllFilled());
  // The visual Spot on the base (contype = conaffinity = 0, from its class) is not counted.
  EXPECT_EQ(Find(r, "base_link").geometries, 1);
  ExpectCommon(r);  // quat and xyaxes give the URDF's rotations
  // Steel from the childclass for the fromto capsule; the knob's own density wins.
  Expect(r, "forearm", Sum({Capsule(7850, 0.03, 0.25, kI, {0, 0, 0.125}), Sphere(1000, 0.04, {0, 0, 0.32})}));
  // euler with eulerseq "xyz": rotations about the moving axes, R = Rx Ry Rz.
  const Matrix3 xyz = (Eigen::AngleAxisd(0.3, Vector3::UnitX()) * Eigen::AngleAxisd(0.4, Vector3::UnitY()) *
                       Eigen::AngleAxisd(0.5, Vector3::UnitZ()))
                          .toRotationMatrix();
  Expect(r, "tag_plate", Box(1000, {0.1, 0.1, 1e-9}, xyz, {0.02, 0, 0}), 1e-9);
  // MuJoCo refuses I1 + I2 < I3 by any amount: the written moments of the plate obey it.
  const std::string& d = r.document;
  const std::size_t at = d.find("diaginertia=\"", d.find("name=\"tag_plate\""));
  ASSERT_NE(at, std::string::npos);
  double m[3];
  ASSERT_EQ(std::sscanf(d.c_str() + at, "diaginertia=\"%lf %lf %lf", &m[0], &m[1], &m[2]), 3);
  EXPECT_GE(m[0] + m[1], m[2]);
}

TEST(Fill, VisualGeometries) {
  FillOptions o;
  o.from = GeometrySource::kVisual;
  const FillResult urdf = FillRobotDescription(DataPath("robots/demo_arm.urdf"), o);
  Expect(urdf, "base_link", Box(1000, {0.2, 0.2, 0.1}, Rpy(0, 0, 0.3), {0, 0, 0.05}));
  EXPECT_EQ(Find(urdf, "upper_arm").status, LinkStatus::kNoGeometry);
  const FillResult mjcf = FillRobotDescription(DataPath("robots/demo_arm.xml"), o);
  Expect(mjcf, "base_link", Mesh(DataPath("meshes/spot.obj"), 1000, {0.1, 0.1, 0.1}, kI, Vector3::Zero()));
}

TEST(Fill, DensitiesMassesAndKeptMasses) {
  FillOptions o;
  o.density = 2700;
  o.link_masses = {{"base_link", TotalMass{10}}, {"fore*", Density{7850}}};
  FillResult r = FillRobotDescription(DataPath("robots/demo_arm.urdf"), o);
  Body base = Box(1, {0.2, 0.2, 0.1}, Rpy(0, 0, 0.3), {0, 0, 0.05});
  base.I *= 10 / base.m;
  base.m = 10;
  Expect(r, "base_link", base);
  Expect(r, "forearm", Sum({Cylinder(7850, 0.03, 0.25, kI, {0, 0, 0.125}), Sphere(7850, 0.04, {0, 0, 0.3})}));
  Expect(r, "tag_plate", Box(2700, {0.1, 0.1, 1e-9}, Rpy(0.3, 0.4, 0.5), {0.02, 0, 0}), 1e-9);
  // --keep-mass: the upper arm states 1.5 kg; the others state none and take the density.
  o = {};
  o.keep_mass = true;
  r = FillRobotDescription(DataPath("robots/demo_arm.urdf"), o);
  Body arm = Mesh(DataPath("robots/meshes/t_handle.obj"), 1, {2, 1, 0.5}, Rpy(0.5, -0.2, 1.0), {0.01, 0.02, 0.3});
  arm.I *= 1.5 / arm.m;
  arm.m = 1.5;
  Expect(r, "upper_arm", arm);
  Expect(r, "base_link", Box(1000, {0.2, 0.2, 0.1}, Rpy(0, 0, 0.3), {0, 0, 0.05}));
  // A map entry that matches no link is a mistake, not a default.
  o = {};
  o.link_masses = {{"elbow_link", Density{1}}};
  EXPECT_THROW(FillRobotDescription(DataPath("robots/demo_arm.urdf"), o), std::invalid_argument);
}

// A link whose mesh is missing or open is named and left as it was; the others are filled.
TEST(Fill, FailedLinksAreLeftAsTheyWere) {
  const std::string dir = ::testing::TempDir() + "/fill_failures";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/open.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n";
  const std::string urdf = dir + "/r.urdf";
  std::ofstream(urdf) << "<robot name=\"r\">\n"
                         "  <link name=\"ok\"><collision><geometry><sphere radius=\"0.1\"/></geometry></collision>"
                         "</link>\n"
                         "  <link name=\"missing\"><inertial><mass value=\"2\"/></inertial>"
                         "<collision><geometry><mesh filename=\"nowhere.stl\"/></geometry></collision></link>\n"
                         "  <link name=\"open\"><collision><geometry><mesh filename=\"open.obj\"/></geometry>"
                         "</collision></link>\n"
                         "  <link name=\"bad\"><collision><geometry><box size=\"1 2\"/></geometry></collision></link>\n"
                         "  <link name=\"pkg\"><collision><geometry><mesh filename=\"package://nopkg/m.stl\"/>"
                         "</geometry></collision></link>\n"
                         "</robot>\n";
  const FillResult r = FillRobotDescription(urdf);
  EXPECT_FALSE(r.AllFilled());
  Expect(r, "ok", Sphere(1000, 0.1, Vector3::Zero()));
  EXPECT_EQ(Find(r, "missing").status, LinkStatus::kFailed);
  EXPECT_THAT(Find(r, "missing").message.marked(), HasSubstr("nowhere.stl"));
  EXPECT_THAT(Find(r, "open").message.marked(), HasSubstr("open"));
  EXPECT_THAT(Find(r, "bad").message.marked(), HasSubstr("expected 3 numbers"));
  EXPECT_THAT(Find(r, "pkg").message.marked(), HasSubstr("package 'nopkg' is not found"));
  EXPECT_THAT(r.document, HasSubstr("<link name=\"missing\"><inertial><mass value=\"2\"/></inertial>"));
  // A package mapped by hand resolves.
  std::filesystem::create_directories(dir + "/pkgroot");
  std::filesystem::copy_file(DataPath("robots/meshes/t_handle.obj"), dir + "/pkgroot/m.obj",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir + "/p.urdf") << "<robot name=\"p\"><link name=\"a\"><collision><geometry>"
                                    "<mesh filename=\"package://mine/m.obj\"/></geometry></collision></link></robot>";
  FillOptions o;
  o.packages = {{"mine", dir + "/pkgroot"}};
  Expect(FillRobotDescription(dir + "/p.urdf", o), "a",
         Mesh(DataPath("robots/meshes/t_handle.obj"), 1000, Vector3::Ones(), kI, Vector3::Zero()));
}

TEST(Fill, FilesItDoesNotFollow) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/x.xml") << "<scene/>";
  EXPECT_THROW(FillRobotDescription(dir + "/x.xml"), std::runtime_error);
  std::ofstream(dir + "/inc.xml") << "<mujoco><include file=\"other.xml\"/><worldbody/></mujoco>";
  try {
    FillRobotDescription(dir + "/inc.xml");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("<include file=\"other.xml\">: "));
    EXPECT_THAT(e.what(), HasSubstr("other.xml is not a regular file"));
  }
  std::ofstream(dir + "/broken.urdf") << "<robot><link name=\"a\">";
  EXPECT_THROW(FillRobotDescription(dir + "/broken.urdf"), std::runtime_error);
}

}  // namespace
}  // namespace massprops
