#pragma once
// Shared by the high-cloud texture tests: a fixture with its own disk cache folder (so every
// test really bakes), scenes, and the textures read back through a frame graph.
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec4.hpp>
#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/scene/scene.h"
#include "engine/shader/shader_compiler.h"
#include "private_cache_test.h"
#include "passes/high_cloud_textures/high_cloud_textures.h"

namespace sky::test {

// tests/data/high_clouds
inline std::filesystem::path highCloudData() {
  const char* v = std::getenv("SKY_TEST_DATA");
  return std::filesystem::path(v ? v : "tests/data") / "high_clouds";
}

inline Scene proceduralScene(const std::string& style, double cover, int resolution = 128,
                             int seed = 1) {
  Scene scene;
  scene.highClouds.source = HighCloudSource::Procedural;
  scene.highClouds.style = enumValue<HighCloudStyle>(style).value();
  scene.highClouds.cover = cover;
  scene.highClouds.resolution = resolution;
  scene.highClouds.seed = seed;
  scene.baseDir = highCloudData();
  return scene;
}

inline Scene imageScene(const std::string& coefficients, const std::string& normals = "") {
  Scene scene;
  scene.highClouds.source = HighCloudSource::Image;
  scene.highClouds.coefficients = coefficients;
  scene.highClouds.normals = normals;
  scene.baseDir = highCloudData();
  return scene;
}

// The textures as floats (RGBA interleaved, row 0 = north) plus what addTo reported.
// rankShape when addTo gave one (procedural), coverCoarse and the table with regional cover.
struct Fetched {
  uint32_t size = 0, coarseSize = 0;
  std::vector<float> coefficients, normals, coarse, rankShape, coverCoarse;
  glm::vec4 mean{0.0f};
  float rampWidth = 0.0f;
  std::array<glm::vec4, HIGH_CLOUD_COVER_STEPS> farField{};
  HighCloudTextures::Activity activity;
  std::vector<std::string> graphPasses;  // the passes addTo left in the caller's graph

  float at(const std::vector<float>& image, uint32_t x, uint32_t y, int c) const {
    return image[(size_t(y) * size + x) * 4 + size_t(c)];
  }
  float opacity(uint32_t x, uint32_t y) const { return 1.0f - at(coefficients, x, y, 2); }
};

class HighCloudTest : public PrivateCacheTest {
protected:
  HighCloudTest() : PrivateCacheTest("sky-high-clouds") {}

  std::unique_ptr<HighCloudTextures> make() {
    return std::make_unique<HighCloudTextures>(ctx(), compiler(), runtime());
  }

  // addTo on a fresh graph that only reads the textures back.
  Fetched fetch(HighCloudTextures& textures, const Scene& scene, bool regionalCover = false) {
    FrameGraph graph(runtime());
    HighCloudTextures::Outputs out = textures.addTo(graph, scene, regionalCover);
    Fetched f;
    for (const PassNode& p : graph.desc().passes) f.graphPasses.push_back(p.name);
    graph.requestOutput(out.coefficients, "coefficients");
    graph.requestOutput(out.normals, "normals");
    graph.requestOutput(out.coarse, "coarse");
    if (out.rankShape.valid()) graph.requestOutput(out.rankShape, "rank_shape");
    if (out.coverCoarse.valid()) graph.requestOutput(out.coverCoarse, "cover_coarse");
    FrameResult r = graph.execute();
    f.size = r.output("coefficients").width;
    f.coarseSize = r.output("coarse").width;
    f.coefficients = r.output("coefficients").pixels;
    f.normals = r.output("normals").pixels;
    f.coarse = r.output("coarse").pixels;
    if (out.rankShape.valid()) f.rankShape = r.output("rank_shape").pixels;
    if (out.coverCoarse.valid()) f.coverCoarse = r.output("cover_coarse").pixels;
    f.mean = out.mean;
    f.rampWidth = out.rampWidth;
    f.farField = out.farField;
    f.activity = textures.lastActivity();
    return f;
  }
};

// Largest absolute difference between two images of equal size.
inline float maxDifference(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  float worst = 0.0f;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
    worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

}  // namespace sky::test
