// The public API: a Sky renders what skyrender renders, the same bits every time, keeps its
// scene when a key is wrong, and gives the host the lights of its scene.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <skylayers/skylayers.h>

#include <nlohmann/json.hpp>

#include "engine/core/files.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"

namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

// Small frames: the API's own cost is what is tested, not the clouds'.
std::string readText(const fs::path& path) {
  return sky::readTextFile(path);
}

const std::vector<std::string> kSmall = {"output.width=32", "output.height=18"};

skylayers::Sky defaultSky(std::vector<std::string> extra = {}) {
  std::vector<std::string> overrides = kSmall;
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  return skylayers::Sky::fromDefault(overrides);
}

TEST(SkylayersApi, RendersTheBeautyLayersAndDisplayOfTheDefaultScene) {
  // Looking north at noon, away from the sun.
  skylayers::Sky sky = defaultSky({"camera.heading=0", "camera.pitch=30"});
  const skylayers::Frame frame = sky.render({.layers = true, .display = true});
  ASSERT_EQ(frame.beauty.width, 32);
  ASSERT_EQ(frame.beauty.height, 18);
  EXPECT_EQ(frame.beauty.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  ASSERT_EQ(frame.beauty.pixels.size(), 32u * 18u * 4u);
  for (float v : frame.beauty.pixels) ASSERT_TRUE(std::isfinite(v));
  // A blue noon sky away from the sun (the sky layer: the sky without the clouds).
  EXPECT_GT(frame.layer("sky").at(16, 0, "B"), 1.3 * frame.layer("sky").at(16, 0, "R"));
  for (const char* name : {"sky", "high_clouds", "clouds"})
    EXPECT_EQ(frame.layer(name).pixels.size(), 32u * 18u * frame.layer(name).channels.size())
        << name;
  EXPECT_EQ(frame.layer("clouds").channels.back(), "depth");
  EXPECT_THROW(frame.layer("nonsense"), std::out_of_range);
  EXPECT_THROW(frame.beauty.at(32, 0, "R"), std::out_of_range);
  ASSERT_EQ(frame.display.size(), 32u * 18u * 4u);
  EXPECT_EQ(frame.display[3], 255);
  EXPECT_GT(frame.gpuMs, 0.0);
  EXPECT_EQ(sky.validationMessages(), 0u);
}

TEST(SkylayersApi, AFrameIsTheSameBitsEveryTimeAndInEverySky) {
  skylayers::Sky a = defaultSky();
  skylayers::Sky b = defaultSky();
  const skylayers::Frame first = a.render({.layers = true});
  const skylayers::Frame again = a.render({.layers = true});
  const skylayers::Frame other = b.render({.layers = true});
  EXPECT_EQ(first.beauty.pixels, again.beauty.pixels);
  EXPECT_EQ(first.beauty.pixels, other.beauty.pixels);
  ASSERT_EQ(first.layers.size(), other.layers.size());
  for (size_t i = 0; i < first.layers.size(); ++i)
    EXPECT_EQ(first.layers[i].pixels, other.layers[i].pixels) << first.layers[i].name;
}

// Many views in one frame: each view's frame is, bit for bit, the one render() gives with the
// camera turned and sized as the view says; the views share one frame graph.
TEST(SkylayersApi, ManyViewsInOneFrameAreEachTheViewsOwnRender) {
  for (const char* model : {"kozlov", "physical"}) {
    SCOPED_TRACE(model);
    skylayers::Sky sky = defaultSky(
        {std::string("sky.model=") + model, "time=2024-06-21T20:30:00+02:00", "camera.pitch=5"});
    const std::vector<skylayers::View> views = {
        {.headingDeg = 280, .pitchDeg = 5, .verticalFovDeg = 60, .width = 40, .height = 24},
        {.headingDeg = 10,
         .pitchDeg = 2,
         .rollDeg = 15,
         .verticalFovDeg = 45,
         .width = 32,
         .height = 32},
        {.headingDeg = 100, .pitchDeg = 40, .verticalFovDeg = 90, .width = 24, .height = 16},
        {.headingDeg = 190, .pitchDeg = -10, .verticalFovDeg = 30, .width = 48, .height = 20}};
    const std::vector<skylayers::Frame> frames = sky.renderViews(views, {.layers = true});
    ASSERT_EQ(frames.size(), views.size());
    const nlohmann::json report = nlohmann::json::parse(frames[0].report);
    size_t composites = 0;
    for (const auto& pass : report["passes"])
      composites += pass["name"] == "atmosphere_composite" ? 1 : 0;
    EXPECT_EQ(composites, views.size()) << "one graph with a composite per view";
    const skylayers::GeoPose place = sky.camera();
    for (size_t i = 0; i < views.size(); ++i) {
      SCOPED_TRACE(i);
      const skylayers::View& v = views[i];
      sky.setCamera({place.latitudeDeg, place.longitudeDeg, place.altitudeM, v.headingDeg,
                     v.pitchDeg, v.rollDeg});
      sky.setVerticalFov(v.verticalFovDeg);
      sky.setSize(v.width, v.height);
      const skylayers::Frame alone = sky.render({.layers = true});
      ASSERT_EQ(frames[i].beauty.width, v.width);
      ASSERT_EQ(frames[i].beauty.height, v.height);
      EXPECT_EQ(frames[i].beauty.pixels, alone.beauty.pixels);
      ASSERT_EQ(frames[i].layers.size(), alone.layers.size());
      for (size_t k = 0; k < alone.layers.size(); ++k)
        EXPECT_EQ(frames[i].layers[k].pixels, alone.layers[k].pixels) << alone.layers[k].name;
    }
    // And the same bits from one such frame to the next.
    EXPECT_EQ(sky.renderViews(views)[3].beauty.pixels, frames[3].beauty.pixels);
  }
  skylayers::Sky sky = defaultSky();
  try {
    sky.renderViews({{.width = 0, .height = 10}});
    ADD_FAILURE() << "an empty view was rendered";
  } catch (const skylayers::Error& e) {
    EXPECT_EQ(e.kind(), skylayers::Error::Kind::BadInput);
    EXPECT_THAT(e.what(), HasSubstr("view 0"));
  }
}

TEST(SkylayersApi, TheBeautyDisplayAndReportAreSkyrendersForTheSameScene) {
  skylayers::Sky sky = defaultSky({"time=2024-06-21T18:30:00+02:00", "camera.heading=270"});
  const skylayers::Frame frame = sky.render({.display = true});
  const fs::path dir = fs::temp_directory_path() / ("skylayers-api-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path scene = dir / "scene.yaml";
  {
    std::FILE* f = std::fopen(scene.c_str(), "w");
    ASSERT_NE(f, nullptr);
    const std::string text = sky.sceneYaml();
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
  }
  const std::string cmd = std::string(std::getenv("SKY_SKYRENDER")) + " render " + scene.string() +
                          " --out " + dir.string() + " >/dev/null";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd;
  const sky::LayeredImage exr = sky::readExr(dir / "sky.exr");
  const sky::Image8 png = sky::readPng(dir / "sky.png");
  const nlohmann::json report = nlohmann::json::parse(readText(dir / "sky.json"));
  fs::remove_all(dir);
  // The display codes are the PNG's, dither and all.
  ASSERT_EQ(png.channels, 4);
  EXPECT_EQ(png.pixels, frame.display);
  // The report says what skyrender's says, but for the wall times and memory.
  const nlohmann::json ours = nlohmann::json::parse(frame.report);
  for (const char* key : {"time", "sun", "moon", "light", "exposure", "settings"})
    EXPECT_EQ(ours.at(key), report.at(key)) << key;
  EXPECT_EQ(ours.at("passes").size(), report.at("passes").size());
  const sky::ImageLayer* beauty = exr.find("");
  ASSERT_NE(beauty, nullptr);
  ASSERT_EQ(beauty->pixels.size(), frame.beauty.pixels.size());
  // The EXR is half float: 11 bits of mantissa.
  double worst = 0.0;
  for (size_t i = 0; i < beauty->pixels.size(); ++i) {
    const double a = frame.beauty.pixels[i], b = beauty->pixels[i];
    worst = std::max(worst, std::abs(a - b) / std::max(std::abs(a), 1e-4));
  }
  EXPECT_LT(worst, 1.0e-3);
}

TEST(SkylayersApi, AWrongKeyOrValueNamesItAndKeepsTheScene) {
  skylayers::Sky sky = defaultSky();
  const std::string before = sky.sceneYaml();
  try {
    sky.set("camera.latitud", "10");
    FAIL() << "a wrong key was taken";
  } catch (const skylayers::Error& e) {
    EXPECT_EQ(e.kind(), skylayers::Error::Kind::BadInput);
    EXPECT_THAT(e.what(), HasSubstr("set camera.latitud=10: unknown key"));
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
  }
  try {
    sky.setCamera({.latitudeDeg = 95.0, .longitudeDeg = 8.0, .altitudeM = 500.0});
    FAIL() << "latitude 95 was taken";
  } catch (const skylayers::Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("camera.latitude"));
  }
  EXPECT_THROW(sky.setTime("yesterday"), skylayers::Error);
  EXPECT_THROW(sky.setSize(0, 10), skylayers::Error);
  EXPECT_EQ(sky.sceneYaml(), before);
  EXPECT_THROW(skylayers::Sky::fromText("camera: {pitch: [", "yaml", "host.yaml"),
               skylayers::Error);
  EXPECT_THROW(skylayers::Sky::fromText("{}", "toml"), skylayers::Error);
  EXPECT_THROW(skylayers::Sky::fromFile("/nonexistent/scene.yaml"), skylayers::Error);
}

TEST(SkylayersApi, TheCameraTimeAndKeysSetWhatTheyName) {
  skylayers::Sky sky = defaultSky();
  sky.setCamera({.latitudeDeg = -33.86,
                 .longitudeDeg = 151.21,
                 .altitudeM = 1200.0,
                 .headingDeg = 45.0,
                 .pitchDeg = 5.5});
  const skylayers::GeoPose pose = sky.camera();
  EXPECT_EQ(pose.latitudeDeg, -33.86);
  EXPECT_EQ(pose.longitudeDeg, 151.21);
  EXPECT_EQ(pose.altitudeM, 1200.0);
  EXPECT_EQ(pose.headingDeg, 45.0);
  EXPECT_EQ(pose.pitchDeg, 5.5);
  sky.setTime("2024-12-21T03:00:00Z");
  EXPECT_EQ(sky.time(), "2024-12-21T03:00:00Z");
  sky.setVerticalFov(40.0);
  sky.setSize(20, 10);
  sky.set("weather.cover_low", "0.25");
  EXPECT_THAT(sky.sceneYaml(), HasSubstr("vertical_fov: 40"));
  const skylayers::Frame frame = sky.render();
  EXPECT_EQ(frame.beauty.width, 20);
  EXPECT_EQ(frame.beauty.height, 10);
  EXPECT_EQ(frame.time, "2024-12-21T03:00:00Z");
}

TEST(SkylayersApi, TheLightsFollowTheClockInLux) {
  // Zurich, midsummer: noon, then two hours after midnight; no low cloud in the way.
  skylayers::Sky sky = defaultSky({"weather.cover_low=0"});
  sky.setCamera({.latitudeDeg = 47.37, .longitudeDeg = 8.54, .altitudeM = 500.0});
  sky.setTime("2024-06-21T13:30:00+02:00");
  const skylayers::Lighting noon = sky.lighting();
  EXPECT_NEAR(noon.sun.elevationDeg, 90.0 - 47.37 + 23.44, 0.5);
  EXPECT_EQ(noon.key, "sun");
  EXPECT_NEAR(noon.dayFactor, 1.0, 1e-9);
  // Direct sunlight at the ground with the sun high: 70-110 klux in every channel.
  for (double e : noon.sun.illuminanceLux) {
    EXPECT_GT(e, 70.0e3);
    EXPECT_LT(e, 120.0e3);
  }
  const auto& d = noon.sun.direction;
  EXPECT_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-9);
  EXPECT_NEAR(std::asin(d[2]) * 180.0 / M_PI, noon.sun.elevationDeg, 1e-6);

  sky.setTime("2024-06-22T02:00:00+02:00");
  const skylayers::Lighting night = sky.lighting();
  EXPECT_LT(night.sun.elevationDeg, -15.0);
  EXPECT_EQ(night.key, "moon");
  EXPECT_LT(night.dayFactor, 0.05);
  for (double e : night.sun.illuminanceLux) EXPECT_EQ(e, 0.0);
}

