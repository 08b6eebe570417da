// Maps from the real GFS fixture (tests/data/weather/, NCEP GFS 2.5 degrees, valid
// 2011-01-15 12Z) through makeWeatherMap's "file" source: over Lu's region (0-55N, 39-105E)
// the figures of each layer from relative humidity and from the model's own tcc, their Dice
// per layer, the altitudes from gh; the NetCDF copy of the same fields; the errors for a missing
// file and a file of another kind. Each case prints its figures (docs/weather.md quotes them).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/weather/cloud_layers_from_fields.h"
#include "engine/weather/coverage_metrics.h"
#include "engine/weather/weather_map.h"
#include "error_capture.h"
#include "gfs_fixture.h"

namespace sky {
namespace {
using test::catchError;

struct LayerFigures {
  double mean = 0.0;     // mean cover over the map
  double covered = 0.0;  // fraction of texels with cover above 0.1
};

LayerFigures figures(const std::vector<float>& cover) {
  LayerFigures f;
  for (float c : cover) {
    f.mean += c;
    f.covered += c > 0.1f ? 1.0 : 0.0;
  }
  f.mean /= double(cover.size());
  f.covered /= double(cover.size());
  return f;
}

std::vector<float> channel(const WeatherMap& map, int c) {
  std::vector<float> v;
  for (const glm::vec4& t : map.texels) v.push_back(t[c]);
  return v;
}

TEST(GfsLayers, LuRegionFromHumidityAndFromTcc) {
  const Scene rh = test::gfsScene(test::kLuRegion, WeatherCover::Rh);
  const Scene tcc = test::gfsScene(test::kLuRegion, WeatherCover::Tcc);
  const WeatherMap a = makeWeatherMap(weatherInputs(rh));
  const WeatherMap b = makeWeatherMap(weatherInputs(tcc));
  ASSERT_EQ(a.width, 256u);
  ASSERT_EQ(a.height, 241u);
  ASSERT_EQ(a.texels.size(), b.texels.size());
  ASSERT_EQ(a.coverHigh.size(), a.texels.size());

  const char* names[3] = {"low", "mid", "high"};
  const std::vector<float> layers[2][3] = {
      {channel(a, 0), channel(a, 1), a.coverHigh},
      {channel(b, 0), channel(b, 1), b.coverHigh},
  };
  for (int l = 0; l < 3; ++l) {
    const LayerFigures fr = figures(layers[0][l]), ft = figures(layers[1][l]);
    // Dice of the texels above 0.1 (one texel per block).
    const CoverageMetrics m = compareCoverage(layers[0][l], layers[1][l], int(a.width),
                                              int(a.height), CoverageOptions{1, 0.1});
    std::printf(
        "[ gfs ] %s: rh mean %.3f covered %.3f | tcc mean %.3f covered %.3f | dice %.3f "
        "correlation %.3f\n",
        names[l], fr.mean, fr.covered, ft.mean, ft.covered, m.dice, m.correlation);
    // A January day over Asia: clouds somewhere in every layer, clear sky elsewhere.
    EXPECT_GT(fr.covered, 0.03) << names[l];
    EXPECT_LT(fr.covered, 0.8) << names[l];
    EXPECT_GT(ft.covered, 0.03) << names[l];
    // The model's cloud scheme is driven by its humidity: the two agree on where clouds are.
    EXPECT_GT(m.correlation, 0.3) << names[l];
  }

  // Altitudes from the file's gh: 1000 hPa near sea level, 800 hPa near 2 km, 450 hPa near
  // 6.3 km (a January mean over 0-55N is a little below the standard atmosphere aloft).
  ASSERT_TRUE(a.layerAltitudesM.has_value());
  const glm::dvec4 alt = *a.layerAltitudesM;
  std::printf("[ gfs ] altitudes: low %.0f..%.0f m, mid %.0f..%.0f m\n", alt.x, alt.y, alt.z,
              alt.w);
  EXPECT_GE(alt.x, 0.0);
  EXPECT_LT(alt.x, 400.0);
  EXPECT_NEAR(alt.y, standardAtmosphereAltitudeM(800.0), 250.0);
  EXPECT_EQ(alt.z, alt.y);
  EXPECT_NEAR(alt.w, standardAtmosphereAltitudeM(450.0), 400.0);
}

TEST(GfsLayers, TheSecondRegionCrossesZeroEast) {
  // Europe and the North Atlantic, 35-70N, 30W-30E: across the grid's seam at 0E.
  const WeatherMap map = makeWeatherMap(weatherInputs(test::gfsScene(test::kAtlanticRegion, WeatherCover::Rh)));
  const LayerFigures low = figures(channel(map, 0)), mid = figures(channel(map, 1));
  std::printf("[ gfs ] atlantic: low mean %.3f covered %.3f, mid mean %.3f covered %.3f\n",
              low.mean, low.covered, mid.mean, mid.covered);
  EXPECT_GT(low.covered + mid.covered, 0.1);
  // No seam: the column on either side of 0E differs no more than neighbours elsewhere.
  const uint32_t seam = map.width / 2;  // 0E is the middle of [-30, 30]
  double across = 0.0, elsewhere = 0.0;
  for (uint32_t y = 0; y < map.height; ++y) {
    across = std::max(across, double(std::fabs(map.at(seam, y).r - map.at(seam - 1, y).r)));
    for (uint32_t x = 1; x < map.width; ++x)
      elsewhere = std::max(elsewhere, double(std::fabs(map.at(x, y).r - map.at(x - 1, y).r)));
  }
  EXPECT_LE(across, elsewhere);
}

TEST(GfsLayers, NetcdfOfTheSameFieldsGivesTheSameMap) {
  // The NetCDF fixture is the GRIB file's r, t and gh from 100 to 1000 hPa through
  // grib_to_netcdf (values packed as 16-bit integers): read by its extension, the same map.
  const Scene grib = test::gfsScene(test::kLuRegion, WeatherCover::Rh);
  Scene nc = grib;
  nc.weather.file = "gfs_trop_r_t_gh_era5style.nc";
  const WeatherMap a = makeWeatherMap(weatherInputs(grib)), b = makeWeatherMap(weatherInputs(nc));
  ASSERT_EQ(a.texels.size(), b.texels.size());
  double worst = 0.0;
  for (size_t i = 0; i < a.texels.size(); ++i) {
    for (int c = 0; c < 4; ++c)
      worst = std::max(worst, double(std::fabs(a.texels[i][c] - b.texels[i][c])));
    worst = std::max(worst, double(std::fabs(a.coverHigh[i] - b.coverHigh[i])));
  }
  std::printf("[ gfs ] grib vs netcdf: largest cover difference %.2e\n", worst);
  EXPECT_LT(worst, 2e-3);
  ASSERT_TRUE(a.layerAltitudesM && b.layerAltitudesM);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR((*a.layerAltitudesM)[k], (*b.layerAltitudesM)[k], 1.0);
}

TEST(GfsLayers, FileErrors) {
  Scene scene = test::gfsScene(test::kLuRegion, WeatherCover::Rh);
  scene.weather.file = "no_such_forecast.grib2";
  Error e = catchError([&] { makeWeatherMap(weatherInputs(scene)); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_EQ(std::string(e.what()).rfind("weather.file: no_such_forecast.grib2: file not found", 0),
            0u)
      << e.what();
  // A file that is neither GRIB nor NetCDF (the fixture's licence text).
  scene.weather.file = "python-grib-doc.copyright";
  e = catchError([&] { makeWeatherMap(weatherInputs(scene)); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_NE(std::string(e.what()).find("weather.file: python-grib-doc.copyright: not a GRIB or "
                                       "NetCDF file"),
            std::string::npos)
      << e.what();
  // An empty file key.
  scene.weather.file = "";
  e = catchError([&] { makeWeatherMap(weatherInputs(scene)); });
  EXPECT_EQ(std::string(e.what()), "weather.file: is required when source is file");
}

}  // namespace
}  // namespace sky
