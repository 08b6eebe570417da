// engine/weather/weather_map.h, procedural source and sampling: the map's mean cover follows
// the settings, spread 1 covers the whole of [0, 1], cover 0 is exactly 0, the layers are
// decorrelated, the same seed gives the same map and another seed another, features have
// one size in km at every latitude, the map's aspect follows the region in km; sample() is
// bilinear between texel centres with row 0 north and clamps at the edges.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/weather/detail/cover_noise.h"
#include "engine/weather/weather_map.h"
#include "error_capture.h"

namespace sky {
namespace {
using test::catchError;

Scene proceduralScene(double low, double mid, double spread, int resolution = 96, int seed = 1) {
  Scene scene;
  scene.weather.source = WeatherMapSource::Procedural;
  scene.weather.region = WeatherRegion{{44.0, 50.0}, {4.0, 13.0}};
  scene.weather.coverLow = low;
  scene.weather.coverMid = mid;
  scene.weather.spread = spread;
  scene.weather.scaleKm = 120.0;
  scene.weather.seed = seed;
  scene.weather.resolution = resolution;
  return scene;
}

std::vector<float> channel(const WeatherMap& map, int c) {
  std::vector<float> v;
  v.reserve(map.texels.size());
  for (const glm::vec4& t : map.texels) v.push_back(t[c]);
  return v;
}

double mean(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return s / double(v.size());
}

double correlation(const std::vector<float>& a, const std::vector<float>& b) {
  const double ma = mean(a), mb = mean(b);
  double ab = 0, aa = 0, bb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

TEST(WeatherMapProcedural, MeanCoverFollowsTheSettings) {
  for (double target : {0.1, 0.25, 0.5, 0.75, 0.9}) {
    SCOPED_TRACE("mean " + std::to_string(target));
    const WeatherMap map = makeWeatherMap(weatherInputs(proceduralScene(target, 1.0 - target, 0.5)));
    EXPECT_NEAR(mean(channel(map, 0)), target, 0.03);
    EXPECT_NEAR(mean(channel(map, 1)), 1.0 - target, 0.03);
    // Not a constant: the pattern varies around the mean.
    const std::vector<float> low = channel(map, 0);
    EXPECT_GT(*std::max_element(low.begin(), low.end()) - *std::min_element(low.begin(), low.end()),
              0.2);
  }
}

TEST(WeatherMapProcedural, SpreadOneCoversTheWholeRange) {
  const WeatherMap map = makeWeatherMap(weatherInputs(proceduralScene(0.5, 0.3, 1.0, 128)));
  for (int c = 0; c < 2; ++c) {
    SCOPED_TRACE("layer " + std::to_string(c));
    const std::vector<float> v = channel(map, c);
    EXPECT_LT(*std::min_element(v.begin(), v.end()), 0.05f);
    EXPECT_GT(*std::max_element(v.begin(), v.end()), 0.95f);
    // Not bimodal only: every tenth of [0, 1] holds texels, and a good share lies between
    // clear and overcast.
    std::array<int, 10> bins{};
    int between = 0;
    for (float x : v) {
      ++bins[size_t(std::min(int(x * 10), 9))];
      between += x > 0.1f && x < 0.9f;
    }
    for (int b = 0; b < 10; ++b) EXPECT_GT(bins[size_t(b)], int(v.size()) / 200) << "bin " << b;
    EXPECT_GT(between, int(v.size()) * 3 / 10);
  }
  // Spread 0: a uniform map at the mean.
  const WeatherMap flat = makeWeatherMap(weatherInputs(proceduralScene(0.4, 0.2, 0.0, 16)));
  for (const glm::vec4& t : flat.texels) {
    ASSERT_FLOAT_EQ(t.x, 0.4f);
    ASSERT_FLOAT_EQ(t.y, 0.2f);
  }
}

TEST(WeatherMapProcedural, CoverZeroIsExactlyZeroAndOneExactlyOne) {
  const WeatherMap map = makeWeatherMap(weatherInputs(proceduralScene(0.0, 1.0, 1.0, 32)));
  for (const glm::vec4& t : map.texels) {
    ASSERT_EQ(t.x, 0.0f);
    ASSERT_EQ(t.y, 1.0f);
  }
  EXPECT_EQ(map.maxCover(), glm::vec2(0.0f, 1.0f));
  const WeatherMap none = makeWeatherMap(weatherInputs(proceduralScene(0.0, 0.0, 0.5, 32)));
  EXPECT_EQ(none.maxCover(), glm::vec2(0.0f));
}

TEST(WeatherMapProcedural, LayersAreDecorrelatedAndTypeAndDensityFilled) {
  Scene scene = proceduralScene(0.5, 0.5, 0.5, 128);
  scene.weather.cloudType = CloudType::Stratocumulus;
  const WeatherMap map = makeWeatherMap(weatherInputs(scene));
  EXPECT_LT(std::abs(correlation(channel(map, 0), channel(map, 1))), 0.25);
  for (const glm::vec4& t : map.texels) {
    ASSERT_EQ(t.z, 0.5f);
    ASSERT_EQ(t.w, 1.0f);
  }
  const glm::vec2 m = map.maxCover();
  const std::vector<float> low = channel(map, 0);
  EXPECT_EQ(m.x, *std::max_element(low.begin(), low.end()));
}

TEST(WeatherMapProcedural, SeedDecidesThePattern) {
  const WeatherMap a = makeWeatherMap(weatherInputs(proceduralScene(0.4, 0.3, 0.5, 64, 7)));
  const WeatherMap b = makeWeatherMap(weatherInputs(proceduralScene(0.4, 0.3, 0.5, 64, 7)));
  ASSERT_EQ(a.texels.size(), b.texels.size());
  EXPECT_TRUE(std::equal(a.texels.begin(), a.texels.end(), b.texels.begin()));
  const WeatherMap c = makeWeatherMap(weatherInputs(proceduralScene(0.4, 0.3, 0.5, 64, 8)));
  double diff = 0;
  for (size_t i = 0; i < a.texels.size(); ++i) diff += std::abs(a.texels[i].x - c.texels[i].x);
  EXPECT_GT(diff / double(a.texels.size()), 0.05);
  EXPECT_LT(std::abs(correlation(channel(a, 0), channel(c, 0))), 0.3);
  // More cover with the same seed grows the same clouds: cover never drops anywhere.
  const WeatherMap more = makeWeatherMap(weatherInputs(proceduralScene(0.6, 0.3, 0.5, 64, 7)));
  for (size_t i = 0; i < a.texels.size(); ++i) ASSERT_GE(more.texels[i].x, a.texels[i].x);
}

// Sign changes of (cover - 0.5) along rows, per km: the pattern's frequency east-west.
double crossingsPerKm(const WeatherMap& map, double widthKm) {
  int crossings = 0;
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 1; x < map.width; ++x)
      crossings += (map.at(x - 1, y).x > 0.5f) != (map.at(x, y).x > 0.5f);
  return crossings / (widthKm * map.height);
}

TEST(WeatherMapProcedural, FeatureSizeIsInKilometresAtEveryLatitude) {
  // Two regions about 1110 km square: at the equator 10 degrees of longitude, at 60N 20.
  Scene equator = proceduralScene(0.5, 0.0, 0.5, 160);
  equator.weather.region = WeatherRegion{{-5.0, 5.0}, {0.0, 10.0}};
  equator.weather.scaleKm = 60.0;
  Scene north = equator;
  north.weather.region = WeatherRegion{{55.0, 65.0}, {0.0, 20.0}};
  const WeatherMap a = makeWeatherMap(weatherInputs(equator)), b = makeWeatherMap(weatherInputs(north));
  EXPECT_EQ(a.width, b.width);
  const double ratio = crossingsPerKm(b, 1112.0) / crossingsPerKm(a, 1112.0);
  // Measured in degrees the northern map would change twice as often per km.
  EXPECT_GT(ratio, 0.75);
  EXPECT_LT(ratio, 1.33);
  // A larger scale_km makes larger features.
  Scene coarse = equator;
  coarse.weather.scaleKm = 240.0;
  EXPECT_LT(crossingsPerKm(makeWeatherMap(weatherInputs(coarse)), 1112.0), 0.6 * crossingsPerKm(a, 1112.0));
}

TEST(WeatherMapProcedural, SizeFollowsTheRegionInKilometres) {
  Scene wide = proceduralScene(0.3, 0.0, 0.5, 100);
  wide.weather.region =
      WeatherRegion{{0.0, 10.0}, {0.0, 20.0}};  // 2 : 1 in km at 5N (cos 5 = 0.996)
  WeatherMap map = makeWeatherMap(weatherInputs(wide));
  EXPECT_EQ(map.width, 100u);
  EXPECT_EQ(map.height, 50u);
  EXPECT_EQ(map.texels.size(), 5000u);
  EXPECT_EQ(map.region, wide.weather.region);

  Scene tall = wide;
  // 2224 km north-south, 10 degrees at 60N: 556 km east-west.
  tall.weather.region = WeatherRegion{{50.0, 70.0}, {0.0, 10.0}};
  map = makeWeatherMap(weatherInputs(tall));
  EXPECT_EQ(map.height, 100u);
  EXPECT_EQ(map.width, 25u);

  Scene thin = wide;
  thin.weather.region->lat = {0.0, 0.05};  // a sliver: still two texels across
  EXPECT_EQ(proceduralMapSize(thin.weather, *thin.weather.region), glm::uvec2(100, 2));
}

TEST(WeatherMapProcedural, TheFbmIsStandardised) {
  // The spread setting rests on the fbm having unit variance whatever the scale.
  for (double scale : {20.0, 500.0}) {
    double s = 0, s2 = 0;
    int n = 0;
    for (int i = 0; i < 4000; ++i) {
      // Points spread over the sphere (a Fibonacci lattice).
      const double z = 1.0 - (i + 0.5) / 2000.0;
      const double r = std::sqrt(1 - z * z), phi = i * 2.399963229728653;
      const double v = weather_detail::standardFbmOnEarth({r * std::cos(phi), r * std::sin(phi), z},
                                                          scale, uint32_t(3 + i % 5));
      s += v;
      s2 += v * v;
      ++n;
    }
    const double m = s / n, sd = std::sqrt(s2 / n - m * m);
    EXPECT_NEAR(m, 0.0, 0.1) << "scale " << scale;
    EXPECT_NEAR(sd, 1.0, 0.1) << "scale " << scale;
  }
}

TEST(WeatherMapProcedural, BadSettingsNameTheKey) {
  Scene scene = proceduralScene(0.3, 0.0, 0.5);
  scene.weather.region = WeatherRegion{{50.0, 40.0}, {5.0, 12.0}};
  Error e = catchError([&] { makeWeatherMap(weatherInputs(scene)); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_NE(std::string(e.what()).find("weather.region.lat"), std::string::npos);
}

TEST(CloudType, ValuesByFamily) {
  EXPECT_EQ(cloudTypeValue(CloudType::Stratus), 0.0f);
  EXPECT_EQ(cloudTypeValue(CloudType::Altostratus), 0.0f);
  EXPECT_EQ(cloudTypeValue(CloudType::Stratocumulus), 0.5f);
  EXPECT_EQ(cloudTypeValue(CloudType::Altocumulus), 0.5f);
  EXPECT_EQ(cloudTypeValue(CloudType::Cumulus), 1.0f);
}

// A 3 x 2 map by hand: texel (x, y) holds (x + 10 y, ...). Region 40..42N, 0..3E, so texel
// centres sit at lon 0.5, 1.5, 2.5 and lat 41.5 (row 0, north), 40.5 (row 1).
WeatherMap handMap() {
  WeatherMap map;
  map.region = WeatherRegion{{40.0, 42.0}, {0.0, 3.0}};
  map.width = 3;
  map.height = 2;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      map.texels.emplace_back(float(x + 10 * y), float(2 * x), float(y), 1.0f);
  return map;
}

// Texel centres are hit up to double rounding of the uv arithmetic.
void expectNear(const glm::vec4& got, const glm::vec4& want) {
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], want[c], 1e-5) << "channel " << c;
}

TEST(WeatherMapSample, TexelCentresRowZeroNorthAndBilinearBetween) {
  const WeatherMap map = handMap();
  expectNear(map.sample(41.5, 0.5), glm::vec4(0, 0, 0, 1));   // north-west texel
  expectNear(map.sample(41.5, 2.5), glm::vec4(2, 4, 0, 1));   // north-east
  expectNear(map.sample(40.5, 0.5), glm::vec4(10, 0, 1, 1));  // south-west: row 1
  // Half way between texel centres: the average; a quarter of the way: 3:1.
  expectNear(map.sample(41.5, 1.0), glm::vec4(0.5f, 1, 0, 1));
  expectNear(map.sample(41.0, 0.5), glm::vec4(5, 0, 0.5f, 1));
  const glm::vec4 q = map.sample(41.25, 1.75);  // x = 1.25, y = 0.25
  EXPECT_FLOAT_EQ(q.x, 1.25f + 2.5f);
  EXPECT_FLOAT_EQ(q.y, 2.5f);
  EXPECT_FLOAT_EQ(q.z, 0.25f);
  // Clamped at the edges: beyond the outer texel centres and outside the region.
  expectNear(map.sample(42.0, 0.0), map.at(0, 0));
  expectNear(map.sample(45.0, -5.0), map.at(0, 0));
  expectNear(map.sample(30.0, 10.0), map.at(2, 1));
  expectNear(map.sample(41.5, 3.0), map.at(2, 0));
  EXPECT_EQ(WeatherMap{}.sample(41.0, 1.0), glm::vec4(0.0f));
  EXPECT_EQ(map.maxCover(), glm::vec2(12, 4));
}

TEST(WeatherMapSample, RegionsAcrossTheAntimeridian) {
  WeatherMap map = handMap();
  map.region.lon = {179.0, 182.0};  // texel centres at 179.5, 180.5 (= -179.5), 181.5
  expectNear(map.sample(41.5, -179.5), map.at(1, 0));
  expectNear(map.sample(41.5, 181.5), map.at(2, 0));
  expectNear(map.sample(41.5, -178.5), map.at(2, 0));
  expectNear(map.sample(41.5, 179.5), map.at(0, 0));
}

}  // namespace
}  // namespace sky
