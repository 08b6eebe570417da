// --set key.path=value: applied to the document before validation, errors name the override.
#include <gtest/gtest.h>

#include "engine/scene/scene_io.h"
#include "tests/scene/scene_compare.h"
#include "tests/scene/scene_test_util.h"

namespace sky {
namespace {

using test::errorOf;

Scene yamlWith(const std::string& text, const std::vector<std::string>& overrides) {
  return loadSceneText(text, ConfigFormat::Yaml, "x.yaml", overrides);
}
std::string overrideError(const std::string& text, const std::vector<std::string>& overrides,
                          ConfigFormat format = ConfigFormat::Yaml) {
  return errorOf([&] {
    loadSceneText(text, format, format == ConfigFormat::Yaml ? "x.yaml" : "x.json", overrides);
  });
}

TEST(SceneOverrides, SetValuesOfEveryKind) {
  Scene s = yamlWith("output:\n  width: 1280\n",
                     {"output.width=64", "output.name=night-2", "sky.sky_color=[0.1,0.2,0.3]",
                      "time=2024-01-01T00:00:00Z", "sun.azimuth=90", "sun.elevation=-2.5",
                      "camera.pitch=+4", "output.view='64'"});
  EXPECT_EQ(s.output.width, 64);
  EXPECT_EQ(s.output.height, 720);
  EXPECT_EQ(s.output.name, "night-2");
  EXPECT_EQ(s.output.view, "64");
  EXPECT_EQ(s.sky.skyColor, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.time.instant, IsoTime::parse("2024-01-01T00:00:00Z").value());
  EXPECT_EQ(s.sun.azimuth, 90.0);
  EXPECT_EQ(s.sun.elevation, -2.5);
  EXPECT_EQ(s.camera.pitch, 4.0);
}

TEST(SceneOverrides, LaterOverridesWinAndFileValuesAreReplaced) {
  Scene s =
      yamlWith("camera:\n  pitch: 10\n  heading: 90\n", {"camera.pitch=20", "camera.pitch=30"});
  EXPECT_EQ(s.camera.pitch, 30.0);
  EXPECT_EQ(s.camera.heading, 90.0);
  // JSON files take YAML-typed overrides too.
  Scene j = loadSceneText("{\"output\": {\"name\": \"a\", \"width\": 3}}", ConfigFormat::Json,
                          "x.json", {"output.name=b", "output.width=64.0"});
  EXPECT_EQ(j.output.name, "b");
  EXPECT_EQ(j.output.width, 64);
}

TEST(SceneOverrides, CompleteTheSunPair) {
  // The file alone would be an error; with the override it is complete.
  Scene s = yamlWith("sun:\n  azimuth: 200\n", {"sun.elevation=35"});
  EXPECT_EQ(s.sun.elevation, 35.0);
  EXPECT_EQ(
      overrideError("", {"sun.azimuth=10"}),
      "--set sun.azimuth=10: sun.azimuth: given without sun.elevation (give both or neither)");
}

TEST(SceneOverrides, ValuesAreValidatedLikeFileValues) {
  EXPECT_EQ(overrideError("", {"output.widht=3"}),
            "--set output.widht=3: unknown key 'output.widht' (did you mean 'width'?)");
  EXPECT_EQ(overrideError("", {"ouput.width=3"}),
            "--set ouput.width=3: unknown key 'ouput' (did you mean 'output'?)");
  EXPECT_EQ(overrideError("", {"output.width=1.5"}),
            "--set output.width=1.5: output.width: expected an integer, got 1.5");
  EXPECT_EQ(overrideError("", {"output.width='64'"}),
            "--set output.width='64': output.width: expected an integer, got a string");
  EXPECT_EQ(overrideError("", {"camera.latitude=95"}),
            "--set camera.latitude=95: camera.latitude: 95 is out of range [-90, 90]");
  EXPECT_EQ(overrideError("", {"camera.pitch=.nan"}),
            "--set camera.pitch=.nan: camera.pitch: .nan is out of range [-90, 90]");
  EXPECT_EQ(overrideError("", {"sky.sky_color=[0.1,0.2]"}),
            "--set sky.sky_color=[0.1,0.2]: sky.sky_color: expected a list of 3 numbers [r, g, b], "
            "got a list of 2");
  EXPECT_EQ(overrideError("", {"time=2024-01-01T00:00:00"}),
            "--set time=2024-01-01T00:00:00: time: '2024-01-01T00:00:00' is not a valid time: "
            "missing time zone: add "
            "Z (UTC) or an offset such as +02:00");
  EXPECT_EQ(overrideError("", {"camera.pitch="}),
            "--set camera.pitch=: camera.pitch: expected a number, got null");
  EXPECT_EQ(overrideError("{}", {"output.width=0"}, ConfigFormat::Json),
            "--set output.width=0: output.width: 0 is out of range [1, 16384]");
  // A file error still points into the file when an override touches something else.
  EXPECT_EQ(overrideError("camera:\n  pitch: 95\n", {"camera.heading=3"}),
            "x.yaml:2:10: camera.pitch: 95 is out of range [-90, 90]");
}

TEST(SceneOverrides, MalformedOverrides) {
  EXPECT_EQ(overrideError("", {"output.width"}),
            "--set output.width: malformed override: expected key.path=value");
  EXPECT_EQ(overrideError("", {"=3"}),
            "--set =3: malformed override: the key path before '=' is empty");
  EXPECT_EQ(overrideError("", {"output..width=3"}),
            "--set output..width=3: malformed override: empty key in 'output..width'");
  EXPECT_EQ(overrideError("", {"output.=3"}),
            "--set output.=3: malformed override: empty key in 'output.'");
  EXPECT_EQ(overrideError("", {"sun={azimuth: 1, elevation: 2}"}),
            "--set sun={azimuth: 1, elevation: 2}: an override value must be a scalar or a [list], "
            "not a map; set one key "
            "at a time");
  std::string syntax = overrideError("", {"sky.sky_color=[1,2"});
  EXPECT_EQ(syntax.rfind("--set sky.sky_color=[1,2: YAML syntax error: ", 0), 0u) << syntax;
}

TEST(SceneOverrides, KeysInsideScalarsAreErrors) {
  EXPECT_EQ(overrideError("time: 2024-06-21T12:00:00Z\n", {"time.zone=1"}),
            "--set time.zone=1: cannot set 'time.zone': 'time' is not a section (it holds "
            "'2024-06-21T12:00:00Z')");
  EXPECT_EQ(overrideError("", {"output.width.x=1"}),
            "--set output.width.x=1: output.width: expected an integer, got a map");
  EXPECT_EQ(
      overrideError("output: 3\n", {"output.width=1"}),
      "--set output.width=1: cannot set 'output.width': 'output' is not a section (it holds '3')");
  EXPECT_EQ(overrideError("", {"time.zone=1"}),
            "--set time.zone=1: time: expected an ISO 8601 time string, got a map");
}

TEST(SceneOverrides, LoadSceneFileAppliesOverrides) {
  Scene s = loadSceneFile(test::sourceDir() / "configs" / "default.yaml",
                          {"output.width=64", "output.height=36"});
  EXPECT_EQ(s.output.width, 64);
  EXPECT_EQ(s.output.height, 36);
}

}  // namespace
}  // namespace sky
