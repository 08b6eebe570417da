// How the volumetric clouds are lit: sunlit tops brighter than the bases under them, the moon
// as the only light at night (in proportion to its illuminance), and the dual-lobe phase
// function's back-scattering (passes/volumetric_clouds cloudParams, Lu (22)-(24)).
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "cloud_test_util.h"
#include "engine/lighting/lighting_state.h"

namespace sky {
namespace {

using test::CloudLayerView;
using test::cloudScene;

class CloudLightingTest : public test::CloudRenderTest {};

// Mean luminance of the clouds' own colour (premultiplied radiance / opacity) over the
// pixels denser than `minAlpha`, and their count.
struct CloudBrightness {
  double meanLuminance = 0.0;
  int pixels = 0;
};

CloudBrightness brightness(const RenderedFrame& frame, float minAlpha = 0.5f) {
  const CloudLayerView c(frame);
  CloudBrightness b;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) {
      const test::CloudPixel p = c.at(x, y);
      if (p.alpha <= minAlpha) continue;
      const glm::vec3 colour = p.rgb / p.alpha;
      b.meanLuminance += test::luminance(&colour.x);
      ++b.pixels;
    }
  if (b.pixels > 0) b.meanLuminance /= b.pixels;
  return b;
}

// Sum of the clouds' premultiplied luminance over the image.
double totalLuminance(const RenderedFrame& frame) {
  const CloudLayerView c(frame);
  double sum = 0.0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) {
      const glm::vec3 rgb = c.at(x, y).rgb;
      sum += test::luminance(&rgb.x);
    }
  return sum;
}

TEST_F(CloudLightingTest, NoonCumulusTopsAreBrighterThanTheirBases) {
  // The same clouds (low layer 500-2500 m, 60 % cover) from 2 m looking up and from 4 km
  // looking down. The sun is placed east, 45 degrees up, and the views are turned so that each
  // looks at 90 degrees from it (sin(heading) = -/+ tan(pitch)): the phase function weighs both
  // alike, and what differs is the cloud between the sun and the part we see.
  const std::vector<std::string> common = {"sun.azimuth=90", "sun.elevation=45",
                                           "camera.vertical_fov=40", "weather.cover_low=0.6",
                                           "weather.spread=0"};
  // Averaged over a few places a few kilometres apart, so the test does not rest on which
  // cloud of the (ground-fixed) noise happens to stand over one spot.
  CloudBrightness bases, tops;
  for (const char* latitude :
       {"camera.latitude=47.37", "camera.latitude=47.40", "camera.latitude=47.43"}) {
    std::vector<std::string> below = common, above = common;
    below.insert(below.end(),
                 {latitude, "camera.altitude_m=2", "camera.pitch=30", "camera.heading=324.74"});
    above.insert(above.end(),
                 {latitude, "camera.altitude_m=4000", "camera.pitch=-30", "camera.heading=35.26"});
    const RenderedFrame fromBelow = render(cloudScene("cumulus_noon", below));
    const RenderedFrame fromAbove = render(cloudScene("cumulus_noon", above));
    for (const auto& [frame, overrides] : {std::pair{&fromBelow, below}, {&fromAbove, above}}) {
      const CameraSettings cam = cloudScene("cumulus_noon", overrides).camera;
      const glm::vec3 forward(makeViewState(cam, 64, 36).forward);
      EXPECT_NEAR(glm::dot(forward, glm::vec3(frame->lighting.sun.direction)), 0.0f, 1e-3f);
    }
    for (const auto& [total, frame] : {std::pair{&bases, &fromBelow}, {&tops, &fromAbove}}) {
      const CloudBrightness b = brightness(*frame);
      total->meanLuminance += b.meanLuminance * b.pixels;
      total->pixels += b.pixels;
    }
  }
  bases.meanLuminance /= std::max(bases.pixels, 1);
  tops.meanLuminance /= std::max(tops.pixels, 1);
  ASSERT_GT(bases.pixels, 300);
  ASSERT_GT(tops.pixels, 300);
  EXPECT_GT(tops.meanLuminance, 1.5 * bases.meanLuminance)
      << "tops " << tops.meanLuminance << ", bases " << bases.meanLuminance;
}

