// High clouds whose cover comes per pixel from the weather map's high layer (regional cover):
// the rank/shape texture reproduces the coefficient texture; the far-field table runs from
// clear to the full-cover mean and matches bakes at its covers; the cache keeps the new
// texture; a uniform regional cover looks like the same scene cover; cover 0 draws nothing;
// clouds appear only where the forecast has them (the layer point's latitude computed on the
// CPU); and the choice of cover source, the data's layer altitude and the cover upload.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "engine/io/exr.h"
#include "engine/lighting/lighting_state.h"
#include "engine/render/camera.h"
#include "engine/render/weather_textures.h"
#include "engine/weather/geo.h"
#include "error_capture.h"
#include "passes/atmosphere_luts/atmosphere_luts.h"
#include "passes/sky_high_clouds/sky_high_clouds.h"
#include "tests/high_clouds/high_cloud_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::Fetched;
using test::HighCloudTest;
using test::proceduralScene;

const char* const kStyles[] = {"cirrus", "cirrostratus", "cirrocumulus"};
constexpr uint32_t kSteps = HIGH_CLOUD_COVER_STEPS;

// --- The C++ reference of shaders/common/high_cloud_coverage.glsl, in double. ---
double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}
double presence(double r, double c, double w) {
  const double t = 1.0 - c * (1.0 + w);
  return smoothstep(t, t + w, r);
}
glm::dvec4 coefficientsFromTau(double tau) {
  const double b = std::exp(-tau), alpha = 1.0 - b;
  const double dense = smoothstep(HIGH_CLOUD_TAU_DENSE_LO, HIGH_CLOUD_TAU_DENSE_HI, tau);
  const double edges = 6.75 * alpha * (1.0 - alpha) * (1.0 - alpha);
  return glm::clamp(glm::dvec4(alpha * (1.0 - dense), alpha * dense, b, edges), 0.0, 1.0);
}

double opacityOf(const glm::vec4& c) {
  return 1.0 - double(c.z);
}

// A weather map over `region`, w x h texels, whose high layer is cover(x, y) (row 0 north).
WeatherMap highCoverMap(const WeatherRegion& region, uint32_t w, uint32_t h,
                        const std::function<float(uint32_t, uint32_t)>& cover) {
  WeatherMap map;
  map.region = region;
  map.width = w;
  map.height = h;
  map.texels.assign(size_t(w) * h, glm::vec4(0.0f));
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) map.coverHigh.push_back(cover(x, y));
  return map;
}

WeatherRegion regionAround(const Scene& scene, double south, double north, double west,
                           double east) {
  WeatherRegion r;
  r.lat = {scene.camera.latitude + south, scene.camera.latitude + north};
  r.lon = {scene.camera.longitude + west, scene.camera.longitude + east};
  return r;
}

// 64x36 views of a cirrus (or other) layer at 9 km: straight up, or toward the eastern
// horizon (the far field: coarse texture and table).
enum class View { Up, EastHorizon };
Scene layerScene(const std::string& style, double cover, View view) {
  Scene s = proceduralScene(style, cover, 128, 3);
  s.output.width = 64;
  s.output.height = 36;
  s.highClouds.altitudeM = 9000.0;
  s.highClouds.tileSizeKm = 20.0;
  if (view == View::Up) {
    s.camera.heading = 0.0;
    s.camera.pitch = 90.0;
    s.camera.verticalFov = 90.0;
  } else {
    s.camera.heading = 90.0;
    s.camera.pitch = 4.0;
    s.camera.verticalFov = 30.0;
  }
  return s;
}

