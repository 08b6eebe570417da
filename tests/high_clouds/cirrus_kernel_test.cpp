// shaders/common/cirrus.glsl on the device (Falcor-style kernel tests,
// tests/data/high_clouds/cirrus_kernel.comp), issue 46 "cirrus at every elevation":
//  - the flow has no vortex: its angle stays within a bound of the mean direction (+u, laid
//    downwind by the draw) all over the tile, no streamline of a wisp's length turns more than
//    a bound, and the paths the streaks are drawn along, hooks included, all advance downwind.
//    The flow this one replaced fails each check; the numbers are in the comments;
//  - the cover stays calibrated: the quantile table the rank is read through matches the
//    field's measured quantiles, and in a bake the rank is about uniform, so cover c clouds
//    about a fraction c of the tile.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/pass_context.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"
#include "shaders/common/high_cloud_bake_shared.h"
#include "tests/high_clouds/high_cloud_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::GpuTest;
using test::HighCloudTest;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// The kernel's one output image, `size` x `size` RGBA32F, compiled with `defines`.
std::vector<float> runKernel(const Context& ctx, const std::vector<ShaderDefine>& defines,
                             uint32_t size) {
  ShaderCompiler compiler(shaderDir(), std::nullopt);
  const CompiledShader shader = compiler.compile(
      fs::path(std::getenv("SKY_TEST_DATA")) / "high_clouds" / "cirrus_kernel.comp", defines);
  ComputePipeline pipeline(ctx, "cirrus_kernel", shader.spirv, shader.reflection);
  GraphRuntime runtime(ctx);
  FrameGraph graph(runtime);
  ImageId image;
  GraphBuilder b = graph.addPass("cirrus_kernel", [&](PassContext& pc) {
    pc.dispatch(pipeline, {Binding::of(0, image)}, size / 8, size / 8);
  });
  ImageDesc desc;
  desc.name = "result";
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.width = desc.height = size;
  image = b.write(b.create(desc), Access::StorageWriteCompute);
  graph.requestOutput(image, "result");
  return graph.execute().output("result").pixels;
}

// One seed's quadrant of the flow kernel: the new and the old flow angle on a 256 x 256 grid
// of the tile, the largest |direction| a streak's path takes, and its length.
struct FlowGrid {
  static constexpr int n = 256;
  std::vector<double> angle, oldAngle, pathTurn, length;

  FlowGrid(const std::vector<float>& image, int quadrant) {
    const int qx = quadrant % 2, qy = quadrant / 2;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float* p = &image[(size_t(qy * n + y) * 2 * n + size_t(qx * n + x)) * 4];
        angle.push_back(p[0]);
        oldAngle.push_back(p[1]);
        pathTurn.push_back(p[2]);
        length.push_back(p[3]);
      }
  }
};

// Bilinear lookup of a periodic angle field on an n x n grid of texel centres; uv in tiles.
double sampleAngle(const std::vector<double>& field, int n, double u, double v) {
  const double x = u * n - 0.5, y = v * n - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  auto at = [&](int i, int j) { return field[size_t(((j % n) + n) % n) * n + ((i % n) + n) % n]; };
  const int i = int(fx), j = int(fy);
  const double tx = x - fx, ty = y - fy;
  return (1 - ty) * ((1 - tx) * at(i, j) + tx * at(i + 1, j)) +
         ty * ((1 - tx) * at(i, j + 1) + tx * at(i + 1, j + 1));
}

// The largest turn of a streamline over `length` tiles, from every 4th grid point: the flow
// traced with midpoint steps of 1/512 tile, the turn the largest |angle - angle at the start|
// along it. Rings and the arcs around a vortex turn by half a circle or more within a wisp.
double largestStreamlineTurn(const std::vector<double>& field, int n, double length) {
  const double h = 1.0 / 512.0;
  const int steps = int(std::ceil(length / h));
  double worst = 0;
  for (int y = 0; y < n; y += 4)
    for (int x = 0; x < n; x += 4) {
      double u = (x + 0.5) / n, v = (y + 0.5) / n;
      const double start = sampleAngle(field, n, u, v);
      for (int s = 0; s < steps; ++s) {
        const double a = sampleAngle(field, n, u, v);
        const double mid =
            sampleAngle(field, n, u + 0.5 * h * std::cos(a), v + 0.5 * h * std::sin(a));
        u += h * std::cos(mid);
        v += h * std::sin(mid);
        worst = std::max(worst, std::abs(sampleAngle(field, n, u, v) - start));
      }
    }
  return worst;
}