TEST(SkylayersApi, TheSunBehindACloudIsDimmedByIt) {
  // The default cumulus drift over the camera with the wind: every 10 minutes of an
  // afternoon, the sun's light is the clear sky's times the clouds' transmittance toward it,
  // which is the query's along the same line.
  skylayers::Sky sky = defaultSky();
  const skylayers::GeoPose pose = sky.camera();
  const skylayers::GeoPoint camera{pose.latitudeDeg, pose.longitudeDeg, pose.altitudeM};
  int shaded = 0, clear = 0;
  for (int minute = 0; minute < 240 && (shaded == 0 || clear == 0); minute += 10) {
    char time[40];
    std::snprintf(time, sizeof time, "2024-06-21T%02d:%02d:00+02:00", 13 + minute / 60,
                  minute % 60);
    sky.setTime(time);
    const skylayers::Lighting light = sky.lighting();
    const skylayers::Lighting open =
        skylayers::lightingAt(pose.latitudeDeg, pose.longitudeDeg, pose.altitudeM, time);
    const double t = light.sun.cloudTransmittance;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(light.sun.illuminanceLux[c], open.sun.illuminanceLux[c] * t,
                  1e-9 * open.sun.illuminanceLux[c]);
    // The same line as a query: the camera turned to the sun, its centre pixel's ray.
    const double up = std::sin(light.sun.elevationDeg * M_PI / 180.0);
    const double length = (3500.0 - pose.altitudeM + 500.0) / up;
    char heading[64], pitch[64];
    std::snprintf(heading, sizeof heading, "camera.heading=%.9f", light.sun.azimuthDeg);
    std::snprintf(pitch, sizeof pitch, "camera.pitch=%.9f", light.sun.elevationDeg);
    sky.set(std::vector<std::string>{heading, pitch});
    const double q = sky.transmittance(camera, sky.pixelPoint(16.0, 9.0, length)).cloud;
    sky.setCamera(pose);
    EXPECT_NEAR(t, q, 0.01 + 0.02 * q) << time;
    shaded += t < 0.5;
    clear += t == 1.0;
  }
  EXPECT_GT(shaded, 0) << "the sun was never behind a cloud";
  EXPECT_GT(clear, 0) << "the sun was never clear";
}

