// Golden images of the volumetric clouds (the issue: "cumulus at noon, stratocumulus at dusk,
// altocumulus under a full moon, both models"): the scenes of configs/tests/clouds/ at 64x36
// with clouds.model lu2023 and tang2019; and of the whole composite with its ground and
// haze under a stratus overcast and from 5 km (lu2023). References in
// tests/golden/clouds/<scene>_<model>.exr hold the beauty (R, G, B, A) and the clouds layer
// (R, G, B, A, depth); regenerate them with SKY_UPDATE_GOLDEN=1 after a deliberate change, and
// look at them before committing.
//
// Tolerance (the procedural noise is float maths, so another device may differ slightly):
// radiance is clipped at twice the reference's 99th percentile (so the sun disc does not set
// the scale), then PSNR >= 40 dB against that peak and max error <= 4 % of it, for the
// beauty's RGB and the clouds' premultiplied RGB; the clouds' opacity the same against a peak
// of 1; the depth PSNR >= 30 dB against 60 km, where it is clipped (horizon depths run to
// hundreds of kilometres and would set the scale), and no max error (a jittered sample on the
// other side of a cloud edge moves one pixel's depth by kilometres).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cloud_test_util.h"
#include "engine/io/exr.h"
#include "engine/io/image_metrics.h"

