// The volumetric clouds seen from different places and times: a flight from the ground through
// the low layer to above it, the weather region's bounds, a map without cover, the wind moving
// the clouds without a re-bake, and the debug outputs (step counts, density slice, weather
// map) with their errors.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <gtest/gtest.h>

#include "cloud_test_util.h"
#include "engine/core/error.h"
#include "engine/weather/geo.h"
#include "engine/weather/weather_map.h"
#include "error_capture.h"

namespace sky {
namespace {

using test::CloudLayerView;
using test::cloudScene;
using test::hasPass;
using test::pixelDirection;

class CloudViewTest : public test::CloudRenderTest {};

// Opacity statistics over the pixels whose view ray points above (or below) the horizon by
// more than `marginDeg`; pixels within the margin are skipped.
struct HalfStats {
  int pixels = 0;
  float maxAlpha = 0.0f;
  double meanAlpha = 0.0;
  float minDepth = 1e30f;  // over the cloudy pixels
};

struct Halves {
  HalfStats above, below;
};

Halves splitAtHorizon(const RenderedFrame& frame, const CameraSettings& cam, double marginDeg) {
  const CloudLayerView clouds(frame);
  Halves h;
  const float margin = static_cast<float>(std::sin(marginDeg * 3.14159265358979 / 180.0));
  for (int y = 0; y < clouds.height(); ++y)
    for (int x = 0; x < clouds.width(); ++x) {
      const float z = pixelDirection(cam, clouds.width(), clouds.height(), x, y).z;
      if (std::abs(z) < margin) continue;
      HalfStats& s = z > 0.0f ? h.above : h.below;
      const test::CloudPixel p = clouds.at(x, y);
      ++s.pixels;
      s.meanAlpha += p.alpha;
      s.maxAlpha = std::max(s.maxAlpha, p.alpha);
      if (p.alpha > 0.0f) s.minDepth = std::min(s.minDepth, p.depth);
    }
  for (HalfStats* s : {&h.above, &h.below})
    if (s->pixels > 0) s->meanAlpha /= s->pixels;
  return h;
}

// ---- A flight from the ground to above the clouds ----------------------------------------

// The low layer only (500-2500 m), looking level along the heading, a wide view.
Scene flightScene(double altitudeM) {
  return cloudScene("cumulus_noon",
                    {"camera.altitude_m=" + std::to_string(altitudeM), "camera.pitch=0",
                     "camera.vertical_fov=70", "weather.cover_low=0.6", "weather.spread=0.3"});
}

TEST_F(CloudViewTest, FromTheGroundCloudsAreAboveTheHorizonOnly) {
  // 2 m: a camera on a tripod (sea level itself is the next test).
  const Scene scene = flightScene(2.0);
  const RenderedFrame frame = render(scene);
  ASSERT_TRUE(frame.clouds);
  const Halves h = splitAtHorizon(frame, scene.camera, 0.5);
  ASSERT_GT(h.above.pixels, 0);
  ASSERT_GT(h.below.pixels, 0);
  EXPECT_GT(h.above.meanAlpha, 0.3) << "a 60 % covered layer overhead";
  EXPECT_EQ(h.below.maxAlpha, 0.0f) << "the ground hides everything below the horizon";
  // The layer's base is 500 m up: nothing nearer than that.
  EXPECT_GE(h.above.minDepth, 500.0f);
}

TEST_F(CloudViewTest, AtSeaLevelTheGroundStillHidesTheClouds) {
  // From sea level (R + h == R in float) the ground test once failed and rays below the
  // horizon went through the planet, drawing the clouds beyond it.
  // A map large enough that a ray through the planet comes out inside it.
  Scene scene = flightScene(0.0);
  scene.weather.region = {{20.0, 70.0}, {-20.0, 40.0}};
  const RenderedFrame frame = render(scene);
  const Halves h = splitAtHorizon(frame, scene.camera, 0.5);
  EXPECT_GT(h.above.meanAlpha, 0.3);
  EXPECT_EQ(h.below.maxAlpha, 0.0f);
}

TEST_F(CloudViewTest, InsideTheLayerTheCloudIsNearInEveryDirection) {
  // A stratus deck (low layer, 500-1000 m: cloudTypeRange(0, 0)) covering the whole map, the
  // camera in its middle.
  const Scene scene = cloudScene(
      "stratocumulus_dusk",
      {"camera.altitude_m=750", "camera.pitch=0", "camera.vertical_fov=90", "weather.cover_low=1",
       "weather.spread=0", "weather.cloud_type=stratus", "time=2024-06-21T12:00:00+02:00"});
  const RenderedFrame frame = render(scene);
  const CloudLayerView clouds(frame);
  int opaque = 0, near = 0;
  const int n = clouds.width() * clouds.height();
  for (int y = 0; y < clouds.height(); ++y)
    for (int x = 0; x < clouds.width(); ++x) {
      const test::CloudPixel p = clouds.at(x, y);
      opaque += p.alpha > 0.9f;
      near += p.alpha > 0.0f && p.depth < 500.0f;
    }
  EXPECT_GT(opaque, n * 8 / 10) << "fog all around";
  EXPECT_GT(near, n * 8 / 10) << "and close: the camera is inside it";
}

TEST_F(CloudViewTest, FromAboveTheLayerCloudsAreBelowTheHorizonOnly) {
  const Scene scene = flightScene(4000.0);
  const RenderedFrame frame = render(scene);
  const Halves h = splitAtHorizon(frame, scene.camera, 0.5);
  ASSERT_GT(h.above.pixels, 0);
  ASSERT_GT(h.below.pixels, 0);
  EXPECT_EQ(h.above.maxAlpha, 0.0f) << "only the low layer has cover: nothing above";
  EXPECT_GT(h.below.meanAlpha, 0.3) << "the layer's tops below";
  // The layer's top is 1500 m below the camera.
  EXPECT_GE(h.below.minDepth, 1500.0f);
}

// ---- The weather region ------------------------------------------------------------------

// Looking north from Zurich (8.54 E) with the region's west or east edge on the camera's
// meridian: a ray west of north only meets points west of the camera, so it can have clouds
// only when the region lies west.
TEST_F(CloudViewTest, CloudsOnlyWhereTheSampleIsInsideTheRegion) {
  auto renderWithLon = [&](double west, double east) {
    const Scene scene = cloudScene(
        "cumulus_noon",
        {"camera.heading=0", "camera.pitch=5", "camera.vertical_fov=50", "camera.altitude_m=300",
         "weather.spread=0", "weather.cover_low=0.7",
         "weather.region.lon=[" + std::to_string(west) + ", " + std::to_string(east) + "]"});
    return render(scene);
  };
  struct Sides {
    double west = 0.0, east = 0.0;  // mean opacity left / right of the centre columns
  };
  auto sides = [](const RenderedFrame& frame) {
    const CloudLayerView c(frame);
    Sides s;
    int nw = 0, ne = 0;
    for (int y = 0; y < c.height(); ++y)
      for (int x = 0; x < c.width(); ++x) {
        if (x < c.width() / 2 - 1) s.west += c.at(x, y).alpha, ++nw;
        if (x > c.width() / 2) s.east += c.at(x, y).alpha, ++ne;
      }
    s.west /= nw;
    s.east /= ne;
    return s;
  };
  const Sides eastRegion = sides(renderWithLon(8.54, 15.0));
  const Sides westRegion = sides(renderWithLon(2.0, 8.54));
  EXPECT_EQ(eastRegion.west, 0.0);
  EXPECT_GT(eastRegion.east, 0.1);
  EXPECT_EQ(westRegion.east, 0.0);
  EXPECT_GT(westRegion.west, 0.1);
}

TEST_F(CloudViewTest, ObserverOutsideTheRegionLookingAwaySeesNoCloud) {
  // The region lies 40-560 km east of the camera: looking west nothing, looking east clouds.
  const std::vector<std::string> base = {"camera.pitch=5", "weather.cover_low=0.8",
                                         "weather.spread=0", "weather.region.lon=[9.1, 16]"};
  std::vector<std::string> west = base, east = base;
  west.push_back("camera.heading=270");
  east.push_back("camera.heading=90");
  const RenderedFrame away = render(cloudScene("cumulus_noon", west));
  const RenderedFrame toward = render(cloudScene("cumulus_noon", east));
  ASSERT_TRUE(away.clouds);
  const std::vector<float> a = CloudLayerView(away).alpha();
  const std::vector<float> b = CloudLayerView(toward).alpha();
  EXPECT_EQ(*std::max_element(a.begin(), a.end()), 0.0f);
  EXPECT_GT(*std::max_element(b.begin(), b.end()), 0.5f);
}

TEST_F(CloudViewTest, MapWithoutCoverAddsNoPassAndAnEmptyLayer) {
  const Scene scene = cloudScene("cumulus_noon", {"weather.cover_low=0", "weather.cover_mid=0"});
  const RenderedFrame frame = render(scene);
  EXPECT_FALSE(frame.clouds);
  EXPECT_FALSE(hasPass(frame, "volumetric_clouds"));
  EXPECT_TRUE(hasPass(frame, "atmosphere_composite"));
  const ImageLayer* layer = frame.image.find("clouds");
  ASSERT_NE(layer, nullptr);
  ASSERT_EQ(layer->pixels.size(), static_cast<size_t>(frame.image.width) * frame.image.height * 5);
  EXPECT_EQ(*std::max_element(layer->pixels.begin(), layer->pixels.end()), 0.0f);
  EXPECT_EQ(*std::min_element(layer->pixels.begin(), layer->pixels.end()), 0.0f);
}

// ---- Time and wind -----------------------------------------------------------------------

TEST_F(CloudViewTest, AnotherTimeReRendersWithoutReBakingTheNoise) {
  // A renderer of its own: its first frame is the first to need the noise.
  ShaderCompiler compiler;
  Renderer fresh(ctx(), compiler);
  const Scene scene = cloudScene("cumulus_noon");
  const RenderedFrame first = fresh.render(scene);
  EXPECT_TRUE(first.cloudNoise.baked || first.cloudNoise.loadedCache)
      << "the first frame of a renderer bakes the noise or loads it";
  const RenderedFrame second = fresh.render(scene, scene.time.start.plusSeconds(600.0));
  EXPECT_FALSE(second.cloudNoise.baked);
  EXPECT_FALSE(second.cloudNoise.loadedCache);
  EXPECT_TRUE(second.cloudNoise.bakeTimings.empty());
  for (const PassTiming& t : second.frame.passes)
    EXPECT_EQ(t.name.rfind("cloud_noise", 0), std::string::npos) << t.name << " ran again";
  EXPECT_TRUE(hasPass(second, "volumetric_clouds"));
}

// The shift (x east, y south, in pixels) that best matches b to a: b(x, y) ~ a(x - sx, y - sy),
// by the smallest mean squared difference over the overlap.
glm::ivec2 bestShift(const std::vector<float>& a, const std::vector<float>& b, int w, int h,
                     int maxShift) {
  glm::ivec2 best(0);
  double bestErr = 1e30;
  for (int sy = -maxShift; sy <= maxShift; ++sy)
    for (int sx = -maxShift; sx <= maxShift; ++sx) {
      double err = 0.0;
      int n = 0;
      for (int y = std::max(0, sy); y < std::min(h, h + sy); ++y)
        for (int x = std::max(0, sx); x < std::min(w, w + sx); ++x) {
          const double d =
              b[static_cast<size_t>(y) * w + x] - a[static_cast<size_t>(y - sy) * w + (x - sx)];
          err += d * d;
          ++n;
        }
      err /= n;
      if (err < bestErr) bestErr = err, best = {sx, sy};
    }
  return best;
}

TEST_F(CloudViewTest, WindCarriesTheCloudsDownwind) {
  // A uniform cover, so the only pattern is the noise's, seen top-down over 1.6 x 0.72
  // degrees (about 120 x 80 km). The shape noise repeats every shape_scale_km: 40 km here, so
  // the 12 km the wind blows in the test cannot be mistaken for a shift by a whole repeat.
  const Scene scene = cloudScene(
      "cumulus_noon", {"camera.mode=geographic_topdown", "output.width=64", "output.height=48",
                       "weather.region.lat=[47, 47.72]", "weather.region.lon=[8, 9.6]",
                       "weather.spread=0", "weather.cover_low=0.5", "clouds.shape_scale_km=40",
                       "clouds.wind_speed_ms=20", "clouds.wind_from=270"});
  const int w = scene.output.width, h = scene.output.height;
  const glm::dvec2 pixelKm = regionSizeKm(*scene.weather.region) / glm::dvec2(w, h);
  const double km = 20.0 * 600.0 / 1000.0;  // 20 m/s for 10 minutes
  const IsoTime later = scene.time.start.plusSeconds(600.0);
  const std::vector<float> now = CloudLayerView(render(scene)).alpha();
  // A west wind carries them east.
  const glm::ivec2 east = bestShift(now, CloudLayerView(render(scene, later)).alpha(), w, h, 10);
  EXPECT_NEAR(east.x, km / pixelKm.x, 1.5) << "pixel " << pixelKm.x << " km";
  EXPECT_EQ(east.y, 0);
  // A north wind carries them south (down the image).
  Scene north = scene;
  north.clouds.windFrom = 0.0;
  const glm::ivec2 south = bestShift(now, CloudLayerView(render(north, later)).alpha(), w, h, 10);
  EXPECT_EQ(south.x, 0);
  EXPECT_NEAR(south.y, km / pixelKm.y, 1.5) << "pixel " << pixelKm.y << " km";
}

// ---- Debug outputs -----------------------------------------------------------------------

const DebugImage& debugImage(const RenderedFrame& frame, const std::string& name) {
  for (const DebugImage& d : frame.debug)
    if (d.info.name == name) return d;
  ADD_FAILURE() << "no debug image " << name;
  static const DebugImage none;
  return none;
}

TEST_F(CloudViewTest, StepCountsFollowTheShell) {
  // From 4 km looking up and down: the rays above the horizon never meet the low shell.
  Scene scene = flightScene(4000.0);
  RenderOptions options;
  options.debugOutputs = {"cloud_steps"};
  const RenderedFrame frame = render(scene, options);
  const DebugImage& steps = debugImage(frame, "cloud_steps");
  ASSERT_EQ(steps.image.width, scene.output.width);
  const ImageLayer& s = steps.image.layers.at(0);
  ASSERT_EQ(s.channels.size(), 2u);
  const CloudLayerView clouds(frame);
  int cloudy = 0, above = 0;
  for (int y = 0; y < clouds.height(); ++y)
    for (int x = 0; x < clouds.width(); ++x) {
      const float view = s.pixels[(static_cast<size_t>(y) * clouds.width() + x) * 2];
      const float light = s.pixels[(static_cast<size_t>(y) * clouds.width() + x) * 2 + 1];
      if (clouds.at(x, y).alpha > 0.0f) {
        ++cloudy;
        EXPECT_GT(view, 0.0f) << x << "," << y;
        EXPECT_GT(light, 0.0f) << x << "," << y << ": lit clouds march toward the sun";
      }
      if (pixelDirection(scene.camera, clouds.width(), clouds.height(), x, y).z > 0.01f) {
        ++above;
        EXPECT_EQ(view, 0.0f) << x << "," << y << ": the ray misses the shell";
      }
    }
  EXPECT_GT(cloudy, 0);
  EXPECT_GT(above, 0);
}

TEST_F(CloudViewTest, DensitySliceHasDensityOnlyInTheCoveredLayer) {
  for (const bool mid : {false, true}) {
    SCOPED_TRACE(mid ? "mid layer" : "low layer");
    const Scene scene =
        mid ? cloudScene("altocumulus_full_moon", {"weather.cover_mid=0.8", "weather.spread=0"})
            : cloudScene("cumulus_noon", {"weather.cover_low=0.8", "weather.spread=0"});
    RenderOptions options;
    options.debugOutputs = {"cloud_density_slice"};
    const RenderedFrame frame = render(scene, options);
    const LayeredImage& img = debugImage(frame, "cloud_density_slice").image;
    ASSERT_EQ(img.width, static_cast<int>(CloudDensitySlicePass::kWidth));
    ASSERT_EQ(img.height, static_cast<int>(CloudDensitySlicePass::kHeight));
    const std::vector<float>& px = img.layers.at(0).pixels;
    // Row y's altitude: top row highest, sea level at the bottom (slice.y metres above).
    const double top = std::max(scene.clouds.low.topM, scene.clouds.mid.topM) + 500.0;
    const CloudLayerSettings& covered = mid ? scene.clouds.mid : scene.clouds.low;
    int denseRows = 0;
    for (int y = 0; y < img.height; ++y) {
      const double altitude = (1.0 - (y + 0.5) / img.height) * top;
      const bool inCovered = altitude >= covered.baseM && altitude <= covered.topM;
      // A layer without cover anywhere near reads as no layer (-1), like clear air.
      const float layer = inCovered ? (mid ? 1.0f : 0.0f) : -1.0f;
      float rowMax = 0.0f;
      for (int x = 0; x < img.width; ++x) {
        const float* p = &px[(static_cast<size_t>(y) * img.width + x) * 4];
        rowMax = std::max(rowMax, p[0]);
        if (x == img.width / 2) {
          EXPECT_EQ(p[3], layer) << "row " << y << " at " << altitude << " m";
        }
      }
      if (!inCovered) {
        EXPECT_EQ(rowMax, 0.0f) << "row " << y << " at " << altitude << " m";
      }
      denseRows += inCovered && rowMax > 0.0f;
    }
    EXPECT_GT(denseRows, 3) << "the covered layer has clouds";
  }
}

TEST_F(CloudViewTest, WeatherMapOutputIsTheMapsTexels) {
  const Scene scene = cloudScene("cumulus_noon", {"weather.spread=1", "weather.resolution=64"});
  RenderOptions options;
  options.debugOutputs = {"weather_map"};
  const RenderedFrame frame = render(scene, options);
  const LayeredImage& img = debugImage(frame, "weather_map").image;
  const WeatherMap map = makeWeatherMap(weatherInputs(scene));
  ASSERT_EQ(img.width, static_cast<int>(map.width));
  ASSERT_EQ(img.height, static_cast<int>(map.height));
  const std::vector<float>& px = img.layers.at(0).pixels;
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 0; x < map.width; ++x)
      for (int c = 0; c < 4; ++c) {
        const float want = map.at(x, y)[c];
        // Stored as half floats: 11 significant bits.
        EXPECT_NEAR(px[(static_cast<size_t>(y) * map.width + x) * 4 + c], want,
                    std::abs(want) * 1e-3f + 1e-6f)
            << x << "," << y << " channel " << c;
      }
}

TEST_F(CloudViewTest, CloudDebugOutputWithoutCloudsIsBadInput) {
  // Without cover there is no cloud pass to look into: the frame's graph has none of its
  // images, and asking for one names it and lists what the frame has.
  const Scene scene = cloudScene("cumulus_noon", {"weather.cover_low=0"});
  for (const char* name : {"cloud_steps", "cloud_density_slice", "weather_map"}) {
    RenderOptions options;
    options.debugOutputs = {name};
    try {
      render(scene, options);
      ADD_FAILURE() << name << " rendered";
    } catch (const UnknownImageName& e) {
      EXPECT_EQ(e.kind(), ErrorKind::BadInput);
      EXPECT_EQ(e.name(), name);
      EXPECT_NE(std::find(e.known().begin(), e.known().end(), "beauty"), e.known().end());
      EXPECT_EQ(std::find(e.known().begin(), e.known().end(), name), e.known().end());
    }
  }
}

}  // namespace
}  // namespace sky

