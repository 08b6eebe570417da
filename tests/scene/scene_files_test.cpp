// The shipped scene files and the checked-in JSON Schema.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>

#include <gtest/gtest.h>

#include "engine/core/error.h"
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
    // schema/ holds the schemas, ocio/ colour configs, datasets/ dataset specs (their own
    // format, tests/dataset): none are scenes.
    if (it->is_directory() &&
        (it->path().filename() == "schema" || it->path().filename() == "ocio" ||
         it->path().filename() == "datasets")) {
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

TEST(SceneFiles, DefaultYamlIsTheBuiltInSceneWithAnEveningView) {
  // configs/default.yaml is the scene `skyrender render` uses without a file. It writes out
  // every section (the palette in full) so users can edit it, but it only means to differ
  // from Scene{} in the view, the time and the clouds: looking west on a summer evening with
  // some cirrus and fair-weather cumulus based at 1500 m over the Swiss plateau.
  Scene file = loadSceneFile(configs() / "default.yaml");
  Scene expected;
  expected.camera.heading = 280;
  expected.camera.pitch = 10;
  expected.time.start = IsoTime::parse("2024-06-21T19:00:00+02:00").value();
  expected.highClouds.cover = 0.35;
  expected.weather.coverLow = 0.35;
  expected.clouds.low = {1500.0, 3500.0};
  expected.clouds.mid = {4000.0, 7000.0};
  expected.baseDir = file.baseDir;
  test::expectSameScene(file, expected);
  // The sun and moon follow time and place (no art-directed placement).
  EXPECT_FALSE(file.sun.azimuth.has_value());
  EXPECT_FALSE(file.moon.azimuth.has_value());
  EXPECT_FALSE(file.time.isRange());
}

TEST(SceneFiles, DefaultYamlPaletteIsDefaultPalette) {
  std::vector<PaletteKey> file = loadSceneFile(configs() / "default.yaml").lighting.palette;
  test::expectSamePalette(file, defaultPalette());
  EXPECT_EQ(file, defaultPalette());
  // The file writes the palette out rather than leaving it to the default: a scene without
  // it would not show users what they can change.
  std::string text = readTextFile(configs() / "default.yaml");
  EXPECT_NE(text.find("\n  palette:\n"), std::string::npos);
}

TEST(SceneFiles, DefaultPaletteObeysTheListRule) {
  // What the reader demands of a palette in a file (scene_fields.h: 1..64 keys, increasing
  // sun elevation), plus what the renderer's interpolation needs: the keys cover every
  // sun elevation, so nothing is extrapolated, and no colour is negative.
  std::vector<PaletteKey> p = defaultPalette();
  ASSERT_GE(p.size(), 2u);
  EXPECT_LE(p.size(), 64u);
  EXPECT_EQ(p.front().sunElevation, -90.0);
  EXPECT_EQ(p.back().sunElevation, 90.0);
  for (size_t i = 0; i < p.size(); ++i) {
    SCOPED_TRACE(i);
    if (i > 0) {
      EXPECT_GT(p[i].sunElevation, p[i - 1].sunElevation);
    }
    for (const glm::vec3& c : {p[i].skyColor, p[i].fogColor, p[i].glowColor, p[i].cloudLit,
                               p[i].cloudDark, p[i].ambientTop, p[i].ambientBottom}) {
      EXPECT_GE(std::min({c.x, c.y, c.z}), 0.0f);
      EXPECT_LE(std::max({c.x, c.y, c.z}), 1e6f);
    }
  }
  // Night is darker than day: the zenith sky at the lowest key against the highest.
  EXPECT_LT(p.front().skyColor.z, p.back().skyColor.z);
}

TEST(SceneFiles, ExampleJsonScene) {
  Scene s = loadSceneFile(configs() / "examples" / "clear_noon.json");
  EXPECT_FALSE(s.sun.azimuth.has_value());  // the sun follows time and place
  EXPECT_EQ(s.output.name, "clear_noon");
}

// Every example a user is pointed to loads, and any file it names exists (relative to it).
TEST(SceneFiles, EveryExampleLoadsAndItsFilesExist) {
  int examples = 0;
  for (const std::filesystem::directory_entry& e :
       std::filesystem::directory_iterator(configs() / "examples")) {
    SCOPED_TRACE(e.path().filename().string());
    const Scene s = loadSceneFile(e.path());
    if (s.weather.source == WeatherMapSource::File) {
      EXPECT_TRUE(std::filesystem::exists(s.resolvePath(s.weather.file))) << s.weather.file;
    }
    if (s.weather.source == WeatherMapSource::Image) {
      EXPECT_TRUE(std::filesystem::exists(s.resolvePath(s.weather.image))) << s.weather.image;
    }
    ++examples;
  }
  EXPECT_GE(examples, 8);
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
    if (section == "time") continue;  // printed as a map, described by anyOf (below)
    ASSERT_TRUE(value.is_object()) << section;
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
  for (const char* placed : {"sun", "moon"}) {
    const nlohmann::json& s = schema["properties"][placed];
    EXPECT_EQ(s["dependentRequired"]["azimuth"][0], "elevation") << placed;
    EXPECT_EQ(s["dependentRequired"]["elevation"][0], "azimuth") << placed;
    EXPECT_FALSE(s["properties"]["azimuth"].contains("default")) << placed;
  }
  EXPECT_EQ(schema["properties"]["sun"]["properties"]["disc_scale"]["maximum"], 1000);
  EXPECT_FALSE(schema["properties"]["sky"]["properties"].contains("sky_color"));
}

TEST(SceneSchema, PaletteIsAListOfCompleteKeys) {
  nlohmann::json schema = nlohmann::json::parse(sceneJsonSchema());
  const nlohmann::json& palette = schema["properties"]["lighting"]["properties"]["palette"];
  EXPECT_EQ(palette["type"], "array");
  EXPECT_EQ(palette["minItems"], 1);
  EXPECT_EQ(palette["maxItems"], 64);
  const nlohmann::json& item = palette["items"];
  EXPECT_EQ(item["type"], "object");
  EXPECT_EQ(item["additionalProperties"], false);
  std::vector<std::string> keys;
  for (auto& [key, prop] : item["properties"].items()) {
    keys.push_back(key);
    EXPECT_TRUE(prop.contains("description")) << key;
    EXPECT_FALSE(prop.contains("default")) << key;  // every key is required: no default
  }
  // nlohmann::json sorts object keys; the required list keeps the description's order.
  EXPECT_EQ(item["required"],
            nlohmann::json({"sun_elevation", "sky_color", "fog_color", "glow_color", "cloud_lit",
                            "cloud_dark", "ambient_top", "ambient_bottom"}));
  EXPECT_EQ(keys.size(), 8u);
  const nlohmann::json& color = item["properties"]["fog_color"];
  EXPECT_EQ(color["minItems"], 3);
  EXPECT_EQ(color["maxItems"], 3);
  EXPECT_EQ(color["items"]["minimum"], 0);
  EXPECT_EQ(color["items"]["maximum"], 1000000);
  // The default is the built-in palette as `validate` prints it (floats as short text).
  EXPECT_EQ(palette["default"], sceneToJson(Scene())["lighting"]["palette"]);
  EXPECT_EQ(palette["default"][6]["sky_color"][0], 0.115);
}

TEST(SceneSchema, TimeIsAnInstantOrARange) {
  nlohmann::json schema = nlohmann::json::parse(sceneJsonSchema());
  const nlohmann::json& time = schema["properties"]["time"];
  EXPECT_EQ(time["default"], "2024-06-21T12:00:00+02:00");
  ASSERT_EQ(time["anyOf"].size(), 3u);
  const nlohmann::json& instant = time["anyOf"][0];
  const nlohmann::json& interval = time["anyOf"][1];
  const nlohmann::json& range = time["anyOf"][2];
  EXPECT_EQ(instant["pattern"], detail::kIsoTimePattern);
  EXPECT_EQ(range["required"], nlohmann::json({"start", "end", "step"}));
  EXPECT_EQ(range["additionalProperties"], false);
  std::regex intervalPattern(interval["pattern"].get<std::string>(), std::regex::ECMAScript);
  for (const char* good : {"2024-06-21T00:00Z/2024-06-22T00:00Z/15m",
                           "2024-06-21T00:00:00+02:00/2024-06-22T00:00:00.5-01:00/PT1H30M"})
    EXPECT_TRUE(std::regex_search(std::string(good), intervalPattern)) << good;
  for (const char* bad :
       {"2024-06-21T00:00Z/2024-06-22T00:00Z", "2024-06-21T00:00Z/2024-06-22T00:00Z/",
        "2024-06-21T00:00Z/2024-06-22T00:00Z/15m/1", "2024-06-21T00:00Z/noon/15m"})
    EXPECT_FALSE(std::regex_search(std::string(bad), intervalPattern)) << bad;
  // A range scene's default is printed the way `validate` prints the range.
  Scene ranged;
  ranged.time.end = ranged.time.start.plusSeconds(3600);
  ranged.time.stepSeconds = 90;
  EXPECT_EQ(sceneToJson(ranged)["time"], nlohmann::json({{"start", "2024-06-21T12:00:00+02:00"},
                                                         {"end", "2024-06-21T13:00:00+02:00"},
                                                         {"step", "1m30s"}}));
}

// A JSON Schema validator for exactly the keywords the scene schema uses; it fails on any
// other keyword so the schema cannot grow a rule these tests silently skip. Returns one
// line per violation, each starting with the JSON path of the value.
class MiniValidator {
public:
  std::vector<std::string> errors;

  void check(const nlohmann::json& schema, const nlohmann::json& v, const std::string& at) {
    static const std::vector<std::string> kKnown = {"$schema",
                                                    "title",
                                                    "description",
                                                    "default",
                                                    "type",
                                                    "properties",
                                                    "required",
                                                    "anyOf",
                                                    "minimum",
                                                    "maximum",
                                                    "minItems",
                                                    "maxItems",
                                                    "items",
                                                    "pattern",
                                                    "minLength",
                                                    "maxLength",
                                                    "additionalProperties",
                                                    "dependentRequired"};
    for (auto& [k, _] : schema.items()) {
      if (std::find(kKnown.begin(), kKnown.end(), k) == kKnown.end())
        ADD_FAILURE() << "MiniValidator does not know the keyword '" << k << "' at " << at;
    }
    if (schema.contains("type") && !hasType(v, schema["type"].get<std::string>())) {
      errors.push_back(at + ": not of type " + schema["type"].get<std::string>());
      return;
    }
    if (schema.contains("anyOf")) {
      bool any = false;
      for (const nlohmann::json& option : schema["anyOf"]) {
        MiniValidator sub;
        sub.check(option, v, at);
        any = any || sub.errors.empty();
      }
      if (!any) errors.push_back(at + ": matches none of anyOf");
    }
    if (v.is_number()) {
      if (schema.contains("minimum") && v.get<double>() < schema["minimum"].get<double>())
        errors.push_back(at + ": below minimum");
      if (schema.contains("maximum") && v.get<double>() > schema["maximum"].get<double>())
        errors.push_back(at + ": above maximum");
    }
    if (v.is_string()) {
      // Lengths in bytes: every scene string the tests use is ASCII.
      const std::string s = v.get<std::string>();
      if (schema.contains("minLength") && s.size() < schema["minLength"].get<size_t>())
        errors.push_back(at + ": too short");
      if (schema.contains("maxLength") && s.size() > schema["maxLength"].get<size_t>())
        errors.push_back(at + ": too long");
      if (schema.contains("pattern") &&
          !std::regex_search(s, std::regex(schema["pattern"].get<std::string>())))
        errors.push_back(at + ": does not match the pattern");
    }
    if (v.is_array()) {
      if (schema.contains("minItems") && v.size() < schema["minItems"].get<size_t>())
        errors.push_back(at + ": too few items");
      if (schema.contains("maxItems") && v.size() > schema["maxItems"].get<size_t>())
        errors.push_back(at + ": too many items");
      if (schema.contains("items")) {
        for (size_t i = 0; i < v.size(); ++i)
          check(schema["items"], v[i], at + "[" + std::to_string(i) + "]");
      }
    }
    if (v.is_object()) {
      for (auto& [k, child] : v.items()) {
        if (schema.contains("properties") && schema["properties"].contains(k))
          check(schema["properties"][k], child, at + "." + k);
        else if (schema.value("additionalProperties", true) == false)
          errors.push_back(at + "." + k + ": not allowed");
      }
      if (schema.contains("required")) {
        for (const nlohmann::json& k : schema["required"])
          if (!v.contains(k.get<std::string>()))
            errors.push_back(at + ": missing " + k.get<std::string>());
      }
      if (schema.contains("dependentRequired")) {
        for (auto& [k, needs] : schema["dependentRequired"].items()) {
          if (!v.contains(k)) continue;
          for (const nlohmann::json& n : needs)
            if (!v.contains(n.get<std::string>()))
              errors.push_back(at + "." + k + ": needs " + n.get<std::string>());
        }
      }
    }
  }

private:
  static bool hasType(const nlohmann::json& v, const std::string& type) {
    if (type == "object") return v.is_object();
    if (type == "array") return v.is_array();
    if (type == "string") return v.is_string();
    if (type == "number") return v.is_number();
    if (type == "boolean") return v.is_boolean();
    // JSON Schema counts 360.0 as an integer; nlohmann keeps integers apart.
    if (type == "integer")
      return v.is_number_integer() ||
             (v.is_number_float() && v.get<double>() == std::floor(v.get<double>()));
    ADD_FAILURE() << "MiniValidator does not know the type '" << type << "'";
    return false;
  }
};

std::vector<std::string> schemaErrors(const nlohmann::json& instance) {
  static const nlohmann::json schema = nlohmann::json::parse(sceneJsonSchema());
  MiniValidator v;
  v.check(schema, instance, "$");
  return v.errors;
}

// The instance every schema default together describes: what an empty file means.
nlohmann::json defaultsOf(const nlohmann::json& schema) {
  if (schema.value("type", "") != "object" || schema.contains("default"))
    return schema.value("default", nlohmann::json());
  nlohmann::json out = nlohmann::json::object();
  for (auto& [key, prop] : schema["properties"].items()) {
    nlohmann::json d = defaultsOf(prop);
    // An optional section (weather.region) has no defaults: absent means absent.
    if (!d.is_null() && !(d.is_object() && d.empty())) out[key] = d;
  }
  return out;
}

TEST(SceneSchema, ValidatesTheScenesWeWrite) {
  for (const nlohmann::json& good :
       {sceneToJson(Scene()), sceneToJson(test::unusualScene()),
        sceneToJson(loadSceneFile(configs() / "default.yaml")), nlohmann::json::object(),
        nlohmann::json::parse(R"({"time": "2024-06-21T00:00Z/2024-06-22T00:00Z/15m"})"),
        nlohmann::json::parse(R"({"moon": {"azimuth": 1, "elevation": -2}})")}) {
    std::vector<std::string> errors = schemaErrors(good);
    EXPECT_TRUE(errors.empty()) << good.dump() << "\n" << (errors.empty() ? "" : errors[0]);
  }
  // The schema's defaults, put together, are the default scene.
  nlohmann::json schema = nlohmann::json::parse(sceneJsonSchema());
  EXPECT_EQ(defaultsOf(schema), sceneToJson(Scene()));
}

TEST(SceneSchema, RejectsWhatTheReaderRejects) {
  // Each document breaks one rule that the schema can express; the reader rejects it too.
  // (Not expressible in the schema: a positive step, end after start, increasing
  // sun_elevation, the frame limit; the reader's error tests cover those.)
  nlohmann::json key = sceneToJson(Scene())["lighting"]["palette"][0];
  nlohmann::json noFog = key;
  noFog.erase("fog_color");
  nlohmann::json extra = key;
  extra["fog_colour"] = {0, 0, 0};
  nlohmann::json shortColor = key;
  shortColor["sky_color"] = {0, 0};
  auto palette = [](const nlohmann::json& items) {
    return nlohmann::json{{"lighting", {{"palette", items}}}};
  };
  const nlohmann::json bad[] = {
      nlohmann::json::parse(R"({"output": {"width": 0}})"),
      nlohmann::json::parse(R"({"output": {"width": 1.5}})"),
      nlohmann::json::parse(R"({"output": {"name": ".hidden"}})"),
      nlohmann::json::parse(R"({"moon": {"azimuth": 10}})"),
      nlohmann::json::parse(R"({"moon": {"earthshine": 101}})"),
      nlohmann::json::parse(R"({"sun": {"disc_intensity": 1}})"),
      nlohmann::json::parse(R"({"sky": {"sky_color": [0, 0, 0]}})"),
      nlohmann::json::parse(R"({"time": "noon"})"),
      nlohmann::json::parse(R"({"time": 12})"),
      nlohmann::json::parse(R"({"time": "2024-06-21T00:00Z/2024-06-22T00:00Z"})"),
      nlohmann::json::parse(R"({"time": {"start": "2024-06-21T00:00Z", "step": "15m"}})"),
      nlohmann::json::parse(R"({"time": {"start": "2024-06-21T00:00Z",
          "end": "2024-06-22T00:00Z", "step": "1m", "zone": "Z"}})"),
      palette(nlohmann::json::array()),
      palette(nlohmann::json::parse(R"({"sun_elevation": 0})")),
      palette(nlohmann::json::array({1, 2})),
      palette(nlohmann::json::array({noFog})),
      palette(nlohmann::json::array({extra})),
      palette(nlohmann::json::array({shortColor})),
  };
  for (const nlohmann::json& doc : bad) {
    EXPECT_FALSE(schemaErrors(doc).empty()) << doc.dump();
    EXPECT_THROW(loadSceneText(doc.dump(), ConfigFormat::Json, "bad.json"), Error) << doc.dump();
  }
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
