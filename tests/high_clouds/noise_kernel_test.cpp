// shaders/common/noise.glsl against a C++ reference (Falcor-style kernel test,
// tests/data/high_clouds/noise_kernel.comp): gradient, value and Worley noise on a grid of
// points, fbm, and the periodicity every baked texture's tiling rests on.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include "noise_hash_reference.h"
#include "engine/core/paths.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/pass_context.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::GpuTest;
using test::hash3;
using test::seedOf;

// --- The reference, line by line as in noise.glsl, in double where GLSL has float. ---
glm::dvec3 hashUnit3(glm::uvec3 v) {
  return glm::dvec3(hash3(v) >> 8u) * (1.0 / 16777216.0);
}
glm::uvec2 wrap2(glm::ivec2 cell, glm::ivec2 period) {
  return glm::uvec2(cell + period * 64) % glm::uvec2(period);
}
glm::dvec2 gradient2(glm::ivec2 cell, glm::ivec2 period, uint32_t seed) {
  const double angle = 2 * M_PI * hashUnit3({wrap2(cell, period), seed}).x - M_PI;
  return {std::cos(angle), std::sin(angle)};
}
glm::dvec2 fade2(glm::dvec2 t) {
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}
double gradientNoise(glm::dvec2 p, glm::ivec2 period, uint32_t seed) {
  const glm::dvec2 i = glm::floor(p), f = p - i;
  const glm::ivec2 c(i);
  const double n00 = glm::dot(gradient2(c, period, seed), f);
  const double n10 = glm::dot(gradient2(c + glm::ivec2(1, 0), period, seed), f - glm::dvec2(1, 0));
  const double n01 = glm::dot(gradient2(c + glm::ivec2(0, 1), period, seed), f - glm::dvec2(0, 1));
  const double n11 = glm::dot(gradient2(c + glm::ivec2(1, 1), period, seed), f - glm::dvec2(1, 1));
  const glm::dvec2 u = fade2(f);
  return std::sqrt(2.0) * glm::mix(glm::mix(n00, n10, u.x), glm::mix(n01, n11, u.x), u.y);
}
double valueNoise(glm::dvec2 p, glm::ivec2 period, uint32_t seed) {
  const glm::dvec2 i = glm::floor(p), f = p - i;
  const glm::ivec2 c(i);
  auto v = [&](glm::ivec2 o) { return hashUnit3({wrap2(c + o, period), seed}).x; };
  const glm::dvec2 u = fade2(f);
  return glm::mix(glm::mix(v({0, 0}), v({1, 0}), u.x), glm::mix(v({0, 1}), v({1, 1}), u.x), u.y);
}
glm::dvec2 worley(glm::dvec2 p, glm::ivec2 period, uint32_t seed, double jitter) {
  const glm::dvec2 i = glm::floor(p), f = p - i;
  const glm::ivec2 c(i);
  std::vector<double> d;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const glm::ivec2 o(dx, dy);
      const glm::dvec2 h(hashUnit3({wrap2(c + o, period), seed}));
      d.push_back(glm::length(glm::dvec2(o) + 0.5 + jitter * (h - 0.5) - f));
    }
  std::sort(d.begin(), d.end());
  return {d[0], d[1]};
}
template <class F>
double fbm(F noise, glm::dvec2 p, glm::ivec2 period, uint32_t seed, int octaves, double gain) {
  double sum = 0, amplitude = 1, norm = 0;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * noise(p, period, seedOf(seed, uint32_t(i)));
    norm += amplitude;
    amplitude *= gain;
    p *= 2.0;
    period *= 2;
  }
  return sum / norm;
}
double ridged(glm::dvec2 p, glm::ivec2 period, uint32_t seed) {
  const double r = 1.0 - std::abs(gradientNoise(p, period, seed));
  return r * r;
}

TEST_F(GpuTest, NoiseMatchesTheReferenceAndIsPeriodic) {
  ShaderCompiler compiler(shaderDir(), std::nullopt);
  const CompiledShader shader = compiler.compile(fs::path(std::getenv("SKY_TEST_DATA")) /
                                                 "high_clouds" / "noise_kernel.comp");
  ComputePipeline pipeline(ctx(), "noise_kernel", shader.spirv, shader.reflection);
  GraphRuntime runtime(ctx());
  FrameGraph graph(runtime);
  ImageId images[3];
  GraphBuilder b = graph.addPass("noise_kernel", [&](PassContext& pc) {
    pc.dispatch(pipeline,
                {Binding::of(0, images[0]), Binding::of(1, images[1]), Binding::of(2, images[2])},
                8, 8);
  });
  const char* names[3] = {"at point", "at shifted", "fbm"};
  for (int i = 0; i < 3; ++i) {
    ImageDesc desc;
    desc.name = names[i];
    desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    desc.width = desc.height = 64;
    images[i] = b.write(b.create(desc), Access::StorageWriteCompute);
  }
  for (int i = 0; i < 3; ++i) graph.requestOutput(images[i], names[i]);
  const FrameResult result = graph.execute();
  const std::vector<float>& point = result.output("at point").pixels;
  const std::vector<float>& shifted = result.output("at shifted").pixels;
  const std::vector<float>& fbms = result.output("fbm").pixels;

  const glm::ivec2 period(5, 3);
  const uint32_t seed = 77;
  // sin/cos on the GPU are good to 2^-11 (Vulkan's bound); the rest is float rounding.
  constexpr double kTolerance = 2e-3;
  double range[2] = {1e9, -1e9};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      SCOPED_TRACE("point " + std::to_string(x) + ", " + std::to_string(y));
      const size_t i = (size_t(y) * 64 + size_t(x)) * 4;
      const glm::dvec2 p = glm::dvec2(x, y) * double(0.173f) - glm::dvec2(2.7, 1.9);
      const glm::dvec2 f = worley(p, period, seed, 0.8);
      const double ref[4] = {gradientNoise(p, period, seed), valueNoise(p, period, seed), f.x, f.y};
      for (int c = 0; c < 4; ++c) {
        ASSERT_NEAR(point[i + size_t(c)], ref[c], kTolerance) << "function " << c;
        // Whole periods away, the same value: what makes every baked texture tile.
        ASSERT_NEAR(shifted[i + size_t(c)], point[i + size_t(c)], 1e-4) << "function " << c;
      }
      ASSERT_NEAR(fbms[i], fbm(gradientNoise, p, period, seed, 4, 0.5), kTolerance);
      ASSERT_NEAR(fbms[i + 1], fbm(valueNoise, p, period, seed, 3, 0.6), kTolerance);
      ASSERT_NEAR(fbms[i + 2], fbm(ridged, p, period, seed, 3, 0.5), kTolerance);
      ASSERT_NEAR(fbms[i + 3], fbms[i], 1e-4);
      range[0] = std::min(range[0], ref[0]);
      range[1] = std::max(range[1], ref[0]);
    }
  // The grid samples the noise well: gradient noise swings through most of [-1, 1].
  EXPECT_LT(range[0], -0.5);
  EXPECT_GT(range[1], 0.5);
}

}  // namespace
}  // namespace sky