TEST(SkylayersApi, AQuerysTransmittanceAlongAPixelsRayIsThatPixelsCloudCoverage) {
  // Looking up into the default scene's cumulus (500 m up, the layer 1.5-3.5 km): every ray
  // leaves the layer within 14 km.
  // No grain filter: it mixes each pixel with its neighbours (cloud_denoise), where the query
  // follows the pixel's centre ray alone; at the cumulus' many small clouds' edges that put
  // 303 pixels more than 0.1 off.
  skylayers::Sky sky = defaultSky(
      {"camera.pitch=30", "camera.vertical_fov=30", "camera.heading=0", "clouds.denoise=false"});
  // 96 x 54: pixels of 10 m at 1.5 km, so the march resolves most of the noise, as the query
  // does (at 32 x 18 the march's level of detail fades the fine octaves to their mean and its
  // coverage came out 0.05 higher).
  sky.setSize(96, 54);
  const skylayers::Frame frame = sky.render({.layers = true});
  const skylayers::Image& clouds = frame.layer("clouds");
  const skylayers::GeoPose pose = sky.camera();
  const skylayers::GeoPoint camera{pose.latitudeDeg, pose.longitudeDeg, pose.altitudeM};
  std::vector<std::array<skylayers::GeoPoint, 2>> lines;
  for (int y = 0; y < clouds.height; ++y)
    for (int x = 0; x < clouds.width; ++x)
      lines.push_back({camera, sky.pixelPoint(x + 0.5, y + 0.5, 20000.0)});
  const std::vector<skylayers::Transmittance> t = sky.transmittance(lines);
  double sumDiff = 0.0, sumA = 0.0, sumQ = 0.0;
  int off = 0, cloudy = 0;
  for (int y = 0; y < clouds.height; ++y)
    for (int x = 0; x < clouds.width; ++x) {
      const double a = clouds.at(x, y, "A");
      const double q = 1.0 - t[size_t(y) * clouds.width + x].cloud;
      sumDiff += std::abs(a - q);
      sumA += a;
      sumQ += q;
      cloudy += a > 0.5;
      // The march stops below clouds.transmittance_cutoff (0.05) and steps longer with
      // distance; the query integrates every 10 m to the end.
      off += std::abs(a - q) > 0.1;
    }
  const double pixels = double(clouds.width * clouds.height);
  std::printf(
      "mean A %.4f, 1 - T %.4f, mean |A - (1 - T)| %.4f, off by > 0.1: %d of %.0f, cloudy %d\n",
      sumA / pixels, sumQ / pixels, sumDiff / pixels, off, pixels, cloudy);
  ASSERT_GT(cloudy, 20) << "the view should hold clouds";
  // Measured: mean A 0.4415 against 0.4424, per pixel 0.005 apart on average, 37 of 5,184
  // pixels more than 0.1 apart (cloud edges the march's longer far steps cross). Cumulus
  // whose sizes spread over a decade (issue 46) have twice as many clouds and edges in view:
  // 0.5483 against 0.5546, 0.0115 apart, 162 pixels (3.1 %) off.
  EXPECT_NEAR(sumA / pixels, sumQ / pixels, 0.01);
  EXPECT_LT(sumDiff / pixels, 0.015);
  EXPECT_LE(off, int(0.05 * pixels));
}

