// engine/weather/grib_reader: the GFS subset in tests/data/weather against the values ecCodes'
// own tools print for it, grids written here with known positions (Lambert conformal,
// reduced Gaussian), several steps, missing values, and one-line errors for bad files.
#include "engine/weather/grib_reader.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <numeric>

#include <gtest/gtest.h>

#include "error_capture.h"
#include "grib_writer.h"

namespace sky {
namespace {

using test::GribWriter;

struct Stats {
  double min = 1e300, max = -1e300, mean = 0.0;
  size_t nan = 0;
};

Stats stats(const std::vector<float>& v) {
  Stats s;
  double sum = 0.0;
  for (float x : v) {
    if (std::isnan(x)) {
      ++s.nan;
      continue;
    }
    s.min = std::min(s.min, double(x));
    s.max = std::max(s.max, double(x));
    sum += x;
  }
  s.mean = sum / double(v.size() - s.nan);
  return s;
}

// A regular lat/lon field of `ni` x `nj` points from (latFirst, lonFirst) stepping 5 degrees
// east and south, on `levelType` (isobaricInhPa, lowCloudLayer...) at `level`.
GribWriter latLonField(const char* shortName, const char* levelType, long level, uint32_t ni,
                       uint32_t nj, const std::vector<double>& values, double latFirst = 10.0,
                       double lonFirst = 0.0) {
  GribWriter w("regular_ll_pl_grib2");
  w.set("Ni", long(ni))
      .set("Nj", long(nj))
      .set("latitudeOfFirstGridPointInDegrees", latFirst)
      .set("latitudeOfLastGridPointInDegrees", latFirst - 5.0 * (nj - 1))
      .set("longitudeOfFirstGridPointInDegrees", lonFirst)
      .set("longitudeOfLastGridPointInDegrees", lonFirst + 5.0 * (ni - 1))
      .set("iDirectionIncrementInDegrees", 5.0)
      .set("jDirectionIncrementInDegrees", 5.0)
      .set("numberOfDataPoints", long(ni * nj))
      .set("dataDate", 20240601L)
      .set("dataTime", 0L)
      .set("centre", 7L)  // NCEP: its local tables define the cloud-layer level types
      .set("typeOfLevel", levelType)
      .set("shortName", shortName)
      .set("level", level);
  if (!values.empty()) w.values(values);
  return w;
}

std::vector<double> ramp(size_t n, double scale) {
  std::vector<double> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = double(i) * scale;
  return v;
}

TEST(GribReader, ReadsTheGfsSubset) {
  WeatherFields w = readGrib2(test::gfsFixture());
  const GridGeometry& g = w.grid;
  EXPECT_EQ(g.nx, 144u);
  EXPECT_EQ(g.ny, 73u);
  ASSERT_EQ(g.size(), 144u * 73u);
  EXPECT_TRUE(g.regularLatLon);
  EXPECT_DOUBLE_EQ(g.latDeg.front(), 90.0);
  EXPECT_DOUBLE_EQ(g.latDeg.back(), -90.0);
  EXPECT_DOUBLE_EQ(g.lonDeg.front(), 0.0);
  EXPECT_DOUBLE_EQ(g.lonDeg[143], 357.5);
  EXPECT_DOUBLE_EQ(g.latDeg[145], 87.5);  // row 1, column 1
  EXPECT_DOUBLE_EQ(g.lonDeg[145], 2.5);

  ASSERT_EQ(w.steps.size(), 1u);
  const WeatherStep& s = w.steps[0];
  EXPECT_EQ(s.validTimeUnix, 1295092800.0);  // 2011-01-15T12:00Z: run 2011-01-10 12Z + 120 h
  EXPECT_EQ(s.levels(FieldKind::RelativeHumidity).size(), 25u);
  EXPECT_EQ(s.levels(FieldKind::Temperature).size(), 26u);
  EXPECT_EQ(s.levels(FieldKind::GeopotentialHeight).size(), 26u);
  EXPECT_EQ(s.levels(FieldKind::RelativeHumidity).front(), 1000.0);
  EXPECT_EQ(s.levels(FieldKind::RelativeHumidity).back(), 10.0);

  // Values as `grib_ls -p min,max,average` prints them (percent there, fractions here).
  const LevelField* r850 = s.find(FieldKind::RelativeHumidity, 850.0);
  ASSERT_TRUE(r850);
  Stats r = stats(r850->values);
  EXPECT_EQ(r.nan, 0u);
  EXPECT_NEAR(r.min, 0.02, 1e-4);
  EXPECT_NEAR(r.max, 1.0, 1e-6);
  EXPECT_NEAR(r.mean, 0.685449, 1e-4);
  EXPECT_NEAR(stats(s.find(FieldKind::RelativeHumidity, 500.0)->values).mean, 0.511277, 1e-4);

  const LevelField* gh500 = s.find(FieldKind::GeopotentialHeight, 500.0);
  ASSERT_TRUE(gh500);
  Stats gh = stats(gh500->values);
  EXPECT_NEAR(gh.min, 4893.2, 0.05);
  EXPECT_NEAR(gh.max, 5901.73, 0.05);
  EXPECT_NEAR(gh.mean, 5509.44, 0.05);

  ASSERT_TRUE(s.find(FieldKind::CloudCoverLow) && s.find(FieldKind::CloudCoverMid) && s.find(FieldKind::CloudCoverHigh));
  EXPECT_NEAR(stats(s.find(FieldKind::CloudCoverLow)->values).mean, 0.309517, 1e-4);
  EXPECT_NEAR(stats(s.find(FieldKind::CloudCoverMid)->values).mean, 0.195937, 1e-4);
  EXPECT_NEAR(stats(s.find(FieldKind::CloudCoverHigh)->values).mean, 0.290483, 1e-4);
  EXPECT_EQ(stats(s.find(FieldKind::CloudCoverHigh)->values).max, 1.0);

  // u and v share one message in the GFS file: both come out only with multi-field support.
  ASSERT_TRUE(s.find(FieldKind::WindU, 500.0) && s.find(FieldKind::WindV, 500.0));
  EXPECT_NEAR(stats(s.find(FieldKind::WindU, 500.0)->values).mean, 6.85428, 1e-3);
  EXPECT_NEAR(stats(s.find(FieldKind::WindV, 500.0)->values).mean, 0.0450989, 1e-3);
  EXPECT_NEAR(stats(s.find(FieldKind::Temperature, 500.0)->values).mean, 253.0, 10.0);  // K, not Celsius
  EXPECT_EQ(s.fields.size(), 25u + 26u + 26u + 3u + 2u);
}

// Snyder, Map Projections - A Working Manual (1987), (15-1)..(15-3) and (14-4) on a sphere:
// the inverse Lambert conformal conic, independent of ecCodes.
struct Lambert {
  double n, f, rho0, lon0, radius;
  Lambert(double lat1, double lat2, double latOrigin, double lonOrigin, double r)
      : lon0(lonOrigin), radius(r) {
    auto t = [](double latDeg) { return std::tan(std::numbers::pi / 4 + rad(latDeg) / 2); };
    n = std::log(std::cos(rad(lat1)) / std::cos(rad(lat2))) / std::log(t(lat2) / t(lat1));
    f = std::cos(rad(lat1)) * std::pow(t(lat1), n) / n;
    rho0 = radius * f / std::pow(t(latOrigin), n);
  }
  static double rad(double d) { return d * std::numbers::pi / 180.0; }
  static double deg(double r) { return r * 180.0 / std::numbers::pi; }
  void forward(double latDeg, double lonDeg, double& x, double& y) const {
    double rho = radius * f / std::pow(std::tan(std::numbers::pi / 4 + rad(latDeg) / 2), n);
    double theta = n * rad(lonDeg - lon0);
    x = rho * std::sin(theta);
    y = rho0 - rho * std::cos(theta);
  }
  void inverse(double x, double y, double& latDeg, double& lonDeg) const {
    double rho = std::copysign(std::hypot(x, rho0 - y), n);
    double theta = std::atan2(x, rho0 - y);
    latDeg = deg(2.0 * std::atan(std::pow(radius * f / rho, 1.0 / n)) - std::numbers::pi / 2);
    lonDeg = lon0 + deg(theta / n);
  }
};

TEST(GribReader, LambertConformalPositionsPerPoint) {
  constexpr uint32_t kNx = 6, kNy = 5;
  constexpr double kDx = 50000.0, kRadius = 6371229.0;  // shapeOfTheEarth 6
  GribWriter w("regular_ll_pl_grib2");
  w.set("gridDefinitionTemplateNumber", 30L)
      .set("shapeOfTheEarth", 6L)
      .set("Nx", long(kNx))
      .set("Ny", long(kNy))
      .set("latitudeOfFirstGridPointInDegrees", 40.0)
      .set("longitudeOfFirstGridPointInDegrees", 260.0)
      .set("LaDInDegrees", 45.0)
      .set("LoVInDegrees", 265.0)
      .set("Latin1InDegrees", 30.0)
      .set("Latin2InDegrees", 60.0)
      .set("DxInMetres", kDx)
      .set("DyInMetres", kDx)
      .set("iScansNegatively", 0L)
      .set("jScansPositively", 1L)
      .set("numberOfDataPoints", long(kNx * kNy))
      .set("typeOfLevel", "isobaricInhPa")
      .set("level", 700L)
      .set("shortName", "r")
      .values(ramp(kNx * kNy, 3.0));  // percent
  std::filesystem::path file = test::tempFile("lambert.grib2");
  w.appendTo(file);

  WeatherFields f = readGrib2(file);
  const GridGeometry& g = f.grid;
  EXPECT_EQ(g.nx, kNx);
  EXPECT_EQ(g.ny, kNy);
  EXPECT_FALSE(g.regularLatLon);
  ASSERT_EQ(g.size(), size_t(kNx * kNy));

  Lambert proj(30.0, 60.0, 45.0, 265.0, kRadius);
  double x0 = 0.0, y0 = 0.0;
  proj.forward(40.0, 260.0, x0, y0);
  double worst = 0.0;
  for (uint32_t j = 0; j < kNy; ++j)
    for (uint32_t i = 0; i < kNx; ++i) {
      double lat = 0.0, lon = 0.0;
      proj.inverse(x0 + i * kDx, y0 + j * kDx, lat, lon);
      size_t k = size_t(j) * kNx + i;
      worst = std::max({worst, std::fabs(g.latDeg[k] - lat), std::fabs(g.lonDeg[k] - lon)});
    }
  EXPECT_LT(worst, 1e-5) << "degrees, worst point";
  // North-east of the first point by rows, and a row is not a parallel.
  EXPECT_GT(g.latDeg[kNx], g.latDeg[0]);
  EXPECT_NE(g.latDeg[0], g.latDeg[kNx - 1]);

  const LevelField* r = f.steps.at(0).find(FieldKind::RelativeHumidity, 700.0);
  ASSERT_TRUE(r);
  for (size_t k = 0; k < r->values.size(); ++k) EXPECT_NEAR(r->values[k], 0.03 * double(k), 1e-4);
}

TEST(GribReader, ReducedGaussianGridIsOneListOfPoints) {
  GribWriter w("reduced_gg_pl_32_grib2");
  w.set("shortName", "r").set("level", 850L);
  std::filesystem::path file = test::tempFile("reduced.grib2");
  w.appendTo(file);
  WeatherFields f = readGrib2(file);
  EXPECT_EQ(f.grid.ny, 1u);
  EXPECT_EQ(f.grid.nx, 6114u);
  EXPECT_FALSE(f.grid.regularLatLon);
  auto [latLo, latHi] = std::minmax_element(f.grid.latDeg.begin(), f.grid.latDeg.end());
  auto [lonLo, lonHi] = std::minmax_element(f.grid.lonDeg.begin(), f.grid.lonDeg.end());
  EXPECT_GT(*latHi, 87.0);  // N32 Gaussian: first latitude 87.86
  EXPECT_LT(*latLo, -87.0);
  EXPECT_GE(*lonLo, 0.0);
  EXPECT_LT(*lonHi, 360.0);
  // Rows shrink toward the poles: the first row holds far fewer points than 128.
  size_t firstRow =
      size_t(std::count(f.grid.latDeg.begin(), f.grid.latDeg.end(), f.grid.latDeg[0]));
  EXPECT_LT(firstRow, 64u);
}

TEST(GribReader, StepsComeOutInValidTimeOrder) {
  std::filesystem::path file = test::tempFile("steps.grib2");
  // Written latest first: the reader sorts by valid time, not by file order.
  latLonField("tcc", "lowCloudLayer", 0, 4, 3, std::vector<double>(12, 80.0))
      .set("step", 6L)
      .appendTo(file);
  latLonField("tcc", "lowCloudLayer", 0, 4, 3, std::vector<double>(12, 20.0))
      .set("step", 0L)
      .appendTo(file);
  WeatherFields f = readGrib2(file);
  ASSERT_EQ(f.steps.size(), 2u);
  EXPECT_EQ(f.steps[0].validTimeUnix, 1717200000.0);  // 2024-06-01T00:00Z
  EXPECT_EQ(f.steps[1].validTimeUnix, 1717200000.0 + 6 * 3600.0);
  ASSERT_TRUE(f.steps[0].find(FieldKind::CloudCoverLow) && f.steps[1].find(FieldKind::CloudCoverLow));
  EXPECT_NEAR(f.steps[0].find(FieldKind::CloudCoverLow)->values[5], 0.2, 1e-4);
  EXPECT_NEAR(f.steps[1].find(FieldKind::CloudCoverLow)->values[5], 0.8, 1e-4);
  EXPECT_EQ(f.grid.nx, 4u);
  EXPECT_EQ(f.grid.ny, 3u);
  EXPECT_TRUE(f.grid.regularLatLon);
}

TEST(GribReader, LongitudesWestOfGreenwichAreNormalised) {
  std::filesystem::path file = test::tempFile("west.grib2");
  latLonField("r", "isobaricInhPa", 850, 5, 2, ramp(10, 10.0), 10.0, 350.0).appendTo(file);
  WeatherFields f = readGrib2(file);
  ASSERT_EQ(f.grid.size(), 10u);
  for (double lon : f.grid.lonDeg) EXPECT_TRUE(lon >= -180.0 && lon < 360.0) << lon;
  EXPECT_TRUE(f.grid.regularLatLon);  // still monotonic across 0
  EXPECT_DOUBLE_EQ(f.grid.lonDeg[4] - f.grid.lonDeg[0], 20.0);
}

TEST(GribReader, BitmapMissingValuesBecomeNaN) {
  std::filesystem::path file = test::tempFile("bitmap.grib2");
  std::vector<double> v = ramp(12, 5.0);
  v[3] = 9999.0;
  v[7] = 9999.0;
  GribWriter w = latLonField("r", "isobaricInhPa", 850, 4, 3, {});
  w.set("missingValue", 9999.0).set("bitmapPresent", 1L).values(v).appendTo(file);
  WeatherFields f = readGrib2(file);
  const LevelField* r = f.steps.at(0).find(FieldKind::RelativeHumidity, 850.0);
  ASSERT_TRUE(r);
  EXPECT_TRUE(std::isnan(r->values[3]));
  EXPECT_TRUE(std::isnan(r->values[7]));
  EXPECT_NEAR(r->values[2], 0.10, 1e-4);
  EXPECT_EQ(stats(r->values).nan, 2u);
}

TEST(GribReader, HumidityOutsidePercentRangeIsClampedWithOneWarning) {
  std::filesystem::path file = test::tempFile("range.grib2");
  std::vector<double> v(12, 50.0);
  v[0] = 112.0;
  v[1] = -4.0;
  v[2] = 100.5;  // within 1 %: clamped silently
  latLonField("r", "isobaricInhPa", 850, 4, 3, v).appendTo(file);
  latLonField("r", "isobaricInhPa", 700, 4, 3, v).appendTo(file);
  testing::internal::CaptureStderr();
  WeatherFields f = readGrib2(file);
  std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find("range.grib2"), std::string::npos) << err;
  EXPECT_NE(err.find("4 values of r"), std::string::npos) << err;
  const LevelField* r = f.steps.at(0).find(FieldKind::RelativeHumidity, 850.0);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->values[0], 1.0f);
  EXPECT_EQ(r->values[1], 0.0f);
  EXPECT_EQ(r->values[2], 1.0f);
  EXPECT_NEAR(r->values[3], 0.5, 1e-4);
}

