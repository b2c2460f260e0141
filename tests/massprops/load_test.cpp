// The library pipeline (load.h) and the single homes it builds on: units, the density-or-mass
// rule, primitives, wording. Truth: closed forms of the T-handle (two boxes) and of the
// primitives, and hand-counted topology.

#include <array>
#include <cmath>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/io/load.h"
#include "massprops/primitive.h"
#include "massprops/principal_axes.h"
#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using testing::DataPath;
using ::testing::HasSubstr;
using testing::NearRel;
using ::testing::Not;

// The T-handle of data/meshes: a crossbar 0.08 × 0.02 × 0.02 m (centre y = 0.01) on a shaft
// 0.02 × 0.06 × 0.02 m (centre y = −0.03).
constexpr double kBarVolume = 0.08 * 0.02 * 0.02, kShaftVolume = 0.02 * 0.06 * 0.02;
constexpr double kVolume = kBarVolume + kShaftVolume;
constexpr double kArea = 2 * (0.08 * 0.02 * 2 + 0.02 * 0.02) + 2 * (0.02 * 0.06 * 2 + 0.02 * 0.02) - 2 * 0.02 * 0.02;

std::string WriteOpenTetrahedron() {
  const std::string path = ::testing::TempDir() + "/open_tetrahedron.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n";
  return path;
}

TEST(Units, OneTable) {
  EXPECT_EQ(MetresPerUnit(ParseLengthUnit("mm")), 0.001);
  EXPECT_EQ(MetresPerUnit(LengthUnit::kInch), 0.0254);
  EXPECT_EQ(MetresPerUnit(LengthUnit::kFoot), 0.3048);
  for (LengthUnit u : kAllLengthUnits) EXPECT_EQ(ParseLengthUnit(UnitName(u)), u);
  EXPECT_FALSE(FindLengthUnit("furlong"));
  EXPECT_THAT([] { ParseLengthUnit("furlong"); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("m, cm, mm, in, ft")));
}

TEST(Units, ReportUnitsAndTheirFactors) {
  const ReportUnits mmgs = ParseReportUnits("mmgs");
  EXPECT_EQ(mmgs.Describe(), "g, mm, g*mm^2");
  EXPECT_EQ(mmgs.Inertia(), 1e-3 * 1e-3 * 1e-3);
  EXPECT_EQ(mmgs.DensityName(), "g/mm^3");
  EXPECT_TRUE(NearRel(mmgs.Density(), 1e6, 1e-15));  // 1 g/mm^3 = 10^6 kg/m^3
  const ReportUnits ips = ParseReportUnits("ips");
  EXPECT_EQ(ips.Inertia(), 0.45359237 * 0.0254 * 0.0254);  // 1 lb*in^2, by the definitions of lb and in
  EXPECT_EQ(ParseReportUnits("lb,ft,lb*ft^2").Inertia(), 0.45359237 * 0.3048 * 0.3048);
  EXPECT_TRUE(ParseReportUnits("si").IsSi());
  EXPECT_EQ(ParseReportUnits("kg,um,kg*mm^2").length, LengthUnit::kMicrometre);
  EXPECT_THAT([] { ParseReportUnits("g,mm"); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("si, mmgs, cgs or ips")));
  EXPECT_THROW(ParseReportUnits("stone,mm,g*mm^2"), std::invalid_argument);
}

// A 1 × 2 × 3 box: about a corner, its inertia has the closed form m(b² + c²)/3 on the diagonal and
// −m·a·b/4 off it; turned by 90° about z, x and y trade places.
TEST(ReferenceFrames, AboutAPointAndInOtherAxes) {
  const MassProperties box = solids::BoxProperties(Vector3(1, 2, 3), 1000.0);  // centred at the origin
  const double m = box.mass;
  ReferenceFrame corner;
  corner.point = Vector3(-0.5, -1, -1.5);
  const Matrix3 I = InertiaInFrame(box, corner);
  EXPECT_TRUE(NearRel(I(0, 0), m * (4 + 9) / 3, 1e-14));
  EXPECT_TRUE(NearRel(I(2, 2), m * (1 + 4) / 3, 1e-14));
  EXPECT_TRUE(NearRel(I(0, 1), -m * 1 * 2 / 4, 1e-14));
  ReferenceFrame turned;
  turned.axes = RotationFromEulerZYX(massprops::kPi / 2, 0, 0);
  const Matrix3 T = InertiaInFrame(box, turned);  // about the center of mass
  EXPECT_TRUE(NearRel(T(0, 0), box.inertia_com(1, 1), 1e-14));
  EXPECT_TRUE(NearRel(T(1, 1), box.inertia_com(0, 0), 1e-14));
  EXPECT_NEAR(T(0, 1), 0, 1e-12 * m);
  EXPECT_NO_THROW(RequireRotation(turned.axes));
  EXPECT_THAT([] { RequireRotation(Matrix3::Identity() * 2); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("not orthonormal")));
  EXPECT_THAT([] { RequireRotation(Vector3(1, 1, -1).asDiagonal()); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("left-handed")));
}

