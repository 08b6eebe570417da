// The bake of both models' textures: sizes and format, tiling of every channel of every
// texture, value ranges and means, frequencies ordered within each texture, the CPU copies
// equal to the GPU textures, and what addTo reports.
#include <cmath>
#include <string>

#include "tests/cloud_noise/cloud_noise_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::CloudNoiseTest;
using test::Fetched;
using test::NoiseTexture;
using test::statsOf;

bool hasTiming(const CloudNoise::Activity& a, const std::string& name) {
  for (const PassTiming& t : a.bakeTimings)
    if (t.name == name) return true;
  return false;
}

// What both models share: the bake ran once, outside the caller's graph; the CPU copies are
// the GPU textures; every channel tiles; the shape's G, B, A and the detail's R, G, B grow in
// frequency (each at least 1.4 times the neighbour difference of the last); the detail's A
// is Lu (14)'s fbm of its R, G, B; the curl texture spans its range with a zero-mean z.
void checkBake(const Fetched& f, const CloudNoise& noise, uint32_t detailSize) {
  EXPECT_TRUE(f.activity.baked);
  EXPECT_FALSE(f.activity.loadedCache);
  EXPECT_TRUE(f.graphPasses.empty()) << "the bake runs in a graph of its own";
  for (const char* pass : {"cloud_noise_shape", "cloud_noise_detail", "cloud_noise_curl"})
    EXPECT_TRUE(hasTiming(f.activity, pass)) << pass;
  EXPECT_GT(f.activity.wallMs, 0.0);

  ASSERT_EQ(f.shape.size, CLOUD_NOISE_SHAPE_SIZE);
  ASSERT_EQ(f.shape.dims, 3u);
  ASSERT_EQ(f.detail.size, detailSize);
  ASSERT_EQ(f.detail.dims, 3u);
  ASSERT_EQ(f.curl.size, CLOUD_NOISE_CURL_SIZE);
  ASSERT_EQ(f.curl.dims, 2u);
  EXPECT_EQ(noise.shapeVolume().size, f.shape.size);
  EXPECT_TRUE(noise.shapeVolume().rgba == f.shape.rgba) << "CPU copy differs from the GPU";
  EXPECT_EQ(noise.detailVolume().size, f.detail.size);
  EXPECT_TRUE(noise.detailVolume().rgba == f.detail.rgba) << "CPU copy differs from the GPU";

  for (int c = 0; c < 4; ++c) {
    test::expectTiles(f.shape, c, "shape");
    test::expectSpansTheRange(f.shape, c, "shape");
    test::expectTiles(f.detail, c, "detail");
    if (c < 3) test::expectSpansTheRange(f.detail, c, "detail");
  }
  for (int c = 0; c < 3; ++c) {
    test::expectTiles(f.curl, c, "curl");
    const test::ChannelStats s = statsOf(f.curl, c);
    EXPECT_LT(s.min, 0.15) << "curl " << c;
    EXPECT_GT(s.max, 0.85) << "curl " << c;
    EXPECT_LT(s.clipped, 0.02) << "curl " << c;
  }
  // d psi_y/dx - d psi_x/dy of a potential periodic in x and y sums to zero over the tile.
  EXPECT_NEAR(statsOf(f.curl, 2).mean, 0.5, 0.01);
  EXPECT_EQ(statsOf(f.curl, 3).min, 1.0) << "curl A is 1";

  for (int c = 1; c < 3; ++c) {
    SCOPED_TRACE("channel " + std::to_string(c));
    EXPECT_GT(statsOf(f.shape, c + 1).neighbour(), 1.4 * statsOf(f.shape, c).neighbour());
    EXPECT_GT(statsOf(f.detail, c).neighbour(), 1.4 * statsOf(f.detail, c - 1).neighbour());
  }
  // R is the shape's low-frequency channel.
  EXPECT_LT(statsOf(f.shape, 0).neighbour(), statsOf(f.shape, 1).neighbour());

  // Detail A = Lu (14) fbm(R, G, B) with Lu (11)'s weights, up to the bytes' rounding.
  double worst = 0;
  for (size_t i = 0; i < f.detail.rgba.size(); i += 4) {
    const double r = f.detail.rgba[i] / 255.0, g = f.detail.rgba[i + 1] / 255.0,
                 b = f.detail.rgba[i + 2] / 255.0, a = f.detail.rgba[i + 3] / 255.0;
    worst = std::max(worst, std::abs(a - (0.625 * r + 0.25 * g + 0.125 * b)));
  }
  EXPECT_LE(worst, 1.01 / 255);
}

TEST_F(CloudNoiseTest, Lu2023TexturesTileSpanTheirRangeAndOrderTheirFrequencies) {
  auto noise = make();
  const Fetched f = fetch(*noise, CloudModel::Lu2023);
  checkBake(f, *noise, CLOUD_NOISE_DETAIL_SIZE_LU2023);
  EXPECT_TRUE(f.activity.wroteCache);
}

TEST_F(CloudNoiseTest, Tang2019TexturesTileSpanTheirRangeAndOrderTheirFrequencies) {
  // A file where the cache folder should be: the bake works, only the entry is not written.
  { std::ofstream(cache() / "cloud_noise") << "in the way"; }
  auto noise = make();
  const Fetched f = fetch(*noise, CloudModel::Tang2019);
  checkBake(f, *noise, CLOUD_NOISE_DETAIL_SIZE_TANG2019);
  EXPECT_FALSE(f.activity.wroteCache);
  EXPECT_FALSE(fs::is_regular_file(f.activity.cacheFile));
}

// The tiling check itself: a smooth texture whose period is not the tile's (1.5 waves a tile
// along x, whole waves along y and z) has a seam at the x edge only, and the check sees it.
TEST(CloudNoiseTilingCheck, SeamIsSeen) {
  NoiseTexture t{32, 3, std::vector<uint8_t>(32 * 32 * 32 * 4)};
  for (uint32_t z = 0; z < 32; ++z)
    for (uint32_t y = 0; y < 32; ++y)
      for (uint32_t x = 0; x < 32; ++x) {
        const double w = 2 * M_PI / 32;
        const double v = 0.5 + 0.2 * std::cos(1.5 * w * (x + 0.5)) +
                         0.1 * std::sin(w * (y + 0.5)) * std::cos(2 * w * (z + 0.5));
        t.rgba[t.index(x, y, z)] = uint8_t(std::lround(v * 255));
      }
  const test::ChannelStats s = statsOf(t, 0);
  EXPECT_GT(test::edgeRoughness(s, 0).first, 3.0);
  EXPECT_GT(test::edgeRoughness(s, 0).second, 3.0);
  EXPECT_LT(test::edgeRoughness(s, 1).first, 1.3);
  EXPECT_LT(test::edgeRoughness(s, 2).first, 1.3);
}

}  // namespace
}  // namespace sky