TEST(SkylayersApi, ThePerceptionLayersAreTheQueriesAnswers) {
  // The default cumulus from below: per pixel the optical depth and the first hit the frame
  // gives, against transmittance() and firstCloud() along the pixel's ray; the frame's
  // sun_visible against the query toward the sun.
  skylayers::Sky sky = defaultSky({"camera.pitch=35", "camera.vertical_fov=30",
                                   "camera.heading=0", "output.perception=true",
                                   "sky.model=physical"});
  sky.setSize(24, 14);
  const skylayers::Frame frame = sky.render({.layers = true});
  const skylayers::Image& clouds = frame.layer("clouds");
  const skylayers::Image& label = frame.layer("label");
  const skylayers::Image& air = frame.layer("air");
  const skylayers::GeoPose pose = sky.camera();
  const skylayers::GeoPoint camera{pose.latitudeDeg, pose.longitudeDeg, pose.altitudeM};
  int hits = 0;
  for (int y = 1; y < 14; y += 3)
    for (int x = 1; x < 24; x += 3) {
      const skylayers::GeoPoint far = sky.pixelPoint(x + 0.5, y + 0.5, 15000.0);
      const skylayers::Transmittance t = sky.transmittance(camera, far);
      const double tau = clouds.at(x, y, "optical_depth");
      // Within 0.05 + 10 %, as Perception.OpticalDepthAndHitDistanceAreTheQueriesField and
      // for its reason (the march's steps through billowed cumulus): 1.65 against 1.83 at the
      // worst pixel.
      EXPECT_NEAR(tau, t.cloudOpticalDepth, 0.05 + 0.1 * t.cloudOpticalDepth) << x << "," << y;
      const double hit = clouds.at(x, y, "distance");
      const double first = sky.firstCloud(camera, far);
      if (t.cloudOpticalDepth > 0.12) {
        EXPECT_NEAR(hit, first, 40.0 + 0.02 * first) << x << "," << y;
        EXPECT_EQ(label.at(x, y, "label"), 2.0f) << "low cloud";
        // The air to the hit: the query's air to the point at that distance.
        const skylayers::Transmittance a =
            sky.transmittance(camera, sky.pixelPoint(x + 0.5, y + 0.5, hit));
        EXPECT_NEAR(air.at(x, y, "transmittance"),
                    0.2126 * a.air[0] + 0.7152 * a.air[1] + 0.0722 * a.air[2], 0.02);
        ++hits;
      } else if (t.cloudOpticalDepth < 0.08) {
        EXPECT_TRUE(std::isinf(hit)) << x << "," << y;
        EXPECT_EQ(first, -1.0);
      }
    }
  EXPECT_GE(hits, 5) << "the view should hold clouds";
  // The sun: its line through the clouds and the air, as a query sees it (to 100 km up).
  const nlohmann::json report = nlohmann::json::parse(frame.report);
  const skylayers::Lighting light = sky.lighting();
  const double up = std::sin(light.sun.elevationDeg * M_PI / 180.0);
  sky.set(std::vector<std::string>{"camera.heading=" + std::to_string(light.sun.azimuthDeg),
                                   "camera.pitch=" + std::to_string(light.sun.elevationDeg)});
  const skylayers::Transmittance toSun =
      sky.transmittance(camera, sky.pixelPoint(12.0, 7.0, (100000.0 - pose.altitudeM) / up));
  const double expected = toSun.cloud * (0.2126 * toSun.air[0] + 0.7152 * toSun.air[1] +
                                         0.0722 * toSun.air[2]);
  EXPECT_NEAR(report["perception"]["sun_visible"].get<double>(), expected, 0.02 + 0.05 * expected);
}

