// Cirrus near a low sun glow by forward scattering (issue 46): ice crystals scatter most of
// the light they take out of the beam within a few tens of degrees of its direction, so thin
// cirrus near the setting sun are brighter than the sky behind them, while away from the sun
// they are not. Small renders with the physical sky (sky.model physical), the sun 5 degrees
// up; the layer's pixel is the sky behind it seen through the layer plus the layer's own
// light, sky (1 - coverage) + rgb, compared with that sky alone.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "engine/core/paths.h"
#include "engine/render/camera.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "tests/high_clouds/high_cloud_test_util.h"

namespace sky {
namespace {
using test::HighCloudTest;

constexpr double kPi = 3.14159265358979323846;

class CirrusLightTest : public HighCloudTest {
protected:
  void TearDown() override {
    mRenderer.reset();
    HighCloudTest::TearDown();
  }
  RenderedFrame render(const Scene& scene) {
    if (!mRenderer) mRenderer = std::make_unique<Renderer>(ctx(), compiler());
    return mRenderer->render(scene, scene.time.start);
  }

private:
  std::unique_ptr<Renderer> mRenderer;
};

double luminance(const float* rgb) {
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

// Over the pixels of the layer with coverage of at least 0.1, at least 2 degrees above the
// horizon, between `minDeg` and `maxDeg` from the sun (2 degrees clear of its disc): the share
// whose light (the sky behind seen through the layer plus the layer's own) is brighter than the
// sky behind, and the median ratio of the two.
struct AgainstTheSky {
  int pixels = 0;
  double brighterShare = 0;
  double medianRatio = 0;
};

AgainstTheSky againstTheSky(const RenderedFrame& frame, const Scene& scene, double minDeg,
                            double maxDeg) {
  const ImageLayer* sky = frame.image.find("sky");
  const ImageLayer* clouds = frame.image.find("high_clouds");
  EXPECT_NE(sky, nullptr);
  EXPECT_NE(clouds, nullptr);
  AgainstTheSky r;
  if (!sky || !clouds) return r;
  const int w = frame.image.width, h = frame.image.height;
  const shared::ViewState view = makeViewState(scene.camera, uint32_t(w), uint32_t(h));
  const glm::dvec3 sun(frame.lighting.sun.direction);
  std::vector<double> ratios;
  int brighter = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::dvec3 V = viewDirection(view, x + 0.5, y + 0.5);
      const double angle = std::acos(std::clamp(glm::dot(V, sun), -1.0, 1.0)) * 180.0 / kPi;
      if (V.z < std::sin(2.0 * kPi / 180.0) || angle < minDeg || angle > maxDeg) continue;
      const size_t i = (size_t(y) * w + size_t(x));
      const float* c = &clouds->pixels[i * 4];
      const float* s = &sky->pixels[i * size_t(sky->channels.size())];
      const float coverage = c[3];
      if (coverage < 0.1f) continue;
      float seen[3];
      for (int k = 0; k < 3; ++k) seen[k] = s[k] * (1.0f - coverage) + c[k];
      const double ratio = luminance(seen) / std::max(luminance(s), 1e-12);
      ratios.push_back(ratio);
      brighter += ratio > 1.0;
    }
  r.pixels = int(ratios.size());
  if (ratios.empty()) return r;
  r.brighterShare = double(brighter) / double(ratios.size());
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  r.medianRatio = ratios[ratios.size() / 2];
  return r;
}

// The peer-like low-sun view: the default scene without its low and mid clouds, the physical
// sky, the sun 5 degrees up in the north, looking at it 10 degrees up (160 x 90, a 512
// texture). Within 20 degrees of the sun, measured: all the cirrus pixels brighter than the sky
// behind them, median ratio 1.39 (bounds: 0.98 of them, median above 1.25); with the shading
// before the ice's phase function 0.85 of them, median 1.12: the thin ones darker than the
// glowing sky. Looking away (south, 20 degrees up), more than 90 degrees from the sun, the
// cirrus are no brighter against the sky than before: median ratio 1.04 (1.03 before; bound
// 1.1), since the phase function's lobe has fallen to 0.018 of the light per steradian there.
TEST_F(CirrusLightTest, CirrusNearALowSunOutshineTheSkyBehindThem) {
  Scene scene =
      loadSceneFile(configDir() / "default.yaml",
                    {"sky.model=physical", "sun.elevation=5", "sun.azimuth=0", "camera.heading=0",
                     "camera.pitch=10", "output.width=160", "output.height=90",
                     "weather.cover_low=0", "weather.cover_mid=0", "high_clouds.resolution=512"});
  const AgainstTheSky nearSun = againstTheSky(render(scene), scene, 2.0, 20.0);
  std::cout << "within 20 deg of the sun: " << nearSun.pixels << " cirrus pixels, "
            << nearSun.brighterShare << " brighter than the sky behind, median ratio "
            << nearSun.medianRatio << "\n";
  ASSERT_GE(nearSun.pixels, 100);
  EXPECT_GT(nearSun.brighterShare, 0.98);
  EXPECT_GT(nearSun.medianRatio, 1.25);

  scene.camera.heading = 180.0;
  scene.camera.pitch = 20.0;
  const AgainstTheSky away = againstTheSky(render(scene), scene, 90.0, 180.0);
  std::cout << "more than 90 deg from the sun: " << away.pixels << " cirrus pixels, "
            << away.brighterShare << " brighter than the sky behind, median ratio "
            << away.medianRatio << "\n";
  ASSERT_GE(away.pixels, 100);
  EXPECT_LT(away.medianRatio, 1.1);
}

}  // namespace
}  // namespace sky
