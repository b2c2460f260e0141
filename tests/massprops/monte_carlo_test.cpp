// Implicit solids and the Monte-Carlo / quasi-Monte-Carlo estimators: every built-in solid and
// CSG shapes against closed forms, calibration of the reported intervals over 200 seeds,
// measured convergence rates, the winding-number path against exact polyhedral results (closed,
// with holes, far from the origin), determinism, the adaptive tolerance, the shape syntax.

#include <cmath>
#include <fstream>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "massprops/composition.h"
#include "massprops/implicit.h"
#include "massprops/io/mesh_io.h"  // ReadSdfGridFile
#include "massprops/monte_carlo.h"
#include "massprops/principal_axes.h"
#include "massprops/solids.h"
#include "test_utils.h"

namespace massprops {
namespace {

using ::testing::HasSubstr;

MonteCarloOptions Qmc(std::int64_t samples, std::uint64_t seed = 1, int R = 16) {
  MonteCarloOptions o;
  o.method = SamplingMethod::kQuasiMonteCarlo;
  o.samples = samples;
  o.randomizations = R;
  o.seed = seed;
  return o;
}
MonteCarloOptions Mc(std::int64_t samples, std::uint64_t seed = 1) {
  MonteCarloOptions o;
  o.method = SamplingMethod::kMonteCarlo;
  o.samples = samples;
  o.seed = seed;
  return o;
}

// |estimate − truth| within k standard errors (plus rounding), field by field.
void ExpectWithinErrorBars(const MassPropertiesEstimate& e, const MassProperties& truth, double k,
                           const std::string& what) {
  const auto& v = e.value;
  const auto& s = e.standard_error;
  const double tiny = 1e-12 * std::abs(truth.mass);
  EXPECT_LE(std::abs(v.volume - truth.volume), k * s.volume + tiny)
      << what << " volume " << v.volume << " vs " << truth.volume;
  EXPECT_LE(std::abs(v.mass - truth.mass), k * s.mass + tiny) << what << " mass";
  const double len = std::cbrt(std::abs(truth.volume));
  for (int i = 0; i < 3; ++i) {
    EXPECT_LE(std::abs(v.center_of_mass[i] - truth.center_of_mass[i]), k * s.center_of_mass[i] + 1e-12 * len)
        << what << " com " << i << ": " << v.center_of_mass[i] << " vs " << truth.center_of_mass[i] << " se "
        << s.center_of_mass[i];
    for (int j = 0; j < 3; ++j) {
      EXPECT_LE(std::abs(v.inertia_com(i, j) - truth.inertia_com(i, j)),
                k * s.inertia_com(i, j) + 1e-12 * truth.inertia_com.cwiseAbs().maxCoeff())
          << what << " I(" << i << "," << j << ") " << v.inertia_com(i, j) << " vs " << truth.inertia_com(i, j)
          << " se " << s.inertia_com(i, j);
    }
  }
  const Vector3 p = ComputePrincipalInertia(truth.inertia_com).moments;
  for (int i = 0; i < 3; ++i) {
    EXPECT_LE(std::abs(e.principal_moments[i] - p[i]), k * e.principal_moments_se[i] + 1e-12 * p[2])
        << what << " principal " << i;
  }
}

TEST(Implicit, EveryBuiltInSolidAgainstItsClosedForm) {
  namespace so = solids;
  struct Case {
    ImplicitPtr solid;
    MassProperties truth;
  } cases[] = {
      {implicit::Sphere(0.7), so::SphereProperties(0.7, 2.0)},
      {implicit::Ellipsoid(Vector3(1, 2, 3)), so::EllipsoidProperties(Vector3(1, 2, 3), 2.0)},
      {implicit::Box(Vector3(1, 2, 3)), so::BoxProperties(Vector3(1, 2, 3), 2.0)},
      {implicit::Cylinder(1, 3), so::CylinderProperties(1, 3, 2.0)},
      {implicit::Cone(1, 3), so::ConeProperties(1, 3, 2.0)},
      {implicit::Torus(2, 0.5), so::TorusProperties(2, 0.5, 2.0)},
      {implicit::Capsule(0.5, 2), so::CapsuleProperties(0.5, 2, 2.0)},
  };
  for (const auto& c : cases) {
    const MassPropertiesEstimate e = EstimateMassProperties(*c.solid, 2.0, Qmc(1 << 20));
    ExpectWithinErrorBars(e, c.truth, 4.5, c.solid->Describe());
    EXPECT_LT(e.standard_error.mass / e.value.mass, 5e-4) << c.solid->Describe();
  }
}

TEST(Implicit, CsgAndTransformsAgainstClosedForms) {
  // A 2 m cube with an off-centre spherical cavity: Subtract of the closed forms.
  const ImplicitPtr s = implicit::ParseShape("difference(box(x=2, y=2, z=2), move(sphere(r=0.6), x=0.3, y=-0.2))");
  const MassProperties truth =
      Subtract(solids::BoxProperties(Vector3(2, 2, 2), 1.0),
               Transformed(solids::SphereProperties(0.6, 1.0), Matrix3::Identity(), Vector3(0.3, -0.2, 0)));
  ExpectWithinErrorBars(EstimateMassProperties(*s, 1.0, Qmc(1 << 20)), truth, 4.5, s->Describe());
  // A turned, scaled, moved ellipsoid: products of inertia are not zero.
  const Matrix3 R = Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()).toRotationMatrix();
  const ImplicitPtr t =
      implicit::Transformed(implicit::Scaled(implicit::Ellipsoid(Vector3(1, 0.5, 0.25)), 2.0), R, Vector3(5, 6, 7));
  const MassProperties et = Transformed(solids::EllipsoidProperties(Vector3(2, 1, 0.5), 1.0), R, Vector3(5, 6, 7));
  ExpectWithinErrorBars(EstimateMassProperties(*t, 1.0, Mc(1 << 20)), et, 4.5, "moved ellipsoid (MC)");
  // Union of disjoint parts and an intersection with a known answer (a half sphere).
  const ImplicitPtr u = implicit::ParseShape("union(move(sphere(r=1), x=-2), move(sphere(r=1), x=2))");
  const MassPropertiesEstimate eu = EstimateMassProperties(*u, 1.0, Qmc(1 << 20));
  EXPECT_NEAR(eu.value.volume, 8 * massprops::kPi / 3, 4.5 * eu.standard_error.volume);
  const ImplicitPtr half = implicit::ParseShape("intersection(sphere(r=1), move(box(x=2, y=2, z=1), z=0.5))");
  const MassPropertiesEstimate eh = EstimateMassProperties(*half, 1.0, Qmc(1 << 20));
  EXPECT_NEAR(eh.value.volume, 2 * massprops::kPi / 3, 4.5 * eh.standard_error.volume);
  EXPECT_NEAR(eh.value.center_of_mass.z(), 3.0 / 8, 4.5 * eh.standard_error.center_of_mass.z());
}

TEST(Implicit, SignedDistanceGridOfASphere) {
  // φ = |x| − 1 sampled on a 41³ grid over [−1.2, 1.2]³: trilinear interpolation of a smooth φ
  // moves the surface by O(h²).
  const int n = 41;
  const double h = 2.4 / (n - 1);
  std::vector<double> v;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) v.push_back(Vector3(-1.2 + i * h, -1.2 + j * h, -1.2 + k * h).norm() - 1.0);
  const std::string path = ::testing::TempDir() + "/sphere.sdf";
  {
    std::ofstream out(path);
    out.precision(17);
    out << "sdfgrid 1\n" << n << " " << n << " " << n << "\n-1.2 -1.2 -1.2\n" << h << " " << h << " " << h << "\n";
    for (double x : v) out << x << "\n";
  }
  const ImplicitPtr g = implicit::ParseShape("grid(file=\"" + path + "\")", ReadSdfGridFile);
  const MassPropertiesEstimate e = EstimateMassProperties(*g, 1.0, Qmc(1 << 18));
  EXPECT_NEAR(e.value.volume / (4 * massprops::kPi / 3), 1.0, 2e-3);
  EXPECT_LT(e.value.center_of_mass.norm(), 1e-3);
  {
    std::ofstream out(path);
    out << "sdfgrid 1\n3 3 3\n0 0 0\n1 1 1\n1 2 3" << std::string(60, ' ') << "\n";
  }
  EXPECT_THROW(ReadSdfGridFile(path), std::runtime_error);
  try {
    ReadSdfGridFile(path);
  } catch (const std::runtime_error& e2) {
    EXPECT_THAT(e2.what(), HasSubstr(path + ": expected 27 values, found 3"));
  }
  {
    std::ofstream out(path);
    out << "sdfgrid 1\n1000 1000 1000\n0 0 0\n1 1 1\n1 2 3\n";
  }
  try {
    ReadSdfGridFile(path);
    FAIL() << "accepted";
  } catch (const std::runtime_error& e3) {
    EXPECT_THAT(e3.what(), HasSubstr("the header promises 1000000000 values, more than the file"));
  }
}

