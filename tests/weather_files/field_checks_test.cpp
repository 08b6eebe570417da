// The one validation path of both forecast readers (engine/weather/field_checks.h).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/warnings.h"
#include "engine/weather/field_checks.h"

namespace sky {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

GridGeometry grid(uint32_t nx, uint32_t ny, std::vector<double> lat, std::vector<double> lon) {
  GridGeometry g;
  g.nx = nx;
  g.ny = ny;
  g.latDeg = std::move(lat);
  g.lonDeg = std::move(lon);
  return g;
}

// The readers' copies had drifted: a 1 x 1 grid was regular in the GRIB reader and not in
// the NetCDF one. A single point has no spacing: not regular, in both.
TEST(FieldChecks, OneRegularGridTest) {
  EXPECT_FALSE(isRegularGrid(grid(1, 1, {45}, {7})));
  EXPECT_TRUE(isRegularGrid(grid(2, 1, {45, 45}, {7, 8})));
  EXPECT_TRUE(isRegularGrid(grid(2, 2, {46, 46, 45, 45}, {7, 8, 7, 8})));
  EXPECT_FALSE(isRegularGrid(grid(2, 2, {46, 46, 45, 45}, {7, 8, 7, 9})));  // lon by row
  EXPECT_FALSE(isRegularGrid(grid(3, 1, {45, 45, 45}, {7, 8, 8})));         // not strict
}

TEST(FieldChecks, LongitudesIntoOneRange) {
  EXPECT_EQ(normaliseLon(-180.0), -180.0);
  EXPECT_EQ(normaliseLon(359.5), 359.5);  // kept as the file wrote it
  EXPECT_EQ(normaliseLon(360.0), 0.0);
  EXPECT_EQ(normaliseLon(-190.0), 170.0);
  EXPECT_EQ(normaliseLon(1e6 + 0.5), std::fmod(1e6 + 0.5 + 180.0, 360.0) - 180.0);
}

// Fractions clamped, one warning per field through the sink; a wholly unusable field is an
// error; values that decoded to NaN are counted.
TEST(FieldChecks, WarningsGoToTheSinkAndAnUnusableFieldIsAnError) {
  std::vector<std::string> lines;
  WarningSink previous = setWarningSink([&](const std::string& l) { lines.push_back(l); });
  const float nan = std::numeric_limits<float>::quiet_NaN();
  FieldChecks checks("f.grib2");
  std::vector<float> r = {50.0f, 100.5f, 112.0f, -4.0f, nan};
  checks.toFraction(r, 0.01, "r");
  EXPECT_FLOAT_EQ(r[1], 1.0f);  // rounding: clamped silently
  EXPECT_FLOAT_EQ(r[3], 0.0f);
  EXPECT_TRUE(std::isnan(r[4]));
  checks.noteNonFinite("gh", 3, 10);
  WeatherFields fields;
  fields.steps.push_back({0.0, {{FieldKind::RelativeHumidity, 850.0, r}, {FieldKind::GeopotentialHeight, 850.0, {1500.0f, nan}}}});
  checks.finish(fields);
  EXPECT_THAT(lines, ElementsAre("f.grib2: 3 of 10 values of gh decoded to NaN or infinity; "
                                 "taken as missing",
                                 "f.grib2: 2 values of r outside [0, 1] by more than 1 % (-0.04 "
                                 "to 1.12), clamped"));
  fields.steps[0].fields[1].values = {nan, nan};
  try {
    FieldChecks("f.grib2").finish(fields);
    ADD_FAILURE() << "a gh with no finite value was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("f.grib2: gh: no finite value in any of its 1 field"));
  }
  setWarningSink(std::move(previous));
}

}  // namespace
}  // namespace sky
