// engine/weather/coverage_metrics.h on hand-made images: a perfect match gives Dice 1, MAE 0,
// r 1; known overlaps give the Dice of Lu (28) by hand; partial edge blocks average what they
// have; constant sides give r 0; and readRenderCoverage finds the layers a top-down render
// writes, combines the two layers' cover, and names the file and any missing layer.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "engine/core/error.h"
#include "engine/io/exr.h"
#include "engine/weather/coverage_metrics.h"
#include "error_capture.h"

namespace sky {
namespace {
using test::catchError;
using ::testing::HasSubstr;

// An image with value `v` inside the rectangle [x0, x1) x [y0, y1), 0 elsewhere.
std::vector<float> rect(int w, int h, int x0, int y0, int x1, int y1, float v = 1.0f) {
  std::vector<float> img(size_t(w) * size_t(h), 0.0f);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) img[size_t(y) * size_t(w) + size_t(x)] = v;
  return img;
}

TEST(CoverageMetrics, PerfectMatchIsOneZeroOne) {
  std::vector<float> img(32 * 24);
  for (size_t i = 0; i < img.size(); ++i) img[i] = float((i * 37) % 101) / 100.0f;
  const CoverageMetrics m = compareCoverage(img, img, 32, 24, {4, 0.3});
  EXPECT_DOUBLE_EQ(m.dice, 1.0);
  EXPECT_DOUBLE_EQ(m.meanAbsoluteError, 0.0);
  EXPECT_NEAR(m.correlation, 1.0, 1e-12);
  EXPECT_EQ(m.blocks, 8u * 6u);
}

TEST(CoverageMetrics, KnownOverlapsGiveLusDice) {
  // Cell 1: A has 8 x 4 = 32 cloudy pixels, B 8 x 4 shifted by 2 rows: 16 shared.
  // Dice = 2 * 16 / (32 + 32) = 0.5.
  const std::vector<float> a = rect(8, 8, 0, 0, 8, 4), b = rect(8, 8, 0, 2, 8, 6);
  CoverageMetrics m = compareCoverage(a, b, 8, 8, {1, 0.5});
  EXPECT_DOUBLE_EQ(m.dice, 0.5);
  EXPECT_DOUBLE_EQ(m.meanAbsoluteError, 32.0 / 64.0);  // 32 pixels differ by 1
  // r of two binary images: (p11 - pa pb) / sqrt(pa (1 - pa) pb (1 - pb)) = (1/4 - 1/4) / ... = 0.
  EXPECT_NEAR(m.correlation, 0.0, 1e-12);
  EXPECT_EQ(m.blocks, 64u);

  // A inside B: |A| = 4, |B| = 16 -> 2 * 4 / 20 = 0.4.
  m = compareCoverage(rect(8, 8, 2, 2, 4, 4), rect(8, 8, 0, 0, 4, 4), 8, 8, {1, 0.5});
  EXPECT_DOUBLE_EQ(m.dice, 0.4);
  // Disjoint: 0.
  m = compareCoverage(rect(8, 8, 0, 0, 2, 2), rect(8, 8, 4, 4, 8, 8), 8, 8, {1, 0.5});
  EXPECT_DOUBLE_EQ(m.dice, 0.0);
  // Both empty: 1 (nothing to miss), r 0 (constant).
  m = compareCoverage(rect(8, 8, 0, 0, 0, 0), rect(8, 8, 0, 0, 0, 0), 8, 8, {2, 0.1});
  EXPECT_DOUBLE_EQ(m.dice, 1.0);
  EXPECT_DOUBLE_EQ(m.correlation, 0.0);
  EXPECT_EQ(m.blocks, 16u);
}

TEST(CoverageMetrics, BlocksAverageBeforeTheThreshold) {
  // A checkerboard of opacity 1 against a uniform cover 0.5: per pixel they disagree
  // everywhere, per 2x2 block they agree exactly.
  std::vector<float> checker(8 * 8), half(8 * 8, 0.5f);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) checker[size_t(y * 8 + x)] = float((x + y) % 2);
  CoverageMetrics m = compareCoverage(checker, half, 8, 8, {2, 0.25});
  EXPECT_DOUBLE_EQ(m.dice, 1.0);
  EXPECT_DOUBLE_EQ(m.meanAbsoluteError, 0.0);
  EXPECT_DOUBLE_EQ(m.correlation, 0.0);  // both constant at the block scale
  m = compareCoverage(checker, half, 8, 8, {1, 0.25});
  EXPECT_DOUBLE_EQ(m.meanAbsoluteError, 0.5);
  EXPECT_DOUBLE_EQ(m.dice, 2.0 * 32 / (32 + 64));