// Every error: BadInput, one line, naming the file.
void expectOneLineInputError(const Error& e, const std::string& file, const std::string& part) {
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  std::string what = e.what();
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  EXPECT_NE(what.find(file), std::string::npos) << what;
  EXPECT_NE(what.find(part), std::string::npos) << what;
}

TEST(GribReader, MissingFile) {
  std::filesystem::path file = test::tempFile("absent.grib2");
  expectOneLineInputError(test::catchError([&] { readGrib2(file); }), "absent.grib2",
                          "no such file");
}

TEST(GribReader, NotGrib) {
  std::filesystem::path file = test::tempFile("notes.grib2");
  // "GRIB" in text is not a message header.
  std::ofstream(file) << "GRIB2 export failed; temperature,humidity\n280,0.5\n";
  expectOneLineInputError(test::catchError([&] { readGrib2(file); }), "notes.grib2",
                          "not a GRIB file");
}

TEST(GribReader, TruncatedFileNamesTheMessage) {
  std::ifstream in(test::gfsFixture(), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 100000u);
  std::filesystem::path file = test::tempFile("cut.grib2");
  // Message 1 is 16299 bytes long: cutting at 20000 leaves message 2 incomplete.
  std::ofstream(file, std::ios::binary).write(bytes.data(), 20000);
  expectOneLineInputError(test::catchError([&] { readGrib2(file); }), "cut.grib2", "message 2");
  // Cut in the middle of the file: still a one-line error, never a partial result.
  std::filesystem::remove(file);
  std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 2));
  expectOneLineInputError(test::catchError([&] { readGrib2(file); }), "cut.grib2", "message ");
}

