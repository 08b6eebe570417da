// Every way a scene can be wrong gives BadInput and a one-line message naming the file,
// the position and the key path.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/scene_io.h"
#include "tests/scene/scene_test_util.h"

namespace sky {
namespace {

using test::errorOf;

std::string yamlError(const std::string& text) {
  return errorOf([&] { loadSceneText(text, ConfigFormat::Yaml, "x.yaml"); });
}
std::string jsonError(const std::string& text) {
  return errorOf([&] { loadSceneText(text, ConfigFormat::Json, "x.json"); });
}
std::string fileError(const std::string& name) {
  return errorOf([&] { loadSceneFile(test::testDataDir() / "scenes" / "bad" / name); });
}
std::string badPath(const std::string& name) {
  return (test::testDataDir() / "scenes" / "bad" / name).string();
}

TEST(SceneErrors, UnknownKeys) {
  EXPECT_EQ(yamlError("ouput:\n  width: 64\n"),
            "x.yaml:1:1: unknown key 'ouput' (did you mean 'output'?)");
  EXPECT_EQ(yamlError("camera:\n  pitch: 3\n  verticalFov: 50\n"),
            "x.yaml:3:3: unknown key 'camera.verticalFov' (did you mean 'vertical_fov'?)");
  EXPECT_EQ(yamlError("sky:\n  cloudiness: 3\n"),
            "x.yaml:2:3: unknown key 'sky.cloudiness' (known keys: model, glow_size, glow_exponent, "
            "haze_height)");
  EXPECT_EQ(jsonError("{\"output\": {}, \"fog\": {}}"),
            "x.json:1:16: unknown key 'fog' (known keys: output, camera, time, sun, moon, sky, "
            "atmosphere, ground, high_clouds, clouds, weather, lighting)");
  EXPECT_EQ(fileError("unknown_key.yaml"),
            badPath("unknown_key.yaml") +
                ":5:3: unknown key 'sky.haze_hieght' (did you mean 'haze_height'?)");
  // Keys that moved or were renamed with the lighting model.
  EXPECT_EQ(yamlError("sun:\n  disc_intensity: 40\n"),
            "x.yaml:2:3: unknown key 'sun.disc_intensity' (known keys: azimuth, elevation, "
            "angular_diameter, disc_scale)");
  EXPECT_EQ(yamlError("sky:\n  sky_color: [0.1, 0.2, 0.3]\n"),
            "x.yaml:2:3: unknown key 'sky.sky_color' (known keys: model, glow_size, glow_exponent, "
            "haze_height)");
  EXPECT_EQ(yamlError("moon:\n  earthshne: 2\n"),
            "x.yaml:2:3: unknown key 'moon.earthshne' (did you mean 'earthshine'?)");
  EXPECT_EQ(yamlError("lighting:\n  turbidty: 2\n"),
            "x.yaml:2:3: unknown key 'lighting.turbidty' (did you mean 'turbidity'?)");
}

TEST(SceneErrors, MessagesAreOneLine) {
  // Keys and values with line breaks are escaped; long text is cut.
  EXPECT_EQ(yamlError("sun:\n  \"angular\\ndiameter\": 1\n"),
            "x.yaml:2:3: unknown key 'sun.angular\\ndiameter' (did you mean 'angular_diameter'?)");
  EXPECT_EQ(
      yamlError("time: \"2024\\n06\"\n"),
      "x.yaml:1:7: time: '2024\\n06' is not a valid time: expected YYYY-MM-DDTHH:MM[:SS[.fff]] "
      "followed by Z or +HH:MM");
  EXPECT_EQ(yamlError("camera:\n  pitch: " + std::string(100, '9') + "\n"),
            "x.yaml:2:10: camera.pitch: " + std::string(60, '9') + "... is out of range [-90, 90]");
}

TEST(SceneErrors, WrongTypes) {
  EXPECT_EQ(fileError("wrong_type.json"),
            badPath("wrong_type.json") + ":2:14: output.width: expected an integer, got a string");
  EXPECT_EQ(yamlError("output:\n  width: \"64\"\n"),
            "x.yaml:2:10: output.width: expected an integer, got a string");
  EXPECT_EQ(yamlError("output:\n  width: wide\n"),
            "x.yaml:2:10: output.width: expected an integer, got 'wide'");
  EXPECT_EQ(yamlError("output:\n  width: 1.5\n"),
            "x.yaml:2:10: output.width: expected an integer, got 1.5");
  EXPECT_EQ(jsonError("{\"output\": {\"width\": 1.5}}"),
            "x.json:1:13: output.width: expected an integer, got 1.5");
  EXPECT_EQ(yamlError("camera:\n  pitch: {a: 1}\n"),
            "x.yaml:2:10: camera.pitch: expected a number, got a map");
  EXPECT_EQ(yamlError("camera:\n  pitch: [1]\n"),
            "x.yaml:2:10: camera.pitch: expected a number, got a list");
  EXPECT_EQ(yamlError("camera:\n  pitch:\n"),
            "x.yaml:2:3: camera.pitch: expected a number, got null");
  EXPECT_EQ(jsonError("{\"camera\": {\"pitch\": true}}"),
            "x.json:1:13: camera.pitch: expected a number, got a boolean");
  EXPECT_EQ(jsonError("{\"output\": {\"name\": 12}}"),
            "x.json:1:13: output.name: expected a string, got a number");
  EXPECT_EQ(yamlError("output:\n  name: [a]\n"),
            "x.yaml:2:9: output.name: expected a string, got a list");
  EXPECT_EQ(yamlError("camera: 3\n"), "x.yaml:1:9: camera: expected a map of settings, got '3'");
  EXPECT_EQ(yamlError("camera:\n"), "x.yaml:1:1: camera: expected a map of settings, got null");
  EXPECT_EQ(jsonError("{\"sky\": []}"), "x.json:1:2: sky: expected a map of settings, got a list");
  EXPECT_EQ(yamlError("time: [2024-06-21T00:00Z]\n"),
            "x.yaml:1:7: time: expected an ISO 8601 time, START/END/STEP or a {start, end, step} "
            "map, got a list");
}

// A palette of complete keys at `elevations`, in block style under "lighting:\n  palette:\n"
// (line 3 is the first key's "- sun_elevation"; each key takes 8 lines). `edit` replaces
// the line of `key` in item `item` ("" drops it).
std::string paletteYaml(const std::vector<std::string>& elevations, size_t item = 0,
                        const std::string& key = "", const std::string& edit = "") {
  static const std::pair<const char*, const char*> kLines[] = {
      {"sky_color", "[0.1, 0.2, 0.3]"},           {"fog_color", "[0.5, 0.5, 0.5]"},
      {"glow_color", "[1, 0.5, 0.25]"},           {"cloud_lit", "[1, 1, 1]"},
      {"cloud_dark", "[0.5, 0.5, 0.5]"},          {"ambient_top", "[0.25, 0.25, 0.25]"},
      {"ambient_bottom", "[0.125, 0.125, 0.125]"}};
  std::string out = "lighting:\n  palette:\n";
  for (size_t i = 0; i < elevations.size(); ++i) {
    bool first = true;  // the item's first line carries the "- "
    auto line = [&](const std::string& k, const std::string& v) {
      std::string text = i == item && k == key ? edit : k + ": " + v;
      if (text.empty()) return;
      out += (first ? "    - " : "      ") + text + "\n";
      first = false;
    };
    line("sun_elevation", elevations[i]);
    for (auto [k, v] : kLines) line(k, v);
  }
  return out;
}

TEST(SceneErrors, Colours) {
  // Colours live in palette keys now; each is a list of three numbers.
  EXPECT_EQ(fileError("colour_pair.yaml"),
            badPath("colour_pair.yaml") +
                ":5:18: lighting.palette[0].fog_color: expected a list of 3 numbers [r, g, b], "
                "got a list of 2");
  EXPECT_EQ(yamlError(paletteYaml({"0"}, 0, "glow_color", "glow_color: [1, 2, 3, 4]")),
            "x.yaml:6:19: lighting.palette[0].glow_color: expected a list of 3 numbers [r, g, b], "
            "got a list of 4");
  EXPECT_EQ(yamlError(paletteYaml({"0"}, 0, "glow_color", "glow_color: white")),
            "x.yaml:6:19: lighting.palette[0].glow_color: expected a list of 3 numbers [r, g, b], "
            "got 'white'");
  EXPECT_EQ(yamlError(paletteYaml({"0", "10"}, 1, "cloud_lit", "cloud_lit: [1, x, 3]")),
            "x.yaml:15:22: lighting.palette[1].cloud_lit[1]: expected a number, got 'x'");
  EXPECT_EQ(yamlError(paletteYaml({"0"}, 0, "ambient_top", "ambient_top: [1, 1, -0.5]")),
            "x.yaml:9:27: lighting.palette[0].ambient_top[2]: -0.5 is out of range [0, 1000000]");
  EXPECT_EQ(jsonError("{\"lighting\": {\"palette\": [{\"sun_elevation\": 0, \"sky_color\": [0.1, "
                      "\"0.2\", 0.3], \"fog_color\": [0, 0, 0], \"glow_color\": [0, 0, 0], "
                      "\"cloud_lit\": [0, 0, 0], \"cloud_dark\": [0, 0, 0], \"ambient_top\": [0, "
                      "0, 0], \"ambient_bottom\": [0, 0, 0]}]}}"),
            "x.json:1:67: lighting.palette[0].sky_color[1]: expected a number, got a string");
}

TEST(SceneErrors, OutOfRange) {
  EXPECT_EQ(fileError("out_of_range.yaml"),
            badPath("out_of_range.yaml") + ":3:13: camera.latitude: 95 is out of range [-90, 90]");
  EXPECT_EQ(yamlError("output:\n  width: 0\n"),
            "x.yaml:2:10: output.width: 0 is out of range [1, 16384]");
  EXPECT_EQ(yamlError("output:\n  height: 1e9\n"),
            "x.yaml:2:11: output.height: 1e9 is out of range [1, 16384]");
  EXPECT_EQ(jsonError("{\"camera\": {\"vertical_fov\": 180}}"),
            "x.json:1:13: camera.vertical_fov: 180 is out of range [1, 179]");
  EXPECT_EQ(yamlError("sun:\n  angular_diameter: 0\n"),
            "x.yaml:2:21: sun.angular_diameter: 0 is out of range [0.01, 20]");
  EXPECT_EQ(yamlError("sky:\n  haze_height: 0.0001\n"),
            "x.yaml:2:16: sky.haze_height: 0.0001 is out of range [0.001, 1]");
  EXPECT_EQ(yamlError("sun:\n  disc_scale: 1001\n"),
            "x.yaml:2:15: sun.disc_scale: 1001 is out of range [0, 1000]");
  EXPECT_EQ(yamlError("moon:\n  earthshine: -1\n"),
            "x.yaml:2:15: moon.earthshine: -1 is out of range [0, 100]");
  EXPECT_EQ(yamlError("moon:\n  azimuth: 361\n  elevation: 0\n"),
            "x.yaml:2:12: moon.azimuth: 361 is out of range [-360, 360]");
  EXPECT_EQ(yamlError("lighting:\n  pressure_hpa: 1200.5\n"),
            "x.yaml:2:17: lighting.pressure_hpa: 1200.5 is out of range [0, 1200]");
  EXPECT_EQ(yamlError("lighting:\n  night_adaptation: 1.01\n"),
            "x.yaml:2:21: lighting.night_adaptation: 1.01 is out of range [0, 1]");
  EXPECT_EQ(yamlError(paletteYaml({"-90.5"})),
            "x.yaml:3:22: lighting.palette[0].sun_elevation: -90.5 is out of range [-90, 90]");
  // The ends of a range are inside it.
  EXPECT_NO_THROW(
      loadSceneText("camera: {latitude: -90, longitude: 180}\noutput: {width: 16384, height: 1}\n",
                    ConfigFormat::Yaml, "x.yaml"));
}

TEST(SceneErrors, NonFiniteNumbers) {
  EXPECT_EQ(fileError("nan.yaml"),
            badPath("nan.yaml") + ":3:15: sun.disc_scale: .nan is out of range [0, 1000]");
  EXPECT_EQ(yamlError("camera:\n  pitch: .inf\n"),
            "x.yaml:2:10: camera.pitch: .inf is out of range [-90, 90]");
  EXPECT_EQ(yamlError("camera:\n  pitch: -.INF\n"),
            "x.yaml:2:10: camera.pitch: -.INF is out of range [-90, 90]");
  EXPECT_EQ(yamlError("camera:\n  pitch: nan\n"),
            "x.yaml:2:10: camera.pitch: nan is out of range [-90, 90]");
  EXPECT_EQ(yamlError("output:\n  width: .inf\n"),
            "x.yaml:2:10: output.width: .inf is out of range [1, 16384]");
  EXPECT_EQ(yamlError(paletteYaml({"0"}, 0, "sky_color", "sky_color: [0, .nan, 0]")),
            "x.yaml:4:22: lighting.palette[0].sky_color[1]: .nan is out of range [0, 1000000]");
  EXPECT_EQ(yamlError(paletteYaml({".inf"})),
            "x.yaml:3:22: lighting.palette[0].sun_elevation: .inf is out of range [-90, 90]");
  EXPECT_EQ(yamlError("lighting:\n  star_brightness: .nan\n"),
            "x.yaml:2:20: lighting.star_brightness: .nan is out of range [0, 1000000]");
  EXPECT_EQ(
      fileError("overflow.json"),
      badPath("overflow.json") + ":3:5: camera.pitch: 1e999 is out of range (not a finite number)");
  // JSON has no NaN: a syntax error, still naming the key.
  std::string nan = jsonError("{\"camera\": {\n  \"pitch\": NaN}}");
  EXPECT_EQ(nan.rfind("x.json:2:12: JSON syntax error: ", 0), 0u) << nan;
  EXPECT_NE(nan.find("camera.pitch"), std::string::npos) << nan;
}

TEST(SceneErrors, DuplicateKeys) {
  EXPECT_EQ(
      fileError("duplicate_key.yaml"),
      badPath("duplicate_key.yaml") + ":4:3: camera.pitch: duplicate key (first given at line 2)");
  EXPECT_EQ(jsonError("{\"sun\": {\"azimuth\": 1, \"elevation\": 2},\n \"sun\": {}}"),
            "x.json:2:2: sun: duplicate key (first given at line 1)");
}

TEST(SceneErrors, BrokenSyntax) {
  std::string yaml = fileError("broken.yaml");
  EXPECT_EQ(yaml,
            badPath("broken.yaml") + ":4:7: YAML syntax error: end of sequence flow not found");
  std::string json = fileError("broken.json");
  EXPECT_EQ(json.rfind(badPath("broken.json") + ":5:3: JSON syntax error: ", 0), 0u) << json;
  EXPECT_NE(json.find("(in output)"), std::string::npos) << json;
}

TEST(SceneErrors, Files) {
  std::filesystem::path missing = test::testDataDir() / "scenes" / "no_such_scene.yaml";
  EXPECT_EQ(errorOf([&] { loadSceneFile(missing); }),
            missing.string() + ": cannot open file: No such file or directory");
  EXPECT_EQ(fileError("scene.toml"),
            badPath("scene.toml") +
                ": unsupported scene file extension '.toml': use .yaml, .yml or .json");
  EXPECT_EQ(errorOf([] { formatForPath("scene"); }),
            "scene: unsupported scene file extension (none): use .yaml, .yml or .json");
  EXPECT_EQ(formatForPath("a/b.yml"), ConfigFormat::Yaml);
  EXPECT_EQ(formatForPath("B.YAML"), ConfigFormat::Yaml);
  EXPECT_EQ(formatForPath("c.Json"), ConfigFormat::Json);
}

TEST(SceneErrors, SunNeedsAzimuthAndElevation) {
  EXPECT_EQ(fileError("sun_half.yaml"),
            badPath("sun_half.yaml") +
                ":2:3: sun.azimuth: given without sun.elevation (give both or neither)");
  EXPECT_EQ(jsonError("{\"sun\": {\"elevation\": 10}}"),
            "x.json:1:10: sun.elevation: given without sun.azimuth (give both or neither)");
  Scene both = loadSceneText("sun: {azimuth: 10, elevation: -5}", ConfigFormat::Yaml, "x.yaml");
  EXPECT_EQ(both.sun.azimuth, 10.0);
  EXPECT_EQ(both.sun.elevation, -5.0);
  Scene neither = loadSceneText("sun: {disc_scale: 3}", ConfigFormat::Yaml, "x.yaml");
  EXPECT_FALSE(neither.sun.azimuth.has_value());
  EXPECT_FALSE(neither.sun.elevation.has_value());
}

TEST(SceneErrors, MoonNeedsAzimuthAndElevation) {
  EXPECT_EQ(fileError("moon_half.yaml"),
            badPath("moon_half.yaml") +
                ":3:3: moon.azimuth: given without moon.elevation (give both or neither)");
  EXPECT_EQ(jsonError("{\"moon\": {\"elevation\": -10}}"),
            "x.json:1:11: moon.elevation: given without moon.azimuth (give both or neither)");
  // The sun's pair does not complete the moon's.
  EXPECT_EQ(yamlError("sun: {azimuth: 1, elevation: 2}\nmoon: {azimuth: 3}\n"),
            "x.yaml:2:8: moon.azimuth: given without moon.elevation (give both or neither)");
  Scene both = loadSceneText("moon: {elevation: -5, azimuth: 10}", ConfigFormat::Yaml, "x.yaml");
  EXPECT_EQ(both.moon.azimuth, 10.0);
  EXPECT_EQ(both.moon.elevation, -5.0);
  EXPECT_FALSE(both.sun.azimuth.has_value());
}

TEST(SceneErrors, Times) {
  EXPECT_EQ(fileError("time_no_zone.yaml"), badPath("time_no_zone.yaml") +
                                                ":1:7: time: '2024-06-21T12:00:00' is not a valid "
                                                "time: missing time zone: add Z (UTC) or an offset "
                                                "such as +02:00");
  EXPECT_EQ(yamlError("time: 2023-02-30T12:00:00Z\n"),
            "x.yaml:1:7: time: '2023-02-30T12:00:00Z' is not a valid time: day out of range for "
            "the month");
  EXPECT_EQ(jsonError("{\n\"time\": \"noon\"}"),
            "x.json:2:1: time: 'noon' is not a valid time: expected YYYY-MM-DDTHH:MM[:SS[.fff]] "
            "followed by Z or "
            "+HH:MM");
  EXPECT_EQ(yamlError("time: 12\n"),
            "x.yaml:1:7: time: '12' is not a valid time: expected YYYY-MM-DDTHH:MM[:SS[.fff]] "
            "followed by Z or +HH:MM");
  EXPECT_EQ(jsonError("{\"time\": 12}"),
            "x.json:1:2: time: expected an ISO 8601 time, START/END/STEP or a {start, end, step} "
            "map, got a number");
  EXPECT_EQ(yamlError("time:\n"),
            "x.yaml:1:1: time: expected an ISO 8601 time, START/END/STEP or a {start, end, step} "
            "map, got null");
}

// JSON positions are those of the key (of the element inside a list), YAML ones those of
// the value.
TEST(SceneErrors, TimeRangeSteps) {
  const std::string range = "time: 2024-06-21T00:00Z/2024-06-22T00:00Z/";
  EXPECT_EQ(fileError("time_negative_step.yaml"),
            badPath("time_negative_step.yaml") + ":2:7: time: step '-15m' must be positive");
  EXPECT_EQ(yamlError(range + "0s\n"), "x.yaml:1:7: time: step '0s' must be positive");
  EXPECT_EQ(yamlError(range + "PT0M\n"), "x.yaml:1:7: time: step 'PT0M' must be positive");
  EXPECT_EQ(yamlError(range + "-0.5s\n"), "x.yaml:1:7: time: step '-0.5s' must be positive");
  const std::string notDuration =
      "is not a duration: expected a duration such as 15m, 1h30m, 90s, 2d or ISO 8601 PT15M";
  EXPECT_EQ(yamlError(range + "15\n"), "x.yaml:1:7: time: step '15' " + notDuration);
  EXPECT_EQ(yamlError(range + "15min\n"), "x.yaml:1:7: time: step '15min' " + notDuration);
  EXPECT_EQ(yamlError(range + "P1DT\n"), "x.yaml:1:7: time: step 'P1DT' " + notDuration);
  EXPECT_EQ(yamlError("time: \"" + range.substr(6) + "\"\n"),
            "x.yaml:1:7: time: step '' " + notDuration);
  // In the map form the message points at the step itself.
  EXPECT_EQ(yamlError("time:\n  start: 2024-06-21T00:00Z\n  end: 2024-06-22T00:00Z\n"
                      "  step: -15m\n"),
            "x.yaml:4:9: time.step: '-15m' must be positive");
  EXPECT_EQ(jsonError("{\"time\": {\"start\": \"2024-06-21T00:00Z\", \"end\": "
                      "\"2024-06-22T00:00Z\",\n \"step\": \"0h\"}}"),
            "x.json:2:2: time.step: '0h' must be positive");
  EXPECT_EQ(yamlError("time:\n  start: 2024-06-21T00:00Z\n  end: 2024-06-22T00:00Z\n"
                      "  step: 15 minutes\n"),
            "x.yaml:4:9: time.step: '15 minutes' " + notDuration);
}

TEST(SceneErrors, TimeRangeEnds) {
  const std::string form =
      "is not a valid time: expected YYYY-MM-DDTHH:MM[:SS[.fff]] followed by Z or +HH:MM";
  EXPECT_EQ(fileError("time_end_before_start.json"),
            badPath("time_end_before_start.json") +
                ":4:5: time.end: '2024-06-21T23:00:00+02:00' is before the start "
                "2024-06-22T00:00:00+02:00");
  EXPECT_EQ(yamlError("time: 2024-06-22T00:00Z/2024-06-21T23:59:59.5Z/15m\n"),
            "x.yaml:1:7: time: end '2024-06-21T23:59:59.5Z' is before the start "
            "2024-06-22T00:00:00Z");
  // Before, in another zone: 01:00+02:00 is 23:00Z the day before.
  EXPECT_EQ(yamlError("time: 2024-06-22T00:00Z/2024-06-22T01:00+02:00/15m\n"),
            "x.yaml:1:7: time: end '2024-06-22T01:00+02:00' is before the start "
            "2024-06-22T00:00:00Z");
  // Malformed start or end, in each form.
  EXPECT_EQ(yamlError("time: 2024-06-21/2024-06-22T00:00Z/15m\n"),
            "x.yaml:1:7: time: start '2024-06-21' " + form);
  EXPECT_EQ(yamlError("time: 2024-06-21T00:00Z/2024-06-22T00:00/15m\n"),
            "x.yaml:1:7: time: end '2024-06-22T00:00' is not a valid time: missing time zone: "
            "add Z (UTC) or an offset such as +02:00");
  EXPECT_EQ(yamlError("time: 2024-06-21T00:00Z/2024-02-30T00:00Z/15m\n"),
            "x.yaml:1:7: time: end '2024-02-30T00:00Z' is not a valid time: day out of range for "
            "the month");
  EXPECT_EQ(yamlError("time:\n  start: noon\n  end: 2024-06-22T00:00Z\n  step: 15m\n"),
            "x.yaml:2:10: time.start: 'noon' " + form);
  EXPECT_EQ(yamlError("time:\n  start: 2024-06-21T00:00Z\n  end: tomorrow\n  step: 15m\n"),
            "x.yaml:3:8: time.end: 'tomorrow' " + form);
  EXPECT_EQ(jsonError("{\"time\": {\"start\": \"2024-06-21T00:00Z\", \"end\": 5, \"step\": "
                      "\"15m\"}}"),
            "x.json:1:41: time.end: expected a string, got a number");
  EXPECT_EQ(yamlError("time: {start: [1], end: 2024-06-22T00:00Z, step: 15m}\n"),
            "x.yaml:1:15: time.start: expected a string, got a list");
  // Neither one time nor three parts.
  const std::string neither =
      "is neither a time nor a range START/END/STEP (e.g. "
      "2024-06-21T00:00Z/2024-06-22T00:00Z/15m)";
  EXPECT_EQ(yamlError("time: 2024-06-21T00:00Z/2024-06-22T00:00Z\n"),
            "x.yaml:1:7: time: '2024-06-21T00:00Z/2024-06-22T00:00Z' " + neither);
  EXPECT_EQ(yamlError("time: 2024-06-21T00:00Z/2024-06-22T00:00Z/15m/2\n"),
            "x.yaml:1:7: time: '2024-06-21T00:00Z/2024-06-22T00:00Z/15m/2' " + neither);
  EXPECT_EQ(yamlError("time: 2024-06-21T00:00Z/PT15M\n"),
            "x.yaml:1:7: time: '2024-06-21T00:00Z/PT15M' " + neither);
}

TEST(SceneErrors, TimeRangeMapKeys) {
  EXPECT_EQ(fileError("time_missing_end.yaml"),
            badPath("time_missing_end.yaml") + ":2:3: time: missing key 'end'");
  EXPECT_EQ(yamlError("time: {end: 2024-06-22T00:00Z, step: 15m}\n"),
            "x.yaml:1:7: time: missing key 'start'");
  EXPECT_EQ(yamlError("time: {}\n"), "x.yaml:1:7: time: missing key 'start'");
  // Unknown keys are reported before missing ones: a misspelt key is the likelier cause.
  EXPECT_EQ(yamlError("time:\n  start: 2024-06-21T00:00Z\n  end: 2024-06-22T00:00Z\n"
                      "  stpe: 15m\n"),
            "x.yaml:4:3: unknown key 'time.stpe' (did you mean 'step'?)");
  EXPECT_EQ(yamlError("time:\n  start: 2024-06-21T00:00Z\n  end: 2024-06-22T00:00Z\n"
                      "  step: 15m\n  zone: Europe/Zurich\n"),
            "x.yaml:5:3: unknown key 'time.zone' (known keys: start, end, step)");
  EXPECT_EQ(jsonError("{\"time\": {\"start\": \"2024-06-21T00:00Z\", \"end\": "
                      "\"2024-06-22T00:00Z\", \"step\": \"15m\",\n \"frames\": 3}}"),
            "x.json:2:2: unknown key 'time.frames' (known keys: start, end, step)");
}

TEST(SceneErrors, TimeRangeFrameLimit) {
  const std::string tooMany =
      "the range has more than 100000 frames; use a longer step or a shorter range";
  EXPECT_EQ(yamlError("time: 2024-01-01T00:00Z/2025-01-01T00:00Z/1s\n"),
            "x.yaml:1:7: time: " + tooMany);
  // One frame past the limit (100001 frames).
  EXPECT_EQ(yamlError("time: 2024-01-01T00:00Z/2024-01-02T03:46:40Z/1s\n"),
            "x.yaml:1:7: time: " + tooMany);
  // A hair under 100000 steps, which frameCount() counts as 100000 steps: used to pass the
  // reader's limit and give 100001 frames.
  EXPECT_EQ(yamlError("time: 2024-01-01T00:00Z/2024-01-02T03:46:39.9999999999Z/1s\n"),
            "x.yaml:1:7: time: " + tooMany);
  // A tiny step over centuries overflows a 64-bit frame count; the limit catches it first.
  EXPECT_EQ(yamlError("time:\n  start: 0001-01-01T00:00Z\n  end: 9999-12-31T23:59:59Z\n"
                      "  step: 0.000001s\n"),
            "x.yaml:4:9: time.step: " + tooMany);
}

TEST(SceneErrors, PaletteShape) {
  EXPECT_EQ(yamlError("lighting:\n  palette: 3\n"),
            "x.yaml:2:12: lighting.palette: expected a list of maps, got '3'");
  EXPECT_EQ(yamlError("lighting:\n  palette:\n    sun_elevation: 0\n"),
            "x.yaml:3:5: lighting.palette: expected a list of maps, got a map");
  EXPECT_EQ(jsonError("{\"lighting\": {\"palette\": \"day\"}}"),
            "x.json:1:15: lighting.palette: expected a list of maps, got a string");
  EXPECT_EQ(yamlError("lighting:\n  palette: []\n"),
            "x.yaml:2:12: lighting.palette: expected 1 to 64 items, got 0");
  EXPECT_EQ(yamlError("lighting:\n  palette:\n"),
            "x.yaml:2:3: lighting.palette: expected a list of maps, got null");
  std::vector<std::string> many;
  for (int i = 0; i < 65; ++i) many.push_back(std::to_string(i));
  EXPECT_EQ(yamlError(paletteYaml(many)),
            "x.yaml:3:5: lighting.palette: expected 1 to 64 items, got 65");
  std::vector<std::string> most(many.begin(), many.end() - 1);
  EXPECT_EQ(loadSceneText(paletteYaml(most), ConfigFormat::Yaml, "x.yaml").lighting.palette.size(),
            64u);
  // Items must be maps.
  EXPECT_EQ(yamlError("lighting:\n  palette: [1]\n"),
            "x.yaml:2:13: lighting.palette[0]: expected a map of settings, got '1'");
  EXPECT_EQ(yamlError(paletteYaml({"0"}) + "    - [0.1, 0.2, 0.3]\n"),
            "x.yaml:11:7: lighting.palette[1]: expected a map of settings, got a list");
  // yaml-cpp marks an empty item at the start of the next line (here past the end).
  EXPECT_EQ(yamlError(paletteYaml({"0"}) + "    -\n"),
            "x.yaml:12:1: lighting.palette[1]: expected a map of settings, got null");
}

TEST(SceneErrors, PaletteKeys) {
  EXPECT_EQ(
      fileError("palette_missing_key.yaml"),
      badPath("palette_missing_key.yaml") + ":12:7: lighting.palette[1]: missing key 'fog_color'");
  EXPECT_EQ(yamlError(paletteYaml({"0"}, 0, "sun_elevation", "")),
            "x.yaml:3:7: lighting.palette[0]: missing key 'sun_elevation'");
  EXPECT_EQ(yamlError("lighting:\n  palette: [{sun_elevation: 0}]\n"),
            "x.yaml:2:13: lighting.palette[0]: missing key 'sky_color'");
  EXPECT_EQ(yamlError(paletteYaml({"0"}, 0, "fog_color", "fog_colour: [0, 0, 0]")),
            "x.yaml:5:7: unknown key 'lighting.palette[0].fog_colour' (did you mean 'fog_color'?)");
  EXPECT_EQ(yamlError(paletteYaml({"-5", "5"}, 1, "cloud_dark", "cloudDark: [0, 0, 0]")),
            "x.yaml:16:7: unknown key 'lighting.palette[1].cloudDark' (did you mean "
            "'cloud_dark'?)");
  EXPECT_EQ(yamlError(paletteYaml({"0"}, 0, "cloud_lit", "cloud_lit: [1, 1, 1]\n      x: 1")),
            "x.yaml:8:7: unknown key 'lighting.palette[0].x' (known keys: sun_elevation, "
            "sky_color, fog_color, glow_color, cloud_lit, cloud_dark, ambient_top, "
            "ambient_bottom)");
  EXPECT_EQ(yamlError(paletteYaml({"0"}, 0, "cloud_lit",
                                  "cloud_lit: [1, 1, 1]\n      "
                                  "cloud_lit: [1, 1, 1]")),
            "x.yaml:8:7: lighting.palette[0].cloud_lit: duplicate key (first given at line 7)");
}

TEST(SceneErrors, PaletteOrder) {
  EXPECT_EQ(fileError("palette_not_increasing.json"),
            badPath("palette_not_increasing.json") +
                ":7:8: lighting.palette[1].sun_elevation: 5 must be greater than the previous "
                "item's 10 (list items in increasing sun_elevation)");
  EXPECT_EQ(yamlError(paletteYaml({"-6", "0", "0"})),
            "x.yaml:19:22: lighting.palette[2].sun_elevation: 0 must be greater than the previous "
            "item's 0 (list items in increasing sun_elevation)");
  EXPECT_EQ(yamlError(paletteYaml({"1e1", "10.0"})),
            "x.yaml:11:22: lighting.palette[1].sun_elevation: 10.0 must be greater than the "
            "previous item's 10 (list items in increasing sun_elevation)");
  // Strictly increasing by any amount passes; a single key has nothing to compare with.
  Scene s =
      loadSceneText(paletteYaml({"-90", "-89.99999999999999", "90"}), ConfigFormat::Yaml, "x.yaml");
  EXPECT_EQ(s.lighting.palette.size(), 3u);
  EXPECT_EQ(s.lighting.palette[1].sunElevation, -89.99999999999999);
  EXPECT_EQ(loadSceneText(paletteYaml({"45"}), ConfigFormat::Yaml, "x.yaml")
                .lighting.palette[0]
                .sunElevation,
            45.0);
}

TEST(SceneErrors, Strings) {
  EXPECT_EQ(yamlError("output:\n  name: ../etc/x\n"),
            "x.yaml:2:9: output.name: '../etc/x' is not allowed: use letters, digits, '.', '_' and "
            "'-', not starting "
            "with '.'");
  EXPECT_EQ(yamlError("output:\n  name: .hidden\n"),
            "x.yaml:2:9: output.name: '.hidden' is not allowed: use letters, digits, '.', '_' and "
            "'-', not starting "
            "with '.'");
  EXPECT_EQ(yamlError("output:\n  display: ''\n"),
            "x.yaml:2:12: output.display: must not be empty");
  EXPECT_EQ(yamlError("output:\n  name: " + std::string(201, 'a') + "\n"),
            "x.yaml:2:9: output.name: is longer than 200 characters");
  // Plain YAML scalars are text where text is expected.
  Scene s = loadSceneText("output: {name: 64, view: Un-tone-mapped}", ConfigFormat::Yaml, "x.yaml");
  EXPECT_EQ(s.output.name, "64");
  EXPECT_EQ(s.output.view, "Un-tone-mapped");
}

TEST(SceneErrors, EveryBadSceneFails) {
  // Each file under tests/data/scenes/bad is rejected as BadInput with its path in front.
  int count = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(test::testDataDir() / "scenes" / "bad")) {
    std::string message = errorOf([&] { loadSceneFile(entry.path()); });
    EXPECT_EQ(message.rfind(entry.path().string() + ":", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    ++count;
  }
  EXPECT_GE(count, 18);
}

TEST(SceneErrors, AtmosphereAndHighCloudRules) {
  EXPECT_EQ(yamlError("atmosphere:\n  rayleigh_scale_height_km: -8\n"),
            "x.yaml:2:29: atmosphere.rayleigh_scale_height_km: -8 is out of range [0.01, 100]");
  EXPECT_EQ(yamlError("atmosphere:\n  mie_scattering: 5\n  mie_extinction: 4.4\n"),
            "x.yaml:3:19: atmosphere.mie_extinction: must be at least mie_scattering "
            "(extinction = scattering + absorption)");
  // A rule whose key is absent points at the section.
  EXPECT_EQ(yamlError("atmosphere:\n  mie_scattering: 5\n"),
            "x.yaml:2:3: atmosphere.mie_extinction: must be at least mie_scattering "
            "(extinction = scattering + absorption)");
  EXPECT_EQ(yamlError("sky:\n  model: hillaire\n"),
            "x.yaml:2:10: sky.model: 'hillaire' is not allowed: use kozlov or physical");
  EXPECT_EQ(yamlError("high_clouds:\n  resolution: 1000\n"),
            "x.yaml:2:15: high_clouds.resolution: must be a power of two");
  EXPECT_EQ(yamlError("high_clouds:\n  source: image\n"),
            "x.yaml:2:3: high_clouds.coefficients: is required when source is image");
  EXPECT_EQ(yamlError("high_clouds:\n  style: nimbus\n"),
            "x.yaml:2:10: high_clouds.style: 'nimbus' is not allowed: use cirrus, cirrostratus or "
            "cirrocumulus");
  EXPECT_EQ(yamlError("camera:\n  projection: fisheye\n"),
            "x.yaml:2:15: camera.projection: 'fisheye' is not allowed: use perspective or "
            "equirectangular");
}

TEST(SceneErrors, TextThatIsNotUtf8IsRefused) {
  // YAML takes the bytes as they are; JSON cannot hold them and a scene written back would
  // change them (U+FFFD), so strings must be UTF-8 (issue 31's fuzzing).
  EXPECT_EQ(yamlError("weather:\n  file: a\xe9.grib2\n"),
            "x.yaml:2:9: weather.file: is not valid UTF-8 (byte 0xE9 at 1); write the text in "
            "UTF-8");
  // Overlong forms and surrogates too; well-formed text of every length passes.
  EXPECT_NE(yamlError("weather:\n  image: \"\xc0\xaf\"\n")
                .find("weather.image: is not valid UTF-8 (byte 0xC0 at 0)"),
            std::string::npos);
  EXPECT_NE(yamlError("weather:\n  image: \"\xed\xa0\x80\"\n").find("(byte 0xED at 0)"),
            std::string::npos);
  EXPECT_EQ(loadSceneText("weather:\n  image: \"\xc3\xa9\xe2\x82\xac\xf0\x9f\x8c\xa7\"\n",
                          ConfigFormat::Yaml, "x.yaml")
                .weather.image,
            "\xc3\xa9\xe2\x82\xac\xf0\x9f\x8c\xa7");
  const std::string set = errorOf(
      [&] { loadSceneText("{}", ConfigFormat::Json, "x.json", {"high_clouds.normals=n\xff"}); });
  EXPECT_NE(set.find("high_clouds.normals: is not valid UTF-8 (byte 0xFF at 1)"),
            std::string::npos)
      << set;
}

TEST(SceneErrors, CloudAndWeatherRules) {
  EXPECT_EQ(yamlError("clouds:\n  low:\n    base_m: 3000\n    top_m: 2000\n"),
            "x.yaml:4:12: clouds.low.top_m: must be above base_m");
  EXPECT_EQ(yamlError("clouds:\n  mid:\n    base_m: 2000\n"),
            "x.yaml:3:5: clouds.mid: base_m must not lie below low.top_m");
  EXPECT_EQ(yamlError("weather:\n  cover_low: 1.5\n"),
            "x.yaml:2:14: weather.cover_low: 1.5 is out of range [0, 1]");
  EXPECT_EQ(yamlError("weather:\n  region:\n    lat: [50, 45]\n    lon: [5, 12]\n"),
            "x.yaml:3:10: weather.region.lat: south (first) must be below north (second)");
  EXPECT_EQ(yamlError("weather:\n  region:\n    lon: [5]\n    lat: [45, 50]\n"),
            "x.yaml:3:10: weather.region.lon: expected a list of 2 numbers [from, to], got a list "
            "of 1");
  EXPECT_EQ(yamlError("weather:\n  region:\n    lat: [-95, 4]\n    lon: [5, 12]\n"),
            "x.yaml:3:11: weather.region.lat[0]: -95 is out of range [-90, 90]");
  // A region is both bounds or none: half of one filled in from defaults would be a guess.
  EXPECT_EQ(yamlError("weather:\n  region:\n    lat: [45, 50]\n"),
            "x.yaml:3:5: weather.region: missing key 'lon'");
  EXPECT_EQ(yamlError("weather:\n  camera_region_km: 5\n"),
            "x.yaml:2:21: weather.camera_region_km: 5 is out of range [10, 10000]");
  EXPECT_EQ(yamlError("clouds:\n  model: schneider\n"),
            "x.yaml:2:10: clouds.model: 'schneider' is not allowed: use lu2023 or tang2019");
  EXPECT_EQ(yamlError("clouds:\n  energy_conserving: yes\n"),
            "x.yaml:2:22: clouds.energy_conserving: expected true or false, got 'yes'");
  EXPECT_EQ(jsonError("{\"clouds\": {\"energy_conserving\": 1}}"),
            "x.json:1:13: clouds.energy_conserving: expected true or false, got '1'");
  EXPECT_EQ(yamlError("weather:\n  source: image\n"),
            "x.yaml:2:3: weather.image: is required when source is image");
  EXPECT_EQ(yamlError("weather:\n  advection: data\n"),
            "x.yaml:2:14: weather.advection: data needs source file (the wind comes from the "
            "forecast); wind uses the scene's");
  EXPECT_EQ(yamlError("weather:\n  time: noon\n"),
            "x.yaml:2:9: weather.time: 'noon' is not a valid time: expected "
            "YYYY-MM-DDTHH:MM[:SS[.fff]] followed by Z or +HH:MM");
  EXPECT_EQ(yamlError("weather:\n  time: 2024-06-21T12:00\n"),
            "x.yaml:2:9: weather.time: '2024-06-21T12:00' is not a valid time: missing time "
            "zone: add Z (UTC) or an offset such as +02:00");
  EXPECT_EQ(yamlError("weather:\n  evolution: dobashi\n"),
            "x.yaml:2:14: weather.evolution: 'dobashi' is not allowed: use none or ca");
  EXPECT_EQ(yamlError("weather:\n  automaton:\n    step_s: 5\n"),
            "x.yaml:3:13: weather.automaton.step_s: 5 is out of range [10, 3600]");
  EXPECT_EQ(yamlError("high_clouds:\n  cover_source: forecast\n"),
            "x.yaml:2:17: high_clouds.cover_source: 'forecast' is not allowed: use auto, scene or "
            "weather");
  EXPECT_EQ(yamlError("camera:\n  mode: orbit\n"),
            "x.yaml:2:9: camera.mode: 'orbit' is not allowed: use observer or geographic_topdown");
}

}  // namespace
}  // namespace sky
