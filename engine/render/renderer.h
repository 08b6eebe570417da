#pragma once
// Scene in, scene-linear layered image out: builds one frame graph per frame from the
// passes, executes it and collects the main image, the AOVs and any debug images. Owns the
// passes' pipelines, the star catalogue, the high-cloud textures and the atmosphere LUTs on
// the GPU, so create it once and render many frames: what does not depend on the time of day
// (baked textures, transmittance and multiple-scattering LUTs) is made once and reused.
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/io/exr.h"
#include "engine/lighting/lighting_state.h"
#include "engine/weather/local_weather.h"
#include "engine/scene/scene.h"
#include "passes/atmosphere_composite/atmosphere_composite.h"
#include "engine/render/cloud_field.h"
#include "engine/render/cloud_layers.h"
#include "engine/render/cloud_reuse.h"
#include "engine/render/cloud_volume.h"
#include "passes/atmosphere_luts/atmosphere_luts.h"
#include "engine/gpu/sampler.h"
#include "passes/cloud_ambient/cloud_ambient.h"
#include "passes/cloud_density_slice/cloud_density_slice.h"
#include "passes/cloud_light_volume/cloud_light_volume.h"
#include "passes/cloud_shadow/cloud_shadow.h"
#include "passes/cloud_upsample/cloud_upsample.h"
#include "passes/display_transform/display_transform.h"
#include "passes/cloud_volume_export/cloud_volume_export.h"
#include "passes/high_cloud_textures/high_cloud_textures.h"
#include "passes/sky_high_clouds/sky_high_clouds.h"
#include "passes/star_field/star_field.h"
#include "passes/volumetric_clouds/volumetric_clouds.h"

