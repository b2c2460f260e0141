// CAD files (STEP, IGES, BREP) through the OpenCASCADE plugin, on files OpenCASCADE itself writes
// (tests/cad/make_cad.cpp): the exact B-rep's numbers against closed forms, the tessellation's
// error against the bound its deflection implies, units, assemblies, materials and faults.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "massprops/io/load.h"
#include "massprops/report/format.h"
#include "massprops/report/picture.h"

namespace massprops {
namespace {

// Every read here goes through the stand-in plugin (tests/fault/fault_plugin.cpp), which forwards
// to the real one unless MASSPROPS_TEST_FAULT asks for a crash or a hang: set before any read, as
// the plugin is loaded once per process.
const bool kThroughFaultPlugin = [] {
  ::setenv("MASSPROPS_CAD_PLUGIN", MASSPROPS_FAULT_PLUGIN, 1);
  ::setenv("MASSPROPS_FAULT_REAL_CAD", MASSPROPS_REAL_CAD_PLUGIN, 1);
  return true;
}();

using massprops::kPi;

namespace fs = std::filesystem;
constexpr double kMm = 1e-3;

class Cad : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = (fs::temp_directory_path() / ("massprops_cad_" + std::to_string(::getpid()))).string();
    fs::create_directories(dir_);
    const std::string command = std::string(MASSPROPS_MAKE_CAD) + " " + dir_;
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string File(const std::string& name) { return dir_ + "/" + name; }
  static std::string dir_;
};
std::string Cad::dir_;

// A solid's closed form, SI, density 1000.
struct Truth {
  double volume;
  Vector3 com;
  Matrix3 inertia;  // about the center of mass
};

Truth Box(double a, double b, double c) {
  a *= kMm, b *= kMm, c *= kMm;
  const double m = 1000 * a * b * c;
  return {a * b * c,
          {a / 2, b / 2, c / 2},
          Vector3(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12).asDiagonal()};
}

Truth Cylinder(double r, double h) {
  r *= kMm, h *= kMm;
  const double v = kPi * r * r * h, m = 1000 * v;
  const double side = m * (3 * r * r + h * h) / 12;
  return {v, {0, 0, h / 2}, Vector3(side, side, m * r * r / 2).asDiagonal()};
}

Truth Sphere(double r) {
  r *= kMm;
  const double v = 4 * kPi * r * r * r / 3, i = 0.4 * 1000 * v * r * r;
  return {v, Vector3::Zero(), Vector3(i, i, i).asDiagonal()};
}

Truth Cone(double r, double h) {  // base on z = 0, apex up
  r *= kMm, h *= kMm;
  const double v = kPi * r * r * h / 3, m = 1000 * v;
  const double side = m * (3 * r * r / 20 + 3 * h * h / 80);
  return {v, {0, 0, h / 4}, Vector3(side, side, 0.3 * m * r * r).asDiagonal()};
}

Truth Torus(double big, double small) {
  big *= kMm, small *= kMm;
  const double v = 2 * kPi * kPi * big * small * small, m = 1000 * v;
  const double side = m * (big * big / 2 + 5 * small * small / 8);
  return {v, Vector3::Zero(), Vector3(side, side, m * (big * big + 3 * small * small / 4)).asDiagonal()};
}

// A 40 × 40 × 10 plate centred on the z axis, z in [0, 10], with a hole of radius 8 along z.
Truth Drilled() {
  const double a = 40 * kMm, t = 10 * kMm, r = 8 * kMm;
  const double vb = a * a * t, vc = kPi * r * r * t, mb = 1000 * vb, mc = 1000 * vc;
  const double ixx = mb * (a * a + t * t) / 12 - mc * (3 * r * r + t * t) / 12;
  const double izz = mb * (a * a + a * a) / 12 - mc * r * r / 2;
  return {vb - vc, {0, 0, t / 2}, Vector3(ixx, ixx, izz).asDiagonal()};
}

void ExpectClose(const MassProperties& mp, const Truth& t, double tolerance, const std::string& what) {
  EXPECT_NEAR(mp.volume, t.volume, tolerance * t.volume) << what;
  const double size = std::cbrt(t.volume);
  EXPECT_LE((mp.center_of_mass - t.com).norm(), tolerance * size) << what;
  EXPECT_LE((mp.inertia_com - t.inertia).norm(), tolerance * t.inertia.norm()) << what;
}

TEST_F(Cad, BrepMatchesTheClosedForms) {
  const std::vector<std::pair<std::string, Truth>> cases = {
      {"box.step", Box(10, 20, 30)}, {"cylinder.step", Cylinder(5, 10)}, {"sphere.step", Sphere(10)},
      {"cone.step", Cone(4, 12)},    {"torus.step", Torus(20, 5)},       {"drilled.step", Drilled()},
      {"drilled.iges", Drilled()},   {"torus.brep", Torus(20, 5)},       {"box.igs", Box(10, 20, 30)},
  };
  for (const auto& [name, truth] : cases) {
    LoadOptions o;  // the default: the exact B-rep is the answer
    if (name.find(".brep") != std::string::npos) {
      o.unit = LengthUnit::kMillimetre;  // a BREP file has no unit
      o.unit_stated = true;
    }
    const SolidResult r = LoadSolid(File(name), o);
    ASSERT_TRUE(r.brep) << name;
    EXPECT_TRUE(r.brep->is_result);
    EXPECT_EQ(r.unit, LengthUnit::kMillimetre) << name;
    ExpectClose(r.mp, truth, 1e-9, name);
    EXPECT_LT(r.brep->estimated_error, 1e-9) << name;
    // The check mesh beside it (welded through the B-rep's edges: closed), within its deflection's
    // reach: |ΔV| ≤ area × deflection, at the default 1e-3 of the diagonal.
    ASSERT_TRUE(r.brep->mesh_checked) << name;
    EXPECT_EQ(r.topology.boundary_edges, 0) << name;
    EXPECT_EQ(r.topology.non_manifold_edges, 0) << name;
    EXPECT_EQ(r.topology.degenerate_faces, 0) << name;
    const double bound = r.mp.surface_area * r.brep->deflection * kMm;
    EXPECT_LE(std::abs(r.brep->mesh.volume - truth.volume), bound) << name;
    EXPECT_GT(r.mp.surface_area, 0) << name;
    for (const Finding& f : r.findings) ADD_FAILURE() << name << ": " << f.message.marked();
  }
}

TEST_F(Cad, StepUnitIsTheFilesAndBothResultsAgreeOnABox) {
  const SolidResult r = LoadSolid(File("box_inches.step"));
  EXPECT_EQ(r.unit, LengthUnit::kInch);
  EXPECT_EQ(r.unit_source, UnitSource::kFile);
  EXPECT_NE(r.loaded.declared_unit_name.find("INCH"), std::string::npos) << r.loaded.declared_unit_name;
  const double in = 0.0254;
  EXPECT_NEAR(r.mp.volume, 6 * in * in * in, 1e-12 * r.mp.volume);
  EXPECT_LE((r.mp.center_of_mass - Vector3(0.5, 1, 1.5) * in).norm(), 1e-12);
  // Planar faces: the tessellation is the solid.
  ASSERT_TRUE(r.brep);
  EXPECT_LT(std::abs(r.brep->volume_difference), 1e-12);
  EXPECT_LT(r.brep->inertia_difference, 1e-12);
  // A stated unit overrides the file's, with a finding.
  LoadOptions mm;
  mm.unit = LengthUnit::kMillimetre;
  mm.unit_stated = true;
  const SolidResult overridden = LoadSolid(File("box_inches.step"), mm);
  EXPECT_NEAR(overridden.mp.volume, 6e-9, 1e-20);
  ASSERT_FALSE(overridden.findings.empty());
  EXPECT_EQ(overridden.findings[0].kind, FindingKind::kUnitOverridden);
}

// The same block written by hand in other systems' habits (tests/cad/field/make_blocks.py: Creo's
// AP203 CONFIG_CONTROL_DESIGN, and an AP242 header with its edges the other way round; inches by
// CONVERSION_BASED_UNIT): the file's unit, the exact B-rep as the answer, the closed form, and the
// numbers of the OpenCASCADE-written block to rounding.
TEST_F(Cad, StepTextFromOtherSystemsGivesTheClosedForm) {
  const SolidResult occ = LoadSolid(File("box_inches.step"));
  const double in = 0.0254, m = 1000 * 6 * in * in * in;
  const Matrix3 inertia = Vector3(m * (4 + 9) / 12, m * (1 + 9) / 12, m * (1 + 4) / 12).asDiagonal() * in * in;
  for (const char* name : {"block_ap203.stp", "block_ap242.stp"}) {
    const SolidResult r = LoadSolid(std::string(MASSPROPS_DATA_DIR) + "/../tests/cad/field/" + name);
    EXPECT_EQ(r.unit, LengthUnit::kInch) << name;
    EXPECT_EQ(r.unit_source, UnitSource::kFile) << name;
    ASSERT_TRUE(r.brep) << name;
    EXPECT_TRUE(r.brep->is_result) << name;
    EXPECT_NEAR(r.mp.volume, 6 * in * in * in, 1e-12 * r.mp.volume) << name;
    EXPECT_LE((r.mp.center_of_mass - Vector3(0.5, 1, 1.5) * in).norm(), 1e-14) << name;
    EXPECT_LE((r.mp.inertia_com - inertia).norm(), 1e-12 * inertia.norm()) << name;
    EXPECT_NEAR(r.mp.volume, occ.mp.volume, 1e-13 * occ.mp.volume) << name;
    for (const Finding& f : r.findings) ADD_FAILURE() << name << ": " << f.message.marked();
  }
}

// An AP203 assembly in millimetres of two parts whose representations declare different units
// (tests/cad/field/make_blocks.py mixed): the 1 × 2 × 3 in block placed at x = 100 mm, a 10 × 20 ×
// 30 mm block at the origin. Composed in millimetres, as the sum of the two closed forms, with and
// without --parts.
TEST_F(Cad, PartsInDifferentUnitsAreComposedInOne) {
  const std::string path = std::string(MASSPROPS_DATA_DIR) + "/../tests/cad/field/mixed_units_assembly.stp";
  const double v_in = 6 * 25.4 * 25.4 * 25.4, v_mm = 6000;  // mm³
  const Vector3 c_in(100 + 12.7, 25.4, 38.1), c_mm(5, 10, 15);
  const Vector3 com = (v_in * c_in + v_mm * c_mm) / (v_in + v_mm) * kMm;
  for (const bool parts : {false, true}) {
    LoadOptions o;
    o.parts = parts;
    const SolidResult r = LoadSolid(path, o);
    EXPECT_EQ(r.unit, LengthUnit::kMillimetre);
    EXPECT_NEAR(r.mp.volume, (v_in + v_mm) * 1e-9, 1e-12 * r.mp.volume);
    EXPECT_LE((r.mp.center_of_mass - com).norm(), 1e-14);
    if (parts) {
      ASSERT_EQ(r.parts.size(), 2u);
      EXPECT_EQ(r.parts[0].part, "INCH_BLOCK");
      EXPECT_EQ(r.parts[0].instance, "INCH_BLOCK:1");  // the component's own name (its NAUO's)
      EXPECT_NEAR(r.parts[0].mp.volume, v_in * 1e-9, 1e-12 * v_in * 1e-9);
      EXPECT_EQ(r.parts[1].part, "MM_BLOCK");
      EXPECT_NEAR(r.parts[1].mp.volume, v_mm * 1e-9, 1e-12 * v_mm * 1e-9);
      // Each part's own declared unit, from its representation's context, in its row and JSON.
      ASSERT_EQ(r.parts[0].loaded.cad_parts.size(), 1u);
      EXPECT_EQ(r.parts[0].loaded.cad_parts[0].unit, "INCH");
      EXPECT_EQ(r.parts[1].loaded.cad_parts[0].unit, "MILLIMETRE");
      const std::string table = report::FormatTable(r, report::FormatOptions{});
      EXPECT_NE(table.find("INCH_BLOCK [INCH_BLOCK:1] (declared in INCH)"), std::string::npos) << table;
      EXPECT_NE(table.find("MM_BLOCK [MM_BLOCK:1] (declared in MILLIMETRE)"), std::string::npos) << table;
      const nlohmann::json j = nlohmann::json::parse(report::FormatJsonLine(r, report::FormatOptions{}));
      EXPECT_EQ(j["parts"][0]["declared_unit"], "INCH");
      EXPECT_EQ(j["parts"][1]["declared_unit"], "MILLIMETRE");
    }
  }
}

// |ΔV| ≤ 1.5 × area × deflection, and ΔV shrinks in proportion to the deflection.
TEST_F(Cad, MeshErrorIsBoundedByTheDeflectionAndShrinksWithIt) {
  for (const std::string name : {"sphere.step", "torus.step", "cylinder.step", "drilled.step"}) {
    std::vector<double> log_d, log_e;
    for (double d : {0.1, 0.05, 0.025, 0.0125}) {
      LoadOptions o;
      o.brep = false;  // the tessellation's numbers as the result
      o.cad.deflection = d;
      o.cad.angular_deflection = 3.0;  // loose: the chordal deflection decides
      const SolidResult r = LoadSolid(File(name), o);
      ASSERT_TRUE(r.brep) << name;
      const double dv = std::abs(r.mp.volume - r.brep->mp.volume) / std::pow(kMm, 3);  // mm^3
      const double area = r.mp.surface_area / (kMm * kMm);
      EXPECT_LE(dv, 1.5 * area * d) << name << " at deflection " << d;
      EXPECT_GT(dv, 0) << name;
      EXPECT_NEAR(r.brep->deflection, d, 1e-12) << name;
      log_d.push_back(std::log(d));
      log_e.push_back(std::log(dv));
    }
    double md = 0, me = 0;
    const auto n = static_cast<double>(log_d.size());
    for (std::size_t i = 0; i < log_d.size(); ++i) md += log_d[i] / n, me += log_e[i] / n;
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < log_d.size(); ++i) {
      sxy += (log_d[i] - md) * (log_e[i] - me);
      sxx += (log_d[i] - md) * (log_d[i] - md);
    }
    const double slope = sxy / sxx;
    EXPECT_GE(slope, 0.8) << name;
    EXPECT_LE(slope, 1.2) << name;
  }
}