TEST(MassSpec, DensityOrMass) {
  EXPECT_EQ(ResolveDensity(Density{2700}, 0.5), 2700);
  EXPECT_EQ(ResolveDensity(TotalMass{3}, 0.5), 6);
  EXPECT_THROW(ResolveDensity(Density{-1}, 1), std::invalid_argument);
  EXPECT_THROW(ResolveDensity(TotalMass{std::nan("")}, 1), std::invalid_argument);
  const MassProperties unit = solids::BoxProperties(Vector3(1, 2, 3), 1.0);
  const MassProperties steel = AtDensity(unit, 7850);
  EXPECT_EQ(steel.mass, 6 * 7850.0);
  EXPECT_TRUE(NearRel(steel.inertia_com(0, 0), 7850 * 6 * (4 + 9) / 12.0, 1e-15));
}

TEST(Primitives, ClosedFormTessellationAndImplicitFormAgree) {
  namespace pr = primitive;
  const std::vector<Primitive> all = {
      pr::Box{Vector3(1, 2, 3)}, pr::Sphere{0.5},    pr::Ellipsoid{Vector3(1, 0.5, 0.25)},
      pr::Cylinder{0.3, 1.0},    pr::Cone{0.4, 1.2}, pr::Torus{1.0, 0.25},
      pr::Capsule{0.2, 0.6}};
  ASSERT_EQ(all.size(), std::size(kPrimitiveNames));
  for (const Primitive& p : all) {
    SCOPED_TRACE(PrimitiveName(p));
    const MassProperties exact = ClosedForm(p, 1000.0);
    // The tessellation converges to the closed form as 1/n² (the box is exact): the error falls
    // about four times when n doubles.
    const MassProperties coarse = ComputeMassProperties(Tessellate(p, 32), 1000.0);
    const MassProperties fine = ComputeMassProperties(Tessellate(p, 64), 1000.0);
    const double e_coarse = std::abs(coarse.volume - exact.volume), e_fine = std::abs(fine.volume - exact.volume);
    EXPECT_TRUE(NearRel(fine.volume, exact.volume, 3e-3));
    EXPECT_TRUE(NearRel(fine.inertia_com.trace(), exact.inertia_com.trace(), 6e-3));
    if (!std::holds_alternative<pr::Box>(p)) {
      EXPECT_NEAR(e_coarse / e_fine, 4.0, 0.5);
    }
    // The implicit form: inside at the center of mass (for the torus, on its ring), outside
    // beyond the bounds.
    const ImplicitPtr solid = ToImplicit(p);
    const Vector3 inside = std::holds_alternative<pr::Torus>(p) ? Vector3(1, 0, 0) : Vector3::Zero();
    EXPECT_TRUE(solid->Inside(inside));
    EXPECT_FALSE(solid->Inside(solid->Bounds().max() + Vector3::Constant(0.01)));
  }
  EXPECT_EQ(Describe(pr::Box{Vector3(1, 2, 3)}), "box 1 x 2 x 3 m");
  EXPECT_THAT(
      [] {
        Validate(pr::Torus{1, 2});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("minor radius")));
  EXPECT_THROW(ClosedForm(pr::Sphere{-1}, 1.0), std::invalid_argument);
}

