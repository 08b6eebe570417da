// The disk cache: a fresh CloudNoise loads what another one baked without baking, with the
// same bytes; the same model again does nothing; a model switch loads or bakes the other
// model; a damaged entry is baked again, to the same bytes (the bake is deterministic), and
// the entry reader rejects every kind of damage without an error.
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/files.h"
#include "passes/cloud_noise/cloud_noise_cache.h"
#include "tests/cloud_noise/cloud_noise_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::CloudNoiseTest;
using test::Fetched;

void expectSameTextures(const Fetched& a, const Fetched& b) {
  EXPECT_TRUE(a.shape.rgba == b.shape.rgba) << "shape differs";
  EXPECT_TRUE(a.detail.rgba == b.detail.rgba) << "detail differs";
  EXPECT_TRUE(a.curl.rgba == b.curl.rgba) << "curl differs";
}

TEST_F(CloudNoiseTest, CacheHitLoadsWithoutBakingAndModelsSwitch) {
  const Fetched baked = fetch(*make(), CloudModel::Lu2023);
  ASSERT_TRUE(baked.activity.baked);
  ASSERT_TRUE(baked.activity.wroteCache);
  auto noise = make();
  EXPECT_EQ(baked.activity.cacheFile,
            cache() / "cloud_noise" / (noise->cacheKey(CloudModel::Lu2023) + ".bin"));
  ASSERT_TRUE(fs::is_regular_file(baked.activity.cacheFile));
  EXPECT_EQ(noise->cacheKey(CloudModel::Lu2023).size(), 16u);
  EXPECT_NE(noise->cacheKey(CloudModel::Lu2023), noise->cacheKey(CloudModel::Tang2019));

  const Fetched loaded = fetch(*noise, CloudModel::Lu2023);
  EXPECT_FALSE(loaded.activity.baked);
  EXPECT_TRUE(loaded.activity.loadedCache);
  EXPECT_TRUE(loaded.activity.bakeTimings.empty());
  expectSameTextures(loaded, baked);
  EXPECT_TRUE(noise->shapeVolume().rgba == baked.shape.rgba);
  EXPECT_TRUE(noise->detailVolume().rgba == baked.detail.rgba);

  // The same model again: only imported.
  const Fetched again = fetch(*noise, CloudModel::Lu2023);
  EXPECT_FALSE(again.activity.baked);
  EXPECT_FALSE(again.activity.loadedCache);
  expectSameTextures(again, baked);

  // Another model bakes into its own entry (another detail size), and back loads the first.
  const Fetched tang = fetch(*noise, CloudModel::Tang2019);
  EXPECT_TRUE(tang.activity.baked);
  EXPECT_NE(tang.activity.cacheFile, baked.activity.cacheFile);
  EXPECT_EQ(tang.detail.size, CLOUD_NOISE_DETAIL_SIZE_TANG2019);
  EXPECT_EQ(noise->detailVolume().size, CLOUD_NOISE_DETAIL_SIZE_TANG2019);
  EXPECT_FALSE(tang.shape.rgba == baked.shape.rgba);
  const Fetched back = fetch(*noise, CloudModel::Lu2023);
  EXPECT_TRUE(back.activity.loadedCache);
  expectSameTextures(back, baked);
  EXPECT_EQ(noise->detailVolume().size, CLOUD_NOISE_DETAIL_SIZE_LU2023);
}