TEST_F(Cad, AssemblyPartsNamesPlacementsAndMaterials) {
  LoadOptions o;
  o.parts = true;
  o.brep = true;
  const SolidResult r = LoadSolid(File("assembly.step"), o);
  EXPECT_EQ(r.unit, LengthUnit::kMillimetre);
  EXPECT_EQ(r.unit_source, UnitSource::kFile);
  ASSERT_EQ(r.parts.size(), 4u);
  const std::vector<std::string> names = {"base", "post", "pin", "pin"};
  const std::vector<double> densities = {7850, 2700, 1000, 1000};
  const std::vector<Vector3> coms = {{50, 30, 5}, {30, 30, 35}, {72, 30, 12}, {80, 42, 12}};
  const std::vector<double> volumes = {100 * 60 * 10, kPi * 100 * 50, 4 * 20 * 4, 4 * 20 * 4};
  double mass = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    const SolidResult& p = r.parts[i];
    EXPECT_EQ(p.part, names[i]);
    EXPECT_EQ(p.mp.density, densities[i]) << names[i];
    EXPECT_NEAR(p.mp.volume, volumes[i] * 1e-9, 1e-9 * volumes[i] * 1e-9) << names[i];
    EXPECT_LE((p.mp.center_of_mass - coms[i] * kMm).norm(), 1e-12) << names[i];
    EXPECT_EQ(p.density_source.empty(), i >= 2) << names[i];
    mass += p.mp.mass;
  }
  EXPECT_NE(r.parts[0].density_source.find("steel"), std::string::npos);
  // The second pin is turned 90 degrees about z: its x and y moments trade places.
  EXPECT_NEAR(r.parts[3].mp.inertia_com(0, 0), r.parts[2].mp.inertia_com(1, 1),
              1e-12 * r.parts[2].mp.inertia_com.norm());
  EXPECT_NEAR(r.mp.mass, mass, 1e-12 * mass);
  ASSERT_TRUE(r.brep);
  EXPECT_NEAR(r.brep->mp.mass, mass, 1e-12 * mass);
  // Without parts asked for, the materials still apply: the parts are computed one by one.
  const SolidResult whole = LoadSolid(File("assembly.step"));
  EXPECT_EQ(whole.parts.size(), 4u);
  EXPECT_FALSE(whole.density_source.empty());
  double whole_mass = 0;
  for (const SolidResult& p : whole.parts) whole_mass += p.mp.mass;
  EXPECT_NEAR(whole.mp.mass, whole_mass, 1e-12 * whole_mass);
  EXPECT_DOUBLE_EQ(whole.parts[1].mp.density, 2700);
}