TEST(Wording, MarkersBecomeEachFrontEndsWords) {
  const Vocabulary scene = [](Option o, std::string_view v) -> std::string {
    if (o == Option::kUnit) return "\"unit\": \"" + std::string(v) + "\"";
    return o == Option::kRepair ? "\"repair\": true" : "?";
  };
  EXPECT_EQ(Worded("try {repair}; or {unit=mm} {unknown} {", scene),
            "try \"repair\": true; or \"unit\": \"mm\" {unknown} {");
  EXPECT_EQ(Worded("pass {allow_open}", ApiVocabulary()), "pass LoadOptions::allow_open = true");
}

TEST(LoadSolid, TheTHandleAgainstItsClosedForm) {
  LoadOptions o;
  o.mass = TotalMass{1.0};
  const SolidResult r = LoadSolid(DataPath("meshes/t_handle.obj"), o);
  EXPECT_EQ(r.model, ModelKind::kSolid);
  EXPECT_TRUE(r.mass_fixed);
  EXPECT_TRUE(NearRel(r.mp.volume, kVolume, 1e-14));
  EXPECT_TRUE(NearRel(r.mp.mass, 1.0, 1e-14));
  EXPECT_TRUE(NearRel(r.mp.center_of_mass.y(), (kBarVolume * 0.01 - kShaftVolume * 0.03) / kVolume, 1e-13));
  EXPECT_TRUE(NearRel(r.mp.surface_area, kArea, 1e-14));
  EXPECT_TRUE(r.validity.valid);
  EXPECT_TRUE(r.findings.empty());
  EXPECT_EQ(r.topology.components, 1);
  EXPECT_EQ(r.path_used, "polygons (Mirtich), faces integrated whole");
  // Principal axes are those of the tensor, computed once by the pipeline.
  const PrincipalInertia p = ComputePrincipalInertia(r.mp.inertia_com);
  EXPECT_EQ(p.moments, r.principal.moments);
  // The same in millimetres: every length ×1000 means a volume ×10⁹ at the same density.
  LoadOptions mm;
  mm.unit = LengthUnit::kMillimetre;
  const SolidResult small = LoadSolid(DataPath("meshes/t_handle.obj"), mm);
  EXPECT_TRUE(NearRel(small.mp.volume, kVolume * 1e-9, 1e-14));
}

// A binary STL of the mesh, in float32 as STL stores them.
std::string WriteStl(const TriangleMesh& m, const std::string& name) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream out(path, std::ios::binary);
  const std::string header(80, ' ');
  out.write(header.data(), 80);
  const auto count = static_cast<std::uint32_t>(m.F.rows());
  out.write(reinterpret_cast<const char*>(&count), 4);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    float rec[12] = {};
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) rec[3 + 3 * k + j] = static_cast<float>(m.V(m.F(f, k), j));
    }
    out.write(reinterpret_cast<const char*>(rec), 48);
    out.write("\0\0", 2);
  }
  return path;
}

// A binary STL of a torus of 4n² triangles.
std::string WriteTorusStl(int n, const std::string& name) { return WriteStl(solids::Torus(2.0, 0.5, n), name); }

// Big binary STLs are integrated as they lie; the checked path (--full-check) welds them. Both
// must give the same numbers for the same float coordinates, and the streamed one says what it
// did not check.
TEST(LoadSolid, StreamedAndCheckedPathsAgree) {
  const std::string path = WriteTorusStl(160, "torus_102400.stl");  // 4·160² = 102 400 triangles
  LoadOptions o;
  o.unit_stated = true;
  const SolidResult streamed = LoadSolid(path, o);
  o.full_check = true;
  const SolidResult checked = LoadSolid(path, o);
  EXPECT_THAT(streamed.path_used, HasSubstr("streamed"));
  EXPECT_FALSE(streamed.full_topology);
  ASSERT_EQ(streamed.findings.size(), 1u);
  EXPECT_EQ(streamed.findings[0].kind, FindingKind::kStreamedChecks);
  EXPECT_THAT(checked.path_used, Not(HasSubstr("streamed")));
  EXPECT_TRUE(checked.full_topology);
  EXPECT_TRUE(checked.findings.empty());
  EXPECT_EQ(checked.topology.faces, 102400);
  EXPECT_EQ(checked.topology.vertices, 51200);
  EXPECT_TRUE(NearRel(streamed.mp.volume, checked.mp.volume, 1e-13));
  EXPECT_TRUE(NearRel(streamed.mp.inertia_com(2, 2), checked.mp.inertia_com(2, 2), 1e-13));
  EXPECT_NEAR(streamed.mp.center_of_mass.norm(), checked.mp.center_of_mass.norm(), 1e-14);
  // Within the tessellation's error of the torus, V = 2π²Ra² (from below).
  const double exact = 2 * massprops::kPi * massprops::kPi * 2.0 * 0.25;
  EXPECT_LT(checked.mp.volume, exact);
  EXPECT_GT(checked.mp.volume, exact * (1 - 1e-3));
  // Just below the threshold, the default path is the checked one.
  const SolidResult small = LoadSolid(WriteTorusStl(150, "torus_90000.stl"), LoadOptions{});
  EXPECT_TRUE(small.full_topology);
}

