#pragma once
// Shared by the volumetric-cloud tests: one Renderer per test suite (its pipelines, the baked
// noise and the calibrated coverage tables are reused by every render of the suite), the
// scenes of configs/tests/clouds/, and reading the "clouds" layer (R, G, B, A, depth).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/render/camera.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"

namespace sky::test {

class CloudRenderTest : public GpuTest {
public:
  // The renderer lives from the suite's first render to its end, before the shared context
  // is destroyed in main().
  static void TearDownTestSuite() {
    sRenderer.reset();
    sCompiler.reset();
  }

protected:
  static Renderer& renderer() {
    if (!sRenderer) {
      sCompiler = std::make_unique<ShaderCompiler>();
      sRenderer = std::make_unique<Renderer>(sharedContext(), *sCompiler);
    }
    return *sRenderer;
  }
  static RenderedFrame render(const Scene& scene, const IsoTime& time,
                              const RenderOptions& options = {}) {
    return renderer().render(scene, time, options);
  }
  static RenderedFrame render(const Scene& scene, const RenderOptions& options = {}) {
    return render(scene, scene.time.start, options);
  }

private:
  static inline std::unique_ptr<ShaderCompiler> sCompiler;
  static inline std::unique_ptr<Renderer> sRenderer;
};

// A suite whose tests each need a renderer of their own, besides the suite's shared one: what
// a renderer keeps between frames (temporal history, the kept shadow map and light volume)
// must not leak from one test into another.
class OwnRendererTest : public CloudRenderTest {
protected:
  // A new renderer, replacing the test's last one; it lives until the test ends.
  Renderer& fresh() {
    mOwnCompiler = std::make_unique<ShaderCompiler>();
    mOwnRenderer = std::make_unique<Renderer>(sharedContext(), *mOwnCompiler);
    return *mOwnRenderer;
  }
  ShaderCompiler& ownCompiler() { return *mOwnCompiler; }
  void TearDown() override {
    mOwnRenderer.reset();
    mOwnCompiler.reset();
  }

private:
  std::unique_ptr<ShaderCompiler> mOwnCompiler;
  std::unique_ptr<Renderer> mOwnRenderer;
};

// configs/tests/clouds/<name>.yaml with `--set`-style overrides.
inline Scene cloudScene(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return loadSceneFile(configDir() / "tests" / "clouds" / (name + ".yaml"), overrides);
}

inline std::filesystem::path goldenDir() {
  return std::filesystem::path(std::getenv("SKY_TEST_DATA")).parent_path() / "golden" / "clouds";
}

inline bool hasPass(const RenderedFrame& f, const std::string& name) {
  return std::any_of(f.frame.passes.begin(), f.frame.passes.end(),
                     [&](const PassTiming& t) { return t.name == name; });
}

inline double luminance(const float* rgb) {
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

// One pixel of the "clouds" layer.
struct CloudPixel {
  glm::vec3 rgb;  // premultiplied radiance
  float alpha;    // opacity, 1 - transmittance
  float depth;    // transmittance-weighted distance (m), 0 where clear
};

class CloudLayerView {
public:
  explicit CloudLayerView(const RenderedFrame& frame)
      : mLayer(frame.image.find("clouds")), mWidth(frame.image.width), mHeight(frame.image.height) {
    if (!mLayer || mLayer->channels.size() < 5)
      ADD_FAILURE() << "the frame has no clouds layer with R, G, B, A, depth";
    mStride = mLayer ? mLayer->channels.size() : 5;
  }
  int width() const { return mWidth; }
  int height() const { return mHeight; }
  CloudPixel at(int x, int y) const {
    const float* p = &mLayer->pixels[(static_cast<size_t>(y) * mWidth + x) * mStride];
    return {{p[0], p[1], p[2]}, p[3], p[4]};
  }
  // The opacity of every pixel, row-major.
  std::vector<float> alpha() const {
    std::vector<float> a(static_cast<size_t>(mWidth) * mHeight);
    for (size_t i = 0; i < a.size(); ++i) a[i] = mLayer->pixels[i * mStride + 3];
    return a;
  }

private:
  const ImageLayer* mLayer;
  int mWidth, mHeight;
  size_t mStride = 5;  // channels per pixel: with the perception layers, 7
};

// The unit view direction (ENU) of pixel (x, y) of a perspective camera, as the renderer's
// view.glsl computes it (pixel centres, row 0 at the top).
inline glm::vec3 pixelDirection(const CameraSettings& cam, int width, int height, int x, int y) {
  const shared::ViewState v =
      makeViewState(cam, static_cast<uint32_t>(width), static_cast<uint32_t>(height));
  const float sx = (2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 1.0f);
  const float sy = (1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height));
  const glm::vec3 d =
      glm::vec3(v.forward) + sx * v.right.w * glm::vec3(v.right) + sy * v.up.w * glm::vec3(v.up);
  return glm::normalize(d);
}

}  // namespace sky::test
