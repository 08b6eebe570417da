#include "engine/render/renderer.h"

#include "engine/core/paths.h"
#include "engine/gpu/context.h"
#include "engine/render/camera.h"

namespace sky {
namespace {

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

Renderer::Renderer(const Context& ctx, ShaderCompiler& compiler)
    : mRuntime(ctx),
      mStars(ctx, compiler, loadStarCatalog(configDir() / "stars" / "bright_star_catalogue.txt")),
      mComposite(ctx, compiler) {}

RenderedFrame Renderer::render(const Scene& scene, const IsoTime& time) {
  RenderedFrame out;
  out.lighting = computeLighting(scene, time);
  const uint32_t width = static_cast<uint32_t>(scene.output.width);
  const uint32_t height = static_cast<uint32_t>(scene.output.height);
  const shared::ViewState view = makeViewState(scene.camera, width, height);

  FrameGraph graph(mRuntime);
  StarFieldPass::Frame stars;
  stars.view = view;
  stars.j2000ToEnu = glm::mat3(out.lighting.ephemeris.equatorialJ2000ToEnu);
  stars.extinction = static_cast<float>(scene.lighting.starExtinction);
  StarFieldPass::Outputs starOut = mStars.addTo(graph, stars);

  AtmosphereCompositePass::Inputs composite{};
  composite.params.view = view;
  composite.lighting = out.lighting.gpu;
  composite.starFlux = starOut.flux;
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
