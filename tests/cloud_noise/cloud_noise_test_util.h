#pragma once
// Shared by the cloud-noise tests: a fixture with its own disk cache folder (so a test really
// bakes), the three textures read back through a frame graph as bytes, and statistics of a
// texture's channel (range, tiling, neighbour differences).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/shader/shader_compiler.h"
#include "private_cache_test.h"
#include "passes/cloud_noise/cloud_noise.h"

namespace sky::test {

// One texture as bytes (RGBA8, x fastest, then y, then z) with its size and dimensionality.
struct NoiseTexture {
  uint32_t size = 0;
  uint32_t dims = 3;  // 3: size^3 volume, 2: size^2 image
  std::vector<uint8_t> rgba;

  size_t index(uint32_t x, uint32_t y, uint32_t z) const {
    return ((size_t(z) * size + y) * size + x) * 4;
  }
  float at(uint32_t x, uint32_t y, uint32_t z, int c) const {
    return float(rgba[index(x, y, z) + size_t(c)]) / 255.0f;
  }
};

// What the GPU textures hold after addTo, read back, plus what addTo reported.
struct Fetched {
  NoiseTexture shape, detail, curl;
  CloudNoise::Activity activity;
  std::vector<std::string> graphPasses;  // the passes addTo left in the caller's graph
};

inline std::vector<uint8_t> toBytes(const std::vector<float>& pixels) {
  std::vector<uint8_t> out(pixels.size());
  for (size_t i = 0; i < pixels.size(); ++i)
    out[i] = static_cast<uint8_t>(std::lround(pixels[i] * 255.0f));
  return out;
}

class CloudNoiseTest : public PrivateCacheTest {
protected:
  CloudNoiseTest() : PrivateCacheTest("sky-cloud-noise") {}

  std::unique_ptr<CloudNoise> make() {
    return std::make_unique<CloudNoise>(ctx(), compiler(), runtime());
  }

  // addTo on a fresh graph that only reads the three textures back.
  Fetched fetch(CloudNoise& noise, CloudModel model) {
    FrameGraph graph(runtime());
    const CloudNoise::Outputs out = noise.addTo(graph, model);
    Fetched f;
    for (const PassNode& p : graph.desc().passes) f.graphPasses.push_back(p.name);
    graph.requestOutput(out.shape, "shape");
    graph.requestOutput(out.detail, "detail");
    graph.requestOutput(out.curl, "curl");
    const FrameResult r = graph.execute();
    auto texture = [&](const char* label) {
      const ReadbackImage& image = r.output(label);
      EXPECT_EQ(image.format, VK_FORMAT_R8G8B8A8_UNORM) << label;
      EXPECT_EQ(image.width, image.height) << label;
      return NoiseTexture{image.width, image.depth > 1 ? 3u : 2u, toBytes(image.pixels)};
    };
    f.shape = texture("shape");
    f.detail = texture("detail");
    f.curl = texture("curl");
    f.activity = noise.lastActivity();
    return f;
  }
};

// One channel of a texture, as the tests look at it. Neighbour differences are |v(x+1) - v(x)|
// in bytes (0..255) along each axis, counted per face between two slices: face k lies between
// slices k and k + 1, face N-1 across the tile's edge (slice N-1 and slice 0 of the next
// repeat).
struct ChannelStats {
  double mean = 0, min = 1, max = 0;
  double clipped = 0;  // fraction of texels at exactly 0 or 1
  // Per axis, per face: a histogram of the differences.
  std::vector<std::array<uint32_t, 256>> faces[3];

