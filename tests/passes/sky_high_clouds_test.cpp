// passes/sky_high_clouds on the device: the Kozlov 3.2-3.4 cloud terms against a C++
// reference on a constant coefficient texture (every pixel), the light at the layer's
// altitude, the wind's drift, sparse edges glowing around the sun and a veil lit by the
// moon, no re-bake when the time changes, and golden images of both sky models.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <ostream>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/io/exr.h"
#include "engine/io/image_metrics.h"
#include "engine/lighting/lighting_state.h"
#include "engine/render/camera.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"
#include "kozlov_reference.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
constexpr double kDeg = 3.14159265358979323846 / 180.0;

class SkyHighCloudsTest : public test::GpuTest {
protected:
  Renderer& renderer() {
    static ShaderCompiler compiler;
    if (!mRenderer) mRenderer = std::make_unique<Renderer>(ctx(), compiler);
    return *mRenderer;
  }
  RenderedFrame render(const Scene& scene, const IsoTime& time) {
    return renderer().render(scene, time);
  }
  RenderedFrame render(const Scene& scene) { return render(scene, scene.time.start); }
  std::unique_ptr<Renderer> mRenderer;
};

Scene testScene(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return loadSceneFile(configDir() / "tests" / "high_clouds" / (name + ".yaml"), overrides);
}