// Over 200 seeds the reported 95 % interval of the volume covers the truth 90–99 % of the time.
TEST(Estimators, CalibrationOfTheReportedIntervals) {
  const ImplicitPtr sphere = implicit::Sphere(1.0);
  const double truth = 4 * massprops::kPi / 3;
  for (bool qmc : {false, true}) {
    int covered = 0;
    for (std::uint64_t seed = 1; seed <= 200; ++seed) {
      const MassPropertiesEstimate e = EstimateMassProperties(*sphere, 1.0, qmc ? Qmc(16 * 256, seed) : Mc(4000, seed));
      if (std::abs(e.value.volume - truth) <= e.interval95_factor * e.standard_error.volume) ++covered;
    }
    RecordProperty(qmc ? "qmc_coverage" : "mc_coverage", covered);
    EXPECT_GE(covered, 180) << (qmc ? "QMC" : "MC");
    EXPECT_LE(covered, 198) << (qmc ? "QMC" : "MC");
  }
}

// Log-log slope of the RMS volume error against N: −1/2 for MC, about −2/3 for scrambled Sobol.
TEST(Estimators, MeasuredConvergenceRates) {
  const ImplicitPtr sphere = implicit::Sphere(1.0);
  const double truth = 4 * massprops::kPi / 3;
  for (bool qmc : {false, true}) {
    std::vector<double> logn, logerr;
    for (int p = 10; p <= 18; p += 2) {
      const std::int64_t n = std::int64_t{1} << p;
      double ss = 0;
      const int seeds = 40;
      for (int s = 1; s <= seeds; ++s) {
        const auto e = EstimateMassProperties(
            *sphere, 1.0, qmc ? Qmc(n, static_cast<std::uint64_t>(s), 2) : Mc(n, static_cast<std::uint64_t>(s)));
        ss += (e.value.volume - truth) * (e.value.volume - truth);
      }
      logn.push_back(std::log(static_cast<double>(n)));
      logerr.push_back(0.5 * std::log(ss / seeds));
    }
    // Least-squares slope.
    double mx = 0, my = 0;
    const double count = static_cast<double>(logn.size());
    for (std::size_t i = 0; i < logn.size(); ++i) mx += logn[i] / count, my += logerr[i] / count;
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < logn.size(); ++i)
      sxy += (logn[i] - mx) * (logerr[i] - my), sxx += (logn[i] - mx) * (logn[i] - mx);
    const double slope = sxy / sxx;
    std::printf("%s: RMS error slope %.3f\n", qmc ? "QMC" : "MC", slope);
    RecordProperty(qmc ? "qmc_slope" : "mc_slope", std::to_string(slope));
    if (qmc) {
      EXPECT_LT(slope, -0.6);
    } else {
      EXPECT_NEAR(slope, -0.5, 0.1);
    }
  }
}

