// engine/weather/cloud_layers_from_fields.h on fields built here: Lu (1)(2) cover, the maximum
// over a layer's levels, the tcc path, missing values, the errors, time interpolation, the
// layer altitudes from gh and the standard atmosphere, and the resampling onto the map
// (exact at data points, smooth, longitude wrap, regions outside the data) for regular
// lat/lon grids and for scattered points.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/weather/cloud_layers_from_fields.h"
#include "error_capture.h"

namespace sky {
namespace {

// Where a test does not care about the region: layerCover's region only sets the altitudes'
// means.
const WeatherRegion kTestRegion{{45.0, 50.0}, {5.0, 12.0}};
using test::catchError;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The GFS 2.5 degree grid: 144 x 73, lat 90 -> -90, lon 0 -> 357.5.
GridGeometry globalGrid() {
  GridGeometry g;
  g.nx = 144;
  g.ny = 73;
  g.regularLatLon = true;
  for (uint32_t j = 0; j < g.ny; ++j)
    for (uint32_t i = 0; i < g.nx; ++i) {
      g.latDeg.push_back(90.0 - 2.5 * j);
      g.lonDeg.push_back(2.5 * i);
    }
  return g;
}

// A field of `grid` from a function of (lat, lon).
template <class F>
LevelField field(const GridGeometry& grid, FieldKind kind, double hpa, F f) {
  LevelField out{kind, hpa, {}};
  for (size_t k = 0; k < grid.size(); ++k)
    out.values.push_back(float(f(grid.latDeg[k], grid.lonDeg[k])));
  return out;
}

LevelField constant(const GridGeometry& grid, FieldKind kind, double hpa, float v) {
  return field(grid, kind, hpa, [&](double, double) { return v; });
}

WeatherFields oneStep(const GridGeometry& grid, std::vector<LevelField> f, double time = 0.0) {
  WeatherFields w;
  w.file = "synthetic.grib2";
  w.grid = grid;
  w.steps.push_back({time, std::move(f)});
  return w;
}

// r on every GFS level from 1000 to 150 hPa, constant `rh`.
std::vector<LevelField> allLevels(const GridGeometry& grid, float rh) {
  std::vector<LevelField> out;
  for (double p : {1000, 975, 950, 925, 900, 850, 800, 750, 700, 650,
                   600,  550, 500, 450, 400, 350, 300, 250, 200, 150})
    out.push_back(constant(grid, FieldKind::RelativeHumidity, p, rh));
  return out;
}

size_t pointAt(const GridGeometry& g, double lat, double lon) {
  for (size_t k = 0; k < g.size(); ++k)
    if (g.latDeg[k] == lat && g.lonDeg[k] == lon) return k;
  ADD_FAILURE() << "no point at " << lat << ", " << lon;
  return 0;
}

TEST(HumidityCover, LuEquationOne) {
  // Zero at and below the critical humidity, one at saturation.
  for (float rhcr : {0.8f, 0.65f}) {
    EXPECT_EQ(humidityCover(rhcr, rhcr), 0.0f);
    EXPECT_EQ(humidityCover(rhcr - 0.1f, rhcr), 0.0f);
    EXPECT_EQ(humidityCover(0.0f, rhcr), 0.0f);
    EXPECT_FLOAT_EQ(humidityCover(1.0f, rhcr), 1.0f);
  }
  // Halfway from rh_cr to saturation is a quarter covered: ((0.9 - 0.8) / 0.2)^2.
  EXPECT_NEAR(humidityCover(0.9f, 0.8f), 0.25f, 1e-6f);
  EXPECT_NEAR(humidityCover(0.825f, 0.65f), 0.25f, 1e-6f);
  EXPECT_NEAR(humidityCover(0.95f, 0.8f), 0.5625f, 1e-6f);
  EXPECT_NEAR(humidityCover(0.72f, 0.65f), 0.04f, 1e-6f);
  // Missing (NaN) is clear; above saturation counts as saturated.
  EXPECT_EQ(humidityCover(kNaN, 0.8f), 0.0f);
  EXPECT_FLOAT_EQ(humidityCover(1.03f, 0.8f), 1.0f);
}

TEST(StandardAtmosphere, IcaoTable) {
  EXPECT_NEAR(standardAtmosphereAltitudeM(1013.25), 0.0, 1e-9);
  EXPECT_NEAR(standardAtmosphereAltitudeM(850.0), 1457.0, 2.0);
  EXPECT_NEAR(standardAtmosphereAltitudeM(500.0), 5574.0, 2.0);
  EXPECT_NEAR(standardAtmosphereAltitudeM(226.32), 11000.0, 1.0);
  EXPECT_NEAR(standardAtmosphereAltitudeM(100.0), 16180.0, 5.0);
}

TEST(LayerCover, MaximumOverTheLayersLevels) {
  const GridGeometry g = globalGrid();
  std::vector<LevelField> f = allLevels(g, 0.5f);
  const size_t k = pointAt(g, 30.0, 60.0);
  const auto set = [&](double p, float rh) {
    for (LevelField& l : f)
      if (l.pressureHpa == p) l.values[k] = rh;
  };
  set(1000, 0.9f);   // low: 0.25
  set(850, 0.95f);   // low: 0.5625, the largest
  set(925, kNaN);    // missing: clear
  set(700, 0.825f);  // mid (rh_cr 0.65): 0.25
  set(500, 0.72f);   // mid: 0.04
  set(300, 0.9f);    // high (rh_cr 0.8): 0.25
  const WeatherSettings w;
  const LayerCover c = layerCover(oneStep(g, f), 0.0, w, kTestRegion);
  ASSERT_EQ(c.low.size(), g.size());
  EXPECT_NEAR(c.low[k], 0.5625f, 1e-6f);
  EXPECT_NEAR(c.mid[k], 0.25f, 1e-6f);
  EXPECT_NEAR(c.high[k], 0.25f, 1e-6f);
  // Everywhere else rh 0.5 is below every critical humidity.
  EXPECT_EQ(c.low[k + 1], 0.0f);
  EXPECT_EQ(*std::max_element(c.mid.begin(), c.mid.begin() + k), 0.0f);
}

TEST(LayerCover, BoundaryLevelsBelongToBothLayersAndBoundsAreSettable) {
  const GridGeometry g = globalGrid();
  std::vector<LevelField> f = allLevels(g, 0.5f);
  for (LevelField& l : f)
    if (l.pressureHpa == 800) l.values.assign(g.size(), 1.0f);
  WeatherSettings w;
  LayerCover c = layerCover(oneStep(g, f), 0.0, w, kTestRegion);
  EXPECT_EQ(c.low[0], 1.0f);  // [800, 1000]
  EXPECT_EQ(c.mid[0], 1.0f);  // [450, 800]
  EXPECT_EQ(c.high[0], 0.0f);
  // Moving the low layer's top below 800 hPa leaves the saturated level out of it; a
  // higher critical humidity lowers the same humidity's cover.
  w.low.topHpa = 850.0;
  w.mid.rhCritical = 0.9;
  for (LevelField& l : f)
    if (l.pressureHpa == 800) l.values.assign(g.size(), 0.95f);
  c = layerCover(oneStep(g, f), 0.0, w, kTestRegion);
  EXPECT_EQ(c.low[0], 0.0f);
  EXPECT_NEAR(c.mid[0], 0.25f, 1e-5f);
}

TEST(LayerCover, TccIsTheModelsOwnCover) {
  const GridGeometry g = globalGrid();
  std::vector<LevelField> f = allLevels(g, 1.0f);  // ignored with cover tcc
  f.push_back(field(g, FieldKind::CloudCoverLow, 0.0, [](double lat, double) { return lat > 0 ? 0.3 : 0.7; }));
  f.push_back(constant(g, FieldKind::CloudCoverMid, 0.0, 0.2f));
  f.push_back(constant(g, FieldKind::CloudCoverHigh, 0.0, kNaN));
  WeatherSettings w;
  w.cover = WeatherCover::Tcc;
  const LayerCover c = layerCover(oneStep(g, f), 0.0, w, kTestRegion);
  EXPECT_FLOAT_EQ(c.low[pointAt(g, 45.0, 10.0)], 0.3f);
  EXPECT_FLOAT_EQ(c.low[pointAt(g, -45.0, 10.0)], 0.7f);
  EXPECT_FLOAT_EQ(c.mid[5], 0.2f);
  EXPECT_EQ(c.high[5], 0.0f);  // missing: clear
}

TEST(LayerCover, Errors) {
  const GridGeometry g = globalGrid();
  WeatherSettings w;
  // No r level within the mid layer: the error names the key and the levels there are.
  std::vector<LevelField> f;
  for (double p : {1000.0, 850.0, 300.0}) f.push_back(constant(g, FieldKind::RelativeHumidity, p, 0.5f));
  Error e = catchError([&] { layerCover(oneStep(g, f), 0.0, w, kTestRegion); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_EQ(std::string(e.what()),
            "weather.mid: synthetic.grib2 has no relative humidity (r) between 450 and 800 hPa "
            "(r levels: 1000, 850, 300 hPa)");
  // No r at all.
  e = catchError(
      [&] { layerCover(oneStep(g, {constant(g, FieldKind::GeopotentialHeight, 500, 5500.0f)}), 0.0, w, kTestRegion); });
  EXPECT_EQ(std::string(e.what()),
            "weather.low: synthetic.grib2 has no relative humidity (r) between 800 and 1000 hPa "
            "(it has no r at all)");
  // tcc asked for but absent.
  w.cover = WeatherCover::Tcc;
  e = catchError([&] { layerCover(oneStep(g, allLevels(g, 0.5f)), 0.0, w, kTestRegion); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_NE(std::string(e.what()).find("weather.cover: tcc needs tcc_low"), std::string::npos)
      << e.what();
  // A file without steps.
  w.cover = WeatherCover::Rh;
  WeatherFields empty;
  empty.file = "empty.nc";
  empty.grid = g;
  e = catchError([&] { layerCover(empty, 0.0, w, kTestRegion); });
  EXPECT_EQ(std::string(e.what()), "weather.file: empty.nc holds no fields");
}

TEST(LayerCover, TimeBetweenStepsInterpolatesCover) {
  const GridGeometry g = globalGrid();
  WeatherFields f = oneStep(g, allLevels(g, 0.8f), 1000.0);  // cover 0
  std::vector<LevelField> wet = allLevels(g, 1.0f);          // cover 1
  wet.push_back(constant(g, FieldKind::GeopotentialHeight, 1000.0, 100.0f));
  f.steps.push_back({4600.0, wet});
  std::vector<LevelField> dry = allLevels(g, 0.9f);  // cover 0.25
  dry.push_back(constant(g, FieldKind::GeopotentialHeight, 1000.0, 300.0f));
  f.steps.push_back({8200.0, dry});
  f.steps[0].fields.push_back(constant(g, FieldKind::GeopotentialHeight, 1000.0, 200.0f));
  const WeatherSettings w;
  const auto lowAt = [&](double t) { return layerCover(f, t, w, kTestRegion).low[100]; };
  EXPECT_EQ(lowAt(1000.0), 0.0f);
  EXPECT_NEAR(lowAt(1900.0), 0.25f, 1e-6f);
  EXPECT_NEAR(lowAt(4600.0), 1.0f, 1e-6f);
  EXPECT_NEAR(lowAt(6400.0), 0.625f, 1e-6f);
  // Outside the steps: the nearest one.
  EXPECT_EQ(lowAt(-1e9), 0.0f);
  EXPECT_NEAR(lowAt(1e12), 0.25f, 1e-6f);
  // The base follows gh in time too: 200 m, 100 m, 300 m at the three steps.
  EXPECT_NEAR(layerCover(f, 2800.0, w, kTestRegion).lowAltM.x, 150.0, 1e-3);
  EXPECT_NEAR(layerCover(f, 6400.0, w, kTestRegion).lowAltM.x, 200.0, 1e-3);
}

TEST(LayerCover, AltitudesFromGeopotentialOrTheStandardAtmosphere) {
  const GridGeometry g = globalGrid();
  WeatherSettings w;
  w.region = WeatherRegion{{0.0, 55.0}, {39.0, 105.0}};
  // Without gh: the standard atmosphere at each layer's bounds.
  LayerCover c = layerCover(oneStep(g, allLevels(g, 0.5f)), 0.0, w, *w.region);
  EXPECT_NEAR(c.lowAltM.x, standardAtmosphereAltitudeM(1000.0), 1e-6);
  EXPECT_NEAR(c.lowAltM.y, standardAtmosphereAltitudeM(800.0), 1e-6);
  EXPECT_NEAR(c.midAltM.y, standardAtmosphereAltitudeM(450.0), 1e-6);
  EXPECT_NEAR(c.highAltM.y, standardAtmosphereAltitudeM(150.0), 1e-6);

  // gh rising northward at 850 and 700 hPa: the region's mean (the map's average over its
  // latitudes, 0..55), and 800 hPa between them in log pressure.
  std::vector<LevelField> f = allLevels(g, 0.5f);
  f.push_back(field(g, FieldKind::GeopotentialHeight, 850, [](double lat, double) { return 1500.0 + 2.0 * lat; }));
  f.push_back(field(g, FieldKind::GeopotentialHeight, 700, [](double lat, double) { return 3000.0 + 4.0 * lat; }));
  f.push_back(field(g, FieldKind::GeopotentialHeight, 400, [](double, double) { return kNaN; }));  // no data: unused
  c = layerCover(oneStep(g, f), 0.0, w, *w.region);
  const double gh850 = 1500.0 + 2.0 * 27.5, gh700 = 3000.0 + 4.0 * 27.5;
  const double t = std::log(850.0 / 800.0) / std::log(850.0 / 700.0);
  EXPECT_NEAR(c.lowAltM.y, gh850 + t * (gh700 - gh850), 0.5);
  // Beyond the file's gh levels: the nearest level plus the standard atmosphere's thickness.
  EXPECT_NEAR(c.lowAltM.x,
              gh850 + standardAtmosphereAltitudeM(1000.0) - standardAtmosphereAltitudeM(850.0),
              0.5);
  EXPECT_NEAR(c.midAltM.y,
              gh700 + standardAtmosphereAltitudeM(450.0) - standardAtmosphereAltitudeM(700.0), 0.5);
  // Never below sea level.
  f.push_back(constant(g, FieldKind::GeopotentialHeight, 1000, -80.0f));
  c = layerCover(oneStep(g, f), 0.0, w, *w.region);
  EXPECT_EQ(c.lowAltM.x, 0.0);
}

// A smooth test function, periodic in longitude.
double smooth(double lat, double lon) {
  return 0.5 + 0.3 * std::sin(glm::radians(2.0 * lat)) * std::cos(glm::radians(3.0 * lon));
}

TEST(Resample, ExactAtGridPointsAndSmoothBetween) {
  const GridGeometry g = globalGrid();
  const LevelField f = field(g, FieldKind::RelativeHumidity, 0, smooth);
  // 27 x 23 texels over [38.75, 106.25] x [-1.25, 56.25]: every texel centre is a grid point.
  WeatherRegion r{{-1.25, 56.25}, {38.75, 106.25}};
  std::vector<float> m = resampleToRegion(g, f.values, r, 27, 23, false);
  for (uint32_t y = 0; y < 23; ++y)
    for (uint32_t x = 0; x < 27; ++x)
      ASSERT_NEAR(m[y * 27 + x], smooth(55.0 - 2.5 * y, 40.0 + 2.5 * x), 2e-6) << x << ", " << y;

  // 8 texels per cell: close to the function (bicubic), and no step between neighbours
  // larger than the function's own change over a texel.
  const uint32_t w = 216, h = 184;
  m = resampleToRegion(g, f.values, r, w, h, false);
  double worst = 0.0, jump = 0.0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const double lat = r.lat[1] - (y + 0.5) / h * (r.lat[1] - r.lat[0]);
      const double lon = r.lon[0] + (x + 0.5) / w * (r.lon[1] - r.lon[0]);
      worst = std::max(worst, std::fabs(m[y * w + x] - smooth(lat, lon)));
      if (x > 0) jump = std::max(jump, double(std::fabs(m[y * w + x] - m[y * w + x - 1])));
      if (y > 0) jump = std::max(jump, double(std::fabs(m[y * w + x] - m[(y - 1) * w + x])));
    }
  // The function's slope is at most 0.3 * 3 * pi / 180 per degree; a texel is 0.3125 deg.
  EXPECT_LT(worst, 2e-4);
  EXPECT_LT(jump, 0.3 * 3.0 * 3.14159 / 180.0 * 0.3125 * 1.1);
}

TEST(Resample, CoverStaysWithinZeroAndOne) {
  const GridGeometry g = globalGrid();
  // A hard edge overshoots with Catmull-Rom; cover is clamped.
  const LevelField f = field(g, FieldKind::RelativeHumidity, 0, [](double, double lon) { return lon < 50.0 ? 0.0 : 1.0; });
  const WeatherRegion r{{0.0, 10.0}, {40.0, 60.0}};
  const std::vector<float> clamped = resampleToRegion(g, f.values, r, 64, 32, true);
  const std::vector<float> raw = resampleToRegion(g, f.values, r, 64, 32, false);
  EXPECT_LT(*std::min_element(raw.begin(), raw.end()), -0.01f);
  EXPECT_EQ(*std::min_element(clamped.begin(), clamped.end()), 0.0f);
  EXPECT_EQ(*std::max_element(clamped.begin(), clamped.end()), 1.0f);
}

TEST(Resample, LongitudeWrapsOnAGlobalGrid) {
  const GridGeometry g = globalGrid();
  const LevelField f = field(g, FieldKind::RelativeHumidity, 0, smooth);
  // Across 0E at 30N: [-11.25, 11.25] with 9 texels puts centres on -10, -7.5, ..., 10
  // (350 .. 10).
  const WeatherRegion west{{28.75, 31.25}, {-11.25, 11.25}};
  const std::vector<float> a = resampleToRegion(g, f.values, west, 9, 1, false);
  for (uint32_t x = 0; x < 9; ++x) EXPECT_NEAR(a[x], smooth(30.0, -10.0 + 2.5 * x), 2e-6) << x;
  // The same place written past 180 (348.75 .. 371.25) gives the same map, and a finer map
  // across the seam has no jump there.
  const WeatherRegion east{{28.75, 31.25}, {348.75, 371.25}};
  const std::vector<float> b = resampleToRegion(g, f.values, east, 9, 1, false);
  for (uint32_t x = 0; x < 9; ++x) EXPECT_NEAR(a[x], b[x], 1e-6) << x;
  const std::vector<float> fine = resampleToRegion(g, f.values, west, 90, 1, false);
  for (uint32_t x = 0; x < 90; ++x)
    EXPECT_NEAR(fine[x], smooth(30.0, -11.25 + (x + 0.5) * 22.5 / 90), 2e-4) << x;
}

TEST(Resample, RegionOutsideARegionalGrid) {
  GridGeometry g;
  g.nx = 17;
  g.ny = 13;
  g.regularLatLon = true;
  for (uint32_t j = 0; j < g.ny; ++j)
    for (uint32_t i = 0; i < g.nx; ++i) {
      g.latDeg.push_back(60.0 - 2.5 * j);
      g.lonDeg.push_back(-20.0 + 2.5 * i);
    }
  const std::vector<float> v(g.size(), 0.5f);
  // Inside (also written as 340 .. 355) works.
  EXPECT_EQ(resampleToRegion(g, v, {{35.0, 55.0}, {340.0, 355.0}}, 8, 8, true)[0], 0.5f);
  const Error e = catchError([&] {
    resampleToRegion(g, v, {{20.0, 40.0}, {0.0, 10.0}}, 8, 8, true);
  });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_EQ(std::string(e.what()),
            "weather.region: lies outside the data (grid covers lat 30..60, lon -20..20)");
}

// Scattered points: a Lambert-like grid (rows and columns not along parallels and
// meridians) given as per-point lat/lon.
GridGeometry rotatedGrid(double spacing) {
  GridGeometry g;
  g.nx = 40;
  g.ny = 30;
  for (uint32_t j = 0; j < g.ny; ++j)
    for (uint32_t i = 0; i < g.nx; ++i) {
      const double u = (i - 20.0) * spacing, v = (j - 15.0) * spacing;
      g.lonDeg.push_back(10.0 + u * 0.94 - v * 0.34);
      g.latDeg.push_back(47.0 + u * 0.34 + v * 0.94);
    }
  return g;
}

TEST(Resample, ScatteredPointsExactAndSmooth) {
  const WeatherRegion r{{44.0, 50.0}, {6.0, 14.0}};
  // Exactness: add the texel centres of a 16 x 12 map to the points with known values.
  GridGeometry g = rotatedGrid(0.5);
  std::vector<float> v;
  for (size_t k = 0; k < g.size(); ++k) v.push_back(float(smooth(g.latDeg[k], g.lonDeg[k])));
  std::vector<float> centres;
  for (uint32_t y = 0; y < 12; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      const double lat = r.lat[1] - (y + 0.5) / 12 * (r.lat[1] - r.lat[0]);
      const double lon = r.lon[0] + (x + 0.5) / 16 * (r.lon[1] - r.lon[0]);
      g.latDeg.push_back(lat);
      g.lonDeg.push_back(lon);
      v.push_back(float(0.1 + 0.8 * ((x * 7 + y * 3) % 11) / 10.0));
      centres.push_back(v.back());
    }
  g.nx = uint32_t(g.size());
  g.ny = 1;
  const std::vector<float> m = resampleToRegion(g, v, r, 16, 12, false);
  for (size_t i = 0; i < m.size(); ++i) ASSERT_EQ(m[i], centres[i]) << i;

  // Smooth: on the rotated grid alone, a fine map follows the function, stays within the
  // data's range (the weights are a convex combination) and has no jumps.
  const GridGeometry plain = rotatedGrid(0.5);
  std::vector<float> pv;
  for (size_t k = 0; k < plain.size(); ++k)
    pv.push_back(float(smooth(plain.latDeg[k], plain.lonDeg[k])));
  const uint32_t w = 128, h = 96;
  const std::vector<float> fine = resampleToRegion(plain, pv, r, w, h, false);
  double worst = 0.0, jump = 0.0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const double lat = r.lat[1] - (y + 0.5) / h * (r.lat[1] - r.lat[0]);
      const double lon = r.lon[0] + (x + 0.5) / w * (r.lon[1] - r.lon[0]);
      worst = std::max(worst, std::fabs(fine[y * w + x] - smooth(lat, lon)));
      if (x > 0) jump = std::max(jump, double(std::fabs(fine[y * w + x] - fine[y * w + x - 1])));
      if (y > 0) jump = std::max(jump, double(std::fabs(fine[y * w + x] - fine[(y - 1) * w + x])));
    }
  EXPECT_LT(worst, 0.01);
  EXPECT_LT(jump, 0.01);  // the function changes by at most ~0.001 per texel

  // Outside the points.
  const Error e = catchError([&] {
    resampleToRegion(plain, pv, {{10.0, 20.0}, {6.0, 14.0}}, 8, 8, true);
  });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_NE(std::string(e.what()).find("weather.region: lies outside the data (grid covers lat "),
            std::string::npos)
      << e.what();
}

TEST(WeatherMapFromFields, ChannelsSizeAndAltitudes) {
  const GridGeometry g = globalGrid();
  // rh 0.9 everywhere but 0.5 from 450 to 200 hPa: low 0.25, mid (0.25 / 0.35)^2 from its
  // levels below 450, high 0.25 from its top level (150 hPa) alone.
  std::vector<LevelField> f = allLevels(g, 0.9f);
  for (LevelField& l : f)
    if (l.pressureHpa <= 450 && l.pressureHpa > 150) l.values.assign(g.size(), 0.5f);
  WeatherSettings w;
  w.source = WeatherMapSource::File;
  w.region = {{0.0, 55.0}, {39.0, 105.0}};
  w.resolution = 64;
  w.cloudType = CloudType::Stratocumulus;
  const WeatherMap map = weatherMapFromFields(oneStep(g, f), 0.0, w, *w.region);
  const glm::uvec2 size = proceduralMapSize(w, *w.region);
  EXPECT_EQ(map.width, size.x);
  EXPECT_EQ(map.height, size.y);
  ASSERT_EQ(map.texels.size(), size_t(size.x) * size.y);
  ASSERT_EQ(map.coverHigh.size(), map.texels.size());
  EXPECT_EQ(map.region, w.region);
  const float mid = (0.25f / 0.35f) * (0.25f / 0.35f);
  for (size_t i = 0; i < map.texels.size(); i += 97) {
    EXPECT_NEAR(map.texels[i].r, 0.25f, 1e-5f);
    EXPECT_NEAR(map.texels[i].g, mid, 1e-5f);
    EXPECT_EQ(map.texels[i].b, 0.5f);  // stratocumulus: cellular
    EXPECT_EQ(map.texels[i].a, 1.0f);
    EXPECT_NEAR(map.coverHigh[i], 0.25f, 1e-5f);
  }
  ASSERT_TRUE(map.layerAltitudesM.has_value());
  EXPECT_NEAR(map.layerAltitudesM->x, standardAtmosphereAltitudeM(1000.0), 1e-6);
  EXPECT_NEAR(map.layerAltitudesM->w, standardAtmosphereAltitudeM(450.0), 1e-6);
}

}  // namespace
}  // namespace sky
