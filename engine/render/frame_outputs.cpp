#include "engine/render/frame_outputs.h"

#include <algorithm>
#include <cmath>

#include "engine/render/frame_layers.h"

namespace sky {
namespace {

// A read-back debug image with what its view needs: how to show it, its channels' names and
// the pass that wrote it with that pass's GPU time.
DebugImage debugImage(const ReadbackImage& readback, const GraphImage& g,
                      const FrameResult& result) {
  DebugImage d;
  d.info = debugImageInfo(g);
  for (const PassTiming& t : result.passes)
    if (t.name == g.writer) d.gpuMs += t.gpuMs;
  d.image.width = static_cast<int>(readback.width * readback.depth);
  d.image.height = static_cast<int>(readback.height);
  d.image.layers.push_back(imageLayer(readback, "", channelNames(g.desc)));
  return d;
}

}  // namespace

DebugImageInfo debugImageInfo(const GraphImage& g) {
  const ImageDesc& d = g.desc;
  return {g.name,
          g.writer,
          d.about,
          d.view,
          d.width,
          d.height,
          d.dim == ImageDim::Tex3D ? d.depth : 1u,
          d.format};
}

void requestOutputs(FrameGraph& graph, FramePlan& plan, const RenderOptions& options,
                    const std::string& prefix) {
  FramePlan::Outputs& o = plan.outputs;
  if (options.readBack != ReadBack::Display)
    o.beauty = graph.requestOutput(plan.beauty, prefix + "beauty");
  if (options.readBack == ReadBack::Layers) {
    o.sky = graph.requestOutput(plan.sky, prefix + "sky");
    o.highClouds = graph.requestOutput(plan.highClouds, prefix + "high_clouds");
    if (plan.clouds.valid()) {
      o.clouds = graph.requestOutput(plan.clouds, prefix + "clouds");
      o.cloudsDepth = graph.requestOutput(plan.cloudsDepth, prefix + "clouds_depth");
    }
    if (plan.perception.valid())
      o.perception = graph.requestOutput(plan.perception, prefix + "perception");
    if (plan.cloudHit.valid())
      o.cloudHit = graph.requestOutput(plan.cloudHit, prefix + "cloud_perception");
  }
  if (plan.display.valid() && !options.displayTarget)
    o.display = graph.requestOutput(plan.display, prefix + "display");
  // The debug images, by the names their passes gave them (the graph is the registry).
  std::vector<std::string> names = options.debugOutputs;
  if (options.allDebugOutputs)
    for (const GraphImage& image : graph.images())
      if (std::find(names.begin(), names.end(), image.name) == names.end())
        names.push_back(image.name);
  for (const std::string& name : names) {
    const GraphImage image = graph.image(name);
    o.debug.emplace_back(graph.requestOutput(image, prefix + "debug " + name), image);
  }
}

void collectOutputs(RenderedFrame& out, const FrameResult& result, const FrameGraph& graph,
                    const FramePlan& plan, const RenderOptions& options) {
  const FramePlan::Outputs& o = plan.outputs;
  const uint32_t width = graph.desc().resources[plan.beauty.id].image.width;
  const uint32_t height = graph.desc().resources[plan.beauty.id].image.height;
  out.image.width = static_cast<int>(width);
  out.image.height = static_cast<int>(height);
  if (options.readBack != ReadBack::Display)
    out.image.layers.push_back(beautyLayer(result.output(o.beauty)));
  if (options.readBack == ReadBack::Layers) {
    const bool clouds = o.clouds.valid();
    appendAovLayers(out.image, result.output(o.sky), result.output(o.highClouds),
                    clouds ? &result.output(o.clouds) : nullptr,
                    clouds ? &result.output(o.cloudsDepth) : nullptr);
    if (o.perception.valid())
      appendPerceptionLayers(out.image, result.output(o.perception),
                             o.cloudHit.valid() ? &result.output(o.cloudHit) : nullptr);
    if (plan.weather)
      out.image.layers.push_back(
          weatherCoverLayer(*plan.weather, plan.weather->region, width, height));
  }
  for (const GraphImage& g : graph.images()) out.images.push_back(debugImageInfo(g));
  for (const auto& [id, image] : o.debug)
    out.debug.push_back(debugImage(result.output(id), image, result));
  if (o.display.valid()) {
    const std::vector<float>& codes = result.output(o.display).pixels;
    out.display.resize(codes.size());
    for (size_t i = 0; i < codes.size(); ++i)
      out.display[i] = static_cast<uint8_t>(std::lround(codes[i] * 255.0f));
  }
}

}  // namespace sky