TEST(WindingNumber, ValuesInsideOutsideAndAgainstTheExactSum) {
  const TriangleMesh torus = solids::Torus(1.0, 0.3, 24);
  const ImplicitPtr w = implicit::WindingNumberSolid(torus);
  const ImplicitPtr exact = implicit::WindingNumberSolid(torus, 1e12);  // never expands: exact sum
  EXPECT_NEAR(implicit::WindingNumber(*exact, Vector3(1, 0, 0)), 1.0, 1e-12);
  EXPECT_NEAR(implicit::WindingNumber(*exact, Vector3(0, 0, 0)), 0.0, 1e-12);  // the hole
  EXPECT_NEAR(implicit::WindingNumber(*exact, Vector3(5, 1, 2)), 0.0, 1e-12);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vector3 x(u(rng), u(rng), 0.3 * u(rng));
    worst = std::max(worst, std::abs(implicit::WindingNumber(*w, x) - implicit::WindingNumber(*exact, x)));
  }
  EXPECT_LT(worst, 0.08);  // the dipole expansion of far clusters at beta = 2: measured 0.05
  // The inside test refines near w = 1/2: it agrees with the exact sum wherever |w − 1/2| > 1e-3.
  int disagreements = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vector3 x(u(rng), u(rng), 0.3 * u(rng));
    const double we = implicit::WindingNumber(*exact, x);
    if (std::abs(we - 0.5) > 1e-3 && w->Inside(x) != (we >= 0.5)) ++disagreements;
  }
  EXPECT_EQ(disagreements, 0);
}