TEST_F(Cad, OneMaterialIsTheDensityUnlessOneIsStated) {
  const SolidResult steel = LoadSolid(File("steel_box.step"));
  EXPECT_EQ(steel.mp.density, 7850);
  EXPECT_NE(steel.density_source.find("steel"), std::string::npos);
  EXPECT_TRUE(steel.parts.empty());
  LoadOptions stated;
  stated.mass = Density{1000};
  stated.mass_stated = true;
  const SolidResult water = LoadSolid(File("steel_box.step"), stated);
  EXPECT_DOUBLE_EQ(water.mp.density, 1000);
  ASSERT_EQ(water.findings.size(), 1u);
  EXPECT_EQ(water.findings[0].kind, FindingKind::kMaterialOverridden);
}

TEST_F(Cad, StepAndTheStlOfItsOwnTessellationAgree) {
  LoadOptions o;
  o.brep = false;  // the tessellation's numbers, to compare with the STL of the same triangles
  o.cad.deflection = 0.05;
  const SolidResult step = LoadSolid(File("cylinder.step"), o);
  LoadOptions mm;
  mm.unit = LengthUnit::kMillimetre;
  mm.unit_stated = true;
  const SolidResult stl = LoadSolid(File("cylinder_0.05.stl"), mm);
  EXPECT_EQ(step.topology.faces, stl.topology.faces);
  EXPECT_NEAR(stl.mp.volume, step.mp.volume, 1e-6 * step.mp.volume);
  EXPECT_LE((stl.mp.center_of_mass - step.mp.center_of_mass).norm(), 1e-6 * step.size_m);
  EXPECT_LE((stl.mp.inertia_com - step.mp.inertia_com).norm(), 1e-6 * step.mp.inertia_com.norm());
}