double luminance(const float* rgb) {
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

// ---- CPU: the wind ----------------------------------------------------------------------

TEST(HighCloudWind, TextureDriftsDownwind) {
  Scene scene;
  scene.highClouds.windSpeedMs = 10.0;
  scene.highClouds.windFrom = 270.0;  // a west wind: clouds move east
  scene.highClouds.tileSizeKm = 1000.0;
  const IsoTime later = scene.time.start.plusSeconds(600.0);
  const LightingState st = computeLighting(scene, later);
  const shared::ViewState view = makeViewState(scene.camera, 8, 8);
  const auto p0 = skyHighCloudsParams(scene, st, scene.time.start, view, true, 64, 4, {});
  const auto p1 = skyHighCloudsParams(scene, st, later, view, true, 64, 4, {});
  EXPECT_EQ(p0.texture.x, 0.0f);
  // A cloud over ground point x at the start is over x + 6 km east ten minutes later, so the
  // texture offset (added to the ground position) is -6 km east.
  EXPECT_NEAR(p1.texture.x, -6000.0f, 1e-2f);
  EXPECT_NEAR(p1.texture.y, 0.0f, 1e-2f);
  scene.highClouds.windFrom = 0.0;  // a north wind: clouds move south
  const auto p2 = skyHighCloudsParams(scene, st, later, view, true, 64, 4, {});
  EXPECT_NEAR(p2.texture.x, 0.0f, 1e-2f);
  EXPECT_NEAR(p2.texture.y, 6000.0f, 1e-2f);
}

// A procedural texture's +u axis (its cirrus streaks' mean direction) is laid downwind; an
// image keeps north up. The drift wraps over whole tiles along the texture's own axes, so
// after any time the offset is a whole number of its periods away from the true drift.
TEST(HighCloudWind, ProceduralTextureLiesAlongTheWind) {
  Scene scene;
  scene.highClouds.source = HighCloudSource::Procedural;
  scene.highClouds.windSpeedMs = 10.0;
  scene.highClouds.tileSizeKm = 30.0;
  const IsoTime later = scene.time.start.plusSeconds(12345.0);  // 123 km, four tiles and more
  const LightingState st = computeLighting(scene, later);
  const shared::ViewState view = makeViewState(scene.camera, 8, 8);
  for (double from : {270.0, 0.0, 225.0, 100.0}) {
    SCOPED_TRACE("wind from " + std::to_string(from));
    scene.highClouds.windFrom = from;
    const auto p = skyHighCloudsParams(scene, st, later, view, true, 64, 4, {});
    const double toward = (from + 180.0) * kDeg;
    EXPECT_NEAR(p.tileUEast, std::sin(toward), 1e-6);
    EXPECT_NEAR(p.tileUNorth, std::cos(toward), 1e-6);
    // The offset along +u: minus the drift, wrapped into one tile; none across it.
    const double u = p.texture.x * p.tileUEast + p.texture.y * p.tileUNorth;
    const double v = p.texture.x * p.tileUNorth - p.texture.y * p.tileUEast;
    EXPECT_NEAR(u, -std::fmod(123450.0, 30000.0), 0.05);
    EXPECT_NEAR(v, 0.0, 0.05);
  }
  scene.highClouds.source = HighCloudSource::Image;
  scene.highClouds.windFrom = 225.0;
  const auto image = skyHighCloudsParams(scene, st, later, view, true, 64, 4, {});
  EXPECT_EQ(image.tileUEast, 1.0f);
  EXPECT_EQ(image.tileUNorth, 0.0f);
}

// ---- GPU: the shading against a reference ------------------------------------------------

// The high_clouds layer of a scene with a constant coefficient texture and flat normals,
// computed independently of the shader (kozlov model): Kozlov 3.2-3.4 and the ice's forward
// scattering for sun and moon, faded into the sky by Kozlov 3.1's haze. With a constant
// texture the level of detail does not matter, so every pixel can be compared.
TEST_F(SkyHighCloudsTest, CloudTermsMatchTheReference) {
  const fs::path dir = fs::temp_directory_path() / ("sky-hc-ref-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const glm::vec4 coefficients(0.5f, 0.3f, 0.4f, 0.2f);
  LayeredImage tex;
  tex.width = tex.height = 16;
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 4; ++c)
      tex.layers.resize(1), tex.layers[0].pixels.push_back(coefficients[c]);
  tex.layers[0].channels = {"R", "G", "B", "A"};
  writeExr(dir / "coefficients.exr", tex);
  for (int i = 0; i < 256; ++i)
    tex.layers[0].pixels[i * 4 + 0] = 0.0f, tex.layers[0].pixels[i * 4 + 1] = 0.0f,
                                 tex.layers[0].pixels[i * 4 + 2] = 1.0f;
  writeExr(dir / "normals.exr", tex);

  Scene scene = testScene("clear_noon");
  scene.sun.azimuth = 180.0;
  scene.sun.elevation = 35.0;
  scene.highClouds.source = HighCloudSource::Image;
  scene.highClouds.coefficients = (dir / "coefficients.exr").string();
  scene.highClouds.normals = (dir / "normals.exr").string();
  scene.highClouds.brightness = 1.5;
  RenderedFrame frame = render(scene);
  fs::remove_all(dir);

  const LightingState& st = frame.lighting;
  const int w = scene.output.width, h = scene.output.height;
  const shared::ViewState view = makeViewState(scene.camera, w, h);
  const shared::SkyHighCloudsParams params =
      skyHighCloudsParams(scene, st, scene.time.start, view, true, 16, 4, coefficients);
  const ImageLayer* clouds = frame.image.find("high_clouds");
  ASSERT_NE(clouds, nullptr);
  const double R = 6371000.0, camR = R + scene.camera.altitudeM,
               layerR = R + scene.highClouds.altitudeM;
  const float edgeL = static_cast<float>(scene.highClouds.edgeGlowDeg * kDeg);
  int compared = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 V = test::referenceDirection(scene.camera, w, h, x, y);
      // Camera below the layer: the ray leaves the sphere at the far root.
      const double b = camR * V.z, c = camR * camR - layerR * layerR;
      const double t = -b + std::sqrt(b * b - c);
      const double bg = camR * camR - R * R, disc = b * b - bg;
      const bool groundFirst = disc >= 0.0 && -b - std::sqrt(disc) > 0.0;
      const glm::dvec3 hit = glm::dvec3(0, 0, camR) + t * glm::dvec3(V);
      const glm::vec3 up(glm::normalize(hit));
      glm::vec3 rgb(0.0f);
      const struct {
        glm::vec3 S, E;
        const PaletteKey* p;
      } lights[] = {{glm::vec3(st.sun.direction), glm::vec3(params.sunAtLayer), &st.palette},
                    {glm::vec3(st.moon.direction), glm::vec3(params.moonAtLayer), &st.moonPalette}};
      for (const auto& l : lights) {
        const float cosW = glm::dot(V, l.S);
        // 3.2 with Clight a quarter of the illuminance (a thin cloud seen from below)
        const glm::vec3 lit = 0.25f * l.E * std::max(glm::dot(up, l.S), 0.0f) + l.p->ambientTop;
        const float tDense = cosW > 0.0f ? cosW * cosW : 0.0f;  // 3.3
        const glm::vec3 dense = l.p->cloudDark + (l.p->cloudLit - l.p->cloudDark) * tDense;
        const float wAngle = std::acos(std::clamp(cosW, -1.0f, 1.0f));  // 3.4
        const glm::vec3 edge =
            l.E * std::exp(-wAngle * wAngle / (edgeL * edgeL)) / (3.14159265f * edgeL * edgeL);
        // The ice's forward scattering: the opacity 1 - B times the light times the
        // Henyey-Greenstein phase of g = 0.75, normalised per steradian.
        const float g = 0.75f, denom = 1.0f + g * g - 2.0f * g * cosW;
        const float phase = (1.0f - g * g) / (4.0f * 3.14159265f * denom * std::sqrt(denom));
        const glm::vec3 ice = l.E * phase * (1.0f - coefficients.b);
        // 3.4 with the edge channel read as 0.3 optical depth
        rgb += coefficients.r * lit + coefficients.g * dense + coefficients.a * 0.3f * edge + ice;
      }
      rgb *= 1.5f;
      const float through = test::referenceHaze(V.z, scene.sky);
      const glm::vec3 sky = test::referenceClearSky(V, st, scene.sky);
      const float coverage = 1.0f - coefficients.b;
      glm::vec4 want = groundFirst
                           ? glm::vec4(0.0f)
                           : glm::vec4(rgb * through + coverage * (1.0f - through) * sky, coverage);
      const float* got = &clouds->pixels[(static_cast<size_t>(y) * w + x) * 4];
      for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(got[k], want[k], 2e-3f * std::abs(want[k]) + 1e-4f)
            << "pixel " << x << "," << y << " channel " << k;
      ++compared;
    }
  EXPECT_EQ(compared, w * h);
}

