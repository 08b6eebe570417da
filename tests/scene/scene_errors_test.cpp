// Every way a scene can be wrong gives BadInput and a one-line message naming the file,
// the position and the key path.
#include <filesystem>

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
            "x.yaml:2:3: unknown key 'sky.cloudiness' (known keys: sky_color, fog_color, "
            "sun_color, glow_size, "
            "haze_height)");
  EXPECT_EQ(jsonError("{\"output\": {}, \"clouds\": {}}"),
            "x.json:1:16: unknown key 'clouds' (known keys: output, camera, time, sun, sky)");
  EXPECT_EQ(fileError("unknown_key.yaml"),
            badPath("unknown_key.yaml") +
                ":5:3: unknown key 'sky.sky_colour' (did you mean 'sky_color'?)");
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
  EXPECT_EQ(yamlError("time: {a: 1}\n"),
            "x.yaml:1:7: time: expected an ISO 8601 time string, got a map");
}

TEST(SceneErrors, Colours) {
  EXPECT_EQ(fileError("colour_pair.yaml"),
            badPath("colour_pair.yaml") +
                ":2:14: sky.fog_color: expected a list of 3 numbers [r, g, b], got a list of 2");
  EXPECT_EQ(yamlError("sky:\n  sun_color: [1, 2, 3, 4]\n"),
            "x.yaml:2:14: sky.sun_color: expected a list of 3 numbers [r, g, b], got a list of 4");
  EXPECT_EQ(yamlError("sky:\n  sun_color: white\n"),
            "x.yaml:2:14: sky.sun_color: expected a list of 3 numbers [r, g, b], got 'white'");
  EXPECT_EQ(yamlError("sky:\n  sun_color: [1, x, 3]\n"),
            "x.yaml:2:18: sky.sun_color[1]: expected a number, got 'x'");
  EXPECT_EQ(yamlError("sky:\n  sun_color: [1, 1, -0.5]\n"),
            "x.yaml:2:21: sky.sun_color[2]: -0.5 is out of range [0, 1000000]");
  EXPECT_EQ(jsonError("{\"sky\": {\"sky_color\": [0.1, \"0.2\", 0.3]}}"),
            "x.json:1:29: sky.sky_color[1]: expected a number, got a string");
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
  // The ends of a range are inside it.
  EXPECT_NO_THROW(
      loadSceneText("camera: {latitude: -90, longitude: 180}\noutput: {width: 16384, height: 1}\n",
                    ConfigFormat::Yaml, "x.yaml"));
}

TEST(SceneErrors, NonFiniteNumbers) {
  EXPECT_EQ(fileError("nan.yaml"),
            badPath("nan.yaml") + ":3:19: sun.disc_intensity: .nan is out of range [0, 1000000]");
  EXPECT_EQ(yamlError("camera:\n  pitch: .inf\n"),
            "x.yaml:2:10: camera.pitch: .inf is out of range [-90, 90]");
  EXPECT_EQ(yamlError("camera:\n  pitch: -.INF\n"),
            "x.yaml:2:10: camera.pitch: -.INF is out of range [-90, 90]");
  EXPECT_EQ(yamlError("camera:\n  pitch: nan\n"),
            "x.yaml:2:10: camera.pitch: nan is out of range [-90, 90]");
  EXPECT_EQ(yamlError("output:\n  width: .inf\n"),
            "x.yaml:2:10: output.width: .inf is out of range [1, 16384]");
  EXPECT_EQ(yamlError("sky:\n  sky_color: [0, .nan, 0]\n"),
            "x.yaml:2:18: sky.sky_color[1]: .nan is out of range [0, 1000000]");
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
  Scene neither = loadSceneText("sun: {disc_intensity: 3}", ConfigFormat::Yaml, "x.yaml");
  EXPECT_FALSE(neither.sun.azimuth.has_value());
  EXPECT_FALSE(neither.sun.elevation.has_value());
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
            "x.json:1:2: time: expected an ISO 8601 time string, got a number");
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
  EXPECT_GE(count, 10);
}

}  // namespace
}  // namespace sky