namespace sky {
namespace {
namespace fs = std::filesystem;

constexpr float kDepthClipM = 60000.0f;

struct GoldenCase {
  const char* scene;
  const char* model;
};

void PrintTo(const GoldenCase& c, std::ostream* os) {
  *os << c.scene << " " << c.model;
}

std::string goldenName(const GoldenCase& c) {
  return std::string(c.scene) + "_" + c.model;
}

// Channels [first, first + count) of every pixel of a layer, each clipped at `clip`.
std::vector<float> channels(const ImageLayer& layer, size_t first, size_t count, float clip) {
  std::vector<float> out;
  const size_t stride = layer.channels.size();
  for (size_t i = 0; i < layer.pixels.size() / stride; ++i)
    for (size_t c = first; c < first + count; ++c)
      out.push_back(std::min(layer.pixels[i * stride + c], clip));
  return out;
}

// Twice the 99th percentile of channels [first, first + count); at least `floor`.
float percentileClip(const ImageLayer& layer, size_t first, size_t count, float floor) {
  std::vector<float> v = channels(layer, first, count, 1e30f);
  std::nth_element(v.begin(), v.begin() + v.size() * 99 / 100, v.end());
  return std::max(2.0f * v[v.size() * 99 / 100], floor);
}

const ImageLayer& layerOf(const LayeredImage& image, const char* name) {
  const ImageLayer* l = image.find(name);
  if (!l) {
    ADD_FAILURE() << "no layer '" << name << "'";
    static const ImageLayer empty{"", {"R"}, {0.0f}};
    return empty;
  }
  return *l;
}

// Compares channels [first, first + count) of `name` in `got` against `want`.
void expectClose(const LayeredImage& got, const LayeredImage& want, const char* name, size_t first,
                 size_t count, float clip, double minPsnr, double maxError) {
  SCOPED_TRACE(std::string("layer '") + name + "' channels " + std::to_string(first) + ".." +
               std::to_string(first + count - 1) + ", clip " + std::to_string(clip));
  const std::vector<float> a = channels(layerOf(got, name), first, count, clip);
  const std::vector<float> b = channels(layerOf(want, name), first, count, clip);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_GE(psnr(a, b, clip), minPsnr);
  if (maxError > 0.0) {
    EXPECT_LE(maxAbsError(a, b), maxError * clip);
  }
}

class CloudGolden : public test::CloudRenderTest,
                    public ::testing::WithParamInterface<GoldenCase> {};

TEST_P(CloudGolden, MatchesReference) {
  const GoldenCase& c = GetParam();
  const Scene scene = test::cloudScene(c.scene, {std::string("clouds.model=") + c.model});
  const RenderedFrame frame = render(scene);
  ASSERT_TRUE(frame.clouds);
  LayeredImage image;
  image.width = frame.image.width;
  image.height = frame.image.height;
  image.layers = {layerOf(frame.image, ""), layerOf(frame.image, "clouds")};
  const fs::path golden = test::goldenDir() / (goldenName(c) + ".exr");
  if (const char* u = std::getenv("SKY_UPDATE_GOLDEN"); u && std::string(u) == "1") {
    fs::create_directories(golden.parent_path());
    writeExr(golden, image);
    GTEST_SKIP() << "wrote " << golden;
  }
  const LayeredImage& got = image;
  const LayeredImage want = readExr(golden);
  ASSERT_EQ(got.width, want.width);
  ASSERT_EQ(got.height, want.height);
  const ImageLayer& ref = layerOf(want, "clouds");
  expectClose(got, want, "", 0, 3, percentileClip(layerOf(want, ""), 0, 3, 1e-6f), 40.0, 0.04);
  expectClose(got, want, "clouds", 0, 3, percentileClip(ref, 0, 3, 1e-6f), 40.0, 0.04);
  expectClose(got, want, "clouds", 3, 1, 1.0f, 40.0, 0.04);
  expectClose(got, want, "clouds", 4, 1, kDepthClipM, 30.0, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Scenes, CloudGolden,
                         ::testing::Values(GoldenCase{"cumulus_noon", "lu2023"},
                                           GoldenCase{"cumulus_noon", "tang2019"},
                                           GoldenCase{"stratocumulus_dusk", "lu2023"},
                                           GoldenCase{"stratocumulus_dusk", "tang2019"},
                                           GoldenCase{"altocumulus_full_moon", "lu2023"},
                                           GoldenCase{"altocumulus_full_moon", "tang2019"},
                                           // The whole composite (issue 15): the ground and
                                           // the air under an overcast, and from an aircraft.
                                           GoldenCase{"overcast_stratus", "lu2023"},
                                           GoldenCase{"from_5km", "lu2023"}),
                         [](const ::testing::TestParamInfo<GoldenCase>& param) {
                           return goldenName(param.param);
                         });

// Guards against references that could not catch a lost cloud layer or a swapped model: each
// has clouds with clear sky between them, and the two models differ.
TEST(CloudGoldenSet, ReferencesHaveCloudsAndDifferByModel) {
  for (const char* scene : {"cumulus_noon", "stratocumulus_dusk", "altocumulus_full_moon"}) {
    SCOPED_TRACE(scene);
    const LayeredImage lu = readExr(test::goldenDir() / (std::string(scene) + "_lu2023.exr"));
    const LayeredImage tang = readExr(test::goldenDir() / (std::string(scene) + "_tang2019.exr"));
    const CameraSettings cam = test::cloudScene(scene).camera;
    for (const LayeredImage* image : {&lu, &tang}) {
      const std::vector<float> alpha = channels(layerOf(*image, "clouds"), 3, 1, 1.0f);
      ASSERT_EQ(alpha.size(), static_cast<size_t>(image->width) * image->height);
      int sky = 0, dense = 0, clear = 0;
      for (int y = 0; y < image->height; ++y)
        for (int x = 0; x < image->width; ++x) {
          if (test::pixelDirection(cam, image->width, image->height, x, y).z < 0.02f) continue;
          const float a = alpha[static_cast<size_t>(y) * image->width + x];
          ++sky;
          dense += a > 0.8f;
          clear += a < 0.2f;
        }
      EXPECT_GT(dense, sky / 5) << "clouds";
      EXPECT_GT(clear, sky / 50) << "and sky between them";
    }
    const ImageLayer& ref = layerOf(lu, "clouds");
    const float clip = percentileClip(ref, 0, 3, 1e-6f);
    EXPECT_LT(psnr(channels(ref, 0, 3, clip), channels(layerOf(tang, "clouds"), 0, 3, clip), clip),
              30.0)
        << "lu2023 and tang2019 look the same";
  }
}

}  // namespace
}  // namespace sky
