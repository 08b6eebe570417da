#pragma once
// What the layers of a frame (engine/render/sky_layer.h, volumetric_cloud_layer.h) build
// their passes from: the frame's setup (engine/render/frame_setup.h: the weather, the lights
// after it, where the clouds lie), its view, and, in a frame of several views, what the first
// view made for the others.
// Read-only to the layers: each reports what it made in its own Images.
#include <chrono>
#include <cstdint>
#include <optional>

#include "engine/lighting/lighting_state.h"
#include "engine/render/cloud_layers.h"
#include "engine/render/frame_setup.h"
#include "engine/scene/scene.h"
#include "engine/weather/local_weather.h"
#include "passes/atmosphere_luts/atmosphere_luts.h"
#include "passes/cloud_light_volume/cloud_light_volume.h"
#include "passes/cloud_shadow/cloud_shadow.h"
#include "passes/high_cloud_textures/high_cloud_textures.h"
#include "passes/volumetric_clouds/volumetric_clouds.h"
#include "shaders/common/view_shared.h"

namespace sky {

// What the views of a frame of several share, made by the first view's passes.
struct SharedFrame {
  std::optional<HighCloudTextures::Outputs> textures;
  std::optional<ImageId> highCover;
  std::optional<AtmosphereLuts::Outputs> luts;
  struct Clouds {
    CloudLayers::Frame frame;
    ImageId ambient;
    std::optional<CloudLightVolumePass::Outputs> volume;
    CloudShadowPass::Outputs shadow;
  };
  std::optional<Clouds> clouds;
};

// What every part of a frame's graph is built from: the scene, the time, the clouds' setup
// and the view.
struct FrameInputs {
  const Scene& scene;
  const IsoTime& time;
  const FrameSetup& setup;
  shared::ViewState view;
  uint32_t width, height;
  bool physical, topDown;
  SharedFrame* shared;  // a frame of several views: what they share; null for one view
  // What the passes read of the frame, never write: the lights after the local weather, and
  // whether the weather map has low or mid cover.
  const LightingState& lighting;
  bool clouds;
  // Drawing into a host's images with its depth (RenderOptions::host): where its geometry is.
  std::optional<VolumetricCloudsPass::Inputs::HostDepth> hostDepth;
  uint64_t sequenceFrame = 0;  // RenderOptions::sequenceFrame
};

// Milliseconds of wall time since `start`: what a part of a frame reports it spent.
inline double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace sky
