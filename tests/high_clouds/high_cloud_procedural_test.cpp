// HighCloudTextures with source "procedural": cover 0 is a clear texture without a bake; the
// mean opacity grows with cover; the textures tile; the styles differ in the ways they are
// meant to (cirrus fibres running along the tile, cirrocumulus ripples,
// cirrostratus veil); bakes are
// deterministic per seed; channels stay in range; the cover map masks the cover; progress is
// reported; and an unchanged scene adds nothing.
#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "tests/high_clouds/high_cloud_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::Fetched;
using test::HighCloudTest;
using test::proceduralScene;

const char* const kStyles[] = {"cirrus", "cirrostratus", "cirrocumulus"};

std::vector<double> opacityField(const Fetched& f) {
  std::vector<double> a(size_t(f.size) * f.size);
  for (uint32_t y = 0; y < f.size; ++y)
    for (uint32_t x = 0; x < f.size; ++x) a[size_t(y) * f.size + x] = f.opacity(x, y);
  return a;
}

// Within the block of `block` x `block` texels at (bx, by): the opacity's autocorrelation at a
// shift of `lag` texels along u, v and the two diagonals, about the block's own mean.
std::vector<double> blockAutocorrelations(const Fetched& f, int bx, int by, int block, int lag) {
  const std::vector<double> a = opacityField(f);
  const int n = int(f.size);
  auto at = [&](int x, int y) { return a[size_t(((y % n) + n) % n * n + ((x % n) + n) % n)]; };
  double mean = 0;
  for (int y = by; y < by + block; ++y)
    for (int x = bx; x < bx + block; ++x) mean += at(x, y);
  mean /= double(block * block);
  std::vector<double> out;
  const int d = static_cast<int>(std::lround(lag / std::sqrt(2.0)));
  for (const auto& [dx, dy] : {std::pair{lag, 0}, std::pair{0, lag}, std::pair{d, d},
                               std::pair{d, -d}}) {
    double num = 0, den = 0;
    for (int y = by; y < by + block; ++y)
      for (int x = bx; x < bx + block; ++x) {
        const double v = at(x, y) - mean;
        num += v * (at(x + dx, y + dy) - mean);
        den += v * v;
      }
    out.push_back(den > 0 ? num / den : 0.0);
  }
  return out;
}

// Power of the opacity's vertical (north-south) frequency k, cycles per tile, over columns.
double verticalPower(const Fetched& f, int k) {
  const std::vector<double> a = opacityField(f);
  const int n = int(f.size);
  double power = 0;
  for (int x = 0; x < n; ++x) {
    std::complex<double> s = 0;
    for (int y = 0; y < n; ++y)
      s += a[size_t(y * n + x)] * std::polar(1.0, -2.0 * M_PI * k * y / n);
    power += std::norm(s);
  }
  return power / n;
}

// How much the wrap-around seam stands out: the mean |difference| across it (the last column
// against the first, or with `vertical` the last row against the first) over the mean
// |difference| of the two neighbour pairs on each side of it. About 1 where the texture
// continues smoothly across the edge, large where it jumps. (Exact periodicity of the noise,
// cell by cell, is checked by noise_kernel_test.cpp.)
double seamJump(const Fetched& f, const std::vector<float>& image, int c, bool vertical) {
  const uint32_t n = f.size;
  auto at = [&](uint32_t i, uint32_t j) {
    return double(vertical ? f.at(image, j, i % n, c) : f.at(image, i % n, j, c));
  };
  double seam = 0, beside = 0;
  for (uint32_t j = 0; j < n; ++j) {
    seam += std::abs(at(n, j) - at(n - 1, j));
    for (uint32_t i : {n - 3, n - 2, n, n + 1}) beside += std::abs(at(i + 1, j) - at(i, j)) / 4;
  }
  return seam / beside;
}

// The texture cut to its western and northern three quarters: it no longer tiles.
Fetched cutToThreeQuarters(const Fetched& f) {
  Fetched cut = f;
  cut.size = f.size * 3 / 4;
  cut.coefficients.clear();
  for (uint32_t y = 0; y < cut.size; ++y)
    for (uint32_t x = 0; x < cut.size; ++x)
      for (int c = 0; c < 4; ++c) cut.coefficients.push_back(f.at(f.coefficients, x, y, c));
  return cut;
}