  double faceMean(uint32_t axis, uint32_t face) const {
    double sum = 0, count = 0;
    for (int d = 0; d < 256; ++d) {
      sum += double(d) * faces[axis][face][d];
      count += faces[axis][face][d];
    }
    return sum / count / 255.0;
  }
  // The difference that `q` of the face's pairs do not exceed.
  double faceQuantile(uint32_t axis, uint32_t face, double q) const {
    double count = 0, below = 0;
    for (uint32_t c : faces[axis][face]) count += c;
    for (int d = 0; d < 256; ++d)
      if ((below += faces[axis][face][d]) >= q * count) return d / 255.0;
    return 1.0;
  }
  // Mean difference over the faces inside the tile, over all axes.
  double neighbour() const {
    double sum = 0;
    size_t count = 0;
    for (uint32_t a = 0; a < 3; ++a)
      for (uint32_t k = 0; k + 1 < faces[a].size(); ++k, ++count) sum += faceMean(a, k);
    return sum / double(count);
  }
};

inline ChannelStats statsOf(const NoiseTexture& t, int c) {
  ChannelStats s;
  const uint32_t n = t.size, nz = t.dims == 3 ? n : 1;
  for (uint32_t a = 0; a < t.dims; ++a) s.faces[a].assign(n, {});
  size_t texels = 0, clipped = 0;
  for (uint32_t z = 0; z < nz; ++z)
    for (uint32_t y = 0; y < n; ++y)
      for (uint32_t x = 0; x < n; ++x) {
        const int v = t.rgba[t.index(x, y, z) + size_t(c)];
        s.mean += v / 255.0;
        s.min = std::min(s.min, v / 255.0);
        s.max = std::max(s.max, v / 255.0);
        clipped += (v == 0 || v == 255) ? 1 : 0;
        ++texels;
        const uint32_t pos[3] = {x, y, z};
        for (uint32_t a = 0; a < t.dims; ++a) {
          uint32_t next[3] = {x, y, z};
          next[a] = (pos[a] + 1) % n;
          const int w = t.rgba[t.index(next[0], next[1], next[2]) + size_t(c)];
          s.faces[a][pos[a]][size_t(std::abs(w - v))] += 1;
        }
      }
  s.mean /= double(texels);
  s.clipped = double(clipped) / double(texels);
  return s;
}

// How much rougher the face across the tile's edge is than the two faces beside it (faces
// N-2 and 0), by the mean difference (x) and by the 99th percentile (y), which shows a seam
// over part of the edge. 1 for a tiling texture, up to sampling noise and lattice structure.
inline std::pair<double, double> edgeRoughness(const ChannelStats& s, uint32_t axis) {
  const uint32_t edge = uint32_t(s.faces[axis].size()) - 1;
  const double besideMean = (s.faceMean(axis, edge - 1) + s.faceMean(axis, 0)) / 2;
  const double besideP99 =
      std::max(s.faceQuantile(axis, edge - 1, 0.99), s.faceQuantile(axis, 0, 0.99));
  return {s.faceMean(axis, edge) / std::max(besideMean, 1e-9),
          s.faceQuantile(axis, edge, 0.99) / std::max(besideP99, 1.0 / 255)};
}

// The texture tiles in `channel` along every axis: the edge face is at most 1.3 times as
// rough as its neighbours in the mean and 1.5 times at the 99th percentile (a curl face has
// only 128 pairs). Interior faces measured against theirs reach 1.25 and 1.33; lattice noise
// is smoother or rougher on the faces on its coarsest lattice planes, and the edge is one.
// A seam differs like unrelated texels: 2 to 10 times rougher (SeamIsSeen).
inline void expectTiles(const NoiseTexture& t, int channel, const std::string& what) {
  SCOPED_TRACE(what + " channel " + std::to_string(channel));
  const ChannelStats s = statsOf(t, channel);
  for (uint32_t a = 0; a < t.dims; ++a) {
    SCOPED_TRACE("axis " + std::to_string(a));
    const auto [mean, p99] = edgeRoughness(s, a);
    EXPECT_LE(mean, 1.3);
    EXPECT_LE(p99, 1.5);
  }
}

// The channel uses [0, 1]: it reaches both ends, clips at most 2 % of its texels there, and
// its mean lies in the middle half.
inline void expectSpansTheRange(const NoiseTexture& t, int channel, const std::string& what) {
  SCOPED_TRACE(what + " channel " + std::to_string(channel));
  const ChannelStats s = statsOf(t, channel);
  EXPECT_LE(s.min, 0.05);
  EXPECT_GE(s.max, 0.95);
  EXPECT_LT(s.clipped, 0.02);
  EXPECT_GT(s.mean, 0.3);
  EXPECT_LT(s.mean, 0.7);
}

}  // namespace sky::test