TEST(SkylayersApi, QueriesSeeTheCloudsAndTheAir) {
  skylayers::Sky sky = defaultSky();
  const skylayers::GeoPose pose = sky.camera();
  // Straight up through the low layer from under every part of a 20 km line: some lines
  // meet cloud, the cover map says where, and a line under clear sky is let through.
  int cloudy = 0, clear = 0;
  for (int k = 0; k < 40; ++k) {
    const double lat = pose.latitudeDeg + 0.005 * k;
    const skylayers::GeoPoint ground{lat, pose.longitudeDeg, 1000.0};
    const skylayers::GeoPoint aloft{lat, pose.longitudeDeg, 4000.0};
    const skylayers::Transmittance t = sky.transmittance(ground, aloft);
    EXPECT_NEAR(t.cloud, std::exp(-t.cloudOpticalDepth), 1e-12);
    EXPECT_LE(t.air[2], t.air[0]) << "blue is dimmed more than red";
    if (t.cloudOpticalDepth > 1.0) {
      ++cloudy;
      EXPECT_GT(sky.cover(lat, pose.longitudeDeg).low, 0.0);
      const double d = sky.firstCloud(ground, aloft);
      EXPECT_GT(d, 0.0);
      EXPECT_LT(d, 3000.0);
    } else if (t.cloudOpticalDepth == 0.0) {
      ++clear;
      EXPECT_EQ(sky.firstCloud(ground, aloft), -1.0);
    }
  }
  EXPECT_GT(cloudy, 0);
  EXPECT_GT(clear, 0);
  // Above every layer there is no cloud.
  EXPECT_EQ(sky.cloudExtinction({pose.latitudeDeg, pose.longitudeDeg, 12000.0}), 0.0);
}

// The illuminance on level ground from the sky above the horizon, integrated directly over
// an equirectangular frame of the sphere (no spherical harmonics).
std::array<double, 3> upwardIlluminance(skylayers::Sky& sky) {
  skylayers::Sky probe = skylayers::Sky::fromText(
      sky.sceneYaml(), "yaml", "probe",
      {"camera.projection=equirectangular", "camera.heading=0", "output.width=64",
       "output.height=32", "sun.disc_scale=0", "moon.disc_scale=0"});
  const skylayers::Image beauty = probe.render().beauty;
  std::array<double, 3> e{0.0, 0.0, 0.0};
  for (int y = 0; y < beauty.height / 2; ++y) {
    const double elevation = (0.5 - (y + 0.5) / beauty.height) * M_PI;
    const double omega = (2.0 * M_PI / beauty.width) * (M_PI / beauty.height) * std::cos(elevation);
    for (int x = 0; x < beauty.width; ++x)
      for (int c = 0; c < 3; ++c)
        e[c] += beauty.at(x, y, beauty.channels[c]) * 1e4 * std::sin(elevation) * omega;
  }
  return e;
}

