#pragma once
// What a frame is asked for and what it gives back: the options of Renderer::render, the
// views of a frame of several, a host's images to draw into, and the rendered frame with its
// layers, display codes, debug images, timings and costs. Apart from renderer.h so the parts
// of a frame (engine/render/frame_outputs.h) can name them without the Renderer.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/graph/frame_graph.h"
#include "engine/io/exr.h"
#include "engine/lighting/lighting_state.h"
#include "engine/render/perception.h"
#include "engine/scene/scene.h"
#include "engine/weather/local_weather.h"
#include "passes/cloud_noise/cloud_noise.h"
#include "passes/high_cloud_textures/high_cloud_textures.h"
#include "shaders/common/atmosphere_composite_shared.h"
#include "shaders/common/cloud_shadow_shared.h"

namespace sky {

class OcioOutput;

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
  // The frame's index in its sequence (a time-lapse's frame number): a cut of the cloud
  // history numbers its march from here (CloudReuse::step), so `skyrender render --shard`
  // marches a shard's frames as the whole run does once it has warmed up.
  uint64_t sequenceFrame = 0;
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
  // With output.perception and the layers read back: the frame's visibility, sun and label
  // shares (engine/render/perception.h).
  std::optional<PerceptionSummary> perception;
};

}  // namespace sky
