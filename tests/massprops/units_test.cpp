// units.h in isolation: the one table of unit names and factors, against their definitions
// (1 in = 0.0254 m, 1 ft = 0.3048 m, 1 lb = 0.45359237 kg, all exact).

#include "massprops/units.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace massprops {
namespace {

using ::testing::HasSubstr;

TEST(Units, LengthFactorsAreTheDefinitions) {
  EXPECT_EQ(MetresPerUnit(LengthUnit::kMetre), 1.0);
  EXPECT_EQ(MetresPerUnit(LengthUnit::kCentimetre), 0.01);
  EXPECT_EQ(MetresPerUnit(LengthUnit::kMillimetre), 0.001);
  EXPECT_EQ(MetresPerUnit(LengthUnit::kInch), 0.0254);
  EXPECT_EQ(MetresPerUnit(LengthUnit::kFoot), 0.3048);
  EXPECT_EQ(MetresPerUnit(LengthUnit::kMicrometre), 1e-6);
}

TEST(Units, EveryNameParsesBackToItsUnit) {
  for (const LengthUnit u : kAllLengthUnits) {
    EXPECT_EQ(ParseLengthUnit(UnitName(u)), u) << UnitName(u);
    EXPECT_THAT(LengthUnitNames(), HasSubstr(UnitName(u)));
  }
  EXPECT_FALSE(FindLengthUnit("furlong").has_value());
  EXPECT_FALSE(FindLengthUnit("").has_value());
  try {
    ParseLengthUnit("furlong");
    FAIL() << "an unknown unit was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("furlong"));
    EXPECT_THAT(e.what(), HasSubstr("mm"));  // names the known ones
  }
}

TEST(Units, ReportSystemsByName) {
  const ReportUnits si = ParseReportUnits("si");
  EXPECT_TRUE(si.IsSi());
  const ReportUnits mmgs = ParseReportUnits("mmgs");
  EXPECT_FALSE(mmgs.IsSi());
  EXPECT_EQ(mmgs.Mass(), 1e-3);
  EXPECT_EQ(mmgs.Length(), 1e-3);
  EXPECT_DOUBLE_EQ(mmgs.Volume(), 1e-9);
  EXPECT_DOUBLE_EQ(mmgs.Inertia(), 1e-3 * 1e-6);  // g·mm²
  EXPECT_DOUBLE_EQ(mmgs.Density(), 1e-3 / 1e-9);  // g/mm³ in kg/m³
  EXPECT_EQ(mmgs.DensityName(), "g/mm^3");
  const ReportUnits ips = ParseReportUnits("ips");
  EXPECT_EQ(ips.Mass(), 0.45359237);
  EXPECT_EQ(ips.Length(), 0.0254);
  EXPECT_DOUBLE_EQ(ips.Inertia(), 0.45359237 * 0.0254 * 0.0254);
  const ReportUnits cgs = ParseReportUnits("cgs");
  EXPECT_DOUBLE_EQ(cgs.Inertia(), 1e-3 * 1e-4);  // g·cm²
}

TEST(Units, ReportUnitsByTheirThreeNames) {
  const ReportUnits u = ParseReportUnits("kg,mm,kg*mm^2");
  EXPECT_EQ(u.Mass(), 1.0);
  EXPECT_EQ(u.Length(), 1e-3);
  EXPECT_DOUBLE_EQ(u.Inertia(), 1e-6);
  EXPECT_EQ(u.Describe(), "kg, mm, kg*mm^2");
  const ReportUnits lbft = ParseReportUnits("lb,ft,lb*ft^2");
  EXPECT_DOUBLE_EQ(lbft.Inertia(), 0.45359237 * 0.3048 * 0.3048);
  for (const char* bad : {"", "furlongs", "kg,mm", "kg,mm,kg*mm^2,x", "stone,mm,kg*mm^2", "kg,mm,kg*parsec^2"}) {
    EXPECT_THROW(ParseReportUnits(bad), std::invalid_argument) << "'" << bad << "'";
  }
}

}  // namespace
}  // namespace massprops
