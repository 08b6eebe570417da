// passes/atmosphere_composite on the device: the shader against a C++ reference of Kozlov
// 3.1 (every pixel), and golden images of the clear sky at three sun elevations.
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <glm/geometric.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/io/exr.h"
#include "engine/io/image_metrics.h"
#include "engine/render/camera.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"

namespace sky {
namespace {
namespace fs = std::filesystem;

// Kozlov 3.1, written independently of shaders/common/kozlov_sky.glsl.
glm::vec3 referenceClearSky(glm::vec3 v, glm::vec3 s, const SkySettings& sky) {
  const float l = static_cast<float>(sky.glowSize) * std::pow(std::max(glm::dot(v, s), 0.0f), 2.0f);
  const float h = std::min(std::max(v.z, 0.0f) / static_cast<float>(sky.hazeHeight), 1.0f);
  return (sky.skyColor * h + sky.fogColor * (1.0f - h)) * (1.0f - l) + sky.sunColor * l;
}

glm::vec3 referenceDirection(const CameraSettings& cam, int w, int h, int x, int y) {
  shared::ViewState v = makeViewState(cam, w, h);
  const float nx = (x + 0.5f) / w * 2 - 1, ny = (y + 0.5f) / h * 2 - 1;
  return glm::normalize(glm::vec3(v.forward) + nx * v.right.w * glm::vec3(v.right) -
                        ny * v.up.w * glm::vec3(v.up));
}

class AtmosphereCompositeTest : public test::GpuTest {
protected:
  RenderedFrame render(const Scene& scene) {
    static ShaderCompiler compiler;
    if (!mRenderer) mRenderer = std::make_unique<Renderer>(ctx(), compiler);
    return mRenderer->render(scene);
  }
  std::unique_ptr<Renderer> mRenderer;
};

TEST_F(AtmosphereCompositeTest, SkyLayerMatchesKozlov31Everywhere) {
  Scene scene = loadSceneFile(configDir() / "tests" / "clear_sky_low.yaml");
  scene.camera.pitch = 0;  // horizon across the middle: haze, fog below, glow and sky above
  scene.camera.verticalFov = 120;
  RenderedFrame frame = render(scene);
  const ImageLayer* sky = frame.image.find("sky");
  ASSERT_NE(sky, nullptr);
  const glm::vec3 s = directionFromAzEl(*scene.sun.azimuth, *scene.sun.elevation);
  const int w = scene.output.width, h = scene.output.height;
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 ref = referenceClearSky(referenceDirection(scene.camera, w, h, x, y), s, scene.sky);
      for (int c = 0; c < 3; ++c) {
        double got = sky->pixels[(static_cast<size_t>(y) * w + x) * 3 + c];
        // Half-float storage: 11 significant bits.
        worst = std::max(worst, std::abs(got - ref[c]) / std::max(1e-3, std::abs(double(ref[c]))));
      }
    }
  EXPECT_LT(worst, 2e-3) << "largest relative error against the C++ Kozlov 3.1 reference";
}

TEST_F(AtmosphereCompositeTest, SunDiscKeepsItsEnergyAndHidesBelowTheHorizon) {
  Scene scene = loadSceneFile(configDir() / "tests" / "clear_sky_high.yaml");
  RenderedFrame frame = render(scene);
  const ImageLayer* beauty = frame.image.find("");
  const ImageLayer* sky = frame.image.find("sky");
  // Integrated over solid angle (a pixel at angle t off axis covers p^2 cos^3 t), the disc
  // must carry pi r^2 L: box filtering adds at most ~8 %, the pixel grid a little more.
  const shared::ViewState view = makeViewState(scene.camera, 64, 36);
  double energy = 0;
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 64; ++x) {
      const size_t i = static_cast<size_t>(y) * 64 + x;
      const double cosT =
          glm::dot(referenceDirection(scene.camera, 64, 36, x, y), glm::vec3(view.forward));
      energy += (beauty->pixels[i * 4 + 1] - sky->pixels[i * 3 + 1]) * view.forward.w *
                view.forward.w * cosT * cosT * cosT;
    }
  const double r = 0.5 * scene.sun.angularDiameter * 3.14159265358979 / 180;
  const double expected = 3.14159265358979 * r * r * scene.sky.sunColor.g * scene.sun.discIntensity;
  EXPECT_NEAR(energy, expected, 0.15 * expected);

  scene.sun.elevation = -2.0;
  frame = render(scene);
  beauty = frame.image.find("");
  sky = frame.image.find("sky");
  for (size_t i = 0; i < 64 * 36; ++i) ASSERT_FLOAT_EQ(beauty->pixels[i * 4], sky->pixels[i * 3]);
}

// Golden images: 64x36 renders of configs/tests/clear_sky_*.yaml against tests/golden/*.exr.
// Tolerance: PSNR >= 50 dB on RGB (peak = the reference's largest value) and max error
// <= 2 % of the peak, room for GPU-to-GPU float differences but not for a changed sky.
// SKY_UPDATE_GOLDEN=1 rewrites the references instead (scripts/update-goldens.sh).
class ClearSkyGolden : public AtmosphereCompositeTest,
                       public ::testing::WithParamInterface<const char*> {};

std::vector<float> rgbOf(const LayeredImage& image) {
  const ImageLayer* l = image.find("");
  std::vector<float> rgb;
  for (size_t i = 0; i < l->pixels.size() / 4; ++i)
    for (int c = 0; c < 3; ++c) rgb.push_back(l->pixels[i * 4 + c]);
  return rgb;
}

TEST_P(ClearSkyGolden, MatchesReference) {
  const std::string name = GetParam();
  Scene scene = loadSceneFile(configDir() / "tests" / (name + ".yaml"));
  ASSERT_EQ(scene.output.width, 64);
  ASSERT_EQ(scene.output.height, 36);
  RenderedFrame frame = render(scene);
  const fs::path golden =
      fs::path(std::getenv("SKY_TEST_DATA")).parent_path() / "golden" / (name + ".exr");
  if (const char* u = std::getenv("SKY_UPDATE_GOLDEN"); u && std::string(u) == "1") {
    writeExr(golden, frame.image);
    GTEST_SKIP() << "wrote " << golden;
  }
  LayeredImage reference = readExr(golden);
  std::vector<float> got = rgbOf(frame.image), want = rgbOf(reference);
  ASSERT_EQ(got.size(), want.size());
  const double peak = *std::max_element(want.begin(), want.end());
  EXPECT_GE(psnr(got, want, peak), 50.0);
  EXPECT_LE(maxAbsError(got, want), 0.02 * peak);
}

INSTANTIATE_TEST_SUITE_P(SunElevations, ClearSkyGolden,
                         ::testing::Values("clear_sky_high", "clear_sky_low", "clear_sky_sunset"));

TEST(ClearSkyGoldenSet, ReferencesDifferFromEachOther) {
  // Guards against references that could not catch a moved sun.
  const fs::path dir = fs::path(std::getenv("SKY_TEST_DATA")).parent_path() / "golden";
  std::vector<float> high = rgbOf(readExr(dir / "clear_sky_high.exr"));
  std::vector<float> low = rgbOf(readExr(dir / "clear_sky_low.exr"));
  std::vector<float> sunset = rgbOf(readExr(dir / "clear_sky_sunset.exr"));
  const double peak = *std::max_element(high.begin(), high.end());
  EXPECT_LT(psnr(high, low, peak), 40.0);
  EXPECT_LT(psnr(low, sunset, peak), 40.0);
}

}  // namespace
}  // namespace sky
