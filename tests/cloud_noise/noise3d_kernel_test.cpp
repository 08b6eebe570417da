// shaders/common/noise3d.glsl against a C++ reference (Falcor-style kernel test,
// tests/cloud_noise/noise3d_kernel.comp): periodic Perlin noise and its analytic gradient,
// periodic simplex noise, Worley F1, their fbm and curl noise on a grid of points, and the
// periodicity every baked cloud-noise texture's tiling rests on. The reference also checks
// itself where the maths allows: the gradient against finite differences, the curl's
// divergence against zero.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
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
using glm::dvec3;
using glm::dvec4;
using glm::ivec3;
using glm::uvec3;
using test::GpuTest;
using test::hash3;
using test::seedOf;

// --- The reference, function by function as in noise3d.glsl, in double where GLSL has float
// and with exact integer wrapping where GLSL estimates the quotient in float. ---
int wrap(int c, int period) {
  return ((c % period) + period) % period;
}
ivec3 wrap3(ivec3 c, ivec3 period) {
  return {wrap(c.x, period.x), wrap(c.y, period.y), wrap(c.z, period.z)};
}
uvec3 cellHash(ivec3 wrapped, uint32_t seed) {
  return hash3({uint32_t(wrapped.x), uint32_t(wrapped.y), uint32_t(wrapped.z) ^ seed});
}
dvec3 unitOf(uvec3 h) {
  return dvec3(h >> 8u) / 16777216.0;
}

dvec3 perlinGradient(uint32_t h) {
  h >>= 28u;
  const double su = (h & 1u) ? -1 : 1, sv = (h & 2u) ? -1 : 1;
  if (h < 4u) return {su, sv, 0};
  if (h < 8u) return {su, 0, sv};
  if (h == 12u || h == 14u) return {sv, su, 0};
  return {0, su, sv};
}

// Perlin noise as the trilinear blend of the eight corners' ramps; the gradient separately
// by the product rule, so the reference does not share the shader's polynomial form.
dvec4 perlin(dvec3 p, ivec3 period, uint32_t seed) {
  const dvec3 i = glm::floor(p), f = p - i;
  const dvec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
  const dvec3 du = 30.0 * f * f * (f - 1.0) * (f - 1.0);
  double value = 0;
  dvec3 grad(0);
  for (int corner = 0; corner < 8; ++corner) {
    const ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const dvec3 g = perlinGradient(cellHash(wrap3(ivec3(i) + o, period), seed).x);
    const double ramp = glm::dot(g, f - dvec3(o));
    dvec3 w, dw;  // per-axis weights and their derivatives
    for (int a = 0; a < 3; ++a) {
      w[a] = o[a] ? u[a] : 1 - u[a];
      dw[a] = o[a] ? du[a] : -du[a];
    }
    const double weight = w.x * w.y * w.z;
    value += weight * ramp;
    grad += weight * g + ramp * dvec3(dw.x * w.y * w.z, w.x * dw.y * w.z, w.x * w.y * dw.z);
  }
  return {value, grad};
}

dvec3 unitVector(uvec3 h) {
  const dvec3 r = unitOf(h);
  const double z = 1 - 2 * r.x, s = std::sqrt(std::max(1 - z * z, 0.0));
  const double angle = 2 * M_PI * r.y - M_PI;
  return {s * std::cos(angle), s * std::sin(angle), z};
}

// Gustavson and McEwan's lattice: vertices Mi * i of the Kuhn simplex around M p.
double simplex(dvec3 p, ivec3 period, uint32_t seed) {
  const dvec3 uvw(p.y + p.z, p.x + p.z, p.x + p.y);
  const dvec3 i0f = glm::floor(uvw), f0 = uvw - i0f;
  const ivec3 i0(i0f);
  const ivec3 o1(f0.x > f0.y && f0.x > f0.z, f0.y >= f0.x && f0.y > f0.z,
                 f0.z >= f0.x && f0.z >= f0.y);
  const ivec3 o2(f0.x > f0.y || f0.x > f0.z, f0.y >= f0.x || f0.y > f0.z,
                 f0.z >= f0.x || f0.z >= f0.y);
  const std::array<ivec3, 4> corners = {i0, i0 + o1, i0 + o2, i0 + 1};
  double n = 0;
  for (const ivec3& i : corners) {
    const ivec3 v2(i.y + i.z - i.x, i.x + i.z - i.y, i.x + i.y - i.z);
    const dvec3 x = p - 0.5 * dvec3(v2);
    const double w = std::max(0.5 - glm::dot(x, x), 0.0);
    const ivec3 v = wrap3(v2, 2 * period);
    const ivec3 id = ivec3(v.y + v.z, v.x + v.z, v.x + v.y) / 2;
    n += w * w * w * glm::dot(unitVector(cellHash(id, seed)), x);
  }
  return 39.5 * n;
}

