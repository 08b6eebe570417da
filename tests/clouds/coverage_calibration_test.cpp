// engine/clouds/coverage_calibration: the calibrated thresholds give the cover as mean column
// opacity on columns the calibration never saw, for both models and several cloud types; the
// paper's 1 - CMc does not (why the calibration exists); the table's ends, shape, determinism,
// cost and errors; and the trilinear noise sampler it rests on.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include <gtest/gtest.h>

#include "engine/clouds/cloud_math.h"
#include "engine/clouds/coverage_calibration.h"
#include "engine/core/error.h"
#include "synthetic_noise.h"

namespace sky::test {
namespace {
using namespace sky::clouds;

class CoverageCalibrationTest : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    sShape = syntheticShapeVolume(32, 11);
    sDetail = syntheticDetailVolume(16, 12);
  }
  static NoiseVolume sShape, sDetail;
};
NoiseVolume CoverageCalibrationTest::sShape, CoverageCalibrationTest::sDetail;

// The default layers and noise scales of CloudSettings with the cloud type's range.
CoverageColumn column(CloudModel model, int layer, float type) {
  CoverageColumn c;
  c.thicknessM = layer == 0 ? 2000.0 : 3500.0;
  c.shapeScaleM = 16000.0;
  c.detailScaleM = 2000.0;
  c.extinction = 0.04;
  c.typeRange = cloudTypeRange(layer, type);
  c.model = model;
  c.type = type;
  return c;
}

// Columns the calibration did not use: more of them, with more heights, shifted in all three
// coordinates (the raymarch's columns cross the tile at every depth).
const OpacityGrid kFreshGrid{4096, 40, {0.37f, 0.71f, 0.53f}};

TEST_F(CoverageCalibrationTest, CalibratedThresholdsGiveTheCoverOnFreshColumns) {
  struct Case {
    CloudModel model;
    int layer;
    float type;
    float profileCover;
    float textureKeep = 1.0f;  // 0: a stratiform sheet's, fine octaves at their means
  };
  const Case cases[] = {
      {CloudModel::Lu2023, 0, 1.0f, -1.0f},   {CloudModel::Lu2023, 0, 0.0f, -1.0f},
      {CloudModel::Lu2023, 1, 0.5f, -1.0f},   {CloudModel::Lu2023, 0, 1.0f, 1.0f},
      {CloudModel::Lu2023, 1, 0.5f, 1.0f},    {CloudModel::Tang2019, 0, 1.0f, -1.0f},
      {CloudModel::Tang2019, 0, 0.0f, -1.0f}, {CloudModel::Tang2019, 1, 0.5f, -1.0f},
      {CloudModel::Lu2023, 1, 0.0f, 1.0f, 0.0f},  {CloudModel::Tang2019, 0, 0.0f, -1.0f, 0.0f}};
  for (const Case& k : cases) {
    SCOPED_TRACE(std::string(enumName(k.model)) + " layer " + std::to_string(k.layer) + " type " +
                 std::to_string(k.type) + " profile cover " + std::to_string(k.profileCover) +
                 " texture kept " + std::to_string(k.textureKeep));
    CoverageColumn col = column(k.model, k.layer, k.type);
    col.profileCover = k.profileCover;
    col.textureKeep = k.textureKeep;
    const CoverageLut lut = calibrateCoverage(sShape, sDetail, col);
    double worst = 0;
    for (int i = 1; i <= 9; ++i) {
      const float cover = 0.1f * float(i);
      const double opacity =
          meanColumnOpacity(sShape, sDetail, col, cover, coverageThreshold(lut, cover), kFreshGrid);
      EXPECT_NEAR(opacity, cover, 0.02) << "cover " << cover;
      worst = std::max(worst, std::abs(opacity - cover));
    }
    std::cout << enumName(k.model) << " layer " << k.layer << " type " << k.type
              << " profile cover " << k.profileCover << " texture kept " << k.textureKeep
              << ": worst |opacity - cover| " << worst
              << "\n";
  }
}

TEST_F(CoverageCalibrationTest, PaperThresholdsLeaveThinCoverNearlyClear) {
  // The issue: with 1 - CMc only sparse noise peaks pass, so a 30 % cell renders far below 30 %
  // (lu2023: 0.001 on this noise). Tang's remap lets more through, 0.23 at 30 % over the whole
  // tile, but a 20 % cell still renders far below 20 %.
  for (CloudModel model : {CloudModel::Lu2023, CloudModel::Tang2019}) {
    const float thin = model == CloudModel::Lu2023 ? 0.3f : 0.2f;
    const CoverageColumn col = column(model, 0, 1.0f);
    const CoverageLut lut = calibrateCoverage(sShape, sDetail, col);
    std::printf("%s cover: paper opacity / calibrated opacity (threshold)\n", enumName(model));
    for (float cover : {0.1f, 0.2f, 0.3f, 0.5f, 0.7f, 0.9f}) {
      const double paper = meanColumnOpacity(sShape, sDetail, col, cover, 1.0f - cover, kFreshGrid);
      const float t = coverageThreshold(lut, cover);
      const double calibrated = meanColumnOpacity(sShape, sDetail, col, cover, t, kFreshGrid);
      std::printf("  %.1f: %.3f / %.3f (%.3f)\n", double(cover), paper, calibrated, double(t));
      if (cover <= thin) {
        EXPECT_LT(paper, 0.6 * cover) << enumName(model) << " cover " << cover;
      }
    }
  }
}

