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
                     {"output.width=64", "output.name=night-2", "lighting.turbidity=0.25",
                      "time=2024-01-01T00:00:00Z", "sun.azimuth=90", "sun.elevation=-2.5",
                      "camera.pitch=+4", "output.view='64'", "moon.earthshine=3",
                      "moon.azimuth=-10", "moon.elevation=45", "sky.glow_size=0.5"});
  EXPECT_EQ(s.output.width, 64);
  EXPECT_EQ(s.output.height, 720);
  EXPECT_EQ(s.output.name, "night-2");
  EXPECT_EQ(s.output.view, "64");
  EXPECT_EQ(s.lighting.turbidity, 0.25);
  EXPECT_EQ(s.time.start, IsoTime::parse("2024-01-01T00:00:00Z").value());
  EXPECT_FALSE(s.time.isRange());
  EXPECT_EQ(s.moon.earthshine, 3.0);
  EXPECT_EQ(s.moon.azimuth, -10.0);
  EXPECT_EQ(s.moon.elevation, 45.0);
  EXPECT_EQ(s.sky.glowSize, 0.5);
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
  EXPECT_EQ(overrideError("", {"sky.sky_color=[0.1,0.2,0.3]"}),
            "--set sky.sky_color=[0.1,0.2,0.3]: unknown key 'sky.sky_color' (known keys: "
            "model, glow_size, glow_exponent, haze_height)");
  EXPECT_EQ(overrideError("", {"sun.disc_scale=1e4"}),
            "--set sun.disc_scale=1e4: sun.disc_scale: 1e4 is out of range [0, 1000]");
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
            "--set time.zone=1: unknown key 'time.zone' (known keys: start, end, step)");
}

TEST(SceneOverrides, TimeRanges) {
  // A whole range as one value, replacing a file's instant.
  Scene s = yamlWith("time: 2024-06-21T12:00:00+02:00\n",
                     {"time=2024-06-21T00:00Z/2024-06-22T00:00Z/15m"});
  ASSERT_TRUE(s.time.isRange());
  EXPECT_EQ(s.time.start.format(), "2024-06-21T00:00:00Z");
  EXPECT_EQ(s.time.end->format(), "2024-06-22T00:00:00Z");
  EXPECT_EQ(s.time.stepSeconds, 900.0);
  EXPECT_EQ(s.time.frameCount(), 97);
  // ... and replacing a file's range map by an instant.
  const std::string rangeMap =
      "time:\n  start: 2024-06-21T00:00Z\n  end: 2024-06-22T00:00Z\n  step: 15m\n";
  Scene instant = yamlWith(rangeMap, {"time=2024-06-21T05:00Z"});
  EXPECT_FALSE(instant.time.isRange());
  EXPECT_EQ(instant.time.start.format(), "2024-06-21T05:00:00Z");
  // One part of a file's range map.
  Scene slower = yamlWith(rangeMap, {"time.step=1h", "time.end=2024-06-21T12:00+02:00"});
  EXPECT_EQ(slower.time.stepSeconds, 3600.0);
  EXPECT_EQ(slower.time.end->format(), "2024-06-21T12:00:00+02:00");
  EXPECT_EQ(slower.time.frameCount(), 11);
  // A range built from nothing needs all three parts.
  Scene built = yamlWith(
      "", {"time.start=2024-06-21T00:00Z", "time.end=2024-06-21T01:00Z", "time.step=PT30M"});
  EXPECT_EQ(built.time.frameCount(), 3);
  EXPECT_EQ(overrideError("", {"time.start=2024-06-21T00:00Z", "time.step=15m"}),
            "--set time.start=2024-06-21T00:00Z: time: missing key 'end'");
  // Errors in a range override name the override.
  EXPECT_EQ(overrideError("", {"time=2024-06-21T00:00Z/2024-06-22T00:00Z/-15m"}),
            "--set time=2024-06-21T00:00Z/2024-06-22T00:00Z/-15m: time: step '-15m' must be "
            "positive");
  EXPECT_EQ(overrideError(rangeMap, {"time.step=0s"}),
            "--set time.step=0s: time.step: '0s' must be positive");
  EXPECT_EQ(overrideError(rangeMap, {"time.end=2024-06-20T00:00Z"}),
            "--set time.end=2024-06-20T00:00Z: time.end: '2024-06-20T00:00Z' is before the start "
            "2024-06-21T00:00:00Z");
  // A file's instant is a string: it has no parts to set.
  EXPECT_EQ(overrideError("time: 2024-06-21T00:00Z\n", {"time.step=15m"}),
            "--set time.step=15m: cannot set 'time.step': 'time' is not a section (it holds "
            "'2024-06-21T00:00Z')");
}