TEST_F(HighCloudTest, CoverZeroIsAClearTextureWithoutABake) {
  auto textures = make();
  const Fetched f = fetch(*textures, proceduralScene("cirrus", 0.0));
  EXPECT_FALSE(f.activity.baked);
  EXPECT_FALSE(f.activity.loadedCache);
  EXPECT_TRUE(f.activity.bakeTimings.empty());
  EXPECT_TRUE(f.activity.cacheFile.empty());
  EXPECT_EQ(f.size, 16u);
  EXPECT_EQ(f.coarseSize, 4u);
  for (const std::vector<float>* image : {&f.coefficients, &f.coarse, &f.normals})
    for (size_t i = 0; i < image->size(); i += 4) {
      const bool normals = image == &f.normals;
      ASSERT_EQ((*image)[i], 0.0f);
      ASSERT_EQ((*image)[i + 1], 0.0f);
      ASSERT_EQ((*image)[i + 2], 1.0f);
      ASSERT_EQ((*image)[i + 3], 0.0f) << (normals ? "normals" : "coefficients");
    }
  EXPECT_EQ(f.mean, glm::vec4(0, 0, 1, 0));
  EXPECT_TRUE(fs::is_empty(cache()));
}

TEST_F(HighCloudTest, MeanOpacityGrowsWithCover) {
  auto textures = make();
  for (const char* style : kStyles) {
    SCOPED_TRACE(style);
    double last = 0.0;
    for (double cover : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      const Fetched f = fetch(*textures, proceduralScene(style, cover, 64));
      ASSERT_TRUE(f.activity.baked);
      double opacity = 0;
      for (uint32_t y = 0; y < f.size; ++y)
        for (uint32_t x = 0; x < f.size; ++x) opacity += f.opacity(x, y);
      opacity /= double(f.size) * f.size;
      EXPECT_NEAR(1.0 - f.mean.z, opacity, 1e-3) << "cover " << cover;
      EXPECT_GT(opacity, last + 0.01) << "cover " << cover;
      last = opacity;
    }
  }
}

TEST_F(HighCloudTest, TexturesTileSeamlessly) {
  auto textures = make();
  for (const char* style : kStyles) {
    SCOPED_TRACE(style);
    const Fetched f = fetch(*textures, proceduralScene(style, 0.6));
    for (bool vertical : {false, true}) {
      SCOPED_TRACE(vertical ? "north-south seam" : "east-west seam");
      EXPECT_LT(seamJump(f, f.coefficients, 2, vertical), 1.5);
      EXPECT_LT(seamJump(f, f.normals, vertical ? 1 : 0, vertical), 1.5);
    }
  }
}

// The check above must be able to fail: cut to three quarters, a texture no longer tiles and
// its seam stands out (the smooth veil in both directions, the cirrus fibres across either).
TEST_F(HighCloudTest, SeamCheckCatchesANonTilingTexture) {
  auto textures = make();
  const Fetched veil = cutToThreeQuarters(fetch(*textures, proceduralScene("cirrostratus", 0.6)));
  EXPECT_GT(seamJump(veil, veil.coefficients, 2, false), 3.0);
  EXPECT_GT(seamJump(veil, veil.coefficients, 2, true), 3.0);
  const Fetched cirrus = cutToThreeQuarters(fetch(*textures, proceduralScene("cirrus", 0.6)));
  // Tiling textures stay below 1.5 (above); fibres crossing a cut in both directions jump.
  EXPECT_GT(seamJump(cirrus, cirrus.coefficients, 2, false), 2.0);
  EXPECT_GT(seamJump(cirrus, cirrus.coefficients, 2, true), 2.0);
}

TEST_F(HighCloudTest, CirrusFibresRunAlongTheTile) {
  // In 8 x 8 blocks of the tile, the opacity's autocorrelation at a 4-texel shift along u, v
  // and the diagonals: cirrus is fibrous in each block (its best direction correlates well
  // above its worst), and the fibres run along u, the axis the draw lays downwind, wandering
  // a little: u leads in most blocks and v, across the wind, in almost none. Measured: u, v
  // and the diagonals lead in 46, 1, 8 and 9 of the 64 blocks, median spread 0.50. Issue 30's
  // cirrus, whose flow turned right round over the tile, gave 30, 11, 14 and 9: it fails.
  auto textures = make();
  const Fetched f = fetch(*textures, proceduralScene("cirrus", 0.5));
  const int block = int(f.size) / 8;
  std::vector<double> spread;
  int leads[4] = {0, 0, 0, 0};
  for (int by = 0; by < int(f.size); by += block)
    for (int bx = 0; bx < int(f.size); bx += block) {
      const std::vector<double> c = blockAutocorrelations(f, bx, by, block, 4);
      const auto best = std::max_element(c.begin(), c.end());
      spread.push_back(*best - *std::min_element(c.begin(), c.end()));
      ++leads[best - c.begin()];
    }
  std::sort(spread.begin(), spread.end());
  const double cirrus = spread[spread.size() / 2];
  std::cout << "cirrus: median directional spread " << cirrus << "; blocks led by u, v, "
            << "diagonals: " << leads[0] << ", " << leads[1] << ", " << leads[2] << ", " << leads[3]
            << "\n";
  EXPECT_GT(cirrus, 0.15) << "fibrous within each block";
  EXPECT_GT(leads[0], 64 * 6 / 10) << "the fibres do not run along u";
  EXPECT_LE(leads[1], 64 / 10) << "fibres across the wind";
}