TEST(SkylayersApi, TheAmbientIsTheSkysLightAsSphericalHarmonics) {
  // A clear sky at midsummer noon.
  skylayers::Sky sky =
      defaultSky({"time=2024-06-21T13:30:00+02:00", "weather.cover_low=0", "high_clouds.cover=0"});
  const std::vector<float> before = sky.render().beauty.pixels;
  const skylayers::SphericalHarmonics clear = sky.ambient();
  const std::array<double, 3> up = skylayers::irradiance(clear, {0.0, 0.0, 1.0});
  const std::array<double, 3> down = skylayers::irradiance(clear, {0.0, 0.0, -1.0});
  const std::array<double, 3> direct = upwardIlluminance(sky);
  std::printf(
      "clear noon: up %.0f %.0f %.0f lux (direct sum %.0f %.0f %.0f), down %.0f %.0f %.0f\n", up[0],
      up[1], up[2], direct[0], direct[1], direct[2], down[0], down[1], down[2]);
  for (int c = 0; c < 3; ++c) {
    // Diffuse light on level ground under a clear midsummer noon sky: 5-30 klux.
    EXPECT_GT(up[c], 5.0e3) << c;
    EXPECT_LT(up[c], 3.0e4) << c;
    // Three bands hold the cosine lobe to a few per cent; the ground below adds a little.
    EXPECT_NEAR(up[c], direct[c], 0.1 * direct[c]) << c;
  }
  // From below, the ground (albedo 0.1, 0.12, 0.07) sends back that share of the sun's and
  // the sky's light on it; the air between adds a little, most in blue, so red and green
  // are checked.
  const skylayers::Lighting light = sky.lighting();
  const double albedo[2] = {0.1, 0.12};
  for (int c = 0; c < 2; ++c) {
    const double onGround =
        light.sun.illuminanceLux[c] * std::sin(light.sun.elevationDeg * M_PI / 180.0) + up[c];
    EXPECT_NEAR(down[c], albedo[c] * onGround, 0.25 * albedo[c] * onGround) << c;
  }
  EXPECT_GT(up[2], 1.3 * up[0]) << "the clear sky's light is blue";
  // The Sky's own frame is as it was.
  EXPECT_EQ(sky.render().beauty.pixels, before);

  // Broken sunlit cumulus send down more diffuse light than the clear sky.
  sky.set("weather.cover_low", "0.35");
  EXPECT_GT(skylayers::irradiance(sky.ambient(), {0.0, 0.0, 1.0})[1], 1.2 * up[1]);

  sky.setTime("2024-06-22T02:00:00+02:00");
  const std::array<double, 3> night = skylayers::irradiance(sky.ambient(), {0.0, 0.0, 1.0});
  for (int c = 0; c < 3; ++c) EXPECT_LT(std::abs(night[c]), 1.0) << c;
}