namespace sky {

class Context;
class OcioOutput;
class ShaderCompiler;

// An image of a frame's graph that a debug view can ask for by its name: every image a pass
// declares (the graph is the one registry; ImageDesc says how to show it).
struct DebugImageInfo {
  std::string name;   // e.g. "atmosphere_transmittance"
  std::string pass;   // the pass that writes it; "" for an image no pass of the frame writes
                      // (uploaded, baked before the frame, or kept from an earlier frame)
  std::string about;  // one line on what it holds
  DebugView view = DebugView::Color;
  uint32_t width = 0, height = 0, depth = 1;
  VkFormat format = VK_FORMAT_UNDEFINED;
};

// What a frame reads back to the host. Each 32-bit layer at 1280 x 720 is 15 MB to copy and
// convert: a still wants the EXR's layers, a viewer or a benchmark frame only a picture.
enum class ReadBack {
  Layers,   // the EXR's: beauty, sky, high_clouds, clouds (and weather for a top-down view)
  Beauty,   // the beauty alone
  Display,  // RenderedFrame::display alone (needs RenderOptions::gpuDisplay)
};

// Drawing a frame into the host's own images (skylayers::Sky::record, docs/library.md): the
// frame is recorded into the host's command buffer, not submitted, and reads nothing back.
// The images are borrowed (Image::borrow), the size of the scene's output.
struct HostTarget {
  VkCommandBuffer cmd = VK_NULL_HANDLE;  // recording
  PersistentImage* colour = nullptr;     // scene-linear rgba16f or rgba32f, storage usage
  VkImageLayout colourLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // before and after the frame
  PersistentImage* depth = nullptr;                        // optional; sampled usage
  VkImageLayout depthLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  shared::HostDepth depthMapping{};  // how its values map to distance
};

// One camera of a frame of several views (Renderer::render with views): where it looks, its
// field of view and its size. Every view stands at the scene camera's place, so they share
// the frame's lights, bakes, LUTs, weather map, noise, light volume and shadow map.
struct FrameView {
  double headingDeg = 0.0, pitchDeg = 0.0, rollDeg = 0.0;  // as camera.heading/pitch/roll
  double verticalFovDeg = 60.0;                            // camera.vertical_fov
  CameraProjection projection = CameraProjection::Perspective;
  uint32_t width = 0, height = 0;
};

struct RenderOptions {
  // Images of the frame's graph to read back by name (Renderer::debugImages lists them);
  // a name the frame does not have is an UnknownImageName error (BadInput).
  std::vector<std::string> debugOutputs;
  bool allDebugOutputs = false;  // every image of the frame (skyrender --debug-passes)
  ReadBack readBack = ReadBack::Layers;
  // The GPU display path (passes/display_transform): with an OCIO config here, the frame's
  // display image comes back as RenderedFrame::display, through the scene's display, view,
  // night look and exposure (auto or fixed; a histogram exposure meters the read-back frame
  // and needs the CPU path). The config must outlive the call.
  const OcioOutput* gpuDisplay = nullptr;
  // The GPU display path writes its codes into this image instead, and reads nothing back
  // (skyview: the image it blits into its window, so a frame never leaves the GPU). RGBA8
  // UNORM with storage usage, the output's size; the frame finds it in `displayTargetLayout`
  // and leaves it there with its writes made available. Needs gpuDisplay and
  // ReadBack::Display; the caller must not use it while the frame runs.
  PersistentImage* displayTarget = nullptr;
  VkImageLayout displayTargetLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  // Draw into the host's images instead (readBack, debugOutputs and gpuDisplay are ignored:
  // nothing is read back). The target must outlive the call; its images, until the host's
  // command buffer has run.
  const HostTarget* host = nullptr;
};

struct DebugImage {
  DebugImageInfo info;
  double gpuMs = 0.0;  // the GPU time of the pass that wrote it, this frame
  LayeredImage image;  // main layer, channels named; a 3D image has its slices side by side
};

// What a render() call spent its wall time on besides the frame itself: what a first frame
// pays once (making pipelines, baking or loading textures) and later frames keep.
struct FrameCosts {
  double renderMs = 0.0;      // the whole call
  double pipelinesMs = 0.0;   // making pipelines: shader variants the frame used first
  double texturesMs = 0.0;    // the noise and high-cloud textures: kept, loaded from their cache
                              // files or baked (their own graphs), and the cover calibration
  double lutBakeGpuMs = 0.0;  // GPU time of the frame's one-time bakes (the atmosphere's
                              // transmittance and multiple-scattering LUTs)
  // A Renderer's first frame only: constructing the Renderer (before render() was called),
  // and of that, making the pipelines of its passes.
  double rendererMs = 0.0;
  double rendererPipelinesMs = 0.0;
  // The part that is not this frame's own drawing: pipelines (the Renderer's and the
  // frame's), textures and LUT bakes. The Renderer's other construction (the star
  // catalogue, samplers) is in rendererMs alone.
  double setupMs() const { return rendererPipelinesMs + pipelinesMs + texturesMs + lutBakeGpuMs; }
};

struct RenderedFrame {
  // "" = beauty (R,G,B,A); "sky" (R,G,B); "high_clouds" (R,G,B,A); "clouds" (R,G,B,A,depth);
  // with camera.mode geographic_topdown also "weather" (cover_low, cover_mid); as
  // RenderOptions::readBack says (ReadBack::Display: no layer).
  LayeredImage image;
  FrameResult frame;       // per-pass GPU timings, wall time
  FrameCosts costs;        // where render() spent its wall time
  std::string graphDot;    // the compiled graph with timings (for --dump-graph)
  LightingState lighting;  // the sun, moon, palette and night state the frame was lit by
  HighCloudTextures::Activity highClouds;  // whether the textures were baked, loaded or kept
  bool clouds = false;                     // the weather map has low or mid cover
  CloudNoise::Activity cloudNoise;         // whether the cloud noise was baked, loaded or kept
  // The cloud shadow map's ground square (passes/cloud_shadow), valid 0 without clouds.
  shared::CloudShadowMap cloudShadow{};
  // The weather around the camera (Kozlov section 5), already applied to `lighting`.
  LocalWeather localWeather;
  // Where the weather map lay (weather.region, or the square around the camera) and its size.
  WeatherRegion weatherRegion;
  glm::uvec2 weatherTexels{0};
  std::vector<DebugImage> debug;  // as requested in RenderOptions
  // Every image of the frame's graph: the names RenderOptions::debugOutputs can ask for.
  std::vector<DebugImageInfo> images;
  // With RenderOptions::gpuDisplay: the display image, 8-bit RGBA codes (row 0 the top; empty
  // with a displayTarget, which holds them), and the exposure it was made with (EV).
  std::vector<uint8_t> display;
  double displayEv = 0.0;
};

// The physical sky's atmosphere for `scene`: its atmosphere settings with the ground's albedo
// and, with atmosphere.aerosols turbidity, the Mie coefficients of lighting.turbidity: the
// aerosol optical depth at 550 nm spread over the Mie scale height, Hillaire's single-
// scattering albedo, the lighting model's Angstrom exponent and continental aerosol's phase
// (kContinentalAerosolG, in place of atmosphere.mie_anisotropy), so the sky and the sunlight
// cross the same aerosols.
AtmosphereSettings physicalAtmosphere(const Scene& scene);
// Cornette-Shanks g of the aerosol that atmosphere.aerosols turbidity stands for.
inline constexpr double kContinentalAerosolG = 0.6;

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