// A closed mesh's inside test counts the faces a ray crosses (exact), and takes the hierarchy where
// the count is not certified: points on the mesh's own coordinates (rays along edges and faces).
TEST(WindingNumber, CrossingCountsAgreeWithTheExactSum) {
  const TriangleMesh prism = Triangulate(solids::RegularPrism(400, 1.0, 0.2));  // slivers on the side
  const ImplicitPtr w = implicit::WindingNumberSolid(prism);
  const ImplicitPtr exact = implicit::WindingNumberSolid(prism, 1e12);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  std::uniform_int_distribution<int> vertex(0, static_cast<int>(prism.V.rows()) - 1);
  int disagreements = 0, checked = 0;
  for (int i = 0; i < 4000; ++i) {
    Vector3 x(u(rng), u(rng), 0.2 * u(rng));
    if (i % 2 == 1) {  // two coordinates of a vertex: the ray runs along an edge or a side face
      const Vector3 v = prism.V.row(vertex(rng)).transpose();
      x[0] = v[0];
      x[1] = v[1];
      if (i % 4 == 3) x[2] = v[2];
    }
    const double we = implicit::WindingNumber(*exact, x);
    if (std::abs(we - 0.5) < 1e-3) continue;
    ++checked;
    if (w->Inside(x) != (we >= 0.5)) ++disagreements;
  }
  EXPECT_GT(checked, 3000);
  EXPECT_EQ(disagreements, 0);
}

TEST(WindingNumber, ClosedMeshWithHolesAndFarAwayAgreesWithTheExactResult) {
  const TriangleMesh torus = solids::Torus(1.0, 0.3, 32);
  const MassProperties polyhedral = ComputeMassProperties(torus, 1.0);
  const MassPropertiesEstimate closed = EstimateMassProperties(*implicit::WindingNumberSolid(torus), 1.0, Qmc(1 << 18));
  ExpectWithinErrorBars(closed, polyhedral, 4.5, "closed torus");
  // Five triangles removed: no exact polyhedral answer any more; the winding number still agrees.
  TriangleMesh holed = torus;
  for (int f : {10, 200, 555, 901, 1500})
    holed.F.row(f) = holed.F.row(holed.F.rows() - 1), holed.F.conservativeResize(holed.F.rows() - 1, 3);
  const MassPropertiesEstimate open = EstimateMassProperties(*implicit::WindingNumberSolid(holed), 1.0, Qmc(1 << 18));
  ExpectWithinErrorBars(open, polyhedral, 4.5, "torus with 5 holes");
  // Far from the origin: the same answer, moved.
  TriangleMesh far = holed;
  const Vector3 shift(3e4, -2e4, 1e4);
  far.V.rowwise() += shift.transpose();
  const MassPropertiesEstimate moved = EstimateMassProperties(*implicit::WindingNumberSolid(far), 1.0, Qmc(1 << 18));
  EXPECT_NEAR(moved.value.mass, open.value.mass, 1e-6 * open.value.mass);
  EXPECT_TRUE(testing::MatrixNearRel(moved.value.center_of_mass - shift, open.value.center_of_mass, 1e-6, 1));
  EXPECT_TRUE(
      testing::MatrixNearRel(moved.value.inertia_com, open.value.inertia_com, 1e-6, open.value.inertia_com.norm()));
}

