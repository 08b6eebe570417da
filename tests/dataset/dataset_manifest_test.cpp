// The manifest: shards, a last line a killed run left half-written, and merging shards with
// what is missing or present twice.
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/dataset/dataset_manifest.h"

namespace sky {
namespace {
namespace fs = std::filesystem;

class ManifestTest : public ::testing::Test {
protected:
  void SetUp() override {
    mDir = fs::temp_directory_path() / ("dataset-manifest-" + std::to_string(::getpid()));
    fs::remove_all(mDir);
    fs::create_directories(mDir / "a");
    fs::create_directories(mDir / "b");
  }
  void TearDown() override { fs::remove_all(mDir); }
  static nlohmann::ordered_json line(int64_t index, const std::string& spec = "s1") {
    return {{"index", index},
            {"count", 6},
            {"spec", spec},
            {"files", {{"exr", {{"name", "sample_" + std::to_string(index) + ".exr"}}}}}};
  }
  fs::path mDir;
};

TEST(Shard, ParsesAndSharesOutTheWork) {
  const Shard s = parseShard("2/3", "--shard");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 3);
  EXPECT_TRUE(s.takes(1));
  EXPECT_TRUE(s.takes(4));
  EXPECT_FALSE(s.takes(0));
  // Every item in exactly one shard.
  for (int64_t k = 0; k < 20; ++k) {
    int n = 0;
    for (int i = 1; i <= 3; ++i) n += parseShard(std::to_string(i) + "/3", "--shard").takes(k);
    EXPECT_EQ(n, 1);
  }
  for (const char* bad : {"0/2", "3/2", "1/0", "1", "a/2", "1/2x", "-1/2", "1/-2", ""}) {
    try {
      parseShard(bad, "--shard");
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--shard"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(manifestPath("d", Shard{}), fs::path("d/manifest.jsonl"));
  EXPECT_EQ(manifestPath("d", Shard{2, 4}), fs::path("d/manifest.2-of-4.jsonl"));
}

TEST_F(ManifestTest, AHalfWrittenLastLineIsNoLineAndIsCutOff) {
  const fs::path m = mDir / "a" / "manifest.jsonl";
  {
    ManifestWriter w(m);
    w.append(line(0));
    w.append(line(1));
  }
  std::ofstream(m, std::ios::app) << R"({"index": 2, "cou)";
  ManifestLines r = readManifest(m);
  EXPECT_EQ(r.lines.size(), 2u);
  EXPECT_TRUE(r.hasTorn);
  {
    ManifestWriter w(m);  // cuts it off
    w.append(line(2));
  }
  r = readManifest(m);
  ASSERT_EQ(r.lines.size(), 3u);
  EXPECT_FALSE(r.hasTorn);
  EXPECT_EQ(r.lines[2]["index"], 2);
  // A broken complete line is an error naming the file and the line.
  std::ofstream(m, std::ios::app) << "not json\n";
  try {
    readManifest(m);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("manifest.jsonl:4"), std::string::npos) << e.what();
  }
}

TEST_F(ManifestTest, MergeJoinsShardsAndReportsWhatIsMissingOrTwice) {
  {
    ManifestWriter one(manifestPath(mDir / "a", Shard{1, 2}));
    one.append(line(0));
    one.append(line(2));
    ManifestWriter two(manifestPath(mDir / "b", Shard{2, 2}));
    two.append(line(1));
    two.append(line(2));  // rendered twice
  }
  const MergeResult r = mergeManifests({mDir / "a", mDir / "b"});
  EXPECT_EQ(r.expected, 6);
  EXPECT_EQ(r.samples.size(), 3u);
  EXPECT_EQ(r.missing, (std::vector<int64_t>{3, 4, 5}));
  ASSERT_EQ(r.duplicates.size(), 1u);
  EXPECT_EQ(r.duplicates.at(2), 2);
  // The other folder's files are named from the first.
  EXPECT_EQ(r.samples.at(1)["files"]["exr"]["name"], "../b/sample_1.exr");
  EXPECT_EQ(r.samples.at(0)["files"]["exr"]["name"], "sample_0.exr");
  EXPECT_EQ(indexRanges({0, 1, 2, 5, 7, 8}), "0-2, 5, 7-8");
}

TEST_F(ManifestTest, MergeRefusesTwoSpecs) {
  {
    ManifestWriter one(manifestPath(mDir / "a", Shard{1, 2}));
    one.append(line(0, "s1"));
    ManifestWriter two(manifestPath(mDir / "a", Shard{2, 2}));
    two.append(line(1, "s2"));
  }
  try {
    mergeManifests({mDir / "a"});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("another dataset spec"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sky