// Two shells in a file big enough to stream: the per-triangle checks all pass (every edge matched,
// no face twice), so only counting shells can tell them from one. They go to the full check, which
// refuses a torus inside another when both face outward (their volumes would be summed: 1.97 for
// these) and computes the hollow one when the inner faces inward — the same numbers as the two
// tori integrated apart.
TEST(LoadSolid, NestedShellsInABigStlGoToTheFullCheck) {
  const TriangleMesh outer = solids::Torus(2.0, 0.5, 160);  // 102 400 triangles
  const TriangleMesh inner = solids::Torus(2.0, 0.25, 120);
  auto both = [&](bool reverse_inner) {
    TriangleMesh m;
    m.V.resize(outer.V.rows() + inner.V.rows(), 3);
    m.V << outer.V, inner.V;
    Eigen::MatrixXi fi = inner.F.array() + static_cast<int>(outer.V.rows());
    if (reverse_inner) fi.col(1).swap(fi.col(2));
    m.F.resize(outer.F.rows() + inner.F.rows(), 3);
    m.F << outer.F, fi;
    return m;
  };
  LoadOptions o;
  o.unit_stated = true;
  try {
    LoadSolid(WriteStl(both(false), "nested_outward.stl"), o);
    ADD_FAILURE() << "two nested outward tori computed";
  } catch (const LoadError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nested_outward.stl"));
    EXPECT_THAT(e.what(), HasSubstr("inside"));
  }
  const SolidResult hollow = LoadSolid(WriteStl(both(true), "nested_hollow.stl"), o);
  EXPECT_TRUE(hollow.full_topology);
  EXPECT_THAT(hollow.path_used, Not(HasSubstr("streamed")));
  EXPECT_EQ(hollow.topology.components, 2);
  const double v_outer = LoadSolid(WriteStl(outer, "outer.stl"), o).mp.volume;
  const double v_inner = LoadSolid(WriteStl(inner, "inner.stl"), o).mp.volume;
  EXPECT_TRUE(NearRel(hollow.mp.volume, v_outer - v_inner, 1e-12));
  // Overlapping (the inner one moved to cross the outer's surface): refused as well.
  TriangleMesh moved = inner;
  moved.V.col(2).array() += 0.5;
  TriangleMesh crossing = both(false);
  crossing.V.bottomRows(inner.V.rows()) = moved.V;
  EXPECT_THROW(LoadSolid(WriteStl(crossing, "crossing.stl"), o), LoadError);
}

