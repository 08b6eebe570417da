// engine/weather/local_weather.h (Kozlov section 5): the cover around the camera, filtered
// over a few km so it changes smoothly as the camera moves, and what it does to the light
// (engine/lighting applyOvercast).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "engine/lighting/light_model.h"
#include "engine/lighting/lighting_state.h"
#include "engine/weather/geo.h"
#include "engine/weather/local_weather.h"

namespace sky {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// A map over 1 x 1 degree at the equator: low cover `west` left of longitude 0.5, `east`
// right of it, mid and high cover uniform.
WeatherMap halves(float west, float east, float mid, float high, uint32_t size = 200) {
  WeatherMap map;
  map.region = {{-0.5, 0.5}, {0.0, 1.0}};
  map.width = map.height = size;
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x)
      map.texels.emplace_back(x < size / 2 ? west : east, mid, 0.5f, 1.0f);
  map.coverHigh.assign(map.texels.size(), high);
  return map;
}

TEST(LocalWeather, UniformCoverIsItselfAndTheLayersOverlapAtRandom) {
  const WeatherMap map = halves(0.4f, 0.4f, 0.5f, 0.2f);
  const LocalWeather w = localWeather(map, 0.0, 0.5, 5.0);
  EXPECT_NEAR(w.low, 0.4f, 1e-5f);
  EXPECT_NEAR(w.mid, 0.5f, 1e-5f);
  EXPECT_NEAR(w.high, 0.2f, 1e-5f);
  EXPECT_NEAR(w.overcast, 1.0f - 0.6f * 0.5f * 0.8f, 1e-5f);
  // Far outside the region there are no clouds; an empty map has none anywhere.
  EXPECT_EQ(localWeather(map, 10.0, 0.5, 5.0).overcast, 0.0f);
  EXPECT_EQ(localWeather(WeatherMap{}, 0.0, 0.5, 5.0).overcast, 0.0f);
}

TEST(LocalWeather, ChangesSmoothlyAsTheCameraCrossesACloudEdge) {
  // Overcast west of 0.5E, clear east of it: walk east across the edge in 100 m steps.
  const WeatherMap map = halves(1.0f, 0.0f, 0.0f, 0.0f);
  const double radiusKm = 5.0;
  const double metresPerDeg = kEarthRadiusM * kDeg;
  double previous = localWeather(map, 0.0, 0.5 - 8000.0 / metresPerDeg, radiusKm).low;
  EXPECT_NEAR(previous, 1.0, 1e-4) << "8 km inside the overcast";
  double largestStep = 0.0;
  for (double m = -8000.0 + 100.0; m <= 8000.0; m += 100.0) {
    const double c = localWeather(map, 0.0, 0.5 + m / metresPerDeg, radiusKm).low;
    EXPECT_LE(c, previous + 1e-6) << "the cover only falls walking out of the cloud, at " << m;
    largestStep = std::max(largestStep, previous - c);
    previous = c;
  }
  EXPECT_NEAR(previous, 0.0, 1e-4) << "8 km out in the clear";
  // The kernel (1 - r^2/R^2)^2 spreads the edge over 2R = 10 km. Its steepest slope, at the
  // edge, is (16/15) / (pi/3) = 1.02 per R: 0.020 per 100 m (the 61 samples add a little);
  // an unfiltered map would jump by 1 at once.
  std::printf("largest change per 100 m across the edge: %.4f\n", largestStep);
  EXPECT_LT(largestStep, 0.035);
  EXPECT_NEAR(localWeather(map, 0.0, 0.5, radiusKm).low, 0.5, 0.02) << "at the edge itself";
  // A smaller radius makes a sharper but still continuous edge.
  EXPECT_GT(localWeather(map, 0.0, 0.5 - 2000.0 / metresPerDeg, 1.0).low, 0.99);
}

TEST(LocalWeather, OvercastDimsTheGroundLightGreysTheSkyLightAndRaisesTheHaze) {
  Scene scene;
  const LightingState clear = computeLighting(scene, scene.time.start);
  LightingState none = clear;
  applyOvercast(none, scene.sky, 0.0);
  EXPECT_EQ(none.gpu.palette.ambientTop, clear.gpu.palette.ambientTop);
  EXPECT_EQ(none.gpu.palette.ambientBottom, clear.gpu.palette.ambientBottom);
  EXPECT_EQ(none.gpu.palette.fog, clear.gpu.palette.fog) << "no overcast, no change";

  for (double n : {0.5, 1.0}) {
    LightingState st = clear;
    applyOvercast(st, scene.sky, n);
    EXPECT_EQ(st.overcast, n);
    // Kasten and Czeplak: the ground gets 1 - 0.75 N^3.4 of its clear-sky light.
    const float ground = float(1.0 - 0.75 * std::pow(n, 3.4));
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(st.gpu.palette.ambientBottom[c], clear.gpu.palette.ambientBottom[c] * ground,
                  1e-6f);
    // The light from above keeps its luminance and loses colour.
    const glm::dvec3 top(st.gpu.palette.ambientTop), before(clear.gpu.palette.ambientTop);
    EXPECT_NEAR(light::luminance(top), light::luminance(before), 1e-6);
    const auto spread = [](const glm::dvec3& v) { return v.b - v.r; };
    EXPECT_NEAR(spread(top), (1.0 - n) * spread(before), 1e-6);
    // The haze top rises halfway to the zenith at full overcast.
    EXPECT_NEAR(st.gpu.palette.fog.w, scene.sky.hazeHeight + (1.0 - scene.sky.hazeHeight) * 0.5 * n,
                1e-6);
    EXPECT_EQ(st.gpu.moonPalette.fog.w, st.gpu.palette.fog.w);
    // The direct light is the sky's business above the clouds: unchanged.
    EXPECT_EQ(st.gpu.sun.illuminance, clear.gpu.sun.illuminance);
  }
}

}  // namespace
}  // namespace sky