// ---- GPU: what the layer looks like ------------------------------------------------------

// Mean luminance of the high-cloud layer over pixels within / beyond an angle of `to`.
std::pair<double, double> nearAndFar(const RenderedFrame& frame, const Scene& scene, glm::vec3 to,
                                     double nearDeg, double farDeg) {
  const ImageLayer* clouds = frame.image.find("high_clouds");
  const int w = frame.image.width, h = frame.image.height;
  double nearSum = 0, farSum = 0;
  int nearN = 0, farN = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 V = test::referenceDirection(scene.camera, w, h, x, y);
      if (V.z < 0.05f) continue;  // above the haze line
      const double angle = std::acos(std::clamp(glm::dot(V, to), -1.0f, 1.0f)) / kDeg;
      const double l = luminance(&clouds->pixels[(static_cast<size_t>(y) * w + x) * 4]);
      if (angle < nearDeg) nearSum += l, ++nearN;
      if (angle > farDeg) farSum += l, ++farN;
    }
  EXPECT_GT(nearN, 0);
  EXPECT_GT(farN, 0);
  return {nearSum / std::max(nearN, 1), farSum / std::max(farN, 1)};
}

TEST_F(SkyHighCloudsTest, CirrusEdgesGlowAroundTheSettingSun) {
  Scene scene = testScene("cirrus_sunset");
  RenderedFrame frame = render(scene);
  const auto [nearSun, farSun] =
      nearAndFar(frame, scene, glm::vec3(frame.lighting.sun.direction), 12.0, 35.0);
  EXPECT_GT(nearSun, 3.0 * farSun) << "Kozlov 3.4: sparse edges glow around the light";
  // Narrower glow, same energy: brighter at its centre.
  scene.highClouds.edgeGlowDeg = 3.0;
  RenderedFrame narrow = render(scene);
  const auto [nearNarrow, farNarrow] =
      nearAndFar(narrow, scene, glm::vec3(frame.lighting.sun.direction), 4.0, 35.0);
  const auto [nearWide, farWide] =
      nearAndFar(frame, scene, glm::vec3(frame.lighting.sun.direction), 4.0, 35.0);
  EXPECT_GT(nearNarrow, nearWide);
  EXPECT_NEAR(farNarrow, farWide, 0.05 * farWide) << "away from the sun the glow is gone";
}

TEST_F(SkyHighCloudsTest, CirrostratusIsLitByTheFullMoon) {
  Scene scene = testScene("cirrostratus_full_moon");
  RenderedFrame frame = render(scene);
  EXPECT_EQ(frame.lighting.key, "moon");
  const auto [nearMoon, farMoon] =
      nearAndFar(frame, scene, glm::vec3(frame.lighting.moon.direction), 10.0, 40.0);
  EXPECT_GT(farMoon, 0.0) << "the veil is lit everywhere";
  EXPECT_GT(nearMoon, 2.0 * farMoon) << "and glows around the moon";
  // Without the moon (placed below the layer's horizon) the veil is darker.
  scene.moon.azimuth = 0.0;
  scene.moon.elevation = -30.0;
  RenderedFrame moonless = render(scene);
  const auto [nearNone, farNone] =
      nearAndFar(moonless, scene, glm::vec3(frame.lighting.moon.direction), 10.0, 40.0);
  EXPECT_LT(nearNone, 0.2 * nearMoon);
  (void)farNone;
}

