// The "done when": a top-down render (camera.mode geographic_topdown, calibrated
// coverage) of the GFS fixture's map, at 8 pixels per 2.5 degree data cell, against the map's
// cover seen from above (1 - (1 - low)(1 - mid), as `skyrender dsc` reads it) at the data's
// cell size: Lu (28)'s Dice, the mean absolute error and the correlation of 8 px block
// averages. Over Lu's region and over Europe and the North Atlantic (across 0E). Each case
// prints its figures (docs/weather.md quotes them).
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../volumetric_clouds/cloud_test_util.h"
#include "engine/weather/coverage_metrics.h"
#include "gfs_fixture.h"

namespace sky {
namespace {

struct RenderCase {
  const char* name;
  WeatherRegion region;
  int width, height;  // 8 px per 2.5 degree cell
};

void PrintTo(const RenderCase& c, std::ostream* os) {
  *os << c.name;
}

class GfsRender : public test::CloudRenderTest, public ::testing::WithParamInterface<RenderCase> {};

TEST_P(GfsRender, MatchesTheMapAtTheDataCellSize) {
  const RenderCase& c = GetParam();
  Scene scene = test::cloudScene("cumulus_noon",
                                 {"camera.mode=geographic_topdown", "clouds.coverage=calibrated"});
  const Scene gfs = test::gfsScene(c.region, "rh");
  scene.baseDir = gfs.baseDir;
  scene.weather = gfs.weather;
  scene.output.width = c.width;
  scene.output.height = c.height;
  const RenderedFrame frame = render(scene);
  const ImageLayer* weather = frame.image.find("weather");
  ASSERT_NE(weather, nullptr);
  std::vector<float> cover(weather->pixels.size() / 2);
  for (size_t i = 0; i < cover.size(); ++i)
    cover[i] = 1.0f - (1.0f - weather->pixels[i * 2]) * (1.0f - weather->pixels[i * 2 + 1]);
  const std::vector<float> opacity = test::CloudLayerView(frame).alpha();
  const CoverageMetrics m =
      compareCoverage(opacity, cover, c.width, c.height, CoverageOptions{8, 0.1});
  double meanCover = 0.0;
  for (float v : cover) meanCover += v;
  meanCover /= double(cover.size());
  std::printf(
      "[ gfs render ] %s %dx%d: dsc %.3f mae %.3f correlation %.3f blocks %llu, map cover %.3f "
      "(%.0f ms GPU)\n",
      c.name, c.width, c.height, m.dice, m.meanAbsoluteError, m.correlation,
      static_cast<unsigned long long>(m.blocks), meanCover, frame.frame.gpuMs);
  EXPECT_EQ(m.blocks, uint64_t((c.width + 7) / 8) * uint64_t((c.height + 7) / 8));
  EXPECT_GE(m.dice, 0.90);
  EXPECT_LE(m.meanAbsoluteError, 0.05);
  EXPECT_GE(m.correlation, 0.95);
}

INSTANTIATE_TEST_SUITE_P(
    Regions, GfsRender,
    // Lu's 66 x 55 degrees is 26.4 x 22 cells; the Atlantic's 60 x 35 degrees 24 x 14.
    ::testing::Values(RenderCase{"lu_region", test::kLuRegion, 211, 176},
                      RenderCase{"atlantic", test::kAtlanticRegion, 192, 112}),
    [](const ::testing::TestParamInfo<RenderCase>& param) {
      return std::string(param.param.name);
    });

}  // namespace
}  // namespace sky