  // A 5 x 3 image in 4 x 4 cells: blocks 4x3 and 1x3 (the edge averages its 3 pixels).
  std::vector<float> a(15, 0.0f), b(15, 0.0f);
  for (int y = 0; y < 3; ++y) a[size_t(y * 5 + 4)] = 1.0f;  // the last column: edge block 1.0
  b[0] = 1.0f;                                              // first block 1/12
  m = compareCoverage(a, b, 5, 3, {4, 0.5});
  EXPECT_EQ(m.blocks, 2u);
  EXPECT_DOUBLE_EQ(m.dice, 0.0);  // a's edge block is cloudy; b has no block above 0.5
  EXPECT_NEAR(m.meanAbsoluteError, (1.0 / 12 + 1.0) / 2, 1e-12);
  EXPECT_NEAR(m.correlation, -1.0, 1e-12);  // two blocks in opposite order
}

TEST(CoverageMetrics, CorrelationFollowsTheBlockAverages) {
  // b = 0.5 a + 0.1 exactly: r = 1; with one block changed r drops below 1.
  std::vector<float> a(16 * 16), b(16 * 16);
  for (size_t i = 0; i < a.size(); ++i) {
    a[i] = float(i % 16) / 16.0f;
    b[i] = 0.5f * a[i] + 0.1f;
  }
  CoverageMetrics m = compareCoverage(a, b, 16, 16, {4, 0.2});
  EXPECT_NEAR(m.correlation, 1.0, 1e-6);
  // Block (0, 0) of b raised from 0.147 to 1: r = 0.33215 (Pearson over the 16 block
  // averages, worked out separately in double).
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) b[size_t(y * 16 + x)] = 1.0f;
  m = compareCoverage(a, b, 16, 16, {4, 0.2});
  EXPECT_NEAR(m.correlation, 0.33215, 1e-4);
}

TEST(CoverageMetrics, MismatchedInputsAreInternalErrors) {
  const std::vector<float> a(16), b(15);
  EXPECT_EQ(catchError([&] { compareCoverage(a, b, 4, 4, {}); }).kind(), ErrorKind::Internal);
  EXPECT_EQ(catchError([&] { compareCoverage(a, a, 4, 4, {0, 0.1}); }).kind(), ErrorKind::Internal);
}

class RenderCoverageTest : public ::testing::Test {
protected:
  void SetUp() override {
    mDir = std::filesystem::temp_directory_path() /
           ("sky-render-coverage-" + std::to_string(::getpid()));
    std::filesystem::create_directories(mDir);
  }
  void TearDown() override { std::filesystem::remove_all(mDir); }
  std::filesystem::path mDir;
};

TEST_F(RenderCoverageTest, ReadsOpacityAndCombinesTheLayersCover) {
  LayeredImage exr;
  exr.width = 2;
  exr.height = 1;
  exr.layers.push_back({"", {"R", "G", "B", "A"}, std::vector<float>(8, 0.0f)});
  exr.layers.push_back({"clouds", {"R", "G", "B", "A"}, {0, 0, 0, 0.25f, 0, 0, 0, 1.0f}});
  exr.layers.push_back({"weather", {"cover_low", "cover_mid"}, {0.5f, 0.5f, 0.0f, 1.0f}});
  writeExr(mDir / "render.exr", exr);
  const RenderCoverage r = readRenderCoverage(mDir / "render.exr");
  EXPECT_EQ(r.width, 2);
  EXPECT_EQ(r.height, 1);
  EXPECT_EQ(r.opacity, (std::vector<float>{0.25f, 1.0f}));
  // 1 - (1 - 0.5)(1 - 0.5) = 0.75; 1 - (1 - 0)(1 - 1) = 1.
  EXPECT_EQ(r.cover, (std::vector<float>{0.75f, 1.0f}));
}

TEST_F(RenderCoverageTest, MissingLayersNameTheFileAndLayer) {
  LayeredImage exr;
  exr.width = exr.height = 1;
  exr.layers.push_back({"", {"R", "G", "B", "A"}, {0, 0, 0, 1}});
  writeExr(mDir / "plain.exr", exr);
  const std::string file = (mDir / "plain.exr").string();
  Error e = catchError([&] { readRenderCoverage(mDir / "plain.exr"); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_EQ(std::string(e.what()),
            file + ": no layer clouds.A (render with camera.mode geographic_topdown)");
  exr.layers.push_back({"clouds", {"R", "G", "B", "A"}, {0, 0, 0, 1}});
  exr.layers.push_back({"weather", {"cover_low"}, {0.5f}});
  writeExr(mDir / "plain.exr", exr);
  e = catchError([&] { readRenderCoverage(mDir / "plain.exr"); });
  EXPECT_THAT(std::string(e.what()), HasSubstr(": no layer weather.cover_mid"));
  e = catchError([&] { readRenderCoverage(mDir / "missing.exr"); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_THAT(std::string(e.what()), HasSubstr("missing.exr"));
}

}  // namespace
}  // namespace sky