TEST(Estimators, SameBitsForAnyThreadCount) {
  const ImplicitPtr s = implicit::ParseShape("difference(box(x=2, y=2, z=2), sphere(r=0.8))");
  for (MonteCarloOptions o : {Qmc(1 << 17), Mc(1 << 17)}) {
    o.num_threads = 1;
    const auto a = EstimateMassProperties(*s, 1.0, o);
    o.num_threads = 3;
    const auto b = EstimateMassProperties(*s, 1.0, o);
    EXPECT_TRUE(testing::SameBits(a.value, b.value));
    EXPECT_TRUE(testing::SameBits(a.standard_error, b.standard_error));
  }
}

TEST(Estimators, ToleranceIsMetByAddingSamples) {
  const ImplicitPtr s = implicit::Torus(1, 0.25);
  MonteCarloOptions o = Qmc(1 << 12);
  o.tolerance = 2e-4;
  const auto e = EstimateMassProperties(*s, 1.0, o);
  EXPECT_TRUE(e.tolerance_met);
  EXPECT_LT(e.MaxRelativeError(), 2e-4);
  EXPECT_GT(e.samples, 1 << 12);
  ExpectWithinErrorBars(e, solids::TorusProperties(1, 0.25, 1.0), 4.5, "adaptive torus");
  o.max_samples = 1 << 14;
  o.tolerance = 1e-9;
  EXPECT_FALSE(EstimateMassProperties(*s, 1.0, o).tolerance_met);
}

TEST(Implicit, PolygonizedSurfaceIsClosedAndNearTheSolid) {
  const ImplicitPtr s = implicit::ParseShape("difference(box(x=2, y=2, z=2), sphere(r=0.7))");
  const TriangleMesh m = implicit::Polygonize(*s, 40);
  const double truth = 8 - 4 * massprops::kPi / 3 * 0.343;
  IntegrationOptions a, b;
  a.reference = Vector3(0, 0, 0);
  b.reference = Vector3(3, -5, 7);
  const double va = IntegrateTriangles(m.V, m.F, a).volume, vb = IntegrateTriangles(m.V, m.F, b).volume;
  EXPECT_NEAR(va, vb, 1e-9 * va);  // closed: the signed volume does not depend on the reference
  EXPECT_NEAR(va, truth, 0.02 * truth);
}

TEST(ShapeSyntax, ParsesAndRefusesWithThePlace) {
  EXPECT_EQ(implicit::ParseShape(" torus( R = 1, r=0.25 ) ")->Describe(), "torus(R=1, r=0.25)");
  auto error = [](const std::string& s) {
    try {
      implicit::ParseShape(s, ReadSdfGridFile);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_THAT(error("torus(R=1)"), HasSubstr("torus: missing r="));
  EXPECT_THAT(error("torus(R=1, r=2)"), HasSubstr("r must be smaller than R"));
  EXPECT_THAT(error("spere(r=1)"), HasSubstr("character 1: unknown shape 'spere'"));
  EXPECT_THAT(error("sphere(r=1, q=2)"), HasSubstr("unknown parameter 'q'"));
  EXPECT_THAT(error("sphere(r=-1)"), HasSubstr("r must be finite and positive"));
  EXPECT_THAT(error("union(sphere(r=1))"), HasSubstr("union takes two or more shapes"));
  EXPECT_THAT(error("sphere(r=1"), HasSubstr("expected ')'"));
  EXPECT_THAT(error("sphere(r=1) x"), HasSubstr("after the shape"));
  EXPECT_THAT(error("grid(file=\"/no/such.sdf\")"), HasSubstr("/no/such.sdf: cannot open"));
  EXPECT_THAT(error("grid(file=\"/dev/zero\")"), HasSubstr("/dev/zero: not a regular file"));
  // The core alone opens no file.
  EXPECT_THROW(
      try { implicit::ParseShape("grid(file=\"/no/such.sdf\")"); } catch (const std::invalid_argument& e) {
        EXPECT_THAT(e.what(), HasSubstr("needs massprops::io"));
        throw;
      },
      std::invalid_argument);
  std::string deep;
  for (int i = 0; i < 1000; ++i) deep += "scale(";
  EXPECT_THAT(error(deep), HasSubstr("nested more than 200 deep"));
}

}  // namespace
}  // namespace massprops