TEST(SkylayersApi, AForecastsCloudMapIsSkyrenderWeathers) {
  const std::string grib = std::string(std::getenv("SKY_DATA_DIR")) +
                           "/tests/data/weather/gfs_2p5deg_r_gh_t_tcc_uv500.grib2";
  const std::vector<std::string> region = {"weather.region.lat=[0,55]",
                                           "weather.region.lon=[90,150]"};
  const skylayers::WeatherGrid grid = skylayers::weatherMap(grib, region);
  EXPECT_EQ(grid.southDeg, 0.0);
  EXPECT_EQ(grid.northDeg, 55.0);
  EXPECT_EQ(grid.westDeg, 90.0);
  EXPECT_EQ(grid.eastDeg, 150.0);
  ASSERT_EQ(grid.image.channels.size(), 10u);
  EXPECT_EQ(grid.image.channels[0], "cover_low");
  EXPECT_EQ(grid.image.channels[9], "high_top_m");

  const fs::path dir =
      fs::temp_directory_path() / ("skylayers-weather-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string cmd = std::string(std::getenv("SKY_SKYRENDER")) + " weather " + grib +
                          " --set 'weather.region.lat=[0,55]' --set 'weather.region.lon=[90,150]'" +
                          " --out " + dir.string() + " >/dev/null";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd;
  const sky::LayeredImage exr = sky::readExr(dir / "gfs_2p5deg_r_gh_t_tcc_uv500.weather.exr");
  fs::remove_all(dir);
  ASSERT_EQ(exr.width, grid.image.width);
  ASSERT_EQ(exr.height, grid.image.height);
  const sky::ImageLayer* layer = exr.find("");
  ASSERT_NE(layer, nullptr);
  // The same map, channel by channel (the EXR reader orders them by name).
  for (size_t c = 0; c < layer->channels.size(); ++c)
    for (int y = 0; y < exr.height; ++y)
      for (int x = 0; x < exr.width; ++x)
        ASSERT_EQ(layer->pixels[(size_t(y) * exr.width + x) * layer->channels.size() + c],
                  grid.image.at(x, y, layer->channels[c]))
            << layer->channels[c] << " at " << x << ", " << y;

  try {
    skylayers::weatherMap("/nonexistent/forecast.grib2");
    FAIL() << "a missing file was taken";
  } catch (const skylayers::Error& e) {
    EXPECT_EQ(e.kind(), skylayers::Error::Kind::BadInput);
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/forecast.grib2"));
  }
}

TEST(SkylayersApi, ARolledCameraTurnsTheImage) {
  // Banked 90 degrees right, the right wing down: the image's right edge looks down at the
  // ground, its left edge up (the world turns counter-clockwise in the image).
  skylayers::Sky sky = defaultSky({"camera.pitch=0", "camera.heading=90"});
  sky.set("camera.roll", "90");
  const skylayers::GeoPose pose = sky.camera();
  EXPECT_EQ(pose.rollDeg, 90.0);
  EXPECT_LT(sky.pixelPoint(31.5, 9.0, 1000.0).altitudeM, pose.altitudeM - 400.0);
  EXPECT_GT(sky.pixelPoint(0.5, 9.0, 1000.0).altitudeM, pose.altitudeM + 400.0);
  // Rolled 180 degrees, the sky is the unrolled image turned upside down: pixel (x, y) is
  // pixel (W - 1 - x, H - 1 - y) of the level camera.
  sky.set("camera.pitch", "20");
  sky.set("camera.roll", "0");
  const skylayers::Frame level = sky.render({.layers = true});
  sky.set("camera.roll", "180");
  const skylayers::Frame turned = sky.render({.layers = true});
  const skylayers::Image& a = level.layer("sky");
  const skylayers::Image& b = turned.layer("sky");
  double worst = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (const char* c : {"R", "G", "B"}) {
        const double u = a.at(x, y, c), v = b.at(a.width - 1 - x, a.height - 1 - y, c);
        worst = std::max(worst, std::abs(u - v) / std::max(std::abs(u), 1e-3));
      }
  EXPECT_LT(worst, 1e-3);
  // From a host's axes: looking north-east 10 degrees up, banked 30 degrees left.
  const double h = 45.0 * M_PI / 180.0, p = 10.0 * M_PI / 180.0, r = -30.0 * M_PI / 180.0;
  const std::array<double, 3> f = {std::sin(h) * std::cos(p), std::cos(h) * std::cos(p),
                                   std::sin(p)};
  const std::array<double, 3> level3 = {std::cos(h), -std::sin(h), 0.0};
  // levelUp = level x forward; up = sin(r) level + cos(r) levelUp.
  const std::array<double, 3> levelUp = {level3[1] * f[2] - level3[2] * f[1],
                                         level3[2] * f[0] - level3[0] * f[2],
                                         level3[0] * f[1] - level3[1] * f[0]};
  std::array<double, 3> up;
  for (int i = 0; i < 3; ++i) up[i] = std::sin(r) * level3[i] + std::cos(r) * levelUp[i];
  sky.setCameraAxes(f,
                    {2.0 * up[0] + 0.3 * f[0], 2.0 * up[1] + 0.3 * f[1], 2.0 * up[2] + 0.3 * f[2]});
  EXPECT_NEAR(sky.camera().headingDeg, 45.0, 1e-9);
  EXPECT_NEAR(sky.camera().pitchDeg, 10.0, 1e-9);
  EXPECT_NEAR(sky.camera().rollDeg, -30.0, 1e-6);
  EXPECT_THROW(sky.setCameraAxes(f, f), skylayers::Error);
}

// A host's Earth-centred pose (WGS84 ECEF): its position and camera axes, made here from a
// GeoPose with the textbook geodetic-to-ECEF formulas, must give that GeoPose back.
TEST(SkylayersApi, AnEcefPoseIsTheGeoPoseItNames) {
  skylayers::Sky sky = defaultSky();
  constexpr double kA = 6378137.0, kE2 = 6.69437999014e-3, kRad = M_PI / 180.0;
  const skylayers::GeoPose poses[] = {{47.37, 8.54, 500.0, 305.0, 10.0, 5.0},
                                      {-33.86, 151.21, 12000.0, 45.0, -20.0, -30.0},
                                      {89.5, -120.0, 3000.0, 180.0, 30.0, 0.0},
                                      {0.0, 179.9, 0.0, 90.0, 0.0, 60.0}};
  for (const skylayers::GeoPose& g : poses) {
    const double lat = g.latitudeDeg * kRad, lon = g.longitudeDeg * kRad;
    const double n = kA / std::sqrt(1.0 - kE2 * std::sin(lat) * std::sin(lat));
    const std::array<double, 3> position = {(n + g.altitudeM) * std::cos(lat) * std::cos(lon),
                                            (n + g.altitudeM) * std::cos(lat) * std::sin(lon),
                                            (n * (1.0 - kE2) + g.altitudeM) * std::sin(lat)};
    // The camera's axes in east-north-up (as ARolledCameraTurnsTheImage), then in ECEF.
    const double h = g.headingDeg * kRad, p = g.pitchDeg * kRad, r = g.rollDeg * kRad;
    const double f[3] = {std::sin(h) * std::cos(p), std::cos(h) * std::cos(p), std::sin(p)};
    const double level[3] = {std::cos(h), -std::sin(h), 0.0};
    const double levelUp[3] = {level[1] * f[2] - level[2] * f[1], level[2] * f[0] - level[0] * f[2],
                               level[0] * f[1] - level[1] * f[0]};
    const double east[3] = {-std::sin(lon), std::cos(lon), 0.0};
    const double north[3] = {-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon),
                             std::cos(lat)};
    const double up[3] = {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon),
                          std::sin(lat)};
    std::array<double, 3> forward{}, cameraUp{};
    for (int i = 0; i < 3; ++i) {
      const double u[3] = {std::sin(r) * level[0] + std::cos(r) * levelUp[0],
                           std::sin(r) * level[1] + std::cos(r) * levelUp[1],
                           std::sin(r) * level[2] + std::cos(r) * levelUp[2]};
      forward[i] = f[0] * east[i] + f[1] * north[i] + f[2] * up[i];
      cameraUp[i] = u[0] * east[i] + u[1] * north[i] + u[2] * up[i];
    }
    sky.setCameraEcef(position, forward, cameraUp);
    const skylayers::GeoPose got = sky.camera();
    SCOPED_TRACE(std::to_string(g.latitudeDeg) + ", " + std::to_string(g.longitudeDeg));
    EXPECT_NEAR(got.latitudeDeg, g.latitudeDeg, 1e-9);
    EXPECT_NEAR(got.longitudeDeg, g.longitudeDeg, 1e-9);
    EXPECT_NEAR(got.altitudeM, g.altitudeM, 1e-3);
    EXPECT_NEAR(std::remainder(got.headingDeg - g.headingDeg, 360.0), 0.0, 1e-6);  // -55 is 305
    EXPECT_NEAR(got.pitchDeg, g.pitchDeg, 1e-6);
    EXPECT_NEAR(got.rollDeg, g.rollDeg, 1e-6);
  }
  // All or nothing: a position at the Earth's centre, or axes along each other, change nothing.
  const skylayers::GeoPose before = sky.camera();
  try {
    sky.setCameraEcef({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
    ADD_FAILURE() << "the Earth's centre was taken";
  } catch (const skylayers::Error& e) {
    EXPECT_EQ(e.kind(), skylayers::Error::Kind::BadInput);
    EXPECT_THAT(e.what(), HasSubstr("setCameraEcef: the position (0, 0, 0) m"));
  }
  EXPECT_THROW(sky.setCameraEcef({kA, 0.0, 0.0}, {1.0, 0.0, 0.0}, {2.0, 0.0, 0.0}),
               skylayers::Error);
  EXPECT_EQ(sky.camera().latitudeDeg, before.latitudeDeg);
  EXPECT_EQ(sky.camera().headingDeg, before.headingDeg);
}

TEST(SkylayersApi, AHostsProjectionMatrixSetsTheFieldOfView) {
  skylayers::Sky sky = defaultSky();  // 32 x 18
  // glm::perspective(45 degrees, 32 / 18, 0.1, 1000), column-major.
  const double f = 1.0 / std::tan(0.5 * 45.0 * M_PI / 180.0), aspect = 32.0 / 18.0;
  const double n = 0.1, far = 1000.0;
  std::array<double, 16> m{};
  m[0] = f / aspect;
  m[5] = f;
  m[10] = -(far + n) / (far - n);
  m[11] = -1.0;
  m[14] = -2.0 * far * n / (far - n);
  sky.setProjectionMatrix(m);
  EXPECT_THAT(sky.sceneYaml(), HasSubstr("vertical_fov: 45"));
  // Vulkan's flipped y (m[1][1] < 0) is the same field of view.
  m[5] = -f;
  sky.setProjectionMatrix(m);
  EXPECT_THAT(sky.sceneYaml(), HasSubstr("vertical_fov: 45"));
  std::array<double, 16> offCentre = m;
  offCentre[8] = 0.2;
  EXPECT_THROW(sky.setProjectionMatrix(offCentre), skylayers::Error);
  std::array<double, 16> wide = m;
  wide[0] = f;  // square pixels of a square image, not 32 x 18
  try {
    sky.setProjectionMatrix(wide);
    FAIL() << "a matrix of another aspect was taken";
  } catch (const skylayers::Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("32x18"));
  }
  std::array<double, 16> ortho{};
  ortho[0] = ortho[5] = ortho[10] = ortho[15] = 1.0;
  EXPECT_THROW(sky.setProjectionMatrix(ortho), skylayers::Error);
}

TEST(SkylayersApi, TheDataComesFromTheSourceTreeHere) {
  // In the build tree the tests set SKY_DATA_DIR to the source; the install's own lookup is
  // tests/package's.
  EXPECT_EQ(fs::path(skylayers::dataDirectory()), fs::path(std::getenv("SKY_DATA_DIR")));
  EXPECT_STREQ(skylayers::version(), "0.1.0");
}

}  // namespace
