#pragma once
// Scene in, scene-linear layered image out: builds one frame graph per frame from the
// passes, executes it and collects the main image, the AOVs and any debug images. Create it
// once and render many frames: what does not depend on the time of day (baked textures,
// transmittance and multiple-scattering LUTs) is made once and reused.
//
// Its jobs are parts of their own: the sky (sky_layer.h), the volumetric clouds
// (volumetric_cloud_layer.h) with their history (cloud_reuse.h), and the outputs
// (frame_outputs.h). The Renderer holds what they share (the weather map, the graph's
// memory), builds each frame from them with the composite and the display pass, and runs it.
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/sampler.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/render/cloud_field.h"
#include "engine/render/cloud_layers.h"
#include "engine/render/cloud_volume.h"
#include "engine/render/frame_inputs.h"
#include "engine/render/frame_outputs.h"
#include "engine/render/frame_types.h"
#include "engine/render/sky_layer.h"
#include "engine/render/volumetric_cloud_layer.h"
#include "engine/scene/scene.h"
#include "passes/atmosphere_composite/atmosphere_composite.h"
#include "passes/display_transform/display_transform.h"

namespace sky {

class Context;
class ShaderCompiler;

class Renderer {
public:
  // Loads the star catalogue from configs/stars/ (under dataRoot()).
  Renderer(const Context& ctx, ShaderCompiler& compiler);
  // Renders `scene` at its output size as seen at `time` (one frame of scene.time).
  // Errors: sky::Error (BadInput when the size is impossible on this device or does not fit
  // in memory, or a high-cloud image is missing or malformed).
  RenderedFrame render(const Scene& scene, const IsoTime& time, const RenderOptions& options = {});
  // Frames of a sequence (a time-lapse, a window, a benchmark pan) rendered one after the
  // other through one Renderer reuse each other's clouds when clouds.temporal.mode is on: the
  // first frame, and any after a cut (a setting changed, the camera jumped, a minute passed),
  // marches every pixel; the others 1 / block^2 of them (passes/cloud_temporal).
  // The first (or only) frame of the scene's time.
  RenderedFrame render(const Scene& scene) { return render(scene, scene.time.start); }
  // Several views of `scene` at `time` in one frame graph and one submit, each as render()
  // would draw it with the scene's camera turned and sized as the view says. What does not
  // depend on where a camera looks is made once for all. Without temporal reuse (each view
  // marches all its pixels; the reuse history is left invalid), and without the GPU display
  // path or debug outputs (internal error). One RenderedFrame per view, in order; each holds
  // the whole frame's pass timings. BadInput for no view or a topdown camera.
  std::vector<RenderedFrame> render(const Scene& scene, const IsoTime& time,
                                    const std::vector<FrameView>& views,
                                    const RenderOptions& options = {});
  // The images the frame of `scene` at `time` would have, each of which can be asked for in
  // RenderOptions::debugOutputs: builds the frame's graph (baking what it needs) but does not
  // run it.
  std::vector<DebugImageInfo> debugImages(const Scene& scene, const IsoTime& time,
                                          const RenderOptions& options = {});
  // Called with the share done (0..1) while a high-cloud texture bakes.
  void setBakeProgress(std::function<void(double)> progress);
  // The cloud density field of `scene` at `time` inside `box` (default:
  // defaultCloudVolumeBox) on voxels of `voxelM`, with the camera and the light the clouds
  // are rendered with (skyrender export-volume). BadInput for a top-down camera, a scene
  // without low or mid clouds, or a grid too large.
  CloudVolume exportCloudVolume(const Scene& scene, const IsoTime& time,
                                const std::optional<CloudVolumeBox>& box, double voxelM);
  // The same for several nested parts at once, each its own grid holding its share of the
  // field (cloudVolumeShare), at the level of detail `request.lod` asks for: the field of a
  // path tracer's view toward the horizon, fine near the camera and coarse far from it. BadInput
  // as above, and for parts that are not nested (checkCloudVolumeParts).
  std::vector<CloudVolume> exportCloudVolumes(const Scene& scene, const IsoTime& time,
                                              const CloudVolumeRequest& request);

  // The cloud density field of `scene` at `time` on the CPU (engine/render/cloud_field.h):
  // the raymarch's own parameters, weather map and noise (baked or loaded as a frame would),
  // and the physical atmosphere's air. A scene without low or mid cover gives an empty field.
  // BadInput for a top-down camera (its frame has no observer to hold the field around).
  CloudField cloudField(const Scene& scene, const IsoTime& time);

  // Forgets what a frame keeps for the next (the cloud history, the light volume and the
  // shadow map), so the next frame is drawn as a process's first would be, whatever came
  // before: a dataset's samples each start so, and any process renders sample k the same.
  void startAfresh();

private:
  // A frame in four steps: build the graph (sky, clouds, composite, display), request its
  // outputs (the EXR's layers, the display image, debug images by name), execute, collect.
  // A frame of several views builds each view in turn; what they share, the first makes
  // (SharedFrame) and the others reuse.
  FramePlan buildFrame(FrameGraph& graph, const Scene& scene, const IsoTime& time,
                       const RenderOptions& options, RenderedFrame& out,
                       SharedFrame* shared = nullptr);
  // The costs and timings of a frame once it has run.
  // A frame's perception numbers (RenderedFrame::perception) from the field the queries read,
  // made into `field` on first use (the views of a frame share their place).
  void summarisePerception(RenderedFrame& out, const Scene& scene, const IsoTime& time,
                           std::optional<CloudField>& field);
  void finishCosts(RenderedFrame& out, std::chrono::steady_clock::time_point start,
                   double pipelinesBefore);

  // When construction began and the process's pipeline time then: the first render() reports
  // what constructing took (FrameCosts::rendererMs). Declared first, so initialised first.
  std::chrono::steady_clock::time_point mCreated = std::chrono::steady_clock::now();
  double mPipelinesAtCreation = pipelineBuildMs();
  std::optional<FrameCosts> mConstruction;  // until the first render() reports it
  GraphRuntime mRuntime;
  CloudLayers mWeather;  // the weather map, the cloud noise and their textures: both layers'
  SkyLayer mSky;
  VolumetricCloudLayer mClouds;
  AtmosphereCompositePass mComposite;
  DisplayTransformPass mDisplay;
  Sampler mHostDepthSampler;  // nearest, clamp: a host's depth, fetched texel by texel
};

}  // namespace sky