TEST_F(Cad, IgesAndBrepReadTheSameSolidAsStep) {
  const SolidResult step = LoadSolid(File("drilled.step"));
  const SolidResult iges = LoadSolid(File("drilled.iges"));
  EXPECT_EQ(iges.unit, LengthUnit::kMillimetre);
  LoadOptions mm;
  mm.unit = LengthUnit::kMillimetre;
  mm.unit_stated = true;
  const SolidResult brep = LoadSolid(File("drilled.brep"), mm);
  ASSERT_TRUE(step.brep && iges.brep && brep.brep);
  for (const SolidResult* r : {&iges, &brep}) {
    EXPECT_NEAR(r->brep->mp.volume, step.brep->mp.volume, 1e-9 * step.brep->mp.volume);
    EXPECT_LE((r->brep->mp.inertia_com - step.brep->mp.inertia_com).norm(), 1e-9 * step.brep->mp.inertia_com.norm());
  }
}

TEST_F(Cad, SameFileSameBits) {
  const SolidResult a = LoadSolid(File("torus.step"));
  LoadOptions one;
  one.num_threads = 1;
  const SolidResult b = LoadSolid(File("torus.step"), one);
  EXPECT_EQ(a.mp.volume, b.mp.volume);
  EXPECT_EQ(a.mp.inertia_com, b.mp.inertia_com);
  EXPECT_EQ(a.brep->mp.inertia_com, b.brep->mp.inertia_com);
  // Parts are meshed and integrated in parallel, each part's B-rep integral beside its mesh, and
  // BRepMesh meshes faces in parallel: the same triangles and bits on one thread as on every core.
  for (const char* name : {"assembly.step", "drilled.step"}) {
    const SolidResult all = LoadSolid(File(name));
    const SolidResult single = LoadSolid(File(name), one);
    EXPECT_TRUE(all.loaded.mesh.V == single.loaded.mesh.V) << name;
    EXPECT_EQ(all.loaded.mesh.indices, single.loaded.mesh.indices) << name;
    EXPECT_EQ(all.mp.inertia_com, single.mp.inertia_com) << name;
    EXPECT_EQ(all.mp.center_of_mass, single.mp.center_of_mass) << name;
  }
}