TEST_F(HighCloudTest, CirrocumulusHasARipplePeriodNorthSouth) {
  auto textures = make();
  const Fetched f = fetch(*textures, proceduralScene("cirrocumulus", 0.8, 256));
  const double peak = verticalPower(f, 32);  // shaders/high_cloud_bake.comp: 32 rows a tile
  double around = 0;
  int count = 0;
  for (int k = 16; k <= 48; ++k)
    if (std::abs(k - 32) > 2) {
      around += verticalPower(f, k);
      ++count;
    }
  around /= count;
  EXPECT_GT(peak, 4.0 * around) << "power at 32 rows " << peak << ", around " << around;
  // Cirrus has no such line.
  const Fetched cirrus = fetch(*textures, proceduralScene("cirrus", 0.8, 256));
  double cirrusAround = 0;
  for (int k = 16; k <= 48; ++k)
    if (std::abs(k - 32) > 2) cirrusAround += verticalPower(cirrus, k);
  EXPECT_LT(verticalPower(cirrus, 32), 4.0 * cirrusAround / count);
}

// Opacity statistics: the coefficient of variation, the range, and the roughness (the mean
// |difference| between neighbours, east and south, over the mean).
struct OpacityStats {
  double variation = 0, minimum = 1, maximum = 0, roughness = 0;
};
OpacityStats opacityStats(const Fetched& f) {
  OpacityStats s;
  double sum = 0, sum2 = 0, rough = 0;
  const uint32_t n = f.size;
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const double a = f.opacity(x, y);
      sum += a;
      sum2 += a * a;
      s.minimum = std::min(s.minimum, a);
      s.maximum = std::max(s.maximum, a);
      rough += std::abs(f.opacity((x + 1) % n, y) - a) + std::abs(f.opacity(x, (y + 1) % n) - a);
    }
  const double count = double(n) * n, mean = sum / count;
  s.variation = std::sqrt(std::max(sum2 / count - mean * mean, 0.0)) / mean;
  s.roughness = rough / (2 * count) / mean;
  return s;
}

TEST_F(HighCloudTest, CirrostratusIsAThinLowContrastVeil) {
  auto textures = make();
  const OpacityStats veil = opacityStats(fetch(*textures, proceduralScene("cirrostratus", 1.0)));
  const OpacityStats cirrus = opacityStats(fetch(*textures, proceduralScene("cirrus", 1.0)));
  EXPECT_LT(veil.variation, 0.25);
  EXPECT_GT(veil.minimum, 0.15);  // full cover leaves no gap in the veil
  EXPECT_LT(veil.maximum, 0.6);   // and it stays thin: the sun shows through
  // Cirrus at the same cover is fibrous: far rougher from texel to texel.
  EXPECT_GT(cirrus.roughness, 2.5 * veil.roughness)
      << "cirrus " << cirrus.roughness << ", cirrostratus " << veil.roughness;
}

TEST_F(HighCloudTest, BakesAreDeterministicPerSeed) {
  const Scene scene = proceduralScene("cirrocumulus", 0.5, 64, 7);
  const Fetched first = fetch(*make(), scene);
  ASSERT_TRUE(first.activity.baked);
  fs::remove(first.activity.cacheFile);  // make the second object bake too
  const Fetched again = fetch(*make(), scene);
  ASSERT_TRUE(again.activity.baked);
  EXPECT_EQ(test::maxDifference(first.coefficients, again.coefficients), 0.0f);
  EXPECT_EQ(test::maxDifference(first.normals, again.normals), 0.0f);

  const Fetched other = fetch(*make(), proceduralScene("cirrocumulus", 0.5, 64, 8));
  double difference = 0;
  for (size_t i = 0; i < first.coefficients.size(); ++i)
    difference += std::abs(first.coefficients[i] - other.coefficients[i]);
  EXPECT_GT(difference / double(first.coefficients.size()), 0.02);
}