TEST_F(SkyHighCloudsTest, LayerSeenFromAboveIsNotLostInHaze) {
  // From an aircraft above the layer the clouds lie below the horizon; 3.1's haze must count
  // the downward path, not hide the whole layer as fog.
  Scene scene = testScene("cirrostratus_full_moon", {"camera.altitude_m=11000", "camera.pitch=-40",
                                                     "time=2024-06-21T13:00:00+02:00"});
  RenderedFrame frame = render(scene);
  const ImageLayer* clouds = frame.image.find("high_clouds");
  const ImageLayer* sky = frame.image.find("sky");
  const size_t n = static_cast<size_t>(frame.image.width) * frame.image.height;
  double differs = 0.0;
  int count = 0;
  for (size_t i = 0; i < n; ++i) {
    const float a = clouds->pixels[i * 4 + 3];
    if (a < 0.3f) continue;
    // Lost in haze, the layer would be its coverage times the sky behind it.
    const float fog[3] = {a * sky->pixels[i * 3], a * sky->pixels[i * 3 + 1],
                          a * sky->pixels[i * 3 + 2]};
    differs += std::abs(luminance(&clouds->pixels[i * 4]) - luminance(fog)) /
               std::max(luminance(fog), 1e-6);
    ++count;
  }
  ASSERT_GT(count, static_cast<int>(n / 4)) << "the layer fills the view below";
  EXPECT_GT(differs / count, 0.1) << "the clouds are drawn, not replaced by haze";
}

// ---- No re-bake when the light moves -----------------------------------------------------

bool hasPass(const RenderedFrame& f, const std::string& name) {
  return std::any_of(f.frame.passes.begin(), f.frame.passes.end(),
                     [&](const PassTiming& t) { return t.name == name; });
}

TEST_F(SkyHighCloudsTest, ChangingTheTimeReRendersWithoutReBaking) {
  Scene scene = testScene("cirrus_sunset", {"sky.model=physical"});
  RenderedFrame first = render(scene);
  EXPECT_TRUE(first.highClouds.baked || first.highClouds.loadedCache ||
              !hasPass(first, "atmosphere_transmittance"))
      << "the first frame makes or reuses its textures";
  const IsoTime later = scene.time.start.plusSeconds(1800.0);
  RenderedFrame second = render(scene, later);
  EXPECT_FALSE(second.highClouds.baked);
  EXPECT_FALSE(second.highClouds.loadedCache);
  EXPECT_FALSE(second.highClouds.loadedImages);
  EXPECT_TRUE(second.highClouds.bakeTimings.empty());
  for (const char* pass : {"high_cloud_bake", "high_cloud_normals", "high_cloud_reduce",
                           "atmosphere_transmittance", "atmosphere_multiscattering"})
    EXPECT_FALSE(hasPass(second, pass)) << pass << " ran again";
  EXPECT_TRUE(hasPass(second, "sky_high_clouds"));
  // The frame did change: the sun moved and the wind carried the clouds.
  const ImageLayer* a = first.image.find("high_clouds");
  const ImageLayer* b = second.image.find("high_clouds");
  EXPECT_LT(psnr(a->pixels, b->pixels, *std::max_element(a->pixels.begin(), a->pixels.end())),
            40.0);
  // A changed atmosphere recomputes its LUTs; a changed cover re-bakes (or hits the cache).
  scene.atmosphere.aerosols = AerosolSource::Settings;
  scene.atmosphere.mieScattering = 2.0;
  RenderedFrame third = render(scene, later);
  EXPECT_TRUE(hasPass(third, "atmosphere_transmittance"));
  scene.highClouds.cover = 0.55;
  RenderedFrame fourth = render(scene, later);
  EXPECT_TRUE(fourth.highClouds.baked || fourth.highClouds.loadedCache);
}

// ---- Golden images -----------------------------------------------------------------------

// {scene, sky model, projection}: 64x36 with the scene's camera, and 256x144 equirectangular
// skies. References: tests/golden/high_clouds/*.exr (beauty RGBA only, to stay small).
// Tolerance: the images are clipped at twice the reference's 99th percentile (so the sun
// disc does not set the scale), then PSNR >= 45 dB against that peak and max error <= 4 %
// of it. The procedural noise is float math, so another GPU may differ slightly.
struct GoldenCase {
  const char* scene;
  const char* model;
  bool wide;
};

void PrintTo(const GoldenCase& c, std::ostream* os) {
  *os << c.scene << " " << c.model << (c.wide ? " 256x144" : " 64x36");
}

class HighCloudGolden : public SkyHighCloudsTest,
                        public ::testing::WithParamInterface<GoldenCase> {};