// The convex hull, as collision engines see a body: a convex part is its own hull; the T-handle's
// hull is the prism over the hexagon (±0.04, 0.02), (±0.04, 0), (±0.01, −0.06), 0.02 deep, built
// here by hand and integrated without CGAL.
TEST(LoadSolid, ConvexHullBesideTheExactNumbers) {
  LoadOptions o;
  o.hull = true;
  o.unit_stated = true;
  const SolidResult t = LoadSolid(DataPath("meshes/t_handle.obj"), o);
  ASSERT_TRUE(t.hull.has_value());
  PolygonMesh prism;
  const double xy[6][2] = {{-0.04, 0.02}, {-0.04, 0}, {-0.01, -0.06}, {0.01, -0.06}, {0.04, 0}, {0.04, 0.02}};
  prism.V.resize(12, 3);
  for (int k = 0; k < 6; ++k) {
    prism.V.row(k) << xy[k][0], xy[k][1], 0.01;
    prism.V.row(6 + k) << xy[k][0], xy[k][1], -0.01;
  }
  prism.AddFace(std::vector<int>{0, 1, 2, 3, 4, 5});    // z = +0.01, counter-clockwise seen from +z
  prism.AddFace(std::vector<int>{11, 10, 9, 8, 7, 6});  // z = −0.01
  for (int k = 0; k < 6; ++k) prism.AddFace(std::array<int, 4>{k, 6 + k, 6 + (k + 1) % 6, (k + 1) % 6});
  const MassProperties want = ComputeMassProperties(prism, 1000.0);
  EXPECT_TRUE(NearRel(want.volume, 0.0046 * 0.02, 1e-14));  // the hexagon's area × depth
  EXPECT_TRUE(NearRel(t.hull->mp.volume, want.volume, 1e-13));
  EXPECT_NEAR((t.hull->mp.center_of_mass - want.center_of_mass).norm(), 0, 1e-15);
  EXPECT_LT((t.hull->mp.inertia_com - want.inertia_com).norm(), 1e-13 * want.inertia_com.norm());
  EXPECT_EQ(t.hull->vertices, 12);
  // A convex part is its own hull, and a fixed mass stays the mass of the hull.
  o.mass = TotalMass{2.0};
  const SolidResult moon = LoadSolid(DataPath("meshes/Moon.stl"), o);
  EXPECT_TRUE(NearRel(moon.hull->mp.mass, 2.0, 1e-14));
  LoadedMesh box_mesh;
  box_mesh.mesh = solids::Box(Vector3(1, 2, 3));
  const SolidResult box = SolveMesh(box_mesh, "box", o);
  EXPECT_TRUE(NearRel(box.hull->mp.volume, 6.0, 1e-14));
  EXPECT_LT((box.hull->mp.inertia_com - box.mp.inertia_com).norm(), 1e-14 * box.mp.inertia_com.norm());
  o.model = ShellModel{1.0};
  EXPECT_THROW(LoadSolid(DataPath("meshes/t_handle.obj"), o), std::invalid_argument);
}

TEST(LoadSolid, ShellAndWallModels) {
  LoadOptions shell;
  shell.model = ShellModel{2.0};
  const SolidResult s = LoadSolid(DataPath("meshes/t_handle.obj"), shell);
  EXPECT_EQ(s.model, ModelKind::kShell);
  EXPECT_EQ(s.mp.volume, 0.0);
  EXPECT_TRUE(NearRel(s.mp.mass, 2.0 * kArea, 1e-14));
  shell.mass = TotalMass{3.0};  // a total mass overrides the area density
  EXPECT_TRUE(NearRel(LoadSolid(DataPath("meshes/t_handle.obj"), shell).mp.density, 3.0 / kArea, 1e-14));

  // A 2 mm wall: the T-handle minus the T of sizes reduced by 4 mm (exact: its faces meet three
  // planes at a time).
  LoadOptions wall;
  wall.model = WallModel{0.002};
  const SolidResult w = LoadSolid(DataPath("meshes/t_handle.obj"), wall);
  const double inner = 0.076 * 0.016 * 0.016 + 0.016 * 0.06 * 0.016;  // the shaft loses 2 mm at its foot only
  EXPECT_EQ(w.model, ModelKind::kWall);
  EXPECT_EQ(w.wall_thickness, 0.002);
  EXPECT_TRUE(NearRel(w.mp.volume, kVolume - inner, 1e-12));
  wall.model = WallModel{-1};
  EXPECT_THROW(LoadSolid(DataPath("meshes/t_handle.obj"), wall), std::invalid_argument);
}

std::string WriteCube(const std::string& name, double side) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream out(path);
  out.precision(17);
  for (int i = 0; i < 8; ++i)
    out << "v " << side * (i & 1) << " " << side * (i >> 1 & 1) << " " << side * (i >> 2) << "\n";
  out << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return path;
}

