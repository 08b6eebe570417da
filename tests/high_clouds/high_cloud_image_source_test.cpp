// HighCloudTextures with source "image": the fixtures in tests/data/high_clouds load as
// documented (PNG codes / 255, EXR as is, normal maps decoded n = 2c - 1), normals are derived
// when none are given, the coarse texture and the mean follow from the coefficients, and bad
// files are one-line BadInput errors naming the key path and the file.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <gmock/gmock.h>

#include "engine/core/error.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"
#include "error_capture.h"
#include "tests/high_clouds/high_cloud_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::catchError;
using test::Fetched;
using test::highCloudData;
using test::HighCloudTest;
using test::imageScene;

// Half floats keep 11 significant bits: values in [0, 1] are exact to 2^-11.
constexpr float kHalf = 1.0f / 1024.0f;

// The box filter the coarse texture must equal, in double.
std::vector<float> boxFilter(const Fetched& f) {
  const uint32_t c = f.coarseSize, box = f.size / c;
  std::vector<float> out(size_t(c) * c * 4);
  for (uint32_t cy = 0; cy < c; ++cy)
    for (uint32_t cx = 0; cx < c; ++cx)
      for (int ch = 0; ch < 4; ++ch) {
        double sum = 0;
        for (uint32_t y = 0; y < box; ++y)
          for (uint32_t x = 0; x < box; ++x)
            sum += f.at(f.coefficients, cx * box + x, cy * box + y, ch);
        out[(size_t(cy) * c + cx) * 4 + size_t(ch)] = float(sum / (box * box));
      }
  return out;
}

glm::vec4 meanOf(const std::vector<float>& rgba) {
  glm::dvec4 sum(0.0);
  for (size_t i = 0; i < rgba.size(); i += 4)
    sum += glm::dvec4(rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]);
  return glm::vec4(sum / double(rgba.size() / 4));
}

void expectUnitNormals(const Fetched& f) {
  for (size_t i = 0; i < f.normals.size(); i += 4) {
    const glm::vec3 n(f.normals[i], f.normals[i + 1], f.normals[i + 2]);
    ASSERT_NEAR(glm::length(n), 1.0f, 2e-3f) << "texel " << i / 4;
    ASSERT_GT(n.z, 0.0f) << "texel " << i / 4;  // the normal points out of the layer
    ASSERT_EQ(f.normals[i + 3], 0.0f);
  }
}

TEST_F(HighCloudTest, PngFixtureLoadsWithItsNormalMap) {
  auto textures = make();
  const Fetched f = fetch(*textures, imageScene("coefficients_64.png", "normals_64.png"));
  EXPECT_TRUE(f.activity.loadedImages);
  EXPECT_FALSE(f.activity.baked);
  EXPECT_FALSE(f.activity.loadedCache);
  ASSERT_EQ(f.size, 64u);
  ASSERT_EQ(f.coarseSize, 4u);

  const Image8 png = readPng(highCloudData() / "coefficients_64.png");
  ASSERT_EQ(png.channels, 4);
  for (size_t i = 0; i < png.pixels.size(); ++i)
    ASSERT_NEAR(f.coefficients[i], png.pixels[i] / 255.0f, kHalf) << "value " << i;

  const Image8 normals = readPng(highCloudData() / "normals_64.png");
  ASSERT_EQ(normals.channels, 3);
  for (size_t t = 0; t < 64 * 64; ++t) {
    glm::vec3 n;
    for (int c = 0; c < 3; ++c) n[c] = 2.0f * normals.pixels[t * 3 + size_t(c)] / 255.0f - 1.0f;
    n = glm::normalize(n);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(f.normals[t * 4 + size_t(c)], n[c], kHalf) << t;
  }
  expectUnitNormals(f);

  EXPECT_LE(test::maxDifference(f.coarse, boxFilter(f)), kHalf);
  const glm::vec4 mean = meanOf(f.coefficients);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(f.mean[c], mean[c], kHalf) << "channel " << c;
}

TEST_F(HighCloudTest, ExrFixtureLoadsAsIsWithDerivedNormals) {
  auto textures = make();
  const Fetched f = fetch(*textures, imageScene("coefficients_32.exr"));
  EXPECT_TRUE(f.activity.loadedImages);
  ASSERT_EQ(f.size, 32u);
  ASSERT_EQ(f.coarseSize, 4u);  // 32 / 16 = 2, but never below 4
  const LayeredImage exr = readExr(highCloudData() / "coefficients_32.exr");
  const ImageLayer* layer = exr.find("");
  ASSERT_NE(layer, nullptr);
  for (size_t i = 0; i < layer->pixels.size(); ++i)
    ASSERT_NEAR(f.coefficients[i], layer->pixels[i], kHalf) << "value " << i;
  expectUnitNormals(f);
  EXPECT_LE(test::maxDifference(f.coarse, boxFilter(f)), kHalf);
  // The fixture is not flat: its derived normals must lean somewhere (a gentle wave of 1 and 2
  // cycles a tile under a relief of 0.015 tiles leans them by up to about 0.07).
  float lean = 0.0f;
  for (size_t i = 0; i < f.normals.size(); i += 4)
    lean = std::max(lean, std::hypot(f.normals[i], f.normals[i + 1]));
  EXPECT_GT(lean, 0.03f);
}