// A CAD file's picture draws its tessellation: the box's dimensions are that surface's, marked
// "≈" with the chordal deflection named, and within it of the B-rep's (a cylinder r 5, h 10 mm:
// 10 × 10 × 10 mm).
TEST_F(Cad, PictureBoxIsTheTessellationsMarkedApproximate) {
  const SolidResult r = LoadSolid(File("cylinder.step"));
  ASSERT_TRUE(r.brep);
  const double deflection = r.brep->deflection * 1e-3;  // m
  ASSERT_GT(deflection, 0);
  const std::string svg = report::PictureSvg(r);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, std::regex("within about ([0-9.e+-]+) m of the solid")));
  EXPECT_NEAR(std::stod(m[1].str()), deflection, 1e-3 * deflection);
  int dimensions = 0;
  const std::regex dimension(">[xyz] ≈ ([0-9.e+-]+) m<");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), dimension); it != std::sregex_iterator(); ++it) {
    EXPECT_NEAR(std::stod((*it)[1].str()), 0.01, deflection + 1e-4 * 0.01) << (*it)[0].str();
    ++dimensions;
  }
  EXPECT_EQ(dimensions, 3);
}

TEST_F(Cad, AnOpenShellIsRefusedAsAnOpenMeshIs) {
  try {
    LoadSolid(File("open_box.step"));
    FAIL() << "an open shell was computed";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("does not bound a solid"), std::string::npos) << e.what();
  }
  LoadOptions shell;
  shell.model = ShellModel{2.0};
  const SolidResult s = LoadSolid(File("open_box.step"), shell);
  EXPECT_NEAR(s.mp.surface_area, (10 * 20 * 2 + 10 * 30 * 2 + 20 * 30 * 2 - 10 * 20) * 1e-6, 1e-15);  // no top
  LoadOptions open;
  open.allow_open = true;
  const SolidResult computed = LoadSolid(File("open_box.step"), open);
  EXPECT_FALSE(computed.brep);
  bool said = false;
  for (const Finding& f : computed.findings) said = said || f.kind == FindingKind::kNoBrep;
  EXPECT_TRUE(said);
  // One diagnosis whether the B-rep or the tessellation is asked for as the answer.
  open.brep = false;
  const SolidResult tessellated = LoadSolid(File("open_box.step"), open);
  EXPECT_EQ(tessellated.mp.volume, computed.mp.volume);
  EXPECT_EQ(tessellated.findings.size(), computed.findings.size());
}