TEST_F(HighCloudTest, ChannelsStayInRangeAndPartitionTheTexel) {
  auto textures = make();
  for (const char* style : kStyles)
    for (double cover : {0.2, 1.0}) {
      SCOPED_TRACE(std::string(style) + " cover " + std::to_string(cover));
      const Fetched f = fetch(*textures, proceduralScene(style, cover, 64));
      for (size_t i = 0; i < f.coefficients.size(); i += 4) {
        for (int c = 0; c < 4; ++c) {
          ASSERT_GE(f.coefficients[i + size_t(c)], 0.0f) << "texel " << i / 4 << " channel " << c;
          ASSERT_LE(f.coefficients[i + size_t(c)], 1.0f) << "texel " << i / 4 << " channel " << c;
        }
        // R + G = 1 - B: thin and dense cloud and clear sky share the texel.
        ASSERT_NEAR(f.coefficients[i] + f.coefficients[i + 1] + f.coefficients[i + 2], 1.0f, 2e-3f);
        const glm::vec3 n(f.normals[i], f.normals[i + 1], f.normals[i + 2]);
        ASSERT_NEAR(glm::length(n), 1.0f, 2e-3f);
        ASSERT_GT(n.z, 0.0f);
      }
    }
}

TEST_F(HighCloudTest, CoverMapMasksTheCover) {
  Scene scene = proceduralScene("cirrostratus", 1.0);
  scene.highClouds.coverMap = "cover_half_8x4.png";  // west half 0, east half 1
  auto textures = make();
  const Fetched f = fetch(*textures, scene);
  ASSERT_TRUE(f.activity.baked);
  // Bilinear between texel centres: u in [1/16, 7/16] is exactly 0, [9/16, 15/16] exactly 1.
  double west = 0, east = 0;
  for (uint32_t y = 0; y < f.size; ++y) {
    for (uint32_t x = f.size / 16 + 1; x < f.size * 7 / 16 - 1; ++x)
      west = std::max(west, double(f.opacity(x, y)));
    for (uint32_t x = f.size * 9 / 16 + 1; x < f.size * 15 / 16 - 1; ++x) east += f.opacity(x, y);
  }
  east /= double(f.size) * (f.size * 6 / 16 - 2);
  EXPECT_EQ(west, 0.0);
  EXPECT_GT(east, 0.3);
  // The map is part of the cache key.
  Scene without = scene;
  without.highClouds.coverMap.clear();
  EXPECT_NE(textures->cacheKey(scene), textures->cacheKey(without));
}

TEST_F(HighCloudTest, ProgressRisesToOneDuringABake) {
  auto textures = make();
  std::vector<double> fractions;
  textures->setProgress([&](double fraction) { fractions.push_back(fraction); });
  const Fetched f = fetch(*textures, proceduralScene("cirrus", 0.4, 128));
  ASSERT_TRUE(f.activity.baked);
  ASSERT_GE(fractions.size(), 3u);  // 128 rows bake in two bands
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  for (size_t i = 1; i < fractions.size(); ++i) EXPECT_GT(fractions[i], fractions[i - 1]);
  // Loading what is current reports nothing.
  fractions.clear();
  fetch(*textures, proceduralScene("cirrus", 0.4, 128));
  EXPECT_TRUE(fractions.empty());
}

TEST_F(HighCloudTest, UnchangedSettingsAddNoPassAndReadNothing) {
  auto textures = make();
  const Scene scene = proceduralScene("cirrus", 0.4, 64);
  const Fetched first = fetch(*textures, scene);
  ASSERT_TRUE(first.activity.baked);
  EXPECT_FALSE(first.activity.bakeTimings.empty());
  // Even with the cache entry gone, nothing is baked or read: the GPU textures are current.
  fs::remove(first.activity.cacheFile);
  const Fetched second = fetch(*textures, scene);
  EXPECT_FALSE(second.activity.baked);
  EXPECT_FALSE(second.activity.loadedCache);
  EXPECT_FALSE(second.activity.loadedImages);
  EXPECT_TRUE(second.activity.bakeTimings.empty());
  for (const std::string& pass : second.graphPasses)
    EXPECT_NE(pass.rfind("high_cloud", 0), 0u) << pass;
  EXPECT_EQ(test::maxDifference(first.coefficients, second.coefficients), 0.0f);
  EXPECT_EQ(second.mean, first.mean);
  // Settings that do not touch the textures (wind, altitude, brightness) change nothing either.
  Scene windy = scene;
  windy.highClouds.windSpeedMs = 40;
  windy.highClouds.altitudeM = 11000;
  windy.highClouds.brightness = 2;
  EXPECT_FALSE(fetch(*textures, windy).activity.baked);
}

}  // namespace
}  // namespace sky
