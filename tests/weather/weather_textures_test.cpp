// engine/weather/coarse_cover.h and engine/render/weather_textures.h: the coarse max-cover map
// is conservative (no map texel and no bilinear lookup of the map within a coarse texel
// exceeds it; on the CPU and as the GPU samples the uploaded images), and WeatherTextures
// (RevisionedImage) uploads only when the revision changes, and again after a failed frame.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/pass_context.h"
#include "engine/shader/shader_compiler.h"
#include "engine/render/weather_textures.h"
#include "engine/weather/coarse_cover.h"
#include "gpu_test.h"

namespace sky {
namespace {
using test::GpuTest;

// Random cover over the west third, and two single cloudy texels in the clear rest: a map
// with empty space to skip and cloud edges at every phase of the coarse grid.
WeatherMap sparseMap(uint32_t width, uint32_t height, uint32_t seed) {
  WeatherMap map;
  map.region = WeatherRegion{{10.0, 12.0}, {20.0, 23.0}};
  map.width = width;
  map.height = height;
  map.texels.assign(size_t(width) * height, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width / 3; ++x) {
      glm::vec4& t = map.texels[size_t(y) * width + x];
      if (u(rng) < 0.3f) t.x = 0.2f + 0.8f * u(rng);
      if (u(rng) < 0.2f) t.y = 0.2f + 0.8f * u(rng);
    }
  map.texels[size_t(height / 2) * width + width * 2 / 3].x = 0.5f;
  map.texels[size_t(height - 1) * width + width - 1].y = 0.7f;
  return map;
}

TEST(CoarseCover, EveryTexelAndEveryNearbyLookupIsBelowItsCoarseTexel) {
  for (glm::uvec2 size : {glm::uvec2(64, 48), glm::uvec2(61, 37), glm::uvec2(5, 9)}) {
    SCOPED_TRACE(std::to_string(size.x) + "x" + std::to_string(size.y));
    const WeatherMap map = sparseMap(size.x, size.y, size.x);
    const WeatherMap coarse = coarseCoverMap(map);
    EXPECT_EQ(glm::uvec2(coarse.width, coarse.height), coarseCoverSize(size.x, size.y));
    EXPECT_EQ(coarseCoverSize(size.x, size.y), (size + 7u) / 8u);
    // Each map texel against the coarse texel that holds it.
    for (uint32_t y = 0; y < map.height; ++y)
      for (uint32_t x = 0; x < map.width; ++x) {
        const glm::vec4 c = coarse.at(x * coarse.width / map.width, y * coarse.height / map.height);
        ASSERT_LE(map.at(x, y).x, c.x);
        ASSERT_LE(map.at(x, y).y, c.y);
        ASSERT_EQ(c.z, std::max(c.x, c.y));
      }
    // Skipping: wherever a coarse texel is 0, the map sampled anywhere within one coarse
    // texel of that point is 0.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int skippable = 0;
    for (int i = 0; i < 20000; ++i) {
      const glm::dvec2 uv(u(rng), u(rng));
      const glm::uvec2 cell = glm::min(glm::uvec2(uv * glm::dvec2(coarse.width, coarse.height)),
                                       glm::uvec2(coarse.width - 1, coarse.height - 1));
      if (coarse.at(cell.x, cell.y).z > 0.0f) continue;
      ++skippable;
      for (int k = 0; k < 8; ++k) {
        const glm::dvec2 off =
            (glm::dvec2(u(rng), u(rng)) * 2.0 - 1.0) / glm::dvec2(coarse.width, coarse.height);
        const glm::dvec2 p = uv + off;
        const double lat = map.region.lat[1] - p.y * (map.region.lat[1] - map.region.lat[0]);
        const double lon = map.region.lon[0] + p.x * (map.region.lon[1] - map.region.lon[0]);
        const glm::vec4 s = map.sample(lat, lon);
        ASSERT_EQ(s.x, 0.0f) << "uv " << p.x << ", " << p.y;
        ASSERT_EQ(s.y, 0.0f);
      }
    }
    if (size.x > 8) {
      EXPECT_GT(skippable, 100) << "the test map leaves empty space to skip";
    }
  }
}

class WeatherTexturesTest : public GpuTest {
protected:
  struct Sampled {
    std::vector<float> map, coarse, results, nearest;
  };
  // Reads both images back and runs the sampling kernel on them, in one graph.
  Sampled run(WeatherTextures& texture, const WeatherMap& map, uint64_t revision) {
    ShaderCompiler compiler(shaderDir(), std::nullopt);
    const CompiledShader shader = compiler.compile(std::filesystem::path(SKY_WEATHER_TEST_DIR) /
                                                   "weather_sample_kernel.comp");
    ComputePipeline pipeline(ctx(), "weather_sample_kernel", shader.spirv, shader.reflection);
    FrameGraph graph(mRuntime);
    const WeatherTextures::Clouds out = texture.addClouds(graph, map, revision);
    ImageId results, nearest;
    GraphBuilder b = graph.addPass("weather_sample_kernel", [&](PassContext& pc) {
      pc.dispatch(pipeline,
                  {Binding::of(0, out.map, &texture.sampler()),
                   Binding::of(1, out.coarse, &texture.sampler()), Binding::of(2, results),
                   Binding::of(3, nearest)},
                  8, 8);
    });
    b.read(out.map, Access::SampledCompute);
    b.read(out.coarse, Access::SampledCompute);
    ImageDesc d;
    d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    d.width = d.height = 64;  // WEATHER_KERNEL_SIZE
    d.name = "results";
    results = b.write(b.create(d), Access::StorageWriteCompute);
    d.name = "nearest";
    nearest = b.write(b.create(d), Access::StorageWriteCompute);
    graph.requestOutput(out.map, "map");
    graph.requestOutput(out.coarse, "coarse");
    graph.requestOutput(results, "results");
    graph.requestOutput(nearest, "nearest");
    FrameResult r = graph.execute();
    return {r.output("map").pixels, r.output("coarse").pixels, r.output("results").pixels,
            r.output("nearest").pixels};
  }
  GraphRuntime mRuntime{ctx()};
};

TEST_F(WeatherTexturesTest, UploadedCoarseMapIsConservativeAsTheGpuSamplesIt) {
  const WeatherMap map = sparseMap(61, 45, 9);
  WeatherTextures texture(ctx());
  const Sampled s = run(texture, map, 1);
  const WeatherMap coarse = coarseCoverMap(map);
  ASSERT_EQ(s.map.size(), map.texels.size() * 4);
  ASSERT_EQ(s.coarse.size(), coarse.texels.size() * 4);
  // RGBA16F: the cover as uploaded, to half precision.
  for (size_t i = 0; i < map.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) ASSERT_NEAR(s.map[i * 4 + size_t(c)], map.texels[i][c], 1e-3);
  // Every map texel is at most its coarse texel, as stored on the GPU.
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 0; x < map.width; ++x) {
      const size_t m = (size_t(y) * map.width + x) * 4;
      const size_t c =
          (size_t(y * coarse.height / map.height) * coarse.width + x * coarse.width / map.width) *
          4;
      ASSERT_LE(s.map[m], s.coarse[c]) << x << ", " << y;
      ASSERT_LE(s.map[m + 1], s.coarse[c + 1]) << x << ", " << y;
    }
  // The shader's lookups: the map's bilinear sample never exceeds the coarse one (linear or
  // nearest), and a coarse 0 means a map 0.
  int zeros = 0;
  for (size_t i = 0; i < s.results.size(); i += 4) {
    for (int c = 0; c < 2; ++c) {
      ASSERT_LE(s.results[i + size_t(c)], s.results[i + 2 + size_t(c)] + 1e-6f)
          << "point " << i / 4;
      ASSERT_LE(s.results[i + size_t(c)], s.nearest[i + size_t(c)] + 1e-6f) << "point " << i / 4;
    }
    if (s.nearest[i + 2] == 0.0f) {
      ++zeros;
      ASSERT_EQ(s.results[i], 0.0f);
      ASSERT_EQ(s.results[i + 1], 0.0f);
    }
  }
  EXPECT_GT(zeros, 0) << "the test map leaves empty space to skip";
  EXPECT_EQ(texture.mapUploadCount(), 1u);
}

TEST_F(WeatherTexturesTest, UploadsOnlyWhenTheRevisionChanges) {
  WeatherTextures texture(ctx());
  WeatherMap map = sparseMap(16, 16, 1);
  for (glm::vec4& t : map.texels) t.x = 0.25f;
  EXPECT_EQ(run(texture, map, 7).map[0], 0.25f);
  // Same revision: the images stay as they were even though the map changed.
  for (glm::vec4& t : map.texels) t.x = 0.75f;
  EXPECT_EQ(run(texture, map, 7).map[0], 0.25f);
  EXPECT_EQ(texture.mapUploadCount(), 1u);
  // A new revision uploads, also at a new size.
  EXPECT_EQ(run(texture, map, 8).map[0], 0.75f);
  const WeatherMap bigger = sparseMap(40, 24, 2);
  const Sampled s = run(texture, bigger, 9);
  EXPECT_EQ(s.map.size(), size_t(40 * 24 * 4));
  EXPECT_EQ(s.coarse.size(), size_t(5 * 3 * 4));
  EXPECT_EQ(texture.mapUploadCount(), 3u);
}

TEST_F(WeatherTexturesTest, AFrameThatFailsAfterTheUploadIsRecordedUploadsAgain) {
  WeatherTextures texture(ctx());
  WeatherMap map = sparseMap(16, 16, 1);
  for (glm::vec4& t : map.texels) t.x = 0.25f;
  EXPECT_EQ(run(texture, map, 1).map[0], 0.25f);
  // Revision 2 is added to a frame that is never executed (a later pass's setup failed).
  for (glm::vec4& t : map.texels) t.x = 0.75f;
  {
    FrameGraph failed(mRuntime);
    (void)texture.addClouds(failed, map, 2);
  }
  EXPECT_EQ(texture.mapUploadCount(), 1u);
  // The next frame with revision 2 uploads it: the image never held it.
  EXPECT_EQ(run(texture, map, 2).map[0], 0.75f);
  EXPECT_EQ(texture.mapUploadCount(), 2u);
}

}  // namespace
}  // namespace sky