class CirrusKernelTest : public GpuTest {};

// Over 256 x 256 points of the tile, seeds 1 to 4. Measured: the flow stays within 20 to 21
// degrees of +u (bound 25; 0.4 rad by construction), its rms wander 8 to 10 degrees and its
// circular mean within 0.2 degrees of +u; the old flow reached 89 to 116 degrees. A streamline
// 0.3 of the tile long (the longest wisp) turns by at most 29 to 36 degrees (bound 50; the
// old flow 102 to 150: the arcs around its vortices). Paths with their hooks turn at most 80
// degrees from +u (bound 85: every streak advances downwind), and 17 to 29 % of the texels'
// paths are hooked past 35 degrees (bound > 3 %: the uncinus hooks are kept).
TEST_F(CirrusKernelTest, FlowHasNoVortex) {
  const std::vector<float> image = runKernel(ctx(), {{"CIRRUS_KERNEL_FLOW", "1"}}, 512);
  for (int seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const FlowGrid g(image, seed - 1);
    double largest = 0, oldLargest = 0, sumSquares = 0, c = 0, s = 0, pathLargest = 0;
    int hooked = 0;
    for (size_t i = 0; i < g.angle.size(); ++i) {
      largest = std::max(largest, std::abs(g.angle[i]));
      oldLargest = std::max(oldLargest, std::abs(g.oldAngle[i]));
      sumSquares += g.angle[i] * g.angle[i];
      c += std::cos(g.angle[i]);
      s += std::sin(g.angle[i]);
      pathLargest = std::max(pathLargest, g.pathTurn[i]);
      hooked += g.pathTurn[i] > 35.0 * kDeg;
    }
    const double rms = std::sqrt(sumSquares / double(g.angle.size()));
    const double mean = std::atan2(s, c);
    const double hookedShare = double(hooked) / double(g.angle.size());
    const double turn = largestStreamlineTurn(g.angle, g.n, 0.3);
    const double oldTurn = largestStreamlineTurn(g.oldAngle, g.n, 0.3);
    std::cout << "seed " << seed << ": flow within " << largest / kDeg << " deg of +u (old "
              << oldLargest / kDeg << "), rms wander " << rms / kDeg << " deg, mean " << mean / kDeg
              << " deg; largest streamline turn over 0.3 tile " << turn / kDeg << " deg (old "
              << oldTurn / kDeg << "); paths within " << pathLargest / kDeg
              << " deg, hooked past 35 deg " << hookedShare << "\n";
    // The flow: one mean direction, a modest wander, no part of the tile turned across it.
    EXPECT_LT(largest, 25.0 * kDeg);
    EXPECT_NEAR(mean, 0.0, 5.0 * kDeg);
    EXPECT_GT(rms, 3.0 * kDeg) << "no wander at all: ruled lines";
    EXPECT_LT(turn, 50.0 * kDeg) << "a streamline curls within a wisp's length";
    // The paths, hooks included, never turn back against the wind.
    EXPECT_LT(pathLargest, 85.0 * kDeg);
    EXPECT_GT(hookedShare, 0.03) << "the hooks (uncinus) are gone";
    // The checks can fail: the old flow turned across the tile and its streamlines curled.
    EXPECT_GT(oldLargest, 25.0 * kDeg);
    EXPECT_GT(oldTurn, 90.0 * kDeg);
  }
}