std::string ErrorOf(const std::string& path) {
  try {
    LoadSolid(path);
  } catch (const MeshFileError& e) {
    return e.what();
  }
  return "";
}

TEST_F(Cad, FaultsAreClearErrors) {
  EXPECT_NE(ErrorOf(File("edge_only.step")).find("edge_only.step: "), std::string::npos);
  // Cut short in the middle of its data section.
  {
    std::ifstream in(File("drilled.step"), std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(File("cut.step"), std::ios::binary) << text.substr(0, text.size() / 2);
    std::ofstream(File("noise.igs"), std::ios::binary) << std::string(5000, '\x07') << "S      1\n";
  }
  const std::string cut = ErrorOf(File("cut.step"));
  EXPECT_NE(cut.find("cut.step: "), std::string::npos) << cut;
  const std::string noise = ErrorOf(File("noise.igs"));
  EXPECT_NE(noise.find("noise.igs: "), std::string::npos) << noise;
  ::setenv("MASSPROPS_TEST_FAULT", "hang", 1);
  ::setenv("MASSPROPS_CAD_TIMEOUT", "1", 1);
  const std::string hang = ErrorOf(File("box.step"));
  ::setenv("MASSPROPS_TEST_FAULT", "crash", 1);
  const std::string crash = ErrorOf(File("box.step"));
  ::unsetenv("MASSPROPS_TEST_FAULT");
  ::unsetenv("MASSPROPS_CAD_TIMEOUT");
  EXPECT_NE(hang.find("OpenCASCADE did not finish reading it within 1 s"), std::string::npos) << hang;
  EXPECT_NE(crash.find("OpenCASCADE crashed while reading it"), std::string::npos) << crash;
  EXPECT_NE(ErrorOf(File("missing.step")).find("missing.step"), std::string::npos);
}

}  // namespace
}  // namespace massprops

