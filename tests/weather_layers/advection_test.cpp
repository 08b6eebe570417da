// Weather that moves (Kozlov section 5): the map carried by the wind outside the file's
// steps (weather.advection: data), and advectMap itself against a known shift.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/weather/cloud_layers_from_fields.h"
#include "engine/weather/geo.h"
#include "engine/weather/weather_map.h"
#include "error_capture.h"
#include "gfs_fixture.h"

namespace sky {
namespace {

// The low cover's centroid along x (texels) over rows [0, rows) (all by default).
double centroidX(const WeatherMap& map, uint32_t rows = ~0u) {
  double sum = 0.0, weight = 0.0;
  for (uint32_t y = 0; y < std::min(rows, map.height); ++y)
    for (uint32_t x = 0; x < map.width; ++x) {
      const double c = map.at(x, y).r;
      sum += c * (x + 0.5);
      weight += c;
    }
  return sum / weight;
}

TEST(Advection, AnEastWindMovesTheCloudsEastBySpeedTimesTime) {
  // A 2-degree-wide cloud band in the middle of a 10-degree square on the equator.
  WeatherMap map;
  map.region = {{-5.0, 5.0}, {0.0, 10.0}};
  map.width = map.height = 100;
  for (uint32_t y = 0; y < 100; ++y)
    for (uint32_t x = 0; x < 100; ++x) {
      const double lon = (x + 0.5) / 10.0;
      map.texels.emplace_back(std::exp(-std::pow((lon - 4.0) / 0.7, 2.0)), 0.0f, 0.5f, 1.0f);
    }
  map.coverHigh.assign(map.texels.size(), 0.0f);
  map.coverHigh[50 * 100 + 40] = 1.0f;
  const double before = centroidX(map);
  const std::vector<float> east(map.texels.size(), 20.0f), north(map.texels.size(), 0.0f);
  const double seconds = 3 * 3600.0;
  advectMap(map, east, north, seconds);
  // 20 m/s for 3 h = 216 km = 1.943 degrees at the equator = 19.4 texels.
  const double expected = 20.0 * seconds / (kEarthRadiusM * 3.14159265358979 / 180.0) * 10.0;
  EXPECT_NEAR(centroidX(map) - before, expected, 0.2);
  // The other channels and the high cover ride along.
  EXPECT_FLOAT_EQ(map.at(30, 50).b, 0.5f);
  double highX = 0.0;
  for (uint32_t x = 0; x < 100; ++x) highX += map.coverHigh[50 * 100 + x] * (x + 0.5);
  double highSum = 0.0;
  for (uint32_t x = 0; x < 100; ++x) highSum += map.coverHigh[50 * 100 + x];
  EXPECT_NEAR(highX / highSum - 40.5, expected, 1.0);
  // Back again: negative time undoes it (up to the bilinear blur).
  advectMap(map, east, north, -seconds);
  EXPECT_NEAR(centroidX(map), before, 0.2);
}

TEST(Advection, TheForecastDriftsWithItsWindOnlyOutsideItsSteps) {
  Scene scene = test::gfsScene(test::kLuRegion, WeatherCover::Rh);
  const WeatherFields fields = readWeatherFile(weatherInputs(scene));
  ASSERT_EQ(fields.steps.size(), 1u);
  const double valid = fields.steps[0].validTimeUnix;
  const WeatherMap still =
      weatherMapFromFields(fields, valid + 6 * 3600.0, scene.weather, *scene.weather.region);
  scene.weather.advection = WeatherAdvection::Data;
  const WeatherMap atStep =
      weatherMapFromFields(fields, valid, scene.weather, *scene.weather.region);
  const WeatherMap later =
      weatherMapFromFields(fields, valid + 6 * 3600.0, scene.weather, *scene.weather.region);
  double same = 0.0, moved = 0.0;
  for (size_t i = 0; i < still.texels.size(); ++i) {
    same += std::fabs(atStep.texels[i].r - still.texels[i].r);
    moved += std::fabs(later.texels[i].r - still.texels[i].r);
  }
  same /= double(still.texels.size());
  moved /= double(still.texels.size());
  EXPECT_EQ(same, 0.0) << "at the step's own time nothing moves";
  EXPECT_GT(moved, 0.01) << "six hours of 500 hPa wind move the clouds";
  std::printf("mean |cover change| after 6 h of 500 hPa wind: %.4f\n", moved);
  // North of 35N the 500 hPa westerlies carry the clouds east (the tropics' easterlies may
  // take the rest west).
  const auto north = uint32_t(still.height * (55.0 - 35.0) / 55.0);
  const double shift = centroidX(later, north) - centroidX(still, north);
  std::printf("low-cover centroid shift north of 35N: %.2f texels east\n", shift);
  EXPECT_GT(shift, 0.5);

  // No wind at the steering level: one line naming the key and the levels the file has.
  scene.weather.steeringHpa = 850.0;
  const WeatherRegion& region = *scene.weather.region;
  const Error e = test::catchError(
      [&] { weatherMapFromFields(fields, valid + 3600.0, scene.weather, region); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  const std::string what = e.what();
  EXPECT_NE(what.find("weather.advection: data needs the wind (u and v) at steering_hpa 850"),
            std::string::npos)
      << what;
  EXPECT_NE(what.find("has u at 500 hPa"), std::string::npos) << what;

  // A file with no wind at all says so, not "has u at  hPa" with an empty list.
  WeatherFields calm = fields;
  for (WeatherStep& step : calm.steps)
    std::erase_if(step.fields, [](const LevelField& f) {
      return f.kind == FieldKind::WindU || f.kind == FieldKind::WindV;
    });
  const std::string none = test::catchError([&] {
                             weatherMapFromFields(calm, valid + 3600.0, scene.weather, region);
                           }).what();
  EXPECT_NE(none.find("has no u wind at any level"), std::string::npos) << none;
  EXPECT_EQ(none.find(" at  hPa"), std::string::npos) << none;
}

}  // namespace
}  // namespace sky