TEST(SceneOverrides, PaletteItemsCannotBeSetOneByOne) {
  const std::string hint =
      "'lighting.palette' is a list and --set cannot address its items; set the whole list "
      "(lighting.palette=[...]) or edit the scene file";
  std::string defaultScene = (test::sourceDir() / "configs" / "default.yaml").string();
  auto fileError = [&](const std::string& o) {
    return errorOf([&] { loadSceneFile(defaultScene, {o}); });
  };
  // Against a file that has a palette (the default scene) and one that has none.
  for (const std::string& o :
       {std::string("lighting.palette.0.sky_color=[1,1,1]"), std::string("lighting.palette.0=1"),
        std::string("lighting.palette[0].sky_color=[1,1,1]"),
        std::string("lighting.palette[2]=[1,1,1]")}) {
    SCOPED_TRACE(o);
    std::string expected =
        "--set " + o + ": cannot set '" + o.substr(0, o.find('=')) + "': " + hint;
    EXPECT_EQ(fileError(o), expected);
    EXPECT_EQ(overrideError("", {o}), expected);
  }
  // A key of the list itself, without an index: only the file's list shows it is a list.
  EXPECT_EQ(
      fileError("lighting.palette.sky_color=[1,1,1]"),
      "--set lighting.palette.sky_color=[1,1,1]: cannot set 'lighting.palette.sky_color': " + hint);
  EXPECT_EQ(overrideError("", {"lighting.palette.sky_color=[1,1,1]"}),
            "--set lighting.palette.sky_color=[1,1,1]: lighting.palette: expected a list of maps, "
            "got a map");
  // An index at the front names no list: an unknown key.
  EXPECT_EQ(overrideError("", {"0.width=3"}),
            "--set 0.width=3: unknown key '0' (known keys: output, camera, time, sun, moon, sky, "
            "atmosphere, ground, high_clouds, clouds, weather, lighting)");
  // The whole list can be replaced, in YAML flow style, and is validated like a file's.
  Scene s = loadSceneFile(
      defaultScene,
      {"lighting.palette=[{sun_elevation: -5, sky_color: [0, 0, 0.1], fog_color: [0, 0, 0], "
       "glow_color: [1, 0, 0], cloud_lit: [1, 1, 1], cloud_dark: [0, 0, 0], ambient_top: [0, 0, "
       "0], ambient_bottom: [0, 0, 0]}]"});
  ASSERT_EQ(s.lighting.palette.size(), 1u);
  EXPECT_EQ(s.lighting.palette[0].sunElevation, -5.0);
  EXPECT_EQ(s.lighting.palette[0].skyColor, glm::vec3(0.0f, 0.0f, 0.1f));
  EXPECT_EQ(fileError("lighting.palette=[]"),
            "--set lighting.palette=[]: lighting.palette: expected 1 to 64 items, got 0");
  EXPECT_EQ(fileError("lighting.palette=[1]"),
            "--set lighting.palette=[1]: lighting.palette[0]: expected a map of settings, got '1'");
  EXPECT_EQ(fileError("lighting.palette=[{sun_elevation: 0}]"),
            "--set lighting.palette=[{sun_elevation: 0}]: lighting.palette[0]: missing key "
            "'sky_color'");
  // The other lighting settings are ordinary keys.
  EXPECT_EQ(loadSceneFile(defaultScene, {"lighting.night_adaptation=0.5"}).lighting.nightAdaptation,
            0.5);
}

TEST(SceneOverrides, LoadSceneFileAppliesOverrides) {
  Scene s = loadSceneFile(test::sourceDir() / "configs" / "default.yaml",
                          {"output.width=64", "output.height=36"});
  EXPECT_EQ(s.output.width, 64);
  EXPECT_EQ(s.output.height, 36);
}

}  // namespace
}  // namespace sky