// Where pixel (x, y)'s ray meets the layer, as the pass computes it (a sphere of the pass's
// planet radius around the centre, the camera on its axis), mapped to latitude and longitude;
// nullopt where the ground hides the layer.
std::optional<glm::dvec2> layerLatLon(const Scene& scene, const shared::ViewState& view, int w,
                                      int h, int x, int y) {
  const double nx = (x + 0.5) / w * 2 - 1, ny = (y + 0.5) / h * 2 - 1;
  const glm::dvec3 V =
      glm::normalize(glm::dvec3(view.forward) + nx * double(view.right.w) * glm::dvec3(view.right) -
                     ny * double(view.up.w) * glm::dvec3(view.up));
  const double planetR = scene.sky.model == SkyModel::Physical
                             ? scene.atmosphere.groundRadiusKm * 1000.0
                             : kEarthRadiusM;
  const double camAlt = std::max(scene.camera.altitudeM, 1.0);
  const double camR = planetR + camAlt, layerR = planetR + scene.highClouds.altitudeM;
  const double b = camR * V.z;
  const double t = -b + std::sqrt(b * b - (camR * camR - layerR * layerR));  // from below
  const double ground = b * b - (camR * camR - planetR * planetR);
  if (ground >= 0.0 && -b - std::sqrt(ground) > 0.0 && -b - std::sqrt(ground) < t)
    return std::nullopt;
  // The same direction from the centre on the geographic sphere.
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0, 0, camR) + t * V);
  const glm::dvec3 enu =
      dir * (kEarthRadiusM + scene.highClouds.altitudeM) - glm::dvec3(0, 0, kEarthRadiusM + camAlt);
  const glm::dvec3 lla =
      latLonAltitude({scene.camera.latitude, scene.camera.longitude, camAlt}, enu);
  return glm::dvec2(lla.x, lla.y);
}

// The high_clouds output of the sky pass: RGBA, premultiplied, a = coverage.
struct Layer {
  int width = 0, height = 0;
  std::vector<float> rgba;
  float alpha(int x, int y) const { return rgba[(size_t(y) * width + x) * 4 + 3]; }
  double meanAlpha() const {
    double sum = 0;
    for (size_t i = 3; i < rgba.size(); i += 4) sum += rgba[i];
    return sum / double(width * height);
  }
};

class RegionalCoverTest : public HighCloudTest {
protected:
  void TearDown() override {
    mTextures.reset();
    mPass.reset();
    mCover.reset();
    mLuts.reset();
    HighCloudTest::TearDown();
  }

  HighCloudTextures& textures() {
    if (!mTextures) mTextures = make();
    return *mTextures;
  }
  WeatherTextures& coverTexture() {
    if (!mCover) mCover = std::make_unique<WeatherTextures>(ctx());
    return *mCover;
  }

  // The layer drawn by SkyHighCloudsPass as the renderer would: with `map`, regional cover
  // from its high layer; without, the scene's cover.
  Layer draw(const Scene& scene, const WeatherMap* map) {
    if (!mPass) mPass = std::make_unique<SkyHighCloudsPass>(ctx(), compiler());
    FrameGraph graph(runtime());
    const bool regional = map != nullptr;
    const HighCloudTextures::Outputs tex = textures().addTo(graph, scene, regional);
    const auto w = static_cast<uint32_t>(scene.output.width);
    const auto h = static_cast<uint32_t>(scene.output.height);
    const LightingState lighting = computeLighting(scene, scene.time.start);
    const shared::ViewState view = makeViewState(scene.camera, w, h);
    const auto& resources = graph.desc().resources;
    SkyHighCloudsPass::Inputs in{};
    in.params = skyHighCloudsParams(scene, lighting, scene.time.start, view, true,
                                    resources[tex.coefficients.id].image.width,
                                    resources[tex.coarse.id].image.width, tex.mean);
    in.lighting = lighting.gpu;
    in.textures = {tex.coefficients, tex.normals, tex.coarse, &textures().sampler(), tex.levels};
    if (regional) {
      setRegionalCover(in.params, scene, map->region, tex);
      in.regional = {coverTexture().addHighCover(graph, *map, ++mRevision), &coverTexture().sampler(),
                     tex.rankShape, tex.coverCoarse};
    }
    if (scene.sky.model == SkyModel::Physical) {
      if (!mLuts) mLuts = std::make_unique<AtmosphereLuts>(ctx(), compiler());
      AtmosphereLuts::Frame f;
      f.atmosphere = scene.atmosphere;
      f.cameraAltitudeM = scene.camera.altitudeM;
      f.view = view;
      f.sunDirection = glm::vec3(lighting.sun.direction);
      f.moonDirection = glm::vec3(lighting.moon.direction);
      f.sunIlluminance = glm::vec3(lighting.gpu.sunSpace);
      f.moonIlluminance = glm::vec3(lighting.gpu.moonSpace);
      const AtmosphereLuts::Outputs luts = mLuts->addTo(graph, f);
      in.physical = true;
      in.atmosphere = {mLuts->params(), luts.transmittance, luts.skyViewSun, luts.skyViewMoon,
                       &mLuts->sampler()};
    }
    graph.requestOutput(graph.add(*mPass, in).highClouds, "high_clouds");
    FrameResult result = graph.execute();
    return {int(w), int(h), result.output("high_clouds").pixels};
  }