TEST_F(CloudLightingTest, AtNightTheMoonIsTheKeyLight) {
  const Scene scene = cloudScene("altocumulus_full_moon");
  const LightingState lighting = computeLighting(scene, scene.time.start);
  const shared::ViewState view = makeViewState(scene.camera, 64, 36);
  const shared::CloudParams night =
      cloudParams(volumetricCloudsSettings(scene), lighting, scene.time.start, view,
                  glm::vec2(0.0f, 0.5f), {}, {});
  EXPECT_FALSE(cloudKeyLight(night).isSun) << "the moon";
  EXPECT_NEAR(glm::dot(cloudKeyLight(night).direction, glm::vec3(lighting.moon.direction)), 1.0f,
              1e-6f);
  EXPECT_EQ(night.sunMarched, 0.0f) << "the sun, 64 degrees down, is not marched";
  EXPECT_EQ(night.moonMarched, 1.0f) << "the moon is";
  EXPECT_GT(night.moonAtMid.middle.g, 0.0f);

  const Scene noon = cloudScene("cumulus_noon");
  const LightingState day = computeLighting(noon, noon.time.start);
  const shared::CloudParams p = cloudParams(volumetricCloudsSettings(noon), day, noon.time.start,
                                            view, glm::vec2(0.5f, 0.0f), {}, {});
  EXPECT_TRUE(cloudKeyLight(p).isSun) << "by day the sun";

  const RenderedFrame frame = render(scene);
  EXPECT_EQ(frame.lighting.key, "moon");
  EXPECT_GT(brightness(frame).meanLuminance, 0.0) << "moonlit clouds";
}

TEST_F(CloudLightingTest, MoonlitCloudsScaleWithTheMoonsIlluminance) {
  // The full moon of 2024-12-15 and the last quarter of 2024-12-22, both placed where the full
  // moon stands (so the same air mass dims them) at the same hour (the sun 64 degrees down in
  // both). The clouds' ambient light is the frame's sky (passes/cloud_ambient): with the
  // palette's night keys dark (the sun's own night sky; the moonlit sky is the day keys at the
  // moon's elevation, scaled by the moon) the moon is the only light, direct and through the
  // sky and the ground, so the clouds' radiance follows its illuminance above the atmosphere.
  auto moonlit = [&](const std::string& time) {
    Scene scene = cloudScene("altocumulus_full_moon",
                             {"time=" + time, "moon.azimuth=131.79", "moon.elevation=64.59"});
    for (PaletteKey& key : scene.lighting.palette) {
      key.ambientTop = key.ambientBottom = glm::vec3(0.0f);
      if (key.sunElevation < 0.0) key.skyColor = key.fogColor = key.glowColor = glm::vec3(0.0f);
    }
    return render(scene);
  };
  const RenderedFrame full = moonlit("2024-12-15T23:30:00+01:00");
  const RenderedFrame quarter = moonlit("2024-12-22T23:30:00+01:00");
  const double moonRatio = test::luminance(&quarter.lighting.gpu.moonSpace.x) /
                           test::luminance(&full.lighting.gpu.moonSpace.x);
  ASSERT_LT(moonRatio, 0.5) << "a quarter moon gives much less light";
  const double full0 = totalLuminance(full);
  ASSERT_GT(full0, 0.0);
  EXPECT_NEAR(totalLuminance(quarter) / full0, moonRatio, 0.01 * moonRatio);
  // The clouds themselves are the same: the scene's time starts at each frame, so the wind
  // has not moved them.
  EXPECT_EQ(CloudLayerView(full).alpha(), CloudLayerView(quarter).alpha());
}

TEST_F(CloudLightingTest, DualLobeBackScattersMoreThanHenyeyGreenstein) {
  // The sun behind the camera: the clouds in view scatter it back toward us. The phase
  // function alone, without the diffusion term (whose fall-off reads the phase's mean cosine,
  // lower for the dual lobe, so it is not the phase's direct effect).
  auto withPhase = [&](const char* phase) {
    return render(
        cloudScene("cumulus_noon",
                   {"camera.heading=200", "camera.pitch=25", "sun.azimuth=20", "sun.elevation=30",
                    "clouds.multiple_scattering=0", std::string("clouds.phase=") + phase}));
  };
  const RenderedFrame hg = withPhase("hg");
  const RenderedFrame dual = withPhase("dual_lobe");
  EXPECT_EQ(CloudLayerView(hg).alpha(), CloudLayerView(dual).alpha()) << "the same clouds";
  EXPECT_GT(totalLuminance(dual), 1.1 * totalLuminance(hg));
  // Looking toward the sun instead, the forward lobe dominates: hg (all weight forward) is
  // brighter.
  auto towardSun = [&](const char* phase) {
    return render(
        cloudScene("cumulus_noon",
                   {"camera.heading=20", "camera.pitch=25", "sun.azimuth=20", "sun.elevation=30",
                    "clouds.multiple_scattering=0", std::string("clouds.phase=") + phase}));
  };
  EXPECT_GT(totalLuminance(towardSun("hg")), totalLuminance(towardSun("dual_lobe")));
}

}  // namespace
}  // namespace sky