TEST_F(CoverageCalibrationTest, TableEndsAndShape) {
  struct Case {
    CloudModel model;
    float profileCover;
    bool monotone;
  };
  // Monotone where the cover only moves the threshold (and Tang's density scale): more cover
  // then always needs a lower threshold. Lu with the cell's cover as CMc is not: GS's top (6)
  // and GD (10) grow with CMc, so at a fixed threshold the opacity rises faster than the cover
  // at mid cover and the table turns back up there. The search is per cover, never assuming
  // monotony.
  const Case cases[] = {{CloudModel::Lu2023, -1.0f, false},
                        {CloudModel::Lu2023, 1.0f, true},
                        {CloudModel::Tang2019, -1.0f, true}};
  for (const Case& k : cases) {
    SCOPED_TRACE(std::string(enumName(k.model)) + " profile cover " +
                 std::to_string(k.profileCover));
    CoverageColumn col = column(k.model, 0, 1.0f);
    col.profileCover = k.profileCover;
    const CoverageLut lut = calibrateCoverage(sShape, sDetail, col);
    // Cover 0: no cloud at all; cover 1: the lowest threshold searched.
    EXPECT_EQ(lut.front(), 1.0f);
    EXPECT_EQ(meanColumnOpacity(sShape, sDetail, col, 0.0f, lut.front()), 0.0);
    EXPECT_EQ(lut.back(), -1.0f);
    // Smooth enough to interpolate linearly: neighbours within 0.1. Not at the ends: cover 0
    // has no cloud at any threshold (Lu's GD and Tang's density scale with it), and the last
    // entry jumps to the lowest threshold, where everything is opaque anyway.
    for (int i = 2; i + 1 < kCoverageLutSize; ++i)
      EXPECT_LT(std::abs(lut[size_t(i)] - lut[size_t(i) - 1]), 0.1f) << "entry " << i;
    if (k.monotone) {
      for (int i = 1; i < kCoverageLutSize; ++i)
        EXPECT_LE(lut[size_t(i)], lut[size_t(i) - 1]) << "entry " << i;
    } else {
      const auto [lowest, highest] = std::minmax_element(lut.begin() + 1, lut.end() - 1);
      EXPECT_LT(lowest - lut.begin(), highest - lut.begin());
    }
  }
}

TEST_F(CoverageCalibrationTest, FullHeightProfileCoversAreaNotHaze) {
  // What the two lu2023 profiles look like at 20 % cover: the share of columns more than half
  // opaque. With Lu's CMc-dependent profile the calibration can only spread a faint layer (no
  // column reaches 0.5); with full-height clouds about 20 % of the columns are clouds.
  for (float profileCover : {-1.0f, 1.0f}) {
    CoverageColumn col = column(CloudModel::Lu2023, 0, 1.0f);
    col.profileCover = profileCover;
    const CoverageLut lut = calibrateCoverage(sShape, sDetail, col);
    const float threshold = coverageThreshold(lut, 0.2f);
    int opaque = 0;
    const int n = 32, heights = 32;
    for (int k = 0; k < n * n; ++k) {
      // One column at a time through meanColumnOpacity's own sampling: a 1 x 1 grid, shifted.
      const glm::vec3 offset(float(k % n) / float(n), float(k / n) / float(n), 0.0f);
      opaque +=
          meanColumnOpacity(sShape, sDetail, col, 0.2f, threshold, {1, heights, offset}) > 0.5;
    }
    const double share = double(opaque) / (n * n);
    std::cout << "lu2023 profile cover " << profileCover << ", cover 0.2: " << share
              << " of the columns more than half opaque\n";
    if (profileCover < 0) {
      EXPECT_LT(share, 0.02);
    } else {
      EXPECT_NEAR(share, 0.2, 0.05);
    }
  }
}