  std::unique_ptr<HighCloudTextures> mTextures;
  std::unique_ptr<SkyHighCloudsPass> mPass;
  std::unique_ptr<WeatherTextures> mCover;
  std::unique_ptr<AtmosphereLuts> mLuts;
  uint64_t mRevision = 0;
};

// ---- The textures ------------------------------------------------------------------------

// tau(c) = shape * presence(rank, c, w) from the stored rank and shape gives the coefficient
// texture baked at the scene's cover, up to the half floats the rank and shape are kept in.
TEST_F(RegionalCoverTest, RankShapeReproducesTheCoefficients) {
  for (const char* style : kStyles) {
    SCOPED_TRACE(style);
    const double cover = 0.4;
    const Fetched f = fetch(textures(), proceduralScene(style, cover, 64));
    ASSERT_TRUE(f.activity.baked);
    ASSERT_EQ(f.rankShape.size(), f.coefficients.size());
    EXPECT_EQ(f.rampWidth, HighCloudTextures::rampWidth(enumValue<HighCloudStyle>(style).value()));
    double worstClear = 0, sumDiff = 0;
    for (size_t i = 0; i < f.rankShape.size(); i += 4) {
      ASSERT_EQ(f.rankShape[i + 2], 0.0f);
      ASSERT_EQ(f.rankShape[i + 3], 0.0f);
      const glm::dvec4 want =
          coefficientsFromTau(f.rankShape[i + 1] * presence(f.rankShape[i], cover, f.rampWidth));
      for (int c = 0; c < 4; ++c) sumDiff += std::abs(want[c] - f.coefficients[i + size_t(c)]);
      worstClear = std::max(worstClear, std::abs(want.z - f.coefficients[i + 2]));
    }
    // Half floats: rank to 2.4e-4, which the ramp's steepest slope (1.5 / w) turns into
    // 1.5e-3 of presence; and the channels' own rounding (measured: at most 2.5e-3 in B, 2.4e-4
    // on average). A wrong ramp width or channel would be off by 1e-2 and more.
    EXPECT_LT(worstClear, 6e-3);
    EXPECT_LT(sumDiff / double(f.coefficients.size()), 5e-4);
  }
}