TEST(GribReader, NoHumidityOrCloudCover) {
  std::filesystem::path file = test::tempFile("temperature_only.grib2");
  latLonField("t", "isobaricInhPa", 850, 4, 3, std::vector<double>(12, 280.0)).appendTo(file);
  latLonField("gh", "isobaricInhPa", 850, 4, 3, std::vector<double>(12, 1500.0)).appendTo(file);
  expectOneLineInputError(test::catchError([&] { readGrib2(file); }), "temperature_only.grib2",
                          "no relative humidity or cloud cover");
}

TEST(GribReader, GridChangingBetweenMessages) {
  std::filesystem::path file = test::tempFile("two_grids.grib2");
  latLonField("r", "isobaricInhPa", 850, 4, 3, std::vector<double>(12, 50.0)).appendTo(file);
  latLonField("r", "isobaricInhPa", 700, 3, 4, std::vector<double>(12, 50.0)).appendTo(file);
  expectOneLineInputError(test::catchError([&] { readGrib2(file); }), "two_grids.grib2",
                          "message 2: grid differs");
}

TEST(GribReader, DuplicateFieldIsAnError) {
  std::filesystem::path file = test::tempFile("twice.grib2");
  latLonField("r", "isobaricInhPa", 850, 4, 3, std::vector<double>(12, 50.0)).appendTo(file);
  latLonField("r", "isobaricInhPa", 850, 4, 3, std::vector<double>(12, 60.0)).appendTo(file);
  expectOneLineInputError(test::catchError([&] { readGrib2(file); }), "twice.grib2",
                          "message 2: a second r at 850");
}

}  // namespace
}  // namespace sky
