#include "engine/render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/paths.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/context.h"
#include "engine/lighting/light_model.h"
#include "engine/render/camera.h"
#include "engine/render/frame_layers.h"
#include "engine/scene/scene_io.h"
#include "engine/weather/geo.h"

namespace sky {
Renderer::Renderer(const Context& ctx, ShaderCompiler& compiler)
    : mRuntime(ctx),
      mWeather(ctx, compiler, mRuntime),
      mSky(ctx, compiler, mRuntime, mWeather),
      mClouds(ctx, compiler, mRuntime, mWeather),
      mComposite(ctx, compiler),
      mDisplay(ctx, compiler),
      mHostDepthSampler(ctx, SamplerWrap::Clamp, false) {
  FrameCosts c;
  c.rendererMs = msSince(mCreated);
  c.rendererPipelinesMs = pipelineBuildMs() - mPipelinesAtCreation;
  mConstruction = c;
}

void Renderer::setBakeProgress(std::function<void(double)> progress) {
  mSky.setBakeProgress(std::move(progress));
}

FramePlan Renderer::buildFrame(FrameGraph& graph, const Scene& scene, const IsoTime& time,
                               const RenderOptions& options, RenderedFrame& out,
                               SharedFrame* shared) {
  const FrameSetup setup = frameSetup(mWeather, scene, time);
  const WeatherMap& weather = *setup.weather;
  out.lighting = setup.lighting;
  out.localWeather = setup.localWeather;
  out.weatherRegion = weather.region;
  out.weatherTexels = glm::uvec2(weather.width, weather.height);
  const glm::vec2 maxCover = weather.maxCover();
  out.clouds = maxCover.x > 0.0f || maxCover.y > 0.0f;
  const uint32_t width = static_cast<uint32_t>(scene.output.width);
  const uint32_t height = static_cast<uint32_t>(scene.output.height);
  // A host's depth, imported once: the clouds stop at it and the composite sees through it.
  std::optional<VolumetricCloudsPass::Inputs::HostDepth> hostDepth;
  if (options.host && options.host->depth)
    hostDepth = VolumetricCloudsPass::Inputs::HostDepth{
        graph.importExternal(*options.host->depth, options.host->depthLayout), &mHostDepthSampler,
        options.host->depthMapping};
  const FrameInputs f{scene,
                      time,
                      setup,
                      makeViewState(scene.camera, width, height),
                      width,
                      height,
                      scene.sky.model == SkyModel::Physical,
                      setup.geometry.topDown,
                      shared,
                      setup.lighting,
                      out.clouds,
                      hostDepth,
                      options.sequenceFrame};
  FramePlan plan;
  const SkyLayer::Images sky = mSky.addTo(graph, f);
  out.costs.texturesMs += sky.texturesMs;
  out.highClouds = sky.highClouds;
  std::optional<VolumetricCloudLayer::Images> clouds;
  if (out.clouds) {
    clouds = mClouds.addTo(graph, f, sky, mSky.atmosphere());
    out.costs.texturesMs += clouds->texturesMs;
    out.cloudNoise = clouds->noise;
    out.cloudShadow = clouds->shadow.map;
    plan.reuseStep = clouds->reuseStep;
  }

  AtmosphereCompositeSettings compositeSettings;
  compositeSettings.ground = scene.ground;
  compositeSettings.planetRadiusM = skyPlanetRadiusM(scene);
  compositeSettings.cameraAltitudeM = scene.camera.altitudeM;
  compositeSettings.turbidity = scene.lighting.turbidity;
  compositeSettings.observer = !f.topDown;
  // High clouds lie in front of the volumetric ones when the camera flies above them.
  compositeSettings.aboveHighClouds =
      !f.topDown && scene.camera.altitudeM > sky.highAltitudeM.value_or(scene.highClouds.altitudeM);
  compositeSettings.belowClouds = scene.camera.altitudeM < setup.volumetric.clouds.low.baseM;
  compositeSettings.highCloudsAltitudeM = sky.highAltitudeM.value_or(scene.highClouds.altitudeM);
  AtmosphereCompositePass::Inputs composite{};
  composite.params = atmosphereCompositeParams(compositeSettings, f.lighting, f.view);
  if (clouds)
    composite.clouds = AtmosphereCompositePass::Clouds{clouds->clouds,
                                                       clouds->depth,
                                                       clouds->shadow.shadow,
                                                       clouds->shadow.map,
                                                       clouds->frame.textures.weatherSampler,
                                                       compositeSettings.belowClouds};
  if (f.physical)
    composite.atmosphere = AtmosphereCompositePass::Atmosphere{
        mSky.atmosphere().params(), sky.luts.transmittance, sky.luts.aerialPerspective,
        &mSky.atmosphere().sampler()};
  composite.lighting = f.lighting.gpu;
  if (sky.stars) composite.starFlux = sky.stars->flux;
  composite.sky = sky.sky.sky;
  composite.highClouds = sky.sky.highClouds;
  if (const HostTarget* host = options.host) {
    AtmosphereCompositePass::Host h;
    h.colour = graph.importExternal(*host->colour, host->colourLayout);
    h.colourFormat = host->colour->image.desc().format;
    if (hostDepth) h.depth = hostDepth->depth;
    h.depthMapping = host->depthMapping;
    h.depthSampler = &mHostDepthSampler;
    composite.host = h;
  }
  if (scene.output.perception && !options.host && !f.topDown)
    composite.perception =
        AtmosphereCompositePass::Perception{clouds ? clouds->perception : std::nullopt};
  const AtmosphereCompositePass::Outputs composed = graph.add(mComposite, composite);
  plan.beauty = composed.beauty;
  if (composite.perception) {
    plan.perception = composed.perception;
    if (clouds) plan.cloudHit = *clouds->perception;
  }
  plan.sky = sky.sky.sky;
  plan.highClouds = sky.sky.highClouds;
  if (clouds) {
    plan.clouds = clouds->clouds;
    plan.cloudsDepth = clouds->depth;
  }
  if (options.gpuDisplay && !options.host) {
    if (scene.output.exposure == ExposureMode::Histogram)
      internalError("the GPU display path has no histogram exposure (it meters the frame)");
    DisplayTransformPass::Inputs d;
    d.settings = {options.gpuDisplay, scene.output.display, scene.output.view,
                  (scene.output.exposure == ExposureMode::Auto ? f.lighting.autoExposureEv : 0.0) +
                      scene.output.exposureEv,
                  scene.output.nightLook};
    d.beauty = plan.beauty;
    d.width = width;
    d.height = height;
    if (PersistentImage* target = options.displayTarget) {
      const ImageDesc& t = target->image.desc();
      if (t.format != VK_FORMAT_R8G8B8A8_UNORM || t.width != width || t.height != height ||
          !(t.usage & VK_IMAGE_USAGE_STORAGE_BIT))
        internalError("RenderOptions::displayTarget is not an RGBA8 storage image of the " +
                      std::to_string(width) + "x" + std::to_string(height) + " output");
      d.target = graph.importExternal(*target, options.displayTargetLayout);
    }
    out.displayEv = d.settings.exposureEv;
    plan.display = mDisplay.addTo(graph, d).display;
  }
  if (f.topDown && options.readBack == ReadBack::Layers) plan.weather = &weather;
  return plan;
}

RenderedFrame Renderer::render(const Scene& scene, const IsoTime& time,
                               const RenderOptions& options) {
  if (options.readBack == ReadBack::Display && !options.gpuDisplay)
    internalError("ReadBack::Display without RenderOptions::gpuDisplay");
  if (options.displayTarget && (options.readBack != ReadBack::Display || options.host))
    internalError("RenderOptions::displayTarget without ReadBack::Display, or with a host target");
  const auto start = std::chrono::steady_clock::now();
  const double pipelinesBefore = pipelineBuildMs();
  RenderedFrame out;
  FrameGraph graph(mRuntime);
  FramePlan plan = buildFrame(graph, scene, time, options, out);
  try {
    if (options.host) {
      out.frame = graph.record(options.host->cmd);
    } else {
      requestOutputs(graph, plan, options);
      out.frame = graph.execute();
    }
  } catch (...) {
    mClouds.forgetKept();  // the light volume and shadow map may not have been made
    throw;
  }
  if (plan.reuseStep) mClouds.commitReuse();
  out.graphDot = graph.toDot(&out.frame);
  if (!options.host) {
    collectOutputs(out, out.frame, graph, plan, options);
    for (ReadbackImage& o : out.frame.outputs) o.pixels = {};  // the layers hold the data now
    if (plan.outputs.perception.valid()) {
      std::optional<CloudField> field;
      summarisePerception(out, scene, time, field);
    }
  }
  finishCosts(out, start, pipelinesBefore);
  return out;
}

void Renderer::summarisePerception(RenderedFrame& out, const Scene& scene, const IsoTime& time,
                                   std::optional<CloudField>& field) {
  const ImageLayer* labels = nullptr;
  for (const ImageLayer& layer : out.image.layers)
    if (layer.integer && !layer.channels.empty() && layer.channels[0] == "label") labels = &layer;
  if (!labels) internalError("render: the perception layers lack the labels");
  if (!field) field.emplace(mClouds.field(scene, frameSetup(mWeather, scene, time), time));
  out.perception = perceptionSummary(*field, out.lighting.sun.direction, *labels);
}

void Renderer::finishCosts(RenderedFrame& out, std::chrono::steady_clock::time_point start,
                           double pipelinesBefore) {
  for (const PassTiming& t : out.frame.passes)
    if (t.name == AtmosphereLuts::kTransmittanceName ||
        t.name == AtmosphereLuts::kMultiScatteringName)
      out.costs.lutBakeGpuMs += t.gpuMs;
  out.costs.pipelinesMs = pipelineBuildMs() - pipelinesBefore;
  out.costs.renderMs = msSince(start);
  if (mConstruction) {
    out.costs.rendererMs = mConstruction->rendererMs;
    out.costs.rendererPipelinesMs = mConstruction->rendererPipelinesMs;
    mConstruction.reset();
  }
}

std::vector<RenderedFrame> Renderer::render(const Scene& scene, const IsoTime& time,
                                            const std::vector<FrameView>& views,
                                            const RenderOptions& options) {
  if (views.empty()) inputError("render: no view to render");
  if (scene.camera.mode != CameraMode::Observer)
    inputError("render: several views need an observer camera (camera.mode observer)");
  if (options.gpuDisplay || options.displayTarget || options.host ||
      !options.debugOutputs.empty() || options.allDebugOutputs)
    internalError("a frame of several views has no GPU display, host target or debug output");
  const auto start = std::chrono::steady_clock::now();
  const double pipelinesBefore = pipelineBuildMs();
  std::vector<RenderedFrame> outs(views.size());
  std::vector<FramePlan> plans;
  FrameGraph graph(mRuntime);
  SharedFrame shared;
  for (size_t i = 0; i < views.size(); ++i) {
    const FrameView& v = views[i];
    if (v.width == 0 || v.height == 0)
      inputError("render: view " + std::to_string(i) + " has no size");
    Scene view = scene;
    view.camera.heading = v.headingDeg;
    view.camera.pitch = v.pitchDeg;
    view.camera.roll = v.rollDeg;
    view.camera.verticalFov = v.verticalFovDeg;
    view.camera.projection = v.projection;
    view.output.width = static_cast<int>(v.width);
    view.output.height = static_cast<int>(v.height);
    // Each view's images by their names, "view1/beauty" after the first view's "beauty".
    graph.setNamePrefix(i == 0 ? "" : "view" + std::to_string(i) + "/");
    plans.push_back(buildFrame(graph, view, time, options, outs[i], &shared));
  }
  graph.setNamePrefix("");
  const auto label = [](size_t i) {
    return i == 0 ? std::string() : "view" + std::to_string(i) + "/";
  };
  FrameResult result;
  try {
    for (size_t i = 0; i < views.size(); ++i) requestOutputs(graph, plans[i], options, label(i));
    result = graph.execute();
  } catch (...) {
    mClouds.forgetKept();
    throw;
  }
  // The views marched every pixel; a later sequence frame starts afresh.
  mClouds.invalidateReuse();
  const std::string dot = graph.toDot(&result);
  std::optional<CloudField> field;
  // Each view holds the frame's timings; its images come from the one read-back, not copies.
  FrameResult timings = result;
  timings.outputs.clear();
  for (size_t i = 0; i < views.size(); ++i) {
    outs[i].frame = timings;
    collectOutputs(outs[i], result, graph, plans[i], options);
    // Every view stands at the same place: one field serves them all.
    if (plans[i].outputs.perception.valid()) summarisePerception(outs[i], scene, time, field);
    outs[i].graphDot = dot;
    finishCosts(outs[i], start, pipelinesBefore);
  }
  return outs;
}

std::vector<DebugImageInfo> Renderer::debugImages(const Scene& scene, const IsoTime& time,
                                                  const RenderOptions& options) {
  RenderedFrame out;
  FrameGraph graph(mRuntime);
  buildFrame(graph, scene, time, options, out);
  // Built, never run: what the light volume and the shadow map think they hold is not made.
  mClouds.forgetKept();
  std::vector<DebugImageInfo> list;
  for (const GraphImage& g : graph.images()) list.push_back(debugImageInfo(g));
  return list;
}

CloudVolume Renderer::exportCloudVolume(const Scene& scene, const IsoTime& time,
                                        const std::optional<CloudVolumeBox>& box, double voxelM) {
  CloudVolumeRequest request;
  if (box) request.parts.push_back({*box, voxelM});
  request.defaultVoxelM = voxelM;
  return std::move(exportCloudVolumes(scene, time, request).front());
}

std::vector<CloudVolume> Renderer::exportCloudVolumes(const Scene& scene, const IsoTime& time,
                                                      const CloudVolumeRequest& request) {
  return mClouds.exportVolumes(scene, frameSetup(mWeather, scene, time), time, request);
}

void Renderer::startAfresh() {
  mClouds.forgetKept();
  mClouds.invalidateReuse();
}

CloudField Renderer::cloudField(const Scene& scene, const IsoTime& time) {
  return mClouds.field(scene, frameSetup(mWeather, scene, time), time);
}

}  // namespace sky