// The field x over 512 x 512 texels for seeds 1, 3, 7 and 42 (the table's own measurement):
// its quantiles at 0, 5, ..., 100 %, averaged over the seeds, against CIRRUS_QUANTILES. The
// rank reads x through that table, so a field whose statistics moved would no longer cloud a
// fraction c of the sky at cover c. The table was pasted from this test's output; the flow
// before issue 46 gave quantiles within 0.011 of its own table, the bound is 0.03 (the
// extremes, single texels, 0.25). On a failure the test prints the table to paste into
// high_cloud_bake_shared.h.
TEST_F(CirrusKernelTest, QuantileTableMatchesTheField) {
  const std::vector<float> image = runKernel(ctx(), {{"CIRRUS_KERNEL_FLOW", "0"}}, 1024);
  const float table[] = {CIRRUS_QUANTILES};
  static_assert(std::size(table) == CIRRUS_QUANTILE_COUNT);
  const int n = 512, last = CIRRUS_QUANTILE_COUNT - 1;
  std::vector<double> mean(CIRRUS_QUANTILE_COUNT, 0.0);
  for (int quadrant = 0; quadrant < 4; ++quadrant) {
    std::vector<double> x;
    for (int y = 0; y < n; ++y)
      for (int i = 0; i < n; ++i)
        x.push_back(
            image[(size_t((quadrant / 2) * n + y) * 2 * n + size_t((quadrant % 2) * n + i)) * 4]);
    std::sort(x.begin(), x.end());
    for (int k = 0; k <= last; ++k)
      mean[size_t(k)] +=
          x[std::min(x.size() - 1, size_t(double(k) / last * double(x.size())))] / 4.0;
  }
  std::string measured;
  double inner = 0, ends = 0;
  for (int k = 0; k <= last; ++k) {
    char text[32];
    std::snprintf(text, sizeof text, "%s%.4f", k ? ", " : "", mean[size_t(k)]);
    measured += text;
    const double error = std::abs(mean[size_t(k)] - table[k]);
    (k == 0 || k == last ? ends : inner) = std::max(k == 0 || k == last ? ends : inner, error);
  }
  std::cout << "measured quantiles: " << measured << "\nlargest difference from the table: inner "
            << inner << ", extremes " << ends << "\n";
  EXPECT_LT(inner, 0.03) << "re-measure CIRRUS_QUANTILES: " << measured;
  EXPECT_LT(ends, 0.25) << "re-measure CIRRUS_QUANTILES: " << measured;
}

// Through the real bake (512 x 512, the table's size, seeds 1 to 4, none of them but seed 1
// among the table's): the share of texels whose rank exceeds 1 - c, the texels that cover c
// turns cloudy past the middle of the ramp, against c, for covers 0.1 to 0.9. Averaged over
// the seeds the share is the cover within 0.05; one seed's patches may hold more or less than
// the mean, within 0.08. Measured: 0.085, 0.18, 0.33, 0.48, 0.65, 0.83, 0.94 at covers 0.1,
// 0.2, 0.35, 0.5, 0.65, 0.8, 0.9, at most 0.040 off (the flow before issue 46 with its own
// table: 0.034), one seed 0.069 (0.058). The table itself is held to the field to 0.03 by
// QuantileTableMatchesTheField; this checks the bake reads it right.
TEST_F(HighCloudTest, CirrusCoverCloudsThatShareOfTheTile) {
  auto textures = make();
  const double covers[] = {0.1, 0.2, 0.35, 0.5, 0.65, 0.8, 0.9};
  std::vector<double> mean(std::size(covers), 0.0);
  double worstSeed = 0;
  const int seeds = 4;
  for (int seed = 1; seed <= seeds; ++seed) {
    const test::Fetched f = fetch(*textures, test::proceduralScene("cirrus", 0.5, 512, seed));
    ASSERT_FALSE(f.rankShape.empty());
    for (size_t k = 0; k < std::size(covers); ++k) {
      int above = 0;
      for (size_t i = 0; i < f.rankShape.size(); i += 4) above += f.rankShape[i] > 1.0 - covers[k];
      const double share = double(above) / double(f.rankShape.size() / 4);
      EXPECT_NEAR(share, covers[k], 0.08) << "seed " << seed << ", cover " << covers[k];
      worstSeed = std::max(worstSeed, std::abs(share - covers[k]));
      mean[k] += share / seeds;
    }
  }
  double worstMean = 0;
  std::cout << "share of the tile past the middle of the ramp, mean over the seeds:";
  for (size_t k = 0; k < std::size(covers); ++k) std::cout << " " << covers[k] << ": " << mean[k];
  std::cout << "\n";
  for (size_t k = 0; k < std::size(covers); ++k) {
    EXPECT_NEAR(mean[k], covers[k], 0.05) << "cover " << covers[k];
    worstMean = std::max(worstMean, std::abs(mean[k] - covers[k]));
  }
  std::cout << "rank share off the cover by at most " << worstMean << " over the seeds, "
            << worstSeed << " for one seed\n";
}

}  // namespace
}  // namespace sky