std::string goldenName(const GoldenCase& c) {
  return std::string(c.scene) + "_" + c.model + (c.wide ? "_256x144" : "_64x36");
}

std::vector<float> clippedRgb(const LayeredImage& image, float clip) {
  const ImageLayer* l = image.find("");
  std::vector<float> rgb;
  for (size_t i = 0; i < l->pixels.size() / 4; ++i)
    for (int c = 0; c < 3; ++c) rgb.push_back(std::min(l->pixels[i * 4 + c], clip));
  return rgb;
}

float percentileClip(const LayeredImage& image) {
  std::vector<float> v = clippedRgb(image, 1e30f);
  std::nth_element(v.begin(), v.begin() + v.size() * 99 / 100, v.end());
  return 2.0f * v[v.size() * 99 / 100];
}

TEST_P(HighCloudGolden, MatchesReference) {
  const GoldenCase& c = GetParam();
  std::vector<std::string> overrides = {std::string("sky.model=") + c.model};
  if (c.wide)
    overrides.insert(overrides.end(), {"output.width=256", "output.height=144",
                                       "camera.projection=equirectangular"});
  Scene scene = testScene(c.scene, overrides);
  RenderedFrame frame = render(scene);
  const fs::path golden = fs::path(std::getenv("SKY_TEST_DATA")).parent_path() / "golden" /
                          "high_clouds" / (goldenName(c) + ".exr");
  LayeredImage beauty;
  beauty.width = frame.image.width;
  beauty.height = frame.image.height;
  beauty.layers.push_back(*frame.image.find(""));
  if (const char* u = std::getenv("SKY_UPDATE_GOLDEN"); u && std::string(u) == "1") {
    fs::create_directories(golden.parent_path());
    writeExr(golden, beauty);
    GTEST_SKIP() << "wrote " << golden;
  }
  LayeredImage reference = readExr(golden);
  const float clip = percentileClip(reference);
  ASSERT_GT(clip, 0.0f);
  std::vector<float> got = clippedRgb(beauty, clip), want = clippedRgb(reference, clip);
  ASSERT_EQ(got.size(), want.size());
  EXPECT_GE(psnr(got, want, clip), 45.0);
  EXPECT_LE(maxAbsError(got, want), 0.04 * clip);
}

INSTANTIATE_TEST_SUITE_P(SkyModels, HighCloudGolden,
                         ::testing::Values(GoldenCase{"clear_noon", "kozlov", false},
                                           GoldenCase{"clear_noon", "physical", false},
                                           GoldenCase{"cirrus_sunset", "kozlov", false},
                                           GoldenCase{"cirrus_sunset", "physical", false},
                                           GoldenCase{"cirrostratus_full_moon", "kozlov", false},
                                           GoldenCase{"cirrostratus_full_moon", "physical", false},
                                           GoldenCase{"clear_noon", "kozlov", true},
                                           GoldenCase{"clear_noon", "physical", true},
                                           GoldenCase{"cirrus_sunset", "kozlov", true},
                                           GoldenCase{"cirrus_sunset", "physical", true},
                                           GoldenCase{"cirrostratus_full_moon", "kozlov", true},
                                           GoldenCase{"cirrostratus_full_moon", "physical", true}),
                         [](const ::testing::TestParamInfo<GoldenCase>& param) {
                           return goldenName(param.param);
                         });

TEST(HighCloudGoldenSet, ReferencesDifferFromEachOther) {
  // Guards against references that could not catch a lost cloud layer or a swapped model.
  const fs::path dir =
      fs::path(std::getenv("SKY_TEST_DATA")).parent_path() / "golden" / "high_clouds";
  auto load = [&](const char* name) { return readExr(dir / (std::string(name) + ".exr")); };
  const LayeredImage clear = load("clear_noon_kozlov_256x144");
  const float clip = percentileClip(clear);
  const std::vector<float> kozlov = clippedRgb(clear, clip);
  const std::vector<float> physical = clippedRgb(load("clear_noon_physical_256x144"), clip);
  EXPECT_LT(psnr(kozlov, physical, clip), 35.0) << "the two sky models look the same";
  const LayeredImage cirrus = load("cirrus_sunset_physical_256x144");
  const float c2 = percentileClip(cirrus);
  const std::vector<float> kozlovCirrus = clippedRgb(load("cirrus_sunset_kozlov_256x144"), c2);
  EXPECT_LT(psnr(clippedRgb(cirrus, c2), kozlovCirrus, c2), 35.0);
}

}  // namespace
}  // namespace sky