TEST_F(CloudNoiseTest, DamagedCacheEntryIsBakedAgainToTheSameBytes) {
  const Fetched baked = fetch(*make(), CloudModel::Lu2023);
  ASSERT_TRUE(baked.activity.wroteCache);
  const fs::path file = baked.activity.cacheFile;
  const auto bytes = fs::file_size(file);

  // One flipped byte in the middle of the shape volume: only the checksum can tell.
  {
    std::fstream io(file, std::ios::binary | std::ios::in | std::ios::out);
    io.seekg(std::streamoff(bytes / 2));
    char c = 0;
    io.get(c);
    io.seekp(std::streamoff(bytes / 2));
    io.put(char(c ^ 0x10));
  }
  const Fetched rebaked = fetch(*make(), CloudModel::Lu2023);
  EXPECT_TRUE(rebaked.activity.baked);
  EXPECT_FALSE(rebaked.activity.loadedCache);
  EXPECT_TRUE(rebaked.activity.wroteCache);
  expectSameTextures(rebaked, baked);  // deterministic: a second bake gives the same bytes
  EXPECT_EQ(fs::file_size(file), bytes);

  // Truncated: a miss, not an error (every kind of damage is covered without a bake in
  // ReaderRejectsEveryDamagedEntry).
  fs::resize_file(file, bytes / 2);
  EXPECT_FALSE(cloud_noise::readCacheEntry(file, make()->cacheKey(CloudModel::Lu2023),
                                           CLOUD_NOISE_SHAPE_SIZE, CLOUD_NOISE_DETAIL_SIZE_LU2023,
                                           CLOUD_NOISE_CURL_SIZE));
}

TEST(CloudNoiseCache, ReaderRejectsEveryDamagedEntry) {
  const fs::path dir =
      fs::temp_directory_path() / ("sky-cloud-noise-reader-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const fs::path file = dir / "sub" / "entry.bin";
  cloud_noise::CacheEntry entry;
  entry.shape = {4, std::vector<uint8_t>(4 * 4 * 4 * 4)};
  entry.detail = {2, std::vector<uint8_t>(2 * 2 * 2 * 4)};
  entry.curlSize = 4;
  entry.curl.resize(4 * 4 * 4);
  for (size_t i = 0; i < entry.shape.rgba.size(); ++i) entry.shape.rgba[i] = uint8_t(i * 7);
  for (size_t i = 0; i < entry.detail.rgba.size(); ++i) entry.detail.rgba[i] = uint8_t(i * 5);
  for (size_t i = 0; i < entry.curl.size(); ++i) entry.curl[i] = uint8_t(i * 3);
  const std::string key = "0123456789abcdef";

  auto read = [&](const std::string& k = "0123456789abcdef", uint32_t shape = 4) {
    return cloud_noise::readCacheEntry(file, k, shape, 2, 4);
  };
  EXPECT_FALSE(read()) << "absent";
  cloud_noise::writeCacheEntry(file, key, entry);  // creates the folder
  std::optional<cloud_noise::CacheEntry> back = read();
  ASSERT_TRUE(back);
  EXPECT_EQ(back->shape.rgba, entry.shape.rgba);
  EXPECT_EQ(back->detail.rgba, entry.detail.rgba);
  EXPECT_EQ(back->curl, entry.curl);
  EXPECT_FALSE(read("fedcba9876543210")) << "another key";
  EXPECT_FALSE(read(key, 8)) << "another size";

  const std::vector<uint8_t> good = readBinaryFile(file);
  auto rewrite = [&](const std::vector<uint8_t>& bytes) {
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  };
  for (size_t at : {size_t(0), size_t(9), good.size() / 2, good.size() - 1}) {
    std::vector<uint8_t> bad = good;
    bad[at] ^= 0x01;
    rewrite(bad);
    EXPECT_FALSE(read()) << "byte " << at << " flipped";
  }
  std::vector<uint8_t> bad(good.begin(), good.end() - 1);
  rewrite(bad);
  EXPECT_FALSE(read()) << "truncated by one byte";
  bad = good;
  bad.push_back(0);
  rewrite(bad);
  EXPECT_FALSE(read()) << "one byte too long";
  rewrite({});
  EXPECT_FALSE(read()) << "empty";
  rewrite(good);
  EXPECT_TRUE(read()) << "restored";
  fs::remove(file);
  fs::create_directory(file);
  EXPECT_FALSE(read()) << "a folder";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sky
