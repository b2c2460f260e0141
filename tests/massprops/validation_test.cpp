// The validation users run (massprops validate) asserts what the README promises: second-order
// convergence of every smooth solid's tessellations by both paths, at the origin and far from it,
// and the polyhedra exact to rounding.

#include "massprops/validation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace massprops {
namespace {

TEST(Validation, SecondOrderForSmoothSolidsAndExactPolyhedra) {
  ValidationOptions o;
  o.resolutions = {16, 32, 64};
  const std::vector<ConvergenceRow> rows = ValidateClosedForms(o);
  const std::vector<std::string> exact = {"box", "tetrahedron", "octahedron", "prism"};
  std::map<std::string, int> checked;
  for (const ConvergenceRow& r : rows) {
    const bool polyhedron = std::find(exact.begin(), exact.end(), r.solid) != exact.end();
    if (polyhedron) {
      const double limit = r.far ? 2e-11 : 1e-15;  // far: the moved coordinates' own rounding
      EXPECT_LT(r.volume_error, limit) << r.solid << " " << r.path;
      EXPECT_LT(r.inertia_error, limit) << r.solid << " " << r.path;
      EXPECT_LT(r.com_error, limit) << r.solid << " " << r.path;
    } else if (r.resolution == 64) {
      EXPECT_NEAR(r.volume_order, 2.0, 0.05) << r.solid << " " << r.path << (r.far ? " far" : "");
      EXPECT_NEAR(r.inertia_order, 2.0, 0.05) << r.solid << " " << r.path << (r.far ? " far" : "");
      EXPECT_LT(r.com_error, 1e-12) << r.solid;  // symmetric tessellations: the center stays put
      EXPECT_LT(r.inertia_error, 1e-2) << r.solid;
    }
    ++checked[r.solid];
  }
  EXPECT_EQ(checked.size(), ValidationSolids().size());
  EXPECT_EQ(checked["box"], 4);      // 2 placements × 2 paths
  EXPECT_EQ(checked["sphere"], 12);  // × 3 resolutions
  EXPECT_THROW(ValidateClosedForms(ValidationOptions{{"dodecahedron"}, {8}}), std::invalid_argument);
}

}  // namespace
}  // namespace massprops
