// Dataset specs: read strictly like a scene (file, line and key path in every error), their
// schema checked in, and each sample's scene from (seed, index) alone.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/dataset/dataset_spec.h"
#include "engine/scene/scene_io.h"

namespace sky {
namespace {
namespace fs = std::filesystem;

class DatasetSpecTest : public ::testing::Test {
protected:
  void SetUp() override {
    mDir = fs::temp_directory_path() / ("dataset-spec-" + std::to_string(::getpid()));
    fs::create_directories(mDir);
  }
  void TearDown() override { fs::remove_all(mDir); }
  fs::path write(const std::string& text, const std::string& name = "spec.yaml") {
    std::ofstream(mDir / name) << text;
    return mDir / name;
  }
  // The one-line error loading `text` gives.
  std::string error(const std::string& text) {
    try {
      loadDatasetSpec(write(text));
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::BadInput);
      return e.what();
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return "";
  }
  fs::path mDir;
};

constexpr const char* kSpec = R"(count: 50
seed: 3
output: {width: 32, height: 18}
camera:
  latitude: [40, 50]
  heading: [0, 360]
  pitch: [-5, 30]
time:
  from: 2024-06-21T04:00:00Z
  to: 2024-06-21T20:00:00Z
weather:
  cover_low: [0.1, 0.9]
  cloud_types: [cumulus, stratus]
  seed: [1, 100]
)";

TEST_F(DatasetSpecTest, ReadsAWholeSpec) {
  const DatasetSpec s = loadDatasetSpec(write(kSpec));
  EXPECT_EQ(s.count, 50);
  EXPECT_EQ(s.seed, 3);
  EXPECT_EQ(s.output.width, 32);
  ASSERT_TRUE(s.camera.latitude.has_value());
  EXPECT_EQ(*s.camera.latitude, glm::dvec2(40, 50));
  EXPECT_FALSE(s.camera.altitudeM.has_value());
  ASSERT_EQ(s.weather.cloudTypes.size(), 2u);
  EXPECT_EQ(s.weather.cloudTypes[1], CloudType::Stratus);
  EXPECT_TRUE(s.output.perception);
  EXPECT_EQ(s.baseDir, mDir);
}

TEST_F(DatasetSpecTest, ErrorsSayFileLineAndKey) {
  std::string e = error("count: 5\ncamera:\n  latitud: [1, 2]\n");
  EXPECT_NE(e.find("spec.yaml:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("camera.latitud"), std::string::npos) << e;
  EXPECT_NE(e.find("latitude"), std::string::npos) << "a suggestion: " << e;
  e = error("camera:\n  pitch: [0, 95]\n");
  EXPECT_NE(e.find("camera.pitch[1]"), std::string::npos) << e;
  e = error("weather:\n  cloud_types: [cumulus, nimbus]\n");
  EXPECT_NE(e.find("weather.cloud_types[1]"), std::string::npos) << e;
  e = error("weather:\n  cloud_types: []\n");
  EXPECT_NE(e.find("empty list"), std::string::npos) << e;
  e = error("weather:\n  files: [a.grib2]\n  cover_low: [0, 1]\n");
  EXPECT_NE(e.find("not both"), std::string::npos) << e;
  e = error("time:\n  from: 2024-06-21T04:00:00Z\n");
  EXPECT_NE(e.find("time"), std::string::npos) << e;
  e = error("time:\n  from: 2024-06-21T04:00:00Z\n  to: 2024-06-20T04:00:00Z\n");
  EXPECT_NE(e.find("before from"), std::string::npos) << e;
  e = error("count: 0\n");
  EXPECT_NE(e.find("count"), std::string::npos) << e;
}

TEST_F(DatasetSpecTest, EachSampleComesFromSeedAndIndexAlone) {
  const DatasetSpec spec = loadDatasetSpec(write(kSpec));
  const Scene base;
  // The same sample twice, in any order, is the same scene.
  const Scene a = datasetSampleScene(spec, base, 17);
  datasetSampleScene(spec, base, 3);
  EXPECT_EQ(datasetSampleScene(spec, base, 17), a);
  EXPECT_EQ(a.output.name, "sample_000017");
  EXPECT_EQ(a.output.width, 32);
  EXPECT_TRUE(a.output.perception);
  EXPECT_FALSE(a.time.isRange());
  // Each draw inside its range; the keys the spec leaves alone keep the base's values.
  bool types[2] = {false, false};
  double minHeading = 360, maxHeading = 0;
  for (int k = 0; k < spec.count; ++k) {
    const Scene s = datasetSampleScene(spec, base, k);
    EXPECT_GE(s.camera.latitude, 40.0);
    EXPECT_LE(s.camera.latitude, 50.0);
    EXPECT_GE(s.camera.pitch, -5.0);
    EXPECT_LE(s.camera.pitch, 30.0);
    EXPECT_EQ(s.camera.longitude, base.camera.longitude);
    EXPECT_EQ(s.camera.altitudeM, base.camera.altitudeM);
    EXPECT_GE(s.weather.seed, 1);
    EXPECT_LE(s.weather.seed, 100);
    const double t = s.time.start.secondsSince(*IsoTime::parse("2024-06-21T04:00:00Z"));
    EXPECT_GE(t, 0.0);
    EXPECT_LE(t, 16 * 3600.0);
    EXPECT_EQ(t, std::floor(t)) << "whole seconds";
    types[s.weather.cloudType == CloudType::Stratus] = true;
    minHeading = std::min(minHeading, s.camera.heading);
    maxHeading = std::max(maxHeading, s.camera.heading);
  }
  EXPECT_TRUE(types[0] && types[1]) << "both cloud types drawn in 50 samples";
  EXPECT_LT(minHeading, 60.0);
  EXPECT_GT(maxHeading, 300.0);
  // Another seed draws other scenes; a range added leaves the other keys' draws as they were.
  DatasetSpec other = spec;
  other.seed = 4;
  EXPECT_NE(datasetSampleScene(other, base, 17).camera.heading, a.camera.heading);
  DatasetSpec more = spec;
  more.camera.verticalFov = glm::dvec2(30, 90);
  const Scene b = datasetSampleScene(more, base, 17);
  EXPECT_EQ(b.camera.heading, a.camera.heading);
  EXPECT_EQ(b.weather.coverLow, a.weather.coverLow);
  EXPECT_NE(b.camera.verticalFov, a.camera.verticalFov);
}

TEST_F(DatasetSpecTest, ASamplesSceneFileRendersTheSameScene) {
  const DatasetSpec spec = loadDatasetSpec(write(kSpec));
  const Scene s = datasetSampleScene(spec, Scene(), 9);
  Scene back = loadSceneText(writeScene(s, ConfigFormat::Yaml), ConfigFormat::Yaml, "sample");
  back.baseDir = s.baseDir;
  EXPECT_EQ(back, s);
}

TEST_F(DatasetSpecTest, TheChecksumTellsSpecsApart) {
  const DatasetSpec a = loadDatasetSpec(write(kSpec));
  DatasetSpec b = a;
  EXPECT_EQ(datasetSpecChecksum(a, Scene()), datasetSpecChecksum(b, Scene()));
  b.count = 51;
  EXPECT_NE(datasetSpecChecksum(a, Scene()), datasetSpecChecksum(b, Scene()));
  Scene other;
  other.ground.albedo = glm::vec3(0.3f);
  EXPECT_NE(datasetSpecChecksum(a, Scene()), datasetSpecChecksum(a, other));
}

TEST(DatasetSchema, CheckedInFileMatchesTheDescription) {
  const fs::path file = fs::path(std::getenv("SKY_DATA_DIR")) / "configs" / "schema" /
                        "dataset.schema.json";
  const std::string generated = datasetJsonSchema();
  // SKY_UPDATE_SCHEMA=1 test_dataset rewrites the file.
  if (const char* update = std::getenv("SKY_UPDATE_SCHEMA"); update && std::string(update) == "1")
    writeFileAtomic(file, generated);
  EXPECT_EQ(fs::exists(file) ? readTextFile(file) : std::string(), generated)
      << file.string() << " is out of date: `skyrender schema --dataset > "
      << "configs/schema/dataset.schema.json`";
}

}  // namespace
}  // namespace sky

namespace sky {
namespace {

TEST(DatasetExamples, EveryShippedSpecAndItsBaseSceneLoad) {
  const fs::path dir = fs::path(std::getenv("SKY_DATA_DIR")) / "configs" / "datasets";
  int specs = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const DatasetSpec spec = loadDatasetSpec(e.path());
    const Scene base = datasetBaseScene(spec, Scene());
    for (int64_t k = 0; k < std::min<int64_t>(spec.count, 8); ++k)
      EXPECT_EQ(datasetSampleScene(spec, base, k).output.width, spec.output.width);
    ++specs;
  }
  EXPECT_GE(specs, 1);
}

}  // namespace
}  // namespace sky