// The far-field table: clear at cover 0 (exactly), the full-cover mean at cover 1, opacity
// rising at every step, and at cover 1/2 the mean of a bake at cover 1/2. Regional bakes run
// at the reference cover whatever high_clouds.cover says, even 0.
TEST_F(RegionalCoverTest, FarFieldTableRisesFromClearToTheFullCoverMean) {
  for (const char* style : kStyles) {
    SCOPED_TRACE(style);
    const Fetched f = fetch(textures(), proceduralScene(style, 0.0, 64), true);
    ASSERT_TRUE(f.activity.baked) << "cover 0 must still bake for a regional cover";
    ASSERT_EQ(f.coverCoarse.size(), size_t(f.coarseSize) * f.coarseSize * kSteps * 4);
    EXPECT_EQ(f.farField.front(), glm::vec4(0, 0, 1, 0));
    // The reference bake is at cover 1: its mean is the full-cover mean (rank/shape in halves).
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(f.farField.back()[c], f.mean[c], 2e-3) << c;
    for (uint32_t k = 1; k < kSteps; ++k) {
      EXPECT_GT(opacityOf(f.farField[k]), opacityOf(f.farField[k - 1]) + 1e-3) << "step " << k;
      const glm::vec4& m = f.farField[k];
      EXPECT_NEAR(m.x + m.y + m.z, 1.0f, 2e-3f) << "step " << k;
    }
    const Fetched half = fetch(textures(), proceduralScene(style, 0.5, 64));
    ASSERT_TRUE(half.activity.baked);
    static_assert((kSteps - 1) % 2 == 0, "cover 1/2 is a step of the table");
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(f.farField[(kSteps - 1) / 2][c], half.mean[c], 3e-3) << c;
  }
  // The regional key ignores cover and cover map: it is the key of a bake at the reference.
  Scene a = proceduralScene("cirrus", 0.2, 64), b = proceduralScene("cirrus", 0.9, 64);
  b.highClouds.coverMap = "cover_half_8x4.png";
  Scene full = proceduralScene("cirrus", HIGH_CLOUD_REGIONAL_REFERENCE_COVER, 64);
  EXPECT_EQ(textures().cacheKey(a, true), textures().cacheKey(b, true));
  EXPECT_EQ(textures().cacheKey(a, true), textures().cacheKey(full, false));
}

