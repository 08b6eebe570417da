// The whole picture around the clouds (issue 15), at tiny sizes with stated tolerances: the
// ground under an overcast is darker than the cloud base above it, the aerial perspective
// lowers distant clouds' contrast against the sky and leaves near ones alone, the ground
// seen from an aircraft shows the clouds' shadows, and lighting.turbidity hazes the physical
// sky and reddens the sun together. Each check reads the final scene-linear image (the
// "beauty" layer) and, where stated, the clouds' own layer before the composite.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cloud_test_util.h"

namespace sky {
namespace {

using test::CloudLayerView;

class CompositeLookTest : public test::CloudRenderTest {};

// The default scene at a test size and noon, with overrides.
Scene defaultAt(int width, int height, std::vector<std::string> overrides) {
  std::vector<std::string> all = {"output.width=" + std::to_string(width),
                                  "output.height=" + std::to_string(height),
                                  "time=2024-06-21T14:00:00+02:00"};
  all.insert(all.end(), overrides.begin(), overrides.end());
  return loadSceneFile(configDir() / "default.yaml", all);
}

glm::vec3 beautyAt(const RenderedFrame& f, int x, int y) {
  const ImageLayer& l = f.image.layers.at(0);
  const float* p = &l.pixels[(static_cast<size_t>(y) * f.image.width + x) * l.channels.size()];
  return {p[0], p[1], p[2]};
}

glm::vec3 skyAt(const RenderedFrame& f, int x, int y) {
  const ImageLayer* l = f.image.find("sky");
  const float* p = &l->pixels[(static_cast<size_t>(y) * f.image.width + x) * 3];
  return {p[0], p[1], p[2]};
}

double lum(const glm::vec3& c) {
  return test::luminance(&c.x);
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

TEST_F(CompositeLookTest, GroundUnderAnOvercastIsDarkerThanTheCloudBase) {
  // 95 % stratus at noon, looking level: the cloud base fills the upper half, the ground the
  // lower. A real overcast's ground (albedo ~0.1) is several times darker than the base that
  // lights it; the old composite drew a sky-blue ground brighter than the clouds.
  const RenderedFrame f = render(defaultAt(
      64, 36, {"weather.cover_low=0.95", "weather.cloud_type=stratus", "camera.pitch=0"}));
  const CloudLayerView c(f);
  std::vector<double> base, ground;
  for (int x = 0; x < f.image.width; ++x) {
    for (int y = 2; y < 12; ++y)
      if (c.at(x, y).alpha > 0.9f) base.push_back(lum(beautyAt(f, x, y)));
    for (int y = 24; y < 36; ++y) ground.push_back(lum(beautyAt(f, x, y)));
  }
  ASSERT_GT(base.size(), 200u) << "the overcast fills the upper rows";
  std::cout << "overcast: cloud base " << mean(base) << ", ground " << mean(ground) << "\n";
  EXPECT_LT(mean(ground), 0.5 * mean(base));
}

TEST_F(CompositeLookTest, AerialPerspectiveLowersDistantCloudsContrastAgainstTheSky) {
  // Cumulus toward the horizon. For opaque cloud pixels, the contrast against the clear sky
  // behind them, |beauty - sky|, over the clouds' own contrast before the composite,
  // |clouds - sky|: near 1 for clouds within 4 km, and well below for those beyond 60 km,
  // which fade into the horizon haze (the peer's look). Both sky models.
  for (const char* model : {"kozlov", "physical"}) {
    SCOPED_TRACE(model);
    const RenderedFrame f =
        render(defaultAt(96, 54, {"camera.pitch=2", std::string("sky.model=") + model}));
    const CloudLayerView c(f);
    std::vector<double> nearRatio, farRatio;
    for (int y = 0; y < f.image.height; ++y)
      for (int x = 0; x < f.image.width; ++x) {
        const test::CloudPixel p = c.at(x, y);
        if (p.alpha < 0.98f) continue;
        const double sky = lum(skyAt(f, x, y));
        const double before = std::abs(lum(p.rgb) - sky);
        if (before < 0.05 * sky) continue;  // a cloud as bright as the sky has no contrast to lose
        const double ratio = std::abs(lum(beautyAt(f, x, y)) - sky) / before;
        if (p.depth < 4000.0f) nearRatio.push_back(ratio);
        if (p.depth > 60000.0f) farRatio.push_back(ratio);
      }
    ASSERT_GT(nearRatio.size(), 10u) << "the view holds near clouds";
    ASSERT_GT(farRatio.size(), 10u) << "and distant ones";
    std::cout << model << ": contrast kept near " << mean(nearRatio) << ", far " << mean(farRatio)
              << "\n";
    EXPECT_GT(mean(nearRatio), 0.8);
    EXPECT_LT(mean(farRatio), 0.5);
    EXPECT_LT(mean(farRatio), 0.75 * mean(nearRatio));
  }
}

TEST_F(CompositeLookTest, FromAnAircraftTheGroundShowsTheCloudsShadows) {
  // From 5 km, 60 degrees down onto 40 % cumulus with the sun high: in the gaps between the
  // clouds the ground is sunlit or lies in a cloud's shadow. Without shadows the gaps' ground
  // is one flat colour (its light and haze change slowly across the view).
  const RenderedFrame f = render(
      defaultAt(96, 54, {"camera.altitude_m=5000", "camera.pitch=-60", "weather.cover_low=0.4"}));
  const CloudLayerView c(f);
  std::vector<double> gaps;
  for (int y = 0; y < f.image.height; ++y)
    for (int x = 0; x < f.image.width; ++x)
      if (c.at(x, y).alpha < 0.02f) gaps.push_back(lum(beautyAt(f, x, y)));
  ASSERT_GT(gaps.size(), 500u) << "the view holds gaps between the clouds";
  const double dark = quantile(gaps, 0.1), lit = quantile(gaps, 0.9);
  std::cout << "ground in the gaps: 10th percentile " << dark << ", 90th " << lit << "\n";
  EXPECT_LT(dark, 0.75 * lit) << "shadowed ground is darker than sunlit ground";
  // And the report says where the map lay.
  EXPECT_GT(f.cloudShadow.valid, 0.5f);
  EXPECT_GT(f.cloudShadow.radiusM, 250000.0f) << "past the horizon seen from 5 km";
}

TEST_F(CompositeLookTest, TurbidityHazesThePhysicalSkyAndReddensTheSunTogether) {
  // sky.model physical with atmosphere.aerosols turbidity: more aerosol whitens the sky near
  // the horizon (its blue over red falls) and reddens the sun's light at the ground (blue over
  // red falls too), from the one optical depth.
  struct Look {
    double skyBlueOverRed, sunBlueOverRed;
  };
  auto look = [&](double turbidity) {
    const RenderedFrame f =
        render(defaultAt(64, 36,
                         {"sky.model=physical", "weather.cover_low=0", "high_clouds.cover=0",
                          "camera.pitch=5", "lighting.turbidity=" + std::to_string(turbidity)}));
    glm::vec3 horizon(0.0f);
    // Row 18, about 4 degrees above the horizon: row 20 holds the horizon line itself, where a
    // clear sky is at its reddest, so it measured where the line fell rather than the haze.
    for (int x = 0; x < f.image.width; ++x) horizon += skyAt(f, x, 18);
    const glm::vec4 sun = f.lighting.gpu.sun.illuminance;
    return Look{horizon.b / horizon.r, sun.b / sun.r};
  };
  const Look clear = look(0.05), hazy = look(0.5);
  std::cout << "sky B/R near the horizon " << clear.skyBlueOverRed << " -> " << hazy.skyBlueOverRed
            << ", sun B/R " << clear.sunBlueOverRed << " -> " << hazy.sunBlueOverRed << "\n";
  EXPECT_LT(hazy.skyBlueOverRed, 0.85 * clear.skyBlueOverRed);
  EXPECT_LT(hazy.sunBlueOverRed, 0.85 * clear.sunBlueOverRed);
}

}  // namespace
}  // namespace sky