double worleyF1(dvec3 p, ivec3 period, uint32_t seed) {
  const dvec3 i = glm::floor(p), f = p - i;
  double d2 = 8;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const ivec3 o(dx, dy, dz);
        const dvec3 d = dvec3(o) + unitOf(cellHash(wrap3(ivec3(i) + o, period), seed)) - f;
        d2 = std::min(d2, glm::dot(d, d));
      }
  return std::sqrt(d2);
}

template <class F>
double fbm(F noise, dvec3 p, ivec3 period, uint32_t seed, int octaves, double gain) {
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

dvec3 curl(dvec3 p, ivec3 period, uint32_t seed, int octaves, double gain) {
  dvec3 d[3] = {dvec3(0), dvec3(0), dvec3(0)};  // gradients of psi_x, psi_y, psi_z
  double amplitude = 1, norm = 0;
  for (int i = 0; i < octaves; ++i) {
    for (uint32_t k = 0; k < 3; ++k) {
      const dvec4 n = perlin(p, period, seedOf(seedOf(seed, k), uint32_t(i)));
      d[k] += amplitude * double(1 << i) * dvec3(n.y, n.z, n.w);
    }
    norm += amplitude;
    amplitude *= gain;
    p *= 2.0;
    period *= 2;
  }
  return dvec3(d[2].y - d[1].z, d[0].z - d[2].x, d[1].x - d[0].y) / norm;
}

const ivec3 kPeriod(5, 3, 4);
constexpr uint32_t kSeed = 77;

dvec3 pointOf(int x, int y) {
  const double s = double(0.173f);
  return dvec3(x, y, 0.5 * x - 0.3 * y) * s - dvec3(2.7, 1.9, 0.6);
}

// The reference's own consistency, on the CPU: the Perlin gradient matches central
// differences of the value, and the curl is divergence-free (its divergence from central
// differences of the curl is at the differences' error, far below the curl's size).
TEST(Noise3dReference, GradientIsTheDerivativeAndCurlHasNoDivergence) {
  const double h = 1e-5;
  for (int k = 0; k < 200; ++k) {
    const dvec3 p = pointOf(k % 17, k / 17) + dvec3(0.01 * k, 0.0, -0.02 * k);
    SCOPED_TRACE("point " + std::to_string(k));
    const dvec4 n = perlin(p, kPeriod, kSeed);
    for (int a = 0; a < 3; ++a) {
      dvec3 e(0);
      e[a] = h;
      const double fd =
          (perlin(p + e, kPeriod, kSeed).x - perlin(p - e, kPeriod, kSeed).x) / (2 * h);
      ASSERT_NEAR(n[a + 1], fd, 1e-6) << "axis " << a;
    }
    double divergence = 0, size = 0;
    for (int a = 0; a < 3; ++a) {
      dvec3 e(0);
      e[a] = h;
      divergence +=
          (curl(p + e, kPeriod, kSeed, 2, 0.5)[a] - curl(p - e, kPeriod, kSeed, 2, 0.5)[a]) /
          (2 * h);
      size += std::abs(curl(p, kPeriod, kSeed, 2, 0.5)[a]);
    }
    ASSERT_LT(std::abs(divergence), 1e-4);
    ASSERT_GT(size, 1e-3);  // not trivially zero
  }
}

// Continuity, what tiling by periodic lattices needs besides equal values: along a long line
// in a skew direction (crossing every kind of cell and simplex face), no step of 1e-4 changes
// the noise by more than a Lipschitz bound would allow. A vertex whose kernel reaches past its
// simplex, or a Worley search that misses a nearer point, would show as a jump here.
TEST(Noise3dReference, NoiseIsContinuousAcrossCellsAndSimplices) {
  const dvec3 dir = glm::normalize(dvec3(1.0, 0.37, 0.61));
  const double step = 1e-4;
  double previous[3] = {};
  double worst[3] = {0, 0, 0};
  for (int k = 0; k <= 200000; ++k) {
    const dvec3 p = dvec3(-3.1, 0.2, 1.7) + dir * (step * k);
    const double now[3] = {perlin(p, kPeriod, kSeed).x, simplex(p, kPeriod, kSeed),
                           worleyF1(p, kPeriod, kSeed)};
    for (int f = 0; f < 3 && k > 0; ++f)
      worst[f] = std::max(worst[f], std::abs(now[f] - previous[f]));
    std::copy(now, now + 3, previous);
  }
  // Slopes: Perlin's gradient stays below 4, simplex's below 10, F1's is at most 1.
  EXPECT_LT(worst[0], 4 * step) << "Perlin";
  EXPECT_LT(worst[1], 10 * step) << "simplex";
  EXPECT_LE(worst[2], 1.0001 * step) << "Worley F1";
}

TEST_F(GpuTest, Noise3dMatchesTheReferenceAndIsPeriodic) {
  ShaderCompiler compiler(shaderDir(), std::nullopt);
  const fs::path kernel =
      fs::path(std::getenv("SKY_TEST_DATA")).parent_path() / "cloud_noise" / "noise3d_kernel.comp";
  const CompiledShader shader = compiler.compile(kernel);
  ComputePipeline pipeline(ctx(), "noise3d_kernel", shader.spirv, shader.reflection);
  GraphRuntime runtime(ctx());
  FrameGraph graph(runtime);
  constexpr int kImages = 5;
  ImageId images[kImages];
  GraphBuilder b = graph.addPass("noise3d_kernel", [&](PassContext& pc) {
    pc.dispatch(pipeline,
                {Binding::of(0, images[0]), Binding::of(1, images[1]), Binding::of(2, images[2]),
                 Binding::of(3, images[3]), Binding::of(4, images[4])},
                8, 8);
  });
  const char* names[kImages] = {"perlin", "perlin moved", "cellular", "fbm", "curl"};
  for (int i = 0; i < kImages; ++i) {
    ImageDesc desc;
    desc.name = names[i];
    desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    desc.width = desc.height = 64;
    images[i] = b.write(b.create(desc), Access::StorageWriteCompute);
  }
  for (int i = 0; i < kImages; ++i) graph.requestOutput(images[i], names[i]);
  const FrameResult result = graph.execute();
  const std::vector<float>& perlinAt = result.output("perlin").pixels;
  const std::vector<float>& perlinMoved = result.output("perlin moved").pixels;
  const std::vector<float>& cellular = result.output("cellular").pixels;
  const std::vector<float>& fbms = result.output("fbm").pixels;
  const std::vector<float>& curls = result.output("curl").pixels;

  // Float rounding, and sin/cos (simplex gradients) good to 2^-11 on the GPU (Vulkan's bound).
  constexpr double kTolerance = 2e-3;
  // Whole periods away, the same value up to the float rounding of the moved point.
  constexpr double kPeriodic = 2e-4;
  double simplexRange[2] = {1e9, -1e9}, worleyRange[2] = {1e9, -1e9};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      SCOPED_TRACE("point " + std::to_string(x) + ", " + std::to_string(y));
      const size_t i = (size_t(y) * 64 + size_t(x)) * 4;
      const dvec3 p = pointOf(x, y);
      const dvec4 pn = perlin(p, kPeriod, kSeed);
      for (int c = 0; c < 4; ++c) {
        // The gradient is about 4 times the value's size: a tolerance to match.
        ASSERT_NEAR(perlinAt[i + size_t(c)], pn[c], c == 0 ? kTolerance : 4 * kTolerance)
            << "Perlin component " << c;
        ASSERT_NEAR(perlinMoved[i + size_t(c)], perlinAt[i + size_t(c)], 4 * kPeriodic)
            << "Perlin component " << c;
      }
      const double s = simplex(p, kPeriod, kSeed), f1 = worleyF1(p, kPeriod, kSeed);
      ASSERT_NEAR(cellular[i + 0], s, kTolerance) << "simplex";
      ASSERT_NEAR(cellular[i + 1], f1, kTolerance) << "Worley F1";
      ASSERT_NEAR(cellular[i + 2], cellular[i + 0], kPeriodic) << "simplex, moved";
      ASSERT_NEAR(cellular[i + 3], cellular[i + 1], kPeriodic) << "Worley F1, moved";
      ASSERT_NEAR(fbms[i + 0],
                  fbm([](dvec3 q, ivec3 t, uint32_t sd) { return perlin(q, t, sd).x; }, p, kPeriod,
                      kSeed, 4, 0.5),
                  kTolerance)
          << "Perlin fbm";
      ASSERT_NEAR(fbms[i + 1], fbm(simplex, p, kPeriod, kSeed, 3, 0.6), kTolerance)
          << "simplex fbm (Tang (1))";
      ASSERT_NEAR(fbms[i + 2], fbms[i + 0], kPeriodic) << "Perlin fbm, moved";
      ASSERT_NEAR(fbms[i + 3], fbms[i + 1], kPeriodic) << "simplex fbm, moved";
      const dvec3 cv = curl(p, kPeriod, kSeed, 2, 0.5);
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(curls[i + size_t(c)], cv[c], 8 * kTolerance) << "curl component " << c;
      ASSERT_NEAR(curls[i + 3], curls[i + 0], 8 * kPeriodic) << "curl, moved";
      simplexRange[0] = std::min(simplexRange[0], s);
      simplexRange[1] = std::max(simplexRange[1], s);
      worleyRange[0] = std::min(worleyRange[0], f1);
      worleyRange[1] = std::max(worleyRange[1], f1);
    }
  // The grid samples the noise well: simplex swings through most of [-1, 1], F1 from near a
  // feature point to most of a cell away.
  EXPECT_LT(simplexRange[0], -0.5);
  EXPECT_GT(simplexRange[1], 0.5);
  EXPECT_LT(worleyRange[0], 0.1);
  EXPECT_GT(worleyRange[1], 0.8);
}

}  // namespace
}  // namespace sky
