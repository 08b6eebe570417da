// The perception layers (docs/outputs.md, "Perception layers"): the clouds' optical depth and
// hit distance per pixel against the CPU field the library's queries read, the labels by
// their documented rule, the cloud types, the air's transmittance against the field's air,
// the ground's cloud shadow, and the frame's visibility and sun.
#include <cmath>
#include <limits>

#include "cloud_test_util.h"
#include "engine/lighting/light_model.h"
#include "engine/render/perception.h"
#include "shaders/common/cloud_perception_shared.h"

namespace sky::test {
namespace {

class Perception : public CloudRenderTest {};

// One channel of a layer of the frame, at pixel (x, y).
float channel(const RenderedFrame& f, const std::string& layerName, const std::string& name, int x,
              int y, bool integer = false) {
  for (const ImageLayer& layer : f.image.layers) {
    if (layer.name != layerName || layer.integer != integer) continue;
    for (size_t c = 0; c < layer.channels.size(); ++c)
      if (layer.channels[c] == name)
        return layer.pixels[(size_t(y) * size_t(f.image.width) + size_t(x)) *
                                layer.channels.size() +
                            c];
  }
  ADD_FAILURE() << "no channel " << layerName << "." << name;
  return 0.0f;
}
int label(const RenderedFrame& f, int x, int y) {
  return int(channel(f, "", "label", x, y, true));
}

// How far along `dir` from the camera the ray leaves the cloud layers (above `topM`) or meets
// the ground.
double rayLength(const CloudField& field, const glm::dvec3& dir, double topM) {
  double t = 0.0;
  for (; t < 400000.0; t += 50.0) {
    const double h = field.latLonAltitudeOf(dir * t).z;
    if (h > topM || h < 0.0) break;
  }
  return t;
}

// Cumulus at noon, the sun and the moon placed in the view.
Scene perceptionScene(const std::vector<std::string>& more = {}) {
  std::vector<std::string> o = {"output.perception=true", "sun.azimuth=185", "sun.elevation=30",
                                "moon.azimuth=220", "moon.elevation=25"};
  o.insert(o.end(), more.begin(), more.end());
  return cloudScene("cumulus_noon", o);
}

TEST_F(Perception, OpticalDepthAndHitDistanceAreTheQueriesField) {
  const Scene scene = perceptionScene();
  const RenderedFrame f = render(scene);
  const CloudField field = renderer().cloudField(scene, scene.time.start);
  const shared::ViewState view = makeViewState(scene.camera, 64, 36);
  const double top = std::max(field.params().lowTopM, field.params().midTopM);
  int compared = 0, hits = 0;
  double worst = 0.0;
  for (int y = 1; y < 36; y += 4)
    for (int x = 2; x < 64; x += 7) {
      const glm::dvec3 d = viewDirection(view, x + 0.5, y + 0.5);
      if (d.z < 0.12) continue;  // the long grazing rays cost the CPU march seconds
      const double length = rayLength(field, d, top + 100.0);
      const double tau = field.cloudOpticalDepth(glm::dvec3(0.0), d * length, 5.0);
      const double gpu = channel(f, "clouds", "optical_depth", x, y);
      // Within 0.05 + 10 %: past the hit the perception march takes Lu's steps (tens of
      // metres), the query 5 m ones, and the cumulus' billows at full strength (issue 46,
      // cumulusNDmod) vary the density within such a step. Measured: the worst of 45 pixels
      // (23,13) 8.1 % of (0.05 + tau) apart, 2.09 against 2.28 (the query gives 2.276, 2.275
      // and 2.275 at 10, 2 and 1 m steps); the next (37,9) misses a wisp of 0.004. Steps of
      // at most 10 m past the hit bring every pixel within 4.3 % (5 m: 2.19 at (23,13)), but
      // double the perception pass (517 -> 870-1057 ms, the peer's view at 320 x 180); a cap
      // of one optical depth a step leaves (23,13) as it is: its error is in the thin edge.
      EXPECT_NEAR(gpu, tau, 0.05 + 0.1 * tau) << "pixel " << x << "," << y;
      worst = std::max(worst, std::abs(gpu - tau) / (0.05 + tau));
      ++compared;
      // The hit: where the optical depth passes a tenth; none where it never does (away from
      // the threshold, where a step's placement decides).
      const float hit = channel(f, "clouds", "distance", x, y);
      if (tau > 0.12) {
        const std::optional<double> at =
            field.distanceToOpticalDepth(glm::dvec3(0.0), d, length, 0.1, 5.0);
        ASSERT_TRUE(at.has_value());
        EXPECT_NEAR(hit, *at, 40.0 + 0.02 * *at) << "pixel " << x << "," << y;
        EXPECT_EQ(label(f, x, y), PERCEPTION_LABEL_LOW_CLOUD);
        EXPECT_EQ(int(channel(f, "", "cloud_type", x, y, true)), PERCEPTION_TYPE_CUMULUS);
        ++hits;
      } else if (tau < 0.08) {
        EXPECT_TRUE(std::isinf(hit)) << "pixel " << x << "," << y << " tau " << tau;
        EXPECT_NE(label(f, x, y), PERCEPTION_LABEL_LOW_CLOUD);
      }
    }
  EXPECT_GE(compared, 20);
  EXPECT_GE(hits, 3) << "the view shows cumulus";
  std::printf("optical depth: %d pixels, %d hits, worst error %.3f of (0.05 + tau)\n", compared,
              hits, worst);
}

TEST_F(Perception, LabelsFollowTheDocumentedRule) {
  // Clear air: the sun and the moon in the view, the ground below the horizon.
  const Scene scene = perceptionScene({"weather.cover_low=0"});
  const RenderedFrame f = render(scene);
  ASSERT_TRUE(f.perception.has_value());
  const shared::ViewState view = makeViewState(scene.camera, 64, 36);
  int sun = 0, moon = 0;
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 64; ++x) {
      const glm::dvec3 d = viewDirection(view, x + 0.5, y + 0.5);
      const int l = label(f, x, y);
      EXPECT_TRUE(std::isinf(channel(f, "clouds", "distance", x, y)));
      EXPECT_EQ(channel(f, "clouds", "optical_depth", x, y), 0.0f);
      EXPECT_EQ(int(channel(f, "", "cloud_type", x, y, true)), PERCEPTION_TYPE_NONE);
      EXPECT_EQ(channel(f, "ground", "cloud_shadow", x, y), 1.0f);
      // Below the horizon (the camera 2 m up: it dips by 0.05 degrees) the ground.
      if (d.z < -0.001) {
        EXPECT_EQ(l, PERCEPTION_LABEL_GROUND) << x << "," << y;
      }
      if (d.z > 0.0) {
        EXPECT_NE(l, PERCEPTION_LABEL_GROUND) << x << "," << y;
      }
      if (l == PERCEPTION_LABEL_SUN) {
        // The pixel the sun's centre falls in (a disc under a pixel across).
        EXPECT_LT(std::acos(glm::dot(d, f.lighting.sun.direction)), 1.2 * view.forward.w);
        ++sun;
      }
      if (l == PERCEPTION_LABEL_MOON) {
        EXPECT_LT(std::acos(glm::dot(d, f.lighting.moon.direction)), 1.2 * view.forward.w);
        ++moon;
      }
      // The air's transmittance: to the ground a few metres away (at most 10 m), all but
      // whole (0.999 is 10 m of air that sees 40 km: turbidity 0.15's haze); to space, less.
      const float air = channel(f, "air", "transmittance", x, y);
      EXPECT_GT(air, 0.0f);
      EXPECT_LE(air, 1.0f);
      if (l == PERCEPTION_LABEL_GROUND && d.z < -0.2) {
        EXPECT_GT(air, 0.998f);
      }
      if (l == PERCEPTION_LABEL_SKY) {
        EXPECT_LT(air, 0.95f);
      }
    }
  EXPECT_GE(sun, 1);
  EXPECT_LE(sun, 2);
  EXPECT_GE(moon, 1);
  EXPECT_LE(moon, 2);
  double sum = 0.0;
  for (double s : f.perception->labelShares) sum += s;
  EXPECT_NEAR(sum, 1.0, 1e-9);
  EXPECT_GT(f.perception->labelShares[PERCEPTION_LABEL_GROUND], 0.2);
  EXPECT_GT(f.perception->labelShares[PERCEPTION_LABEL_SKY], 0.4);
  EXPECT_EQ(f.perception->labelShares[PERCEPTION_LABEL_LOW_CLOUD], 0.0);
}

TEST_F(Perception, MidCloudsAndTheirTypeAndTheAirBeforeThem) {
  // Altocumulus in the mid layer, the physical sky: the air to each hit is the field's air.
  const Scene scene = cloudScene("cumulus_noon",
                                 {"output.perception=true", "weather.cover_low=0",
                                  "weather.cover_mid=0.7", "weather.cloud_type=altocumulus",
                                  "sky.model=physical", "camera.pitch=25"});
  const RenderedFrame f = render(scene);
  const CloudField field = renderer().cloudField(scene, scene.time.start);
  const shared::ViewState view = makeViewState(scene.camera, 64, 36);
  int mid = 0;
  for (int y = 0; y < 36; y += 3)
    for (int x = 0; x < 64; x += 3) {
      if (label(f, x, y) != PERCEPTION_LABEL_MID_CLOUD) continue;
      ++mid;
      EXPECT_EQ(int(channel(f, "", "cloud_type", x, y, true)), PERCEPTION_TYPE_ALTOCUMULUS);
      const double hit = channel(f, "clouds", "distance", x, y);
      const glm::dvec3 d = viewDirection(view, x + 0.5, y + 0.5);
      EXPECT_GE(field.latLonAltitudeOf(d * hit).z, field.params().midBaseM - 50.0);
      const glm::dvec3 tau = field.airOpticalDepth(glm::dvec3(0.0), d * hit);
      const double expected = glm::dot(glm::exp(-tau), glm::dvec3(0.2126, 0.7152, 0.0722));
      EXPECT_NEAR(channel(f, "air", "transmittance", x, y), expected, 0.02)
          << "pixel " << x << "," << y << " at " << hit << " m";
    }
  EXPECT_GE(mid, 10) << "the view shows altocumulus";
}

TEST_F(Perception, TheGroundUnderAnOvercastIsInShadowAndTheSunHidden) {
  const Scene clear = cloudScene("overcast_stratus",
                                 {"output.perception=true", "weather.cover_low=0",
                                  "camera.pitch=-30"});
  const Scene overcast = cloudScene("overcast_stratus",
                                    {"output.perception=true", "weather.cover_low=1",
                                     "camera.pitch=-30"});
  const RenderedFrame a = render(clear), b = render(overcast);
  ASSERT_TRUE(a.perception && b.perception);
  double shadow = 0.0;
  int ground = 0;
  for (int y = 18; y < 36; ++y)
    for (int x = 0; x < 64; ++x)
      if (label(b, x, y) == PERCEPTION_LABEL_GROUND) {
        shadow += channel(b, "ground", "cloud_shadow", x, y);
        ++ground;
      }
  ASSERT_GT(ground, 100);
  EXPECT_LT(shadow / ground, 0.3) << "the ground under a full stratus deck is in its shadow";
  // The sun (66 degrees up at noon) through the deck and the air, and through the air alone.
  EXPECT_GT(a.perception->sunVisible, 0.7);
  EXPECT_LT(a.perception->sunVisible, 1.0);
  EXPECT_EQ(a.perception->sunCloud, 1.0);
  EXPECT_LT(b.perception->sunVisible, 0.05);
  // The meteorological optical range of clear air at the ground: ln 20 over the air's
  // extinction at 550 nm, tens of kilometres.
  const CloudField field = renderer().cloudField(clear, clear.time.start);
  EXPECT_NEAR(a.perception->visibilityM, std::log(20.0) / field.airExtinction({}).y, 1.0);
  EXPECT_GT(a.perception->visibilityM, 10000.0);
  EXPECT_LT(a.perception->visibilityM, 400000.0);
}

TEST_F(Perception, TheAirOverheadIsTheHazesWholeColumn) {
  // A hand-made case with a known optical depth: straight up through the kozlov haze, whose
  // extinction falls off exponentially with height (light::hazeMedium), the column from the
  // camera to space is beta H e^(-h / H) per component, over the cosine of the pixel's angle
  // from the zenith.
  const Scene scene = cloudScene("cumulus_noon", {"output.perception=true", "weather.cover_low=0",
                                                  "camera.pitch=90", "camera.altitude_m=300",
                                                  "sky.model=kozlov", "high_clouds.cover=0"});
  const RenderedFrame f = render(scene);
  const light::HazeMedium haze = light::hazeMedium(scene.lighting.turbidity);
  const shared::ViewState view = makeViewState(scene.camera, 64, 36);
  for (const auto& [x, y] : {std::pair{31, 17}, {32, 18}, {20, 10}, {45, 25}}) {
    const glm::dvec3 d = viewDirection(view, x + 0.5, y + 0.5);
    const double h = scene.camera.altitudeM;
    const glm::dvec3 tau = (haze.rayleighPerM * haze.rayleighHeightM *
                                std::exp(-h / haze.rayleighHeightM) +
                            haze.aerosolPerM * haze.aerosolHeightM *
                                std::exp(-h / haze.aerosolHeightM)) /
                           d.z;
    const double expected = glm::dot(glm::exp(-tau), glm::dvec3(0.2126, 0.7152, 0.0722));
    EXPECT_EQ(label(f, x, y), PERCEPTION_LABEL_SKY);
    EXPECT_NEAR(channel(f, "air", "transmittance", x, y), expected, 0.003)
        << "pixel " << x << "," << y << ", " << std::acos(d.z) * 180.0 / M_PI << " deg from the zenith";
  }
}

TEST_F(Perception, EachViewOfAFrameHasItsOwnLabels) {
  // A rig of two views in one frame: each view's layers and numbers are its own render's.
  const Scene scene = perceptionScene({"weather.cover_low=0.6"});
  std::vector<FrameView> views(2);
  views[0] = {200.0, 10.0, 0.0, 60.0, CameraProjection::Perspective, 32, 18};
  views[1] = {20.0, -20.0, 0.0, 60.0, CameraProjection::Perspective, 32, 18};
  const std::vector<RenderedFrame> frames = renderer().render(scene, scene.time.start, views, {});
  ASSERT_EQ(frames.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    Scene alone = scene;
    alone.camera.heading = views[i].headingDeg;
    alone.camera.pitch = views[i].pitchDeg;
    alone.output.width = 32;
    alone.output.height = 18;
    const RenderedFrame single = render(alone);
    ASSERT_TRUE(frames[i].perception && single.perception) << "view " << i;
    EXPECT_EQ(frames[i].perception->labelShares, single.perception->labelShares) << "view " << i;
    EXPECT_EQ(frames[i].perception->sunVisible, single.perception->sunVisible);
  }
  EXPECT_NE(frames[0].perception->labelShares, frames[1].perception->labelShares)
      << "the views look at different things";
}

TEST_F(Perception, InsideACloudTheVisibilityIsItsOwn) {
  // The densest altitude of the deck above the camera's place, found in the field.
  const Scene ground = cloudScene("overcast_stratus", {"weather.cover_low=1"});
  const CloudField deck = renderer().cloudField(ground, ground.time.start);
  double best = 0.0, densest = 0.0;
  for (double h = 500.0; h <= 2500.0; h += 25.0) {
    const double beta = deck.extinction(deck.enuOf(ground.camera.latitude, ground.camera.longitude, h));
    if (beta > densest) {
      densest = beta;
      best = h;
    }
  }
  ASSERT_GT(densest, 0.0) << "a full stratus deck over the camera";
  const Scene scene =
      cloudScene("overcast_stratus", {"output.perception=true", "weather.cover_low=1",
                                      "camera.altitude_m=" + std::to_string(best)});
  const RenderedFrame f = render(scene);
  const CloudField field = renderer().cloudField(scene, scene.time.start);
  ASSERT_TRUE(f.perception.has_value());
  const double beta = field.extinction(glm::dvec3(0.0)) + field.airExtinction({}).y;
  EXPECT_NEAR(f.perception->visibilityM, std::log(20.0) / beta, 1.0);
  EXPECT_LT(f.perception->visibilityM, 2000.0) << "in the cloud at " << best << " m";
}

}  // namespace
}  // namespace sky::test