  // The cloud density field of `scene` at `time` on the CPU (engine/render/cloud_field.h):
  // the raymarch's own parameters, weather map and noise (baked or loaded as a frame would),
  // and the physical atmosphere's air. A scene without low or mid cover gives an empty field.
  // BadInput for a top-down camera (its frame has no observer to hold the field around).
  CloudField cloudField(const Scene& scene, const IsoTime& time);

private:
  // What the clouds of a frame see: the scene with the weather map's region and layer
  // altitudes filled in, the volumetric pass's settings from it, where their rays start, and
  // the lights after the local weather.
  struct CloudSetup {
    Scene cloudScene;
    VolumetricCloudsSettings volumetric;
    CloudFrameGeometry geometry;
    LightingState lighting;
    LocalWeather localWeather;
    const WeatherMap* weather;  // owned by mClouds, valid until the next weatherMap()
  };
  CloudSetup cloudSetup(const Scene& scene, const IsoTime& time);

  // A frame in four steps: build the graph (sky, clouds, composite, display), request its
  // outputs (the EXR's layers, the display image, debug images by name), execute, collect.
  // A frame of several views builds each view in turn; what they share, the first makes
  // (SharedFrame) and the others reuse.
  struct FrameInputs;
  struct SharedFrame;
  struct SkyImages;
  struct CloudImages;
  struct FramePlan {  // what the outputs are read from
    ImageId beauty, sky, highClouds, clouds, cloudsDepth, display;
    // Their read-backs, as requestOutputs asked for them (invalid: not read back), and the
    // debug images'.
    struct Outputs {
      OutputId beauty, sky, highClouds, clouds, cloudsDepth, display;
      std::vector<std::pair<OutputId, GraphImage>> debug;
    } outputs;
    const WeatherMap* weather = nullptr;  // a top-down view's map, for its "weather" layer
    bool reuseStep = false;  // the frame took a step of mReuse: commit it once it has run
  };
  FramePlan buildFrame(FrameGraph& graph, const Scene& scene, const IsoTime& time,
                       const RenderOptions& options, RenderedFrame& out,
                       SharedFrame* shared = nullptr);
  // Each reads the frame from `f` alone (read-only) and writes into `out` only what the
  // frame reports (costs, what was baked or kept, the shadow map's place).
  SkyImages addSky(FrameGraph& graph, const FrameInputs& f, RenderedFrame& out);
  CloudImages addClouds(FrameGraph& graph, const FrameInputs& f, const SkyImages& sky,
                        RenderedFrame& out, bool& reuseStep);
  // `prefix` labels a view's outputs in a frame of several ("view1/"), for errors and dumps.
  void requestOutputs(FrameGraph& graph, FramePlan& plan, const RenderOptions& options,
                      const std::string& prefix = "");
  // The layers, display and debug images of `plan` from `result` (the frame's read-backs).
  void collectOutputs(RenderedFrame& out, const FrameResult& result, const FrameGraph& graph,
                      const FramePlan& plan, const RenderOptions& options);
  // The costs and timings of a frame once it has run.
  void finishCosts(RenderedFrame& out, std::chrono::steady_clock::time_point start,
                   double pipelinesBefore);

  // When construction began and the process's pipeline time then: the first render() reports
  // what constructing took (FrameCosts::rendererMs). Declared first, so initialised first.
  std::chrono::steady_clock::time_point mCreated = std::chrono::steady_clock::now();
  double mPipelinesAtCreation = pipelineBuildMs();
  std::optional<FrameCosts> mConstruction;  // until the first render() reports it
  GraphRuntime mRuntime;
  StarFieldPass mStars;
  HighCloudTextures mHighCloudTextures;
  AtmosphereLuts mAtmosphere;
  SkyHighCloudsPass mSky;
  CloudLayers mClouds;
  CloudAmbientPass mAmbient;
  VolumetricCloudsPass mVolumetric;
  CloudShadowPass mShadow;
  CloudReuse mReuse;  // the cloud history: temporal reuse across a sequence's frames
  SettingsRevisions mFieldSettings;  // what the light volume and shadow map were made for
  CloudUpsamplePass mUpsample;
  CloudLightVolumePass mLightVolume;
  DisplayTransformPass mDisplay;
  Sampler mHostDepthSampler;  // nearest, clamp: a host's depth, fetched texel by texel
  CloudDensitySlicePass mSlice;
  CloudVolumeExportPass mVolumeExport;
  AtmosphereCompositePass mComposite;
};

}  // namespace sky