// Image sources have no rank/shape: a regional cover is an input error naming the key.
TEST_F(RegionalCoverTest, RegionalCoverNeedsAProceduralSource) {
  Scene scene = test::imageScene("coefficients_64.png");
  FrameGraph graph(runtime());
  const Error e = test::catchError([&] { textures().addTo(graph, scene, true); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_NE(std::string(e.what()).find("high_clouds.cover_source"), std::string::npos) << e.what();
}

// A fresh object loads the regional textures from the disk cache: the rank/shape texture to
// the bit, and so the per-cover coarse texture and the table too.
TEST_F(RegionalCoverTest, CacheRoundTripKeepsRankShapeAndTable) {
  const Scene scene = proceduralScene("cirrocumulus", 0.0, 64, 5);
  const Fetched baked = fetch(*make(), scene, true);
  ASSERT_TRUE(baked.activity.baked);
  ASSERT_TRUE(baked.activity.wroteCache);
  const LayeredImage entry = readExr(baked.activity.cacheFile);
  const ImageLayer* layer = entry.find("rank_shape");
  ASSERT_NE(layer, nullptr);
  EXPECT_EQ(layer->channels, (std::vector<std::string>{"rank", "shape"}));

  const Fetched loaded = fetch(*make(), scene, true);
  EXPECT_FALSE(loaded.activity.baked);
  EXPECT_TRUE(loaded.activity.loadedCache);
  EXPECT_EQ(test::maxDifference(loaded.rankShape, baked.rankShape), 0.0f);
  EXPECT_EQ(test::maxDifference(loaded.coverCoarse, baked.coverCoarse), 0.0f);
  EXPECT_EQ(loaded.farField, baked.farField);
  EXPECT_EQ(loaded.rampWidth, baked.rampWidth);
  // An entry without the rank/shape layer (an older format) is baked again.
  LayeredImage old = entry;
  old.layers.erase(std::remove_if(old.layers.begin(), old.layers.end(),
                                  [](const ImageLayer& l) { return l.name == "rank_shape"; }),
                   old.layers.end());
  writeExr(baked.activity.cacheFile, old);
  EXPECT_TRUE(fetch(*make(), scene, true).activity.baked);
}

// ---- The draw ----------------------------------------------------------------------------

// The same cover everywhere on the map looks like that cover in the scene: the same mean
// coverage overhead and toward the horizon (fine, coarse and far-field levels), and block by
// block nearly the same clouds, since both come from the same rank and shape. Blocks of 9 x 9
// pixels, because the two filter differently where a pixel covers a few texels: the scene's
// coefficients through their mip levels, the regional ones between the per-pixel texel, which
// aliases, and the per-cover coarse texture (docs/high-clouds.md, "Filtering"). The blocks'
// difference halves from 4 x 4 to 9 x 9 pixels, as noise does; clouds in the wrong places
// would differ by about the mean coverage (0.08 to 0.33) however large the blocks.
TEST_F(RegionalCoverTest, UniformRegionalCoverMatchesTheSceneCover) {
  for (View view : {View::Up, View::EastHorizon})
    for (double cover : {0.3, 0.7}) {
      SCOPED_TRACE(std::string(view == View::Up ? "up" : "east horizon") + ", cover " +
                   std::to_string(cover));
      const Scene scene = layerScene("cirrus", cover, view);
      const Layer fromScene = draw(scene, nullptr);
      const WeatherMap map = highCoverMap(regionAround(scene, -5, 5, -5, 8), 4, 4,
                                          [&](uint32_t, uint32_t) { return float(cover); });
      Scene sceneZero = scene;
      sceneZero.highClouds.cover = 0.0;  // ignored: the map sets the cover
      const Layer fromMap = draw(sceneZero, &map);
      double difference = 0, pixels = 0;
      int covered = 0;
      const int block = 9;
      for (int by = 0; by < fromScene.height / block; ++by)
        for (int bx = 0; bx < fromScene.width / block; ++bx) {
          double a = 0, b = 0;
          for (int y = by * block; y < (by + 1) * block; ++y)
            for (int x = bx * block; x < (bx + 1) * block; ++x) {
              a += fromScene.alpha(x, y);
              b += fromMap.alpha(x, y);
              pixels += std::abs(fromScene.alpha(x, y) - fromMap.alpha(x, y));
              covered += fromScene.alpha(x, y) > 0.0f;
            }
          difference += std::abs(a - b) / (block * block);
        }
      difference /= double(fromScene.width / block * (fromScene.height / block));
      pixels /= double(fromScene.width / block * block * (fromScene.height / block * block));
      ASSERT_GT(covered, 100);
      std::cout << "mean coverage: scene " << fromScene.meanAlpha() << ", map "
                << fromMap.meanAlpha() << "; mean |difference| of 9x9 blocks " << difference
                << ", of pixels " << pixels << "\n";
      // Measured: means 0.009 apart at most, blocks 0.011 on average (pixels 0.055).
      EXPECT_NEAR(fromMap.meanAlpha(), fromScene.meanAlpha(), 0.015);
      EXPECT_LT(difference, 0.02);
    }
}

// Regional cover 0 draws no high cloud at all, whatever high_clouds.cover says; a region that
// the view does not reach draws none either.
TEST_F(RegionalCoverTest, RegionalCoverZeroDrawsNoCloud) {
  for (View view : {View::Up, View::EastHorizon}) {
    Scene scene = layerScene("cirrostratus", 0.9, view);
    const WeatherMap zero = highCoverMap(regionAround(scene, -5, 5, -5, 8), 4, 4,
                                         [](uint32_t, uint32_t) { return 0.0f; });
    const WeatherMap elsewhere = highCoverMap(regionAround(scene, 20, 25, 20, 25), 4, 4,
                                              [](uint32_t, uint32_t) { return 1.0f; });
    for (const WeatherMap* map : {&zero, &elsewhere}) {
      const Layer layer = draw(scene, map);
      for (float v : layer.rgba) ASSERT_EQ(v, 0.0f);
    }
    EXPECT_GT(draw(scene, nullptr).meanAlpha(), 0.2);  // the same scene with its own cover
  }
}

struct PlacementCase {
  View view;
  SkyModel skyModel;
};

class RegionalPlacementTest : public RegionalCoverTest,
                              public ::testing::WithParamInterface<PlacementCase> {};

// A forecast with full high cover over the northern half of its region and none over the
// southern: the veil appears exactly where the layer point (its latitude and longitude from
// the camera's position, computed on the CPU) lies in the northern half, and nowhere south of
// it or outside the region. Pixels in the bilinear transition between the halves' rows, or
// within a hair of the region's edges, are not judged.
TEST_P(RegionalPlacementTest, CloudsOnlyWhereTheForecastHasThem) {
  const PlacementCase& c = GetParam();
  Scene scene = layerScene("cirrostratus", 0.0, c.view);
  scene.sky.model = c.skyModel;
  // Overhead the region ends within the view on three sides; toward the east it spans the
  // layer out to the horizon and the halves split the view between north-east and south-east.
  const uint32_t rows = c.view == View::Up ? 8 : 16;
  const WeatherRegion region = c.view == View::Up ? regionAround(scene, -0.12, 0.04, -0.12, 0.12)
                                                  : regionAround(scene, -3, 3, -1, 6);
  const WeatherMap map = highCoverMap(
      region, 4, rows, [&](uint32_t, uint32_t y) { return y < rows / 2 ? 1.0f : 0.0f; });
  const Layer layer = draw(scene, &map);
  const shared::ViewState view = makeViewState(scene.camera, 64, 36);
  const double lo = (rows / 2 - 0.5) / rows, hi = (rows / 2 + 0.5) / rows, margin = 2e-3;
  int cloudy = 0, clear = 0;
  for (int y = 0; y < layer.height; ++y)
    for (int x = 0; x < layer.width; ++x) {
      const float a = layer.alpha(x, y);
      const std::optional<glm::dvec2> ll =
          layerLatLon(scene, view, layer.width, layer.height, x, y);
      if (!ll) {
        EXPECT_EQ(a, 0.0f) << "pixel " << x << "," << y << " sees the ground";
        continue;
      }
      glm::dvec2 uv;
      const bool inside = regionUv(region, ll->x, ll->y, uv);
      const bool nearEdge = std::min({std::abs(uv.x), std::abs(uv.x - 1), std::abs(uv.y),
                                      std::abs(uv.y - 1)}) < margin;
      if (nearEdge) continue;
      if (inside && uv.y < lo - margin) {
        EXPECT_GT(a, 0.1f) << "pixel " << x << "," << y << " lat " << ll->x;
        ++cloudy;
      } else if (!inside || uv.y > hi + margin) {
        EXPECT_EQ(a, 0.0f) << "pixel " << x << "," << y << " lat " << ll->x;
        ++clear;
      }
    }
  EXPECT_GT(cloudy, 200);
  EXPECT_GT(clear, 200);
}

INSTANTIATE_TEST_SUITE_P(Views, RegionalPlacementTest,
                         ::testing::Values(PlacementCase{View::Up, SkyModel::Kozlov},
                                           PlacementCase{View::EastHorizon, SkyModel::Kozlov},
                                           PlacementCase{View::EastHorizon, SkyModel::Physical}),
                         [](const ::testing::TestParamInfo<PlacementCase>& p) {
                           return std::string(p.param.view == View::Up ? "Up" : "EastHorizon") +
                                  "_" + enumName(p.param.skyModel);
                         });

// The cover upload follows the caller's revision, like the weather texture.
TEST_F(RegionalCoverTest, CoverUploadsOncePerRevision) {
  const Scene scene = layerScene("cirrus", 0.0, View::Up);
  const WeatherMap map =
      highCoverMap(regionAround(scene, -1, 1, -1, 1), 3, 2,
                   [](uint32_t x, uint32_t y) { return 0.1f * float(x + 3 * y); });
  WeatherTextures& cover = coverTexture();
  for (uint64_t revision : {7u, 7u, 8u}) {
    FrameGraph graph(runtime());
    const ImageId image = cover.addHighCover(graph, map, revision);
    graph.requestOutput(image, "cover");
    const FrameResult result = graph.execute();
    const ReadbackImage& got = result.output("cover");
    ASSERT_EQ(got.width, 3u);
    ASSERT_EQ(got.height, 2u);
    for (size_t i = 0; i < map.coverHigh.size(); ++i)
      EXPECT_NEAR(got.pixels[i], map.coverHigh[i], 1e-3f);  // r16f
  }
  EXPECT_EQ(cover.highCoverUploadCount(), 2u);
  WeatherMap none = map;
  none.coverHigh.clear();
  FrameGraph graph(runtime());
  EXPECT_EQ(test::catchError([&] { cover.addHighCover(graph, none, 9); }).kind(),
            ErrorKind::Internal);
}

// ---- CPU: which cover, which altitude ----------------------------------------------------

TEST(HighCloudCoverSource, WeatherWhenTheMapHasAHighLayer) {
  Scene scene;
  scene.highClouds.source = HighCloudSource::Procedural;
  WeatherMap withHigh = highCoverMap(WeatherRegion{{45.0, 50.0}, {5.0, 12.0}}, 2, 2,
                                     [](uint32_t, uint32_t) { return 0.5f; });
  WeatherMap without = withHigh;
  without.coverHigh.clear();

  scene.highClouds.coverSource = HighCloudCoverSource::Auto;
  EXPECT_TRUE(highCloudsFromWeather(scene, withHigh));
  EXPECT_FALSE(highCloudsFromWeather(scene, without));
  scene.highClouds.coverSource = HighCloudCoverSource::Scene;
  EXPECT_FALSE(highCloudsFromWeather(scene, withHigh));
  scene.highClouds.coverSource = HighCloudCoverSource::Weather;
  EXPECT_TRUE(highCloudsFromWeather(scene, withHigh));
  Error e = test::catchError([&] { highCloudsFromWeather(scene, without); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_NE(std::string(e.what()).find("high_clouds.cover_source"), std::string::npos);

  // An image source cannot follow a cover: auto keeps it, weather is an error.
  scene.highClouds.source = HighCloudSource::Image;
  scene.highClouds.coverSource = HighCloudCoverSource::Auto;
  EXPECT_FALSE(highCloudsFromWeather(scene, withHigh));
  scene.highClouds.coverSource = HighCloudCoverSource::Weather;
  e = test::catchError([&] { highCloudsFromWeather(scene, withHigh); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_NE(std::string(e.what()).find("procedural"), std::string::npos) << e.what();
}

// The layer sits at the data's altitude when one is given: its sphere, and the light it gets.
TEST(HighCloudCoverSource, LayerAltitudeFromTheData) {
  Scene scene;
  scene.highClouds.altitudeM = 9000.0;
  scene.sun.azimuth = 300.0;
  // Below the horizon of 9 km (dip 3.05 degrees + the disc's 0.27), not of 11 km (3.37 + 0.27).
  scene.sun.elevation = -3.5;
  const LightingState st = computeLighting(scene, scene.time.start);
  const shared::ViewState view = makeViewState(scene.camera, 8, 8);
  const auto own = skyHighCloudsParams(scene, st, scene.time.start, view, true, 64, 4, {});
  const auto data =
      skyHighCloudsParams(scene, st, scene.time.start, view, true, 64, 4, {}, 11000.0);
  EXPECT_EQ(own.layer.z, float(kEarthRadiusM + 9000.0));
  EXPECT_EQ(data.layer.z, float(kEarthRadiusM + 11000.0));
  EXPECT_EQ(own.regional.x, 0.0f);
  EXPECT_EQ(glm::vec3(own.sunAtLayer), glm::vec3(0.0f));
  EXPECT_GT(data.sunAtLayer.r, 0.0f);
}

}  // namespace
}  // namespace sky
