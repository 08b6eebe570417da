// Coverage fidelity, the issues' "done when": a top-down render (camera.mode
// geographic_topdown) of a procedural map against the map itself, by Lu (28)'s Dice over
// blocks, their mean absolute error and correlation (engine/weather/coverage_metrics.h).
// Calibrated coverage must match the map; Lu's own remap (clouds.coverage paper) leaves thin
// cover nearly clear, which is why the calibration exists. The default scene's own map, seen
// as issue 30 saw it, must match too. Each case prints its figures (docs/clouds.md quotes
// them).
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cloud_test_util.h"
#include "engine/weather/coverage_metrics.h"

namespace sky {
namespace {

struct CoverageCase {
  const char* name;
  CloudModel model;
  CloudCoverageMode coverage;
  bool mid;  // altocumulus in the mid layer instead of a low cloud
  const char* lowType = "cumulus";  // the low cloud (stratocumulus: rolls, cloudRollWeight)
};

void PrintTo(const CoverageCase& c, std::ostream* os) {
  *os << c.name;
}

// A top-down render of `scene` against its map, `cell` px blocks, with its figures printed.
CoverageMetrics measureCoverage(const RenderedFrame& frame, int cell, const std::string& name) {
  const ImageLayer* weather = frame.image.find("weather");
  EXPECT_NE(weather, nullptr);
  if (!weather) return {};
  // The cover of two independent layers seen from above, as `skyrender dsc` reads it.
  std::vector<float> cover(weather->pixels.size() / 2);
  for (size_t i = 0; i < cover.size(); ++i)
    cover[i] = 1.0f - (1.0f - weather->pixels[i * 2]) * (1.0f - weather->pixels[i * 2 + 1]);
  const std::vector<float> opacity = test::CloudLayerView(frame).alpha();
  const CoverageMetrics m = compareCoverage(opacity, cover, frame.image.width, frame.image.height,
                                            CoverageOptions{cell, 0.1});
  std::printf("[ coverage ] %s: dsc %.3f mae %.3f correlation %.3f blocks %llu (%.0f ms GPU)\n",
              name.c_str(), m.dice, m.meanAbsoluteError, m.correlation,
              static_cast<unsigned long long>(m.blocks), frame.frame.gpuMs);
  return m;
}

class CloudCoverage : public test::CloudRenderTest,
                      public ::testing::WithParamInterface<CoverageCase> {
protected:
  // 128 x 128 px over 5 x 7 degrees (about 550 x 555 km): a 4 px block is 17 km, a tenth of
  // the map's 150 km features, and holds 64 rays (each pixel averages 2 x 2, the top-down
  // march's CLOUD_TOPDOWN_SUBPIXELS) through clouds whose cells are 1.25 km.
  CoverageMetrics measure(const CoverageCase& c) {
    const std::string layerCover = c.mid ? "weather.cover_mid=0.5" : "weather.cover_low=0.5";
    const Scene scene = test::cloudScene(
        "cumulus_noon",
        {"camera.mode=geographic_topdown", "output.width=128", "output.height=128",
         "weather.region.lat=[45, 50]", "weather.region.lon=[5, 12]", "weather.spread=1",
         "weather.scale_km=150", "weather.cover_low=0", layerCover,
         std::string("weather.cloud_type=") + (c.mid ? "altocumulus" : c.lowType),
         std::string("clouds.model=") + enumName(c.model),
         std::string("clouds.coverage=") + enumName(c.coverage)});
    return measureCoverage(render(scene), 4, c.name);
  }
};

// Issue 30's goal: Dice at least 0.97 and blocks within 0.05 of the map on average.
constexpr double kMinDice = 0.97;
constexpr double kMaxMeanAbsoluteError = 0.05;

TEST_P(CloudCoverage, MatchesTheMap) {
  const CoverageCase& c = GetParam();
  const CoverageMetrics m = measure(c);
  EXPECT_EQ(m.blocks, 32u * 32u);
  if (c.coverage == CloudCoverageMode::Calibrated) {
    // Measured: Dice 0.983-0.989, MAE 0.021-0.031, correlation 0.992-0.997. The calibration
    // before issue 30, whose columns all started at the noise tile's z = 0, rendered up to 0.06
    // too much cloud; with one ray a pixel the blocks held 16 rays.
    EXPECT_GE(m.dice, kMinDice);
    EXPECT_LE(m.meanAbsoluteError, kMaxMeanAbsoluteError);
    EXPECT_GE(m.correlation, 0.98);
  } else {
    // Lu's 1 - CMc: the pattern is there (thick cover still renders thick) but thin cover
    // renders nearly clear, so the block averages are off by more than calibration allows.
    EXPECT_GT(m.meanAbsoluteError, 0.05);
    EXPECT_GT(m.correlation, 0.5);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Modes, CloudCoverage,
    ::testing::Values(
        CoverageCase{"lu2023_low_calibrated", CloudModel::Lu2023, CloudCoverageMode::Calibrated,
                     false},
        CoverageCase{"lu2023_low_paper", CloudModel::Lu2023, CloudCoverageMode::Paper, false},
        CoverageCase{"lu2023_stratocumulus_calibrated", CloudModel::Lu2023,
                     CloudCoverageMode::Calibrated, false, "stratocumulus"},
        CoverageCase{"lu2023_mid_calibrated", CloudModel::Lu2023, CloudCoverageMode::Calibrated,
                     true},
        CoverageCase{"lu2023_mid_paper", CloudModel::Lu2023, CloudCoverageMode::Paper, true},
        CoverageCase{"tang2019_low_calibrated", CloudModel::Tang2019, CloudCoverageMode::Calibrated,
                     false},
        CoverageCase{"tang2019_low_paper", CloudModel::Tang2019, CloudCoverageMode::Paper, false}),
    [](const ::testing::TestParamInfo<CoverageCase>& param) {
      return std::string(param.param.name);
    });

// The default scene's own map as issue 30 saw it: `skyrender render --time
// 2021-06-21T04:15:00Z --set camera.mode=geographic_topdown --width 160 --height 120`, then
// `skyrender dsc` (8 px blocks). No region, so the map is the 800 km square around Zurich:
// pixels of 5 x 6.7 km, blocks of 40 x 53 km over a map whose cover runs 0-0.85 about 0.35.
// It measured Dice 0.975, MAE 0.071 (a bias of +0.063: the calibration saw one slab of the
// noise tile), then 0.968 / 0.043 with the calibration fixed and one ray a pixel (each block a
// 64-ray estimate of clouds 1.2 km across), 0.984 / 0.017 with 2 x 2 rays a pixel.
class DefaultMapCoverage : public test::CloudRenderTest {};

TEST_F(DefaultMapCoverage, SeenFromAboveItMatchesTheMap) {
  const Scene scene = loadSceneFile(configDir() / "default.yaml",
                                    {"camera.mode=geographic_topdown", "output.width=160",
                                     "output.height=120", "time=2021-06-21T04:15:00Z"});
  const CoverageMetrics m = measureCoverage(render(scene), 8, "default map");
  EXPECT_EQ(m.blocks, 20u * 15u);
  EXPECT_GE(m.dice, kMinDice);
  EXPECT_LE(m.meanAbsoluteError, kMaxMeanAbsoluteError);
  EXPECT_GE(m.correlation, 0.98);
}

}  // namespace
}  // namespace sky
