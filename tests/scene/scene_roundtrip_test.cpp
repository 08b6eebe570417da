// YAML and JSON give the same Scene; printing the effective settings and loading them back
// gives an identical Scene.
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/scene/scene_io.h"
#include "tests/scene/scene_compare.h"

namespace sky {
namespace {

using test::expectSameScene;

TEST(SceneRoundTrip, EmptyFilesGiveDefaults) {
  Scene defaults;
  expectSameScene(loadSceneText("", ConfigFormat::Yaml, "e.yaml"), defaults);
  expectSameScene(loadSceneText("{}", ConfigFormat::Json, "e.json"), defaults);
  expectSameScene(loadSceneText("output: {}\nsun: {}\n", ConfigFormat::Yaml, "e.yaml"), defaults);
}

TEST(SceneRoundTrip, YamlAndJsonAgree) {
  const char* yaml = R"(
output:
  width: 640
  height: 360.0
  name: "noon"
  exposure_ev: 0.5
camera:
  latitude: -33.8688
  longitude: 151.2093
  altitude_m: 12.5
  heading: -45
  pitch: 1e1
  vertical_fov: 70
time: 2024-12-21T12:00:00.5+11:00
sun:
  elevation: 40.25
  azimuth: 10
  disc_intensity: 100
sky:
  sky_color: [0.1, 0.2, 0.3]
  sun_color: [1, 0.5, 0.25]
  glow_size: 0.2
)";
  const char* json = R"({
  "sky": {"sky_color": [0.1, 0.2, 0.3], "sun_color": [1, 0.5, 0.25], "glow_size": 0.2},
  "sun": {"disc_intensity": 100, "azimuth": 10, "elevation": 40.25},
  "time": "2024-12-21T12:00:00.5+11:00",
  "camera": {"latitude": -33.8688, "longitude": 151.2093, "altitude_m": 12.5, "heading": -45,
             "pitch": 1e1, "vertical_fov": 70},
  "output": {"width": 640, "height": 360.0, "name": "noon", "exposure_ev": 0.5}
})";
  Scene a = loadSceneText(yaml, ConfigFormat::Yaml, "a.yaml");
  Scene b = loadSceneText(json, ConfigFormat::Json, "b.json");
  expectSameScene(a, b);
  EXPECT_EQ(a.output.height, 360);
  EXPECT_EQ(a.camera.pitch, 10.0);
  EXPECT_EQ(a.sun.azimuth, 10.0);
  EXPECT_EQ(a.sky.skyColor.y, 0.2f);
  EXPECT_EQ(a.sky.fogColor, Scene().sky.fogColor);  // untouched keys keep their defaults
  EXPECT_EQ(a.time.instant.offsetMinutes, 11 * 60);
  EXPECT_EQ(writeScene(a, ConfigFormat::Yaml), writeScene(b, ConfigFormat::Yaml));
}

TEST(SceneRoundTrip, WriteThenLoadIsIdentical) {
  for (const Scene& scene : {Scene(), test::unusualScene()}) {
    for (ConfigFormat format : {ConfigFormat::Yaml, ConfigFormat::Json}) {
      std::string text = writeScene(scene, format);
      Scene back = loadSceneText(text, format, "printed");
      expectSameScene(back, scene);
      // Printing is a fixed point.
      EXPECT_EQ(writeScene(back, format), text);
    }
  }
}

TEST(SceneRoundTrip, PrintedYamlLooksLikeAScene) {
  Scene s;
  s.sun.azimuth = 200;
  s.sun.elevation = 35;
  EXPECT_EQ(writeScene(s, ConfigFormat::Yaml),
            "output:\n"
            "  width: 1280\n"
            "  height: 720\n"
            "  name: \"sky\"\n"
            "  exposure_ev: 0\n"
            "  display: \"sRGB\"\n"
            "  view: \"ACES 1.0 - SDR Video\"\n"
            "camera:\n"
            "  latitude: 47.37\n"
            "  longitude: 8.54\n"
            "  altitude_m: 500\n"
            "  heading: 180\n"
            "  pitch: 15\n"
            "  vertical_fov: 60\n"
            "time: \"2024-06-21T12:00:00+02:00\"\n"
            "sun:\n"
            "  azimuth: 200\n"
            "  elevation: 35\n"
            "  angular_diameter: 0.53\n"
            "  disc_intensity: 40\n"
            "sky:\n"
            "  sky_color: [0.07, 0.2, 0.65]\n"
            "  fog_color: [0.5, 0.62, 0.8]\n"
            "  sun_color: [1, 0.85, 0.65]\n"
            "  glow_size: 0.3\n"
            "  haze_height: 0.2\n");
}

TEST(SceneRoundTrip, OptionalSunIsPrintedOnlyWhenSet) {
  std::string yaml = writeScene(Scene(), ConfigFormat::Yaml);
  EXPECT_EQ(yaml.find("azimuth"), std::string::npos);
  EXPECT_EQ(yaml.find("elevation"), std::string::npos);
  std::string json = writeScene(Scene(), ConfigFormat::Json);
  EXPECT_NE(json.find("\"sun\": {\n    \"angular_diameter\": 0.53,"), std::string::npos) << json;
  EXPECT_EQ(json.find("azimuth"), std::string::npos);
}

TEST(SceneRoundTrip, PrintedJsonIsJson) {
  Scene s = test::unusualScene();
  nlohmann::json parsed = nlohmann::json::parse(writeScene(s, ConfigFormat::Json));
  EXPECT_EQ(parsed["output"]["display"], "Display \"P3\"");
  EXPECT_EQ(parsed["output"]["width"], 64);
  EXPECT_TRUE(parsed["output"]["width"].is_number_integer());
  EXPECT_EQ(parsed["sun"]["azimuth"], 200.1);
  EXPECT_EQ(parsed["time"], "2024-12-21T05:30:00.125-03:30");
}

TEST(SceneRoundTrip, SceneToJsonForReports) {
  Scene s = test::unusualScene();
  nlohmann::json j = sceneToJson(s);
  EXPECT_EQ(j["output"]["width"], 64);
  EXPECT_TRUE(j["output"]["width"].is_number_integer());
  EXPECT_EQ(j["camera"]["heading"], 1.0 / 3.0);
  EXPECT_EQ(j["sky"]["sky_color"][0], 0.1);  // the float's shortest text, not 0.10000000149
  EXPECT_EQ(j["sun"]["elevation"], 1e-7);
  EXPECT_EQ(j["time"], "2024-12-21T05:30:00.125-03:30");
  EXPECT_FALSE(sceneToJson(Scene())["sun"].contains("azimuth"));
  // The report reads back as the same scene.
  test::expectSameScene(loadSceneText(j.dump(), ConfigFormat::Json, "report.json"), s);
}

TEST(SceneRoundTrip, HalfASunCannotBePrinted) {
  Scene s;
  s.sun.azimuth = 10;
  try {
    writeScene(s, ConfigFormat::Yaml);
    ADD_FAILURE() << "expected an internal error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Internal);
  }
}

}  // namespace
}  // namespace sky
