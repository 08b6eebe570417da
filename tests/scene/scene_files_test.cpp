// The shipped scene files and the checked-in JSON Schema.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>

#include <gtest/gtest.h>

#include "engine/core/files.h"
#include "engine/scene/detail/schema_builder.h"
#include "engine/scene/scene_io.h"
#include "tests/scene/scene_compare.h"
#include "tests/scene/scene_test_util.h"

namespace sky {
namespace {

namespace fs = std::filesystem;

fs::path configs() {
  return test::sourceDir() / "configs";
}

std::vector<fs::path> sceneFiles() {
  std::vector<fs::path> files;
  for (auto it = fs::recursive_directory_iterator(configs());
       it != fs::recursive_directory_iterator(); ++it) {
    // schema/ holds the schema, ocio/ colour configs: neither are scenes.
    if (it->is_directory() &&
        (it->path().filename() == "schema" || it->path().filename() == "ocio")) {
      it.disable_recursion_pending();
      continue;
    }
    std::string ext = it->path().extension().string();
    if (it->is_regular_file() && (ext == ".yaml" || ext == ".yml" || ext == ".json"))
      files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(SceneFiles, EverySceneInConfigsLoads) {
  std::vector<fs::path> files = sceneFiles();
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    Scene scene;
    EXPECT_NO_THROW(scene = loadSceneFile(f));
    // And its effective settings print and reload to the same scene.
    ConfigFormat format = formatForPath(f);
    test::expectSameScene(loadSceneText(writeScene(scene, format), format, "printed"), scene);
  }
  // default.yaml, the example and the three golden-image scenes at least.
  EXPECT_GE(files.size(), 5u);
}

TEST(SceneFiles, DefaultSceneIsAClearDayWithTheSunInView) {
  Scene s = loadSceneFile(configs() / "default.yaml");
  ASSERT_TRUE(s.sun.azimuth && s.sun.elevation);
  EXPECT_GT(*s.sun.elevation, 10.0);
  // In frame: within half the vertical field of view of the view direction.
  EXPECT_LT(std::fabs(*s.sun.elevation - s.camera.pitch), s.camera.verticalFov / 2);
  EXPECT_LT(std::fabs(*s.sun.azimuth - s.camera.heading), 45.0);
}

TEST(SceneFiles, ExampleJsonScene) {
  Scene s = loadSceneFile(configs() / "examples" / "clear_noon.json");
  EXPECT_FALSE(s.sun.azimuth.has_value());  // the sun follows time and place
  EXPECT_EQ(s.output.name, "clear_noon");
}

TEST(SceneFiles, GoldenImageScenesShareTheCamera) {
  const char* names[] = {"clear_sky_high.yaml", "clear_sky_low.yaml", "clear_sky_sunset.yaml"};
  const double elevations[] = {60, 15, 1};
  Scene first = loadSceneFile(configs() / "tests" / names[0]);
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(names[i]);
    Scene s = loadSceneFile(configs() / "tests" / names[i]);
    EXPECT_EQ(s.output.width, 64);
    EXPECT_EQ(s.output.height, 36);
    ASSERT_TRUE(s.sun.azimuth && s.sun.elevation);
    EXPECT_NEAR(*s.sun.elevation, elevations[i], 1.0);
    EXPECT_EQ(*s.sun.azimuth, s.camera.heading);  // looking toward the sun
    EXPECT_NEAR(s.camera.verticalFov, 80.0, 10.0);
    // The sun is in view vertically.
    EXPECT_LT(std::fabs(*s.sun.elevation - s.camera.pitch), s.camera.verticalFov / 2);
    EXPECT_EQ(s.camera.latitude, first.camera.latitude);
    EXPECT_EQ(s.camera.longitude, first.camera.longitude);
    EXPECT_EQ(s.camera.altitudeM, first.camera.altitudeM);
    EXPECT_EQ(s.camera.heading, first.camera.heading);
    EXPECT_EQ(s.camera.pitch, first.camera.pitch);
    EXPECT_EQ(s.camera.verticalFov, first.camera.verticalFov);
  }
}

TEST(SceneSchema, CheckedInFileMatchesTheDescription) {
  fs::path file = configs() / "schema" / "scene.schema.json";
  std::string generated = sceneJsonSchema();
  // SKY_UPDATE_SCHEMA=1 test_scene --gtest_filter=SceneSchema.* rewrites the file.
  if (const char* update = std::getenv("SKY_UPDATE_SCHEMA"); update && std::string(update) == "1")
    writeFileAtomic(file, generated);
  std::string checkedIn = fs::exists(file) ? readTextFile(file) : std::string();
  EXPECT_EQ(checkedIn, generated)
      << file.string() << " is out of date; regenerate it with `skyrender schema > "
      << "configs/schema/scene.schema.json` or SKY_UPDATE_SCHEMA=1 test_scene";
}

TEST(SceneSchema, DescribesEveryKeyStrictly) {
  nlohmann::json schema = nlohmann::json::parse(sceneJsonSchema());
  EXPECT_EQ(schema["$schema"], "https://json-schema.org/draft/2020-12/schema");
  EXPECT_EQ(schema["additionalProperties"], false);
  // Every key the writer prints is in the schema, and every section is closed.
  nlohmann::json printed = sceneToJson(test::unusualScene());
  for (auto& [section, value] : printed.items()) {
    ASSERT_TRUE(schema["properties"].contains(section)) << section;
    const nlohmann::json& s = schema["properties"][section];
    EXPECT_TRUE(s.contains("description")) << section;
    if (!value.is_object()) continue;
    EXPECT_EQ(s["additionalProperties"], false) << section;
    for (auto& [key, v] : value.items()) {
      ASSERT_TRUE(s["properties"].contains(key)) << section << "." << key;
      EXPECT_TRUE(s["properties"][key].contains("description")) << section << "." << key;
    }
  }
  const nlohmann::json& lat = schema["properties"]["camera"]["properties"]["latitude"];
  EXPECT_EQ(lat["type"], "number");
  EXPECT_EQ(lat["minimum"], -90);
  EXPECT_EQ(lat["maximum"], 90);
  EXPECT_EQ(lat["default"], 47.37);
  const nlohmann::json& width = schema["properties"]["output"]["properties"]["width"];
  EXPECT_EQ(width["type"], "integer");
  EXPECT_EQ(width["default"], 1280);
  const nlohmann::json& color = schema["properties"]["sky"]["properties"]["sky_color"];
  EXPECT_EQ(color["minItems"], 3);
  EXPECT_EQ(color["maxItems"], 3);
  EXPECT_EQ(color["items"]["type"], "number");
  EXPECT_EQ(color["default"][0], 0.07);
  const nlohmann::json& sun = schema["properties"]["sun"];
  EXPECT_EQ(sun["dependentRequired"]["azimuth"][0], "elevation");
  EXPECT_EQ(sun["dependentRequired"]["elevation"][0], "azimuth");
  EXPECT_FALSE(sun["properties"]["azimuth"].contains("default"));
}

TEST(SceneSchema, TimePatternAgreesWithTheParser) {
  // The schema's pattern cannot express calendar rules (Feb 30) or ranges; it must accept
  // every spelling IsoTime::parse accepts and reject every malformed one.
  std::regex pattern(detail::kIsoTimePattern, std::regex::ECMAScript);
  for (const char* good : {"2024-06-21T12:00:00+02:00", "2024-06-21T10:00Z", "2024-06-21t10:00:00z",
                           "2024-06-21 10:00:00.125Z", "2024-06-21T10:00:00,5-03:30",
                           "2024-06-21T10:00:00+0530", "2024-06-21T10:00:00+05"}) {
    EXPECT_TRUE(IsoTime::parse(good).has_value()) << good;
    EXPECT_TRUE(std::regex_search(std::string(good), pattern)) << good;
  }
  for (const char* bad :
       {"2024-06-21T12:00:00", "2024-06-21", "2024-6-21T12:00Z", "2024-06-21T12:00:00.Z",
        "2024-06-21T12:00:00Zx", "2024-06-21T12:00:00+2:00", "2024-06-21T12:00:00+02:0", "noon"}) {
    EXPECT_FALSE(IsoTime::parse(bad).has_value()) << bad;
    EXPECT_FALSE(std::regex_search(std::string(bad), pattern)) << bad;
  }
}

}  // namespace
}  // namespace sky