namespace sky {
namespace {

// The noise is tied to the ground, not to the camera or the region: a fixed point of the
// Earth finds the same texels of every noise texture from two cameras 1.3 km apart at
// different altitudes, over different regions (or none), and the wind moves it by exactly
// speed x time. Compared modulo each texture's repeat, since the textures tile.
TEST(CloudLightVariant, OnlyStepsThatResolveNoNoiseLeaveItOut) {
  // A light sample's footprint is at least a quarter of its (sub-)step and a noise resolves
  // nothing from half a cell, so a sample standing for 4 x half a cell or more never reads the
  // detail (CloudParams.lightNearSteps, a uniform: no pipeline per setting). The clouds'
  // outline is read by every step: the light's footprint is capped to resolve it.
  const auto steps = [](std::vector<std::string> overrides) {
    const Scene s = cloudScene("cumulus_noon", std::move(overrides));
    const shared::ViewState view = makeViewState(s.camera, 8, 8);
    const shared::CloudParams p =
        cloudParams(volumetricCloudsSettings(s), computeLighting(s, s.time.start), s.time.start,
                    view, glm::vec2(0.5f, 0.0f), {}, {});
    return p.lightNearSteps;
  };
  // Detail cells of 200 m (lu2023: 2 a 0.4 km repeat). Split 1: steps of 38.7 ... 619.4 m, the
  // fifth reads no detail. The default split 2 halves them: all five may.
  EXPECT_EQ(steps({"clouds.light_split=1"}), 4u);
  EXPECT_EQ(steps({}), 5u);
  // Tang's detail has 4 cells a repeat (100 m): split 1 from the fourth short step (309.7 m) on
  // none, split 2 from the fifth.
  EXPECT_EQ(steps({"clouds.model=tang2019", "clouds.light_split=1"}), 3u);
  EXPECT_EQ(steps({"clouds.model=tang2019"}), 4u);
  // The reference reads everything.
  EXPECT_EQ(steps({"clouds.quality=reference", "clouds.light_split=1"}), 5u);
}

TEST(CloudNoiseFrame, TheNoiseStaysWithTheGround) {
  Scene a = cloudScene("cumulus_noon");
  Scene b = a;
  b.camera.latitude += 0.009;
  b.camera.longitude -= 0.011;
  b.camera.altitudeM = 1800.0;
  b.weather.region = WeatherRegion{{46.0, 49.0}, {7.0, 10.5}};
  const shared::ViewState view = makeViewState(a.camera, 8, 8);
  const auto params = [&](const Scene& s, const IsoTime& t) {
    return cloudParams(volumetricCloudsSettings(s), computeLighting(s, t), t, view,
                       glm::vec2(0.5f, 0.0f), {}, {});
  };
  const double shapeM = a.clouds.shapeScaleKm * 1000.0, detailM = a.clouds.detailScaleKm * 1000.0;
  const glm::dvec3 point = ecefFromLatLonAltitude(47.38, 8.53, 1200.0);
  // The texel coordinate of `point` (m, before the repeat) seen from `s`.
  const auto at = [&](const Scene& s, const glm::vec4& origin) {
    const glm::dvec3 camera =
        ecefFromLatLonAltitude(s.camera.latitude, s.camera.longitude, s.camera.altitudeM);
    return glm::dvec3(origin) + (point - camera);
  };
  const auto sameTexel = [](const glm::dvec3& p, const glm::dvec3& q, double period) {
    for (int k = 0; k < 3; ++k) {
      const double d = std::remainder(p[k] - q[k], period);
      EXPECT_NEAR(d, 0.0, 0.05) << "axis " << k << " (m)";
    }
  };
  const shared::CloudParams pa = params(a, a.time.start), pb = params(b, b.time.start);
  sameTexel(at(a, pa.shapeOrigin), at(b, pb.shapeOrigin), shapeM);
  sameTexel(at(a, pa.detailOrigin), at(b, pb.detailOrigin), detailM);
  // The origins keep float precision: within one repeat.
  for (int k = 0; k < 3; ++k) {
    EXPECT_GE(pa.shapeOrigin[k], 0.0f);
    EXPECT_LT(pa.shapeOrigin[k], float(shapeM));
  }
  // An hour later the noise has moved with the wind (from 270: toward the east).
  const IsoTime later{a.time.start.unixSeconds + 3600, 0.0, a.time.start.offsetMinutes};
  const shared::CloudParams pl = params(a, later);
  const glm::dvec3 east = enuToEcefRotation(a.camera.latitude, a.camera.longitude)[0];
  sameTexel(at(a, pl.shapeOrigin) + a.clouds.windSpeedMs * 3600.0 * east, at(a, pa.shapeOrigin),
            shapeM);
}

}  // namespace
}  // namespace sky
