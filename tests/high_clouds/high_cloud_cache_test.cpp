// The procedural bake's disk cache: a fresh HighCloudTextures finds what another one baked and
// loads it without baking, with the same textures; other settings bake anew under another key;
// a corrupt or truncated entry is baked again and replaced.
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/high_clouds/high_cloud_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::Fetched;
using test::HighCloudTest;
using test::proceduralScene;

TEST_F(HighCloudTest, FreshObjectLoadsTheBakeFromTheCache) {
  const Scene scene = proceduralScene("cirrus", 0.5, 128, 3);
  const Fetched baked = fetch(*make(), scene);
  ASSERT_TRUE(baked.activity.baked);
  EXPECT_TRUE(baked.activity.wroteCache);
  EXPECT_EQ(baked.activity.cacheFile.parent_path(), cache() / "high_clouds");
  EXPECT_EQ(baked.activity.cacheFile.extension(), ".exr");
  ASSERT_TRUE(fs::is_regular_file(baked.activity.cacheFile));

  const Fetched loaded = fetch(*make(), scene);
  EXPECT_FALSE(loaded.activity.baked);
  EXPECT_TRUE(loaded.activity.loadedCache);
  EXPECT_EQ(loaded.activity.cacheFile, baked.activity.cacheFile);
  for (const PassTiming& t : loaded.activity.bakeTimings) EXPECT_NE(t.name, "high_cloud_bake");
  // The cache stores half floats, the textures' own precision: equal to the bit.
  EXPECT_EQ(test::maxDifference(loaded.coefficients, baked.coefficients), 0.0f);
  EXPECT_EQ(test::maxDifference(loaded.normals, baked.normals), 0.0f);
  EXPECT_LE(test::maxDifference(loaded.coarse, baked.coarse), 1.0f / 2048);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(loaded.mean[c], baked.mean[c], 1e-4f);
}

TEST_F(HighCloudTest, OtherSettingsBakeUnderAnotherKey) {
  const Scene base = proceduralScene("cirrus", 0.5, 64, 3);
  auto textures = make();
  const Fetched first = fetch(*textures, base);
  ASSERT_TRUE(first.activity.baked);
  std::vector<Scene> variants(4, base);
  variants[0].highClouds.cover = 0.6;
  variants[1].highClouds.seed = 4;
  variants[2].highClouds.style = HighCloudStyle::Cirrocumulus;
  variants[3].highClouds.resolution = 128;
  for (const Scene& v : variants) {
    const Fetched f = fetch(*make(), v);  // a fresh object: only the disk cache could answer
    EXPECT_TRUE(f.activity.baked);
    EXPECT_NE(f.activity.cacheFile, first.activity.cacheFile);
  }
  // And back to the first settings: its entry is still there.
  EXPECT_TRUE(fetch(*make(), base).activity.loadedCache);
}

TEST_F(HighCloudTest, CorruptCacheEntryIsBakedAgain) {
  const Scene scene = proceduralScene("cirrostratus", 0.7, 64);
  const Fetched baked = fetch(*make(), scene);
  ASSERT_TRUE(baked.activity.baked);
  const fs::path file = baked.activity.cacheFile;
  const auto bytes = fs::file_size(file);

  { std::ofstream(file, std::ios::binary | std::ios::trunc) << "this is not an EXR file"; }
  Fetched f = fetch(*make(), scene);
  EXPECT_TRUE(f.activity.baked);
  EXPECT_FALSE(f.activity.loadedCache);
  EXPECT_EQ(test::maxDifference(f.coefficients, baked.coefficients), 0.0f);
  EXPECT_EQ(fs::file_size(file), bytes);  // rewritten whole

  fs::resize_file(file, bytes / 2);  // truncated
  f = fetch(*make(), scene);
  EXPECT_TRUE(f.activity.baked);
  EXPECT_TRUE(fetch(*make(), scene).activity.loadedCache);
}

TEST_F(HighCloudTest, UnwritableCacheFolderStillRenders) {
  // A file where the cache folder should be: the bake works, only the entry is not written.
  { std::ofstream(cache() / "high_clouds") << "in the way"; }
  const Fetched f = fetch(*make(), proceduralScene("cirrus", 0.5, 64));
  EXPECT_TRUE(f.activity.baked);
  EXPECT_FALSE(f.activity.wroteCache);
  EXPECT_GT(1.0f - f.mean.z, 0.05f);
}

}  // namespace
}  // namespace sky
