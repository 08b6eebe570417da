#include "engine/render/renderer.h"

#include <cmath>

#include "engine/gpu/context.h"
#include "engine/render/camera.h"

namespace sky {
namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Splits interleaved RGBA read-back into a layer with the first `channels` channels.
ImageLayer toLayer(const ReadbackImage& img, std::string name, std::vector<std::string> channels) {
  ImageLayer layer{std::move(name), std::move(channels), {}};
  const size_t n = static_cast<size_t>(img.width) * img.height, c = layer.channels.size();
  layer.pixels.resize(n * c);
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < c; ++k) layer.pixels[i * c + k] = img.pixels[i * img.channels + k];
  return layer;
}
}  // namespace

HorizontalPosition resolveSun(const Scene& scene, bool* fromTime) {
  const bool computed = !(scene.sun.azimuth && scene.sun.elevation);
  if (fromTime) *fromTime = computed;
  if (!computed) return {*scene.sun.azimuth, *scene.sun.elevation};
  return sunPosition(scene.time.instant.julianDateUtc(), scene.camera.latitude,
                     scene.camera.longitude);
}

Renderer::Renderer(const Context& ctx, ShaderCompiler& compiler)
    : mRuntime(ctx), mComposite(ctx, compiler) {}

RenderedFrame Renderer::render(const Scene& scene) {
  RenderedFrame out;
  out.sun = resolveSun(scene, &out.sunFromTime);
  const uint32_t width = static_cast<uint32_t>(scene.output.width);
  const uint32_t height = static_cast<uint32_t>(scene.output.height);

  AtmosphereCompositePass::Inputs composite{};
  shared::AtmosphereCompositeParams& p = composite.params;
  p.view = makeViewState(scene.camera, width, height);
  p.sunDirection = glm::vec4(directionFromAzEl(out.sun.azimuthDeg, out.sun.elevationDeg),
                             static_cast<float>(0.5 * scene.sun.angularDiameter * kDeg));
  p.sunDisc = glm::vec4(scene.sky.sunColor * static_cast<float>(scene.sun.discIntensity), 0.0f);
  p.skyColor = glm::vec4(scene.sky.skyColor, static_cast<float>(scene.sky.glowSize));
  p.fogColor = glm::vec4(scene.sky.fogColor, static_cast<float>(scene.sky.hazeHeight));
  p.glowColor = glm::vec4(scene.sky.sunColor, 0.0f);

  FrameGraph graph(mRuntime);
  AtmosphereCompositePass::Outputs composited = graph.add(mComposite, composite);
  graph.requestOutput(composited.beauty, "beauty");
  graph.requestOutput(composited.sky, "sky");
  out.frame = graph.execute();
  out.graphDot = graph.toDot(&out.frame);

  out.image.width = static_cast<int>(width);
  out.image.height = static_cast<int>(height);
  out.image.layers.push_back(toLayer(out.frame.output("beauty"), "", {"R", "G", "B", "A"}));
  out.image.layers.push_back(toLayer(out.frame.output("sky"), "sky", {"R", "G", "B"}));
  for (ReadbackImage& o : out.frame.outputs) o.pixels = {};  // the layers hold the data now
  return out;
}

}  // namespace sky