// A wall is a difference of two solids: a thin one keeps only the digits rounding leaves it. A
// 1e-12 m wall on a unit cube (exact volume 6e-12 less the edges' 12·1e-24) carries a bound
// that covers its true error and is below 1 %; a 1e-15 m one would be noise and is refused; a
// 1 mm one has every digit.
TEST(LoadSolid, ThinWallsSayHowManyDigitsTheyHave) {
  const std::string cube = WriteCube("unit_cube.obj", 1.0);
  LoadOptions o;
  o.unit_stated = true;
  o.model = WallModel{1e-12};
  const SolidResult thin = LoadSolid(cube, o);
  const double exact = 1.0 - std::pow(1.0 - 2e-12, 3);
  const double error = std::abs(thin.mp.volume - exact) / exact;
  EXPECT_GT(thin.relative_error_bound, error);
  EXPECT_LT(thin.relative_error_bound, 1e-2);
  ASSERT_EQ(thin.findings.size(), 1u);
  EXPECT_EQ(thin.findings[0].kind, FindingKind::kLimitedPrecision);
  o.model = WallModel{1e-15};
  EXPECT_THAT([&] { LoadSolid(cube, o); },
              ::testing::ThrowsMessage<LoadError>(HasSubstr("too thin for double precision")));
  o.model = WallModel{1e-3};
  const SolidResult mm = LoadSolid(cube, o);
  EXPECT_EQ(mm.relative_error_bound, 0.0);
  EXPECT_TRUE(NearRel(mm.mp.volume, 1.0 - std::pow(0.998, 3), 1e-12));
}

// Numbers that are representable doubles are computed, whatever the size; those that are not are
// refused naming which. A cube 1e60 m on a side (volume 1e180, inertia ~1.7e302) is exact; a
// tetrahedron 1e-300 high has a volume the double sums cannot tell from zero but exact sums can;
// a sphere of radius 1e-100 has an inertia of ~1e-497 and one of 1e300 a volume of ~4e900.
TEST(LoadSolid, ExtremeSizesComputedOrRefusedNamingTheQuantity) {
  LoadOptions o;
  o.unit_stated = true;
  const SolidResult big = LoadSolid(WriteCube("cube_1e60.obj", 1e60), o);
  EXPECT_TRUE(NearRel(big.mp.volume, 1e180, 1e-15));
  EXPECT_TRUE(NearRel(big.mp.inertia_com(2, 2), 1000 * 1e180 * 2e120 / 12, 1e-14));

  auto tetrahedron = [](const std::string& name, const std::string& h) {
    const std::string path = ::testing::TempDir() + "/" + name;
    std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.3 0.3 " << h << "\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
    return path;
  };
  const SolidResult sliver = LoadSolid(tetrahedron("sliver.obj", "1e-300"), o);
  const SolidResult unit = LoadSolid(tetrahedron("tet.obj", "1"), o);
  EXPECT_TRUE(NearRel(sliver.mp.volume, 1e-300 / 6, 1e-15));
  EXPECT_THAT(sliver.path_used, HasSubstr("exact rational"));
  // Heights scale x–y second moments by h (volume) and the z ones by h³ (here underflowing to 0).
  const Matrix3 C1 = 0.5 * unit.mp.inertia_com.trace() * Matrix3::Identity() - unit.mp.inertia_com;
  EXPECT_TRUE(NearRel(sliver.mp.inertia_com(0, 0), 1e-300 * C1(1, 1), 1e-13));
  EXPECT_TRUE(NearRel(sliver.mp.inertia_com(2, 2), 1e-300 * (C1(0, 0) + C1(1, 1)), 1e-13));
  EXPECT_TRUE(NearRel(sliver.mp.inertia_com(0, 1), -1e-300 * C1(0, 1), 1e-13));
  EXPECT_TRUE(NearRel(sliver.mp.center_of_mass.x(), 0.325, 1e-15));
  // A double-sided surface is still zero, exactly.
  EXPECT_THAT([&] { LoadSolid(tetrahedron("flat.obj", "0"), o); },
              ::testing::ThrowsMessage<LoadError>(HasSubstr("zero")));

  ImplicitOptions io;
  io.sampling.samples = 1 << 14;
  EXPECT_THAT([&] { EstimateImplicit(*ToImplicit(primitive::Sphere{1e-100}), io); },
              ::testing::ThrowsMessage<LoadError>(HasSubstr("its inertia")));
  EXPECT_THAT([&] { EstimateImplicit(*ToImplicit(primitive::Sphere{1e300}), io); },
              ::testing::ThrowsMessage<LoadError>(HasSubstr("its volume")));
  // Small but representable: the estimate is made at unit size and scaled back, error bars too
  // (sampled at 1e-40 m directly, their variances underflowed to 0).
  const SolidResult tiny = EstimateImplicit(*ToImplicit(primitive::Sphere{1e-40}), io);
  const MassProperties exact = ClosedForm(primitive::Sphere{1e-40}, 1000.0);
  EXPECT_GT(tiny.estimate->standard_error.inertia_com(0, 0), 0);
  EXPECT_LT(std::abs(tiny.mp.volume - exact.volume), 4.5 * tiny.estimate->standard_error.volume);
  EXPECT_LT(std::abs(tiny.mp.inertia_com(0, 0) - exact.inertia_com(0, 0)),
            4.5 * tiny.estimate->standard_error.inertia_com(0, 0));
}