TEST_F(HighCloudTest, DerivedNormalsAreFlatForAFlatImage) {
  auto textures = make();
  const Fetched f = fetch(*textures, imageScene("flat_64.png"));
  for (size_t i = 0; i < f.normals.size(); i += 4) {
    ASSERT_EQ(f.normals[i], 0.0f) << "texel " << i / 4;
    ASSERT_EQ(f.normals[i + 1], 0.0f) << "texel " << i / 4;
    ASSERT_EQ(f.normals[i + 2], 1.0f) << "texel " << i / 4;
  }
  EXPECT_NEAR(f.mean.x, 100 / 255.0f, kHalf);
  EXPECT_NEAR(f.mean.z, 128 / 255.0f, kHalf);
}

// The derived normals are the documented central differences of the opacity, with wrap, x east
// and y north (towards row 0), for a relief of HIGH_CLOUD_NORMAL_RELIEF tiles.
TEST_F(HighCloudTest, DerivedNormalsFollowTheOpacityUphillConvention) {
  auto textures = make();
  const Fetched f = fetch(*textures, imageScene("coefficients_64.png"));
  const uint32_t n = f.size;
  const float relief = float(HIGH_CLOUD_NORMAL_RELIEF) * float(n);
  auto h = [&](int x, int y) {
    return f.opacity(uint32_t((x + int(n)) % int(n)), uint32_t((y + int(n)) % int(n)));
  };
  float worst = 0.0f;
  for (int y = 0; y < int(n); ++y)
    for (int x = 0; x < int(n); ++x) {
      const float dx = 0.5f * (h(x + 1, y) - h(x - 1, y));
      const float dy = 0.5f * (h(x, y - 1) - h(x, y + 1));  // north is the previous row
      const glm::vec3 ref = glm::normalize(glm::vec3(-relief * dx, -relief * dy, 1.0f));
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(f.at(f.normals, uint32_t(x), uint32_t(y), c) - ref[c]));
    }
  EXPECT_LE(worst, 2e-3f);
  // The fixture's opacity rises eastwards at its west edge (sin(2 pi x / 64) at x = 0): the
  // surface climbs to the east there, so the normal leans west (x < 0).
  EXPECT_LT(f.at(f.normals, 0, 10, 0), -0.02f);
}

std::string errorOf(HighCloudTextures& textures, const Scene& scene, FrameGraph& graph) {
  const Error e = catchError([&] { textures.addTo(graph, scene); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
  const std::string what = e.what();
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  return what;
}

TEST_F(HighCloudTest, BadImagesAreOneLineInputErrorsNamingKeyAndFile) {
  auto textures = make();
  FrameGraph graph(runtime());
  using ::testing::HasSubstr;
  EXPECT_THAT(errorOf(*textures, imageScene("missing.png"), graph),
              HasSubstr("high_clouds.coefficients: missing.png: file not found"));
  EXPECT_EQ(errorOf(*textures, imageScene("rgb_64.png"), graph),
            "high_clouds.coefficients: rgb_64.png: must be RGBA (4 channels), has 3");
  EXPECT_EQ(errorOf(*textures, imageScene("nonsquare_64x32.png"), graph),
            "high_clouds.coefficients: nonsquare_64x32.png: must be square, is 64x32");
  EXPECT_EQ(errorOf(*textures, imageScene("npot_48.png"), graph),
            "high_clouds.coefficients: npot_48.png: size 48x48 must be a power of two from 16 "
            "to 8192");
  EXPECT_EQ(errorOf(*textures, imageScene("coefficients_64.png", "normals_32.png"), graph),
            "high_clouds.normals: normals_32.png: size 32x32 differs from the coefficients' 64x64");
  EXPECT_THAT(errorOf(*textures, imageScene("coefficients_64.png", "nope.exr"), graph),
              HasSubstr("high_clouds.normals: nope.exr: file not found"));
  EXPECT_THAT(errorOf(*textures, imageScene("../high_clouds"), graph),
              HasSubstr("high_clouds.coefficients: ../high_clouds: must be a PNG or EXR file"));

  EXPECT_EQ(errorOf(*textures, imageScene(""), graph),
            "high_clouds.coefficients: is required when source is image");

  // A file that is there but is no PNG: the reader's reason, still one line with key and file.
  const fs::path junk = cache() / "junk.png";
  { std::ofstream(junk) << "not a png"; }
  Scene scene = imageScene(junk.string());
  EXPECT_THAT(errorOf(*textures, scene, graph),
              HasSubstr("high_clouds.coefficients: " + junk.string() + ": cannot read PNG"));

  // After errors the object loads again and works.
  const Fetched f = fetch(*textures, imageScene("flat_64.png"));
  EXPECT_TRUE(f.activity.loadedImages);
  EXPECT_EQ(f.size, 64u);
}

TEST_F(HighCloudTest, ChangedImageFileIsReloaded) {
  const fs::path file = cache() / "clouds.png";
  fs::copy_file(highCloudData() / "flat_64.png", file);
  Scene scene = imageScene(file.string());
  auto textures = make();
  Fetched first = fetch(*textures, scene);
  EXPECT_TRUE(first.activity.loadedImages);
  EXPECT_FALSE(fetch(*textures, scene).activity.loadedImages);  // unchanged: nothing read

  fs::copy_file(highCloudData() / "coefficients_64.png", file,
                fs::copy_options::overwrite_existing);
  fs::last_write_time(file, fs::last_write_time(file) + std::chrono::seconds(2));
  Fetched second = fetch(*textures, scene);
  EXPECT_TRUE(second.activity.loadedImages);
  EXPECT_GT(test::maxDifference(first.coefficients, second.coefficients), 0.1f);
}

}  // namespace
}  // namespace sky