namespace massprops {
namespace {

bool Says(const SolidResult& r, FindingKind kind, const std::string& words = "") {
  for (const Finding& f : r.findings) {
    if (f.kind == kind && f.message.marked().find(words) != std::string::npos) return true;
  }
  return false;
}

// What other systems' files hold: each is found as the solid it is, and the fix is said.
TEST_F(Cad, EverySolidIsFoundAndEachFixIsSaid) {
  const Truth box = Box(10, 20, 30);
  for (const char* name : {"closed_shell.step", "loose_faces.step", "inside_out.step", "solid_and_curves.step"}) {
    const SolidResult r = LoadSolid(File(name));
    ASSERT_TRUE(r.brep) << name;
    EXPECT_TRUE(r.brep->is_result) << name;
    EXPECT_TRUE(r.brep->mesh_checked) << name;
    ExpectClose(r.mp, box, 1e-9, name);
  }
  EXPECT_TRUE(Says(LoadSolid(File("closed_shell.step")), FindingKind::kCadFix, "closed shell"));
  EXPECT_TRUE(Says(LoadSolid(File("loose_faces.step")), FindingKind::kCadFix, "6 unsewn faces sewn"));
  EXPECT_TRUE(Says(LoadSolid(File("solid_and_curves.step")), FindingKind::kCadLeftOut, "only curves"));
}

// The crash of --parts on a product with no faces: named and left out, never integrated.
TEST_F(Cad, EmptyAndCurveOnlyProductsAreLeftOutUnderEveryOption) {
  for (const bool parts : {false, true}) {
    for (const bool brep : {true, false}) {
      LoadOptions o;
      o.parts = parts;
      o.brep = brep;
      const SolidResult r = LoadSolid(File("empty_and_curve_products.step"), o);
      ExpectClose(r.mp, Box(10, 20, 30), brep ? 1e-9 : 1e-12, "empty_and_curve_products.step");
      EXPECT_TRUE(Says(r, FindingKind::kCadLeftOut, "'nothing'"));
      EXPECT_TRUE(Says(r, FindingKind::kCadLeftOut, "'sketch'"));
      if (parts) {
        EXPECT_EQ(r.parts.size(), 1u);
      }
    }
  }
}

// A bolt in a hole of its own radius touches it: the assembly is the sum, and no interference.
TEST_F(Cad, ABoltInAHoleOfItsRadiusIsComposedWithoutInterference) {
  for (const bool parts : {false, true}) {
    LoadOptions o;
    o.parts = parts;
    const SolidResult r = LoadSolid(File("bolt_in_hole.step"), o);
    const double plate = (40 * 40 * 10 - kPi * 25 * 10) * 1e-9, bolt = kPi * 25 * 30 * 1e-9;
    EXPECT_NEAR(r.mp.volume, plate + bolt, 1e-9 * (plate + bolt));
    EXPECT_FALSE(Says(r, FindingKind::kInterference)) << (r.findings.empty() ? "" : r.findings[0].message.marked());
    EXPECT_EQ(r.loaded.cad_interference.measured, 1u);
    EXPECT_EQ(r.parts.size(), parts ? 2u : 0u);
  }
}

// Two blocks sharing 4 × 7 × 10 mm: the sum counts it twice, and the warning measures it.
TEST_F(Cad, OverlappingBlocksAreComposedWithTheirInterferenceMeasured) {
  const SolidResult r = LoadSolid(File("overlapping_blocks.step"));
  EXPECT_NEAR(r.mp.volume, 2e-6, 1e-15);
  ASSERT_EQ(r.loaded.cad_interference.overlaps.size(), 1u);
  EXPECT_NEAR(r.loaded.cad_interference.overlaps[0].volume, 280, 2.8);  // mm^3, within 1 %
  EXPECT_TRUE(Says(r, FindingKind::kInterference, "share 2.8e-07 m^3"));
  // With no budget it is not measured, and says so.
  LoadOptions none;
  none.cad.interference_pairs = 0;
  EXPECT_TRUE(Says(LoadSolid(File("overlapping_blocks.step"), none), FindingKind::kInterference,
                   "not measured for 1 of 1 pairs"));
}

// The exporter's own numbers beside ours: agreeing ones quietly, disagreeing ones warned.
TEST_F(Cad, TheFilesValidationPropertiesAreAThirdOpinion) {
  const SolidResult agree = LoadSolid(File("props_agree.step"));
  ASSERT_TRUE(agree.brep && agree.brep->file_volume_difference);
  EXPECT_LT(std::abs(*agree.brep->file_volume_difference), 1e-12);
  EXPECT_LT(*agree.brep->file_com_difference, 1e-12);
  EXPECT_FALSE(Says(agree, FindingKind::kFileProperties));
  const SolidResult disagree = LoadSolid(File("props_disagree.step"));
  ASSERT_TRUE(disagree.brep && disagree.brep->file_volume_difference);
  EXPECT_NEAR(*disagree.brep->file_volume_difference, 0.02, 1e-12);
  EXPECT_TRUE(Says(disagree, FindingKind::kFileProperties, "volume +2.00e-02"));
}

// Options that only a mesh can do make the tessellation the answer, and say so.
TEST_F(Cad, MeshOnlyOptionsMakeTheTessellationTheAnswer) {
  LoadOptions hull;
  hull.hull = true;
  const SolidResult r = LoadSolid(File("cylinder.step"), hull);
  ASSERT_TRUE(r.brep);
  EXPECT_FALSE(r.brep->is_result);
  EXPECT_TRUE(Says(r, FindingKind::kCadMeshAnswer, "the convex hull needs a mesh"));
  EXPECT_NEAR(r.brep->deflection, 1e-4 * std::sqrt(10 * 10 + 10 * 10 + 10 * 10), 1e-9);  // the finer default
}

}  // namespace
}  // namespace massprops