TEST(LoadSolid, TypedFindingsAndErrorsWordedPerFrontEnd) {
  const std::string open = WriteOpenTetrahedron();
  try {
    LoadSolid(open, {});
    FAIL() << "an open mesh was accepted";
  } catch (const LoadError& e) {
    EXPECT_THAT(e.text(), HasSubstr("open mesh: 3 boundary edges in 1 hole"));
    EXPECT_THAT(e.text(), HasSubstr("try {repair} (it fills holes"));
    EXPECT_THAT(e.text(), HasSubstr("{winding_number} for an estimate with error bars, or pass {allow_open}"));
    EXPECT_THAT(e.what(), HasSubstr("LoadOptions::allow_open = true"));
    const Vocabulary cli = [](Option o, std::string_view) -> std::string {
      return o == Option::kRepair ? "--repair" : o == Option::kWindingNumber ? "--winding-number" : "--allow-open";
    };
    EXPECT_THAT(WordedError(e, cli), HasSubstr("try --repair (it fills holes"));
    EXPECT_THAT(WordedError(e, cli),
                HasSubstr("--winding-number for an estimate with error bars, or pass --allow-open"));
  }
  LoadOptions allow;
  allow.allow_open = true;
  const SolidResult r = LoadSolid(open, allow);
  ASSERT_EQ(r.findings.size(), 1u);
  EXPECT_EQ(r.findings[0].kind, FindingKind::kOpenSurface);
  EXPECT_THAT(r.findings[0].message.marked(), HasSubstr("computed anyway ({allow_open})"));
  // A shell does not care that the surface is open: it says so, as a finding.
  LoadOptions shell;
  shell.model = ShellModel{1.0};
  const SolidResult s = LoadSolid(open, shell);
  ASSERT_EQ(s.findings.size(), 1u);
  EXPECT_THAT(s.findings[0].message.marked(), HasSubstr("fine for a thin shell"));
  EXPECT_TRUE(NearRel(s.mp.mass, 1.5, 1e-15));  // three right triangles of area 1/2
}

TEST(LoadSolid, OverlappingShellsAndInwardSurfacesAreRefused) {
  try {
    LoadSolid(DataPath("meshes/hollow_sphere.off"), {});
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_THAT(e.text(), HasSubstr("both face outward"));
    EXPECT_THAT(e.text(), HasSubstr("{repair} orients it so"));
  }
  EXPECT_THAT([] { LoadSolid(DataPath("meshes/ellipe0.003.off"), {}); },
              ::testing::ThrowsMessage<LoadError>(HasSubstr("the faces point inward")));
}

TEST(EstimateImplicit, ATorusWithinItsErrorBars) {
  ImplicitOptions o;
  o.unit = LengthUnit::kCentimetre;
  o.sampling.samples = 1 << 16;
  const SolidResult r = EstimateImplicit(*ToImplicit(primitive::Torus{1.0, 0.25}), o);
  ASSERT_TRUE(r.estimate);
  const MassProperties exact = ClosedForm(primitive::Torus{0.01, 0.0025}, 1000.0);
  EXPECT_EQ(r.model, ModelKind::kImplicit);
  EXPECT_EQ(r.source, "torus(R=1, r=0.25)");
  EXPECT_LT(std::abs(r.mp.volume - exact.volume), 4.5 * r.estimate->standard_error.volume);
  EXPECT_LT(std::abs(r.mp.inertia_com(2, 2) - exact.inertia_com(2, 2)),
            4.5 * r.estimate->standard_error.inertia_com(2, 2));
}

}  // namespace
}  // namespace massprops