// The far field's table (farMeanDensity) is the field's own statistics: at each cover and
// height slice, the mean density and the share of the space in cloud over fresh points of the
// tile (not the calibration's grid), straight through luCloudDensity at the calibrated
// threshold. Tolerance: 0.02 of the density (the slice's own spread over 8 heights) and 0.03
// of the share. Clear at cover 0; a whole sheet at cover 1 in the slices the type fills.
TEST_F(CoverageCalibrationTest, FarMeanIsTheFieldsMeanAndShareInCloud) {
  CoverageColumn col = column(CloudModel::Lu2023, 0, 1.0f);
  col.profileCover = 1.0f;  // as the renderer calibrates
  const CoverageLut lut = calibrateCoverage(sShape, sDetail, col);
  const FarMeanTable table = farMeanDensity(sShape, sDetail, col, lut);
  for (int j = 0; j < kFarMeanHeights; ++j) {
    EXPECT_EQ(table[0][size_t(j)].density, 0.0f);
    EXPECT_EQ(table[0][size_t(j)].fraction, 0.0f);
  }
  for (int i : {4, 8, 12}) {
    const float cover = float(i) / float(kFarMeanCovers - 1);
    const float threshold = coverageThreshold(lut, cover);
    for (int j = 0; j < kFarMeanHeights; ++j) {
      // 2048 fresh points in the slice: R3 places through the whole tile (the layer crosses
      // it at every depth), each at its own height in the slice (golden-ratio steps).
      double density = 0.0, inCloud = 0.0;
      const int n = 2048;
      for (int k = 0; k < n; ++k) {
        const double g = 1.22074408460575947536;
        glm::dvec3 u = 0.31 + double(k) / glm::dvec3(g, g * g, g * g * g);
        u -= glm::floor(u);
        const double v = std::fmod(0.17 + double(k) * 0.6180339887498949, 1.0);
        const float ph = (float(j) + float(v)) / float(kFarMeanHeights);
        const double range = double(col.typeRange.y) - double(col.typeRange.x);
        const glm::dvec3 p = u * col.shapeScaleM +
                             glm::dvec3(0.0, 0.0, (double(col.typeRange.x) + ph * range) *
                                                      col.thicknessM);
        const glm::vec4 shape = sampleNoise(sShape, glm::vec3(p / col.shapeScaleM));
        const glm::vec3 detail = glm::vec3(sampleNoise(sDetail, glm::vec3(p / col.detailScaleM)));
        const float d = luCloudDensity(shape, detail, ph, 1.0f, threshold);
        density += cloudEdgeDensity(d, col.edgeSharpness);
        inCloud += d > 0.0f ? 1.0 : 0.0;
      }
      const FarMean& m = table[size_t(i)][size_t(j)];
      EXPECT_NEAR(m.density, density / n, 0.02) << "cover " << cover << " slice " << j;
      EXPECT_NEAR(m.fraction, inCloud / n, 0.03) << "cover " << cover << " slice " << j;
    }
  }
  // At full cover the slices the cumulus fills are all cloud.
  EXPECT_GT(table[kFarMeanCovers - 1][kFarMeanHeights / 2].fraction, 0.99f);
}

TEST_F(CoverageCalibrationTest, DeterministicAndWithinBudget) {
  const CoverageColumn col = column(CloudModel::Lu2023, 0, 1.0f);
  const auto start = std::chrono::steady_clock::now();
  const CoverageLut a = calibrateCoverage(sShape, sDetail, col);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const CoverageLut b = calibrateCoverage(sShape, sDetail, col);
  EXPECT_EQ(a, b);
  std::cout << "calibrateCoverage: " << seconds << " s\n";
  // The budget is 0.3 s on 2 idle cores; a shared CI machine gets ten times that.
  EXPECT_LT(seconds, 3.0);
}

TEST_F(CoverageCalibrationTest, Errors) {
  try {
    calibrateCoverage(NoiseVolume{}, sDetail, column(CloudModel::Lu2023, 0, 1.0f));
    FAIL() << "no error for an empty volume";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Internal);
  }
}

TEST(NoiseSampling, TrilinearAndRepeating) {
  NoiseVolume v;
  v.size = 2;
  v.rgba.assign(2 * 2 * 2 * 4, 0);
  v.rgba[0] = 255;          // texel (0, 0, 0), R
  v.rgba[4 * 1 + 1] = 51;   // texel (1, 0, 0), G
  v.rgba[4 * 7 + 3] = 102;  // texel (1, 1, 1), A
  // At a texel centre: that texel (byte / 255).
  EXPECT_FLOAT_EQ(sampleNoise(v, {0.25f, 0.25f, 0.25f}).r, 1.0f);
  EXPECT_FLOAT_EQ(sampleNoise(v, {0.75f, 0.25f, 0.25f}).g, 0.2f);
  EXPECT_FLOAT_EQ(sampleNoise(v, {0.75f, 0.75f, 0.75f}).a, 0.4f);
  // Halfway between texel 0 and 1 along x, and across the wrap (x = 0 sits between texel 1
  // and texel 0 of the next repeat).
  EXPECT_FLOAT_EQ(sampleNoise(v, {0.5f, 0.25f, 0.25f}).r, 0.5f);
  EXPECT_FLOAT_EQ(sampleNoise(v, {0.0f, 0.25f, 0.25f}).r, 0.5f);
  EXPECT_FLOAT_EQ(sampleNoise(v, {1.0f, 0.25f, 0.25f}).r, 0.5f);
  // Whole repeats away, the same value.
  EXPECT_NEAR(sampleNoise(v, {3.3f, -1.9f, 7.6f}).g, sampleNoise(v, {0.3f, 0.1f, 0.6f}).g, 1e-6f);
  EXPECT_GT(sampleNoise(v, {0.3f, 0.1f, 0.6f}).g, 0.0f);
}

}  // namespace
}  // namespace sky::test
