#pragma once
// The volumetric low and mid clouds (Lu et al. 2023, Tang et al. 2019): a raymarch through
// the spherical shells of the two layers (shaders/volumetric_clouds.comp), reading the weather
// map (engine/weather) for cover and type and the baked noise (passes/cloud_noise) for the
// density, lit by the frame's LightingState. Also the density-slice debug view, a vertical
// cut through the density field along the camera's heading. See docs/clouds.md.
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "engine/lighting/lighting_state.h"
#include "engine/scene/scene.h"
#include "shaders/common/lighting_shared.h"
#include "shaders/common/volumetric_clouds_shared.h"

namespace sky {

class Context;
class Sampler;
class ShaderCompiler;

// What the cloud shaders sample: the baked noise and the weather map.
struct CloudTextures {
  ImageId shape, detail, curl;              // passes/cloud_noise
  const Sampler* noiseSampler = nullptr;    // linear, repeat
  ImageId weather, weatherCoarse;           // engine/weather WeatherTexture
  const Sampler* weatherSampler = nullptr;  // linear, clamp
};

// Every pass that samples the cloud field (the raymarch, the density slice, the volume
// export) reads these textures in setup and binds them at the same slots in execute
// (cloud_field.glsl declares them).
void readCloudTextures(GraphBuilder& b, const CloudTextures& t);
// The five sampler bindings; the caller appends its own parameters and images.
std::vector<Binding> cloudTextureBindings(const CloudTextures& t);

// The cloud shaders compiled for the scene's fixed choices (CloudParams.frame x/z/w and
// .options: ray start, light steps, octaves, phase, energy-conserving steps, coverage mode and
// model) as constants, one pipeline per combination, built on first use and kept. A
// time-lapse uses one; changing a choice costs one compile.
class CloudPipelines {
public:
  CloudPipelines(const Context& ctx, ShaderCompiler& compiler, const char* file, const char* name);
  const ComputePipeline& get(const shared::CloudParams& params);

private:
  ComputePipelineVariants mVariants;
};

class VolumetricCloudsPass {
public:
  static constexpr const char* kName = "volumetric_clouds";
  struct Inputs {
    shared::CloudParams params{};
    shared::LightingState lighting{};
    CloudTextures textures;
    // With params.lightVolume.enabled: passes/cloud_light_volume's volume and its sampler.
    ImageId lightVolume;
    const Sampler* lightVolumeSampler = nullptr;
  };
  struct Outputs {
    ImageId clouds;  // RGBA16F: rgb radiance premultiplied, a opacity (1 - transmittance)
    ImageId depth;   // RG32F: transmittance-weighted distance to the clouds (m), 0 where
                     // clear; g: where the ray reaches the shells (m), -1 if never
    ImageId steps;   // RGBA16F: density samples along the view ray, and inside light marches
  };

  VolumetricCloudsPass(const Context& ctx, ShaderCompiler& compiler);
  Outputs setup(GraphBuilder& builder, const Inputs& inputs);
  void execute(PassContext& ctx) const;

private:
  CloudPipelines mPipelines;
  const ComputePipeline* mPipeline = nullptr;  // this frame's variant, chosen in setup()
  Inputs mInputs{};
  Outputs mOutputs;
};

class CloudDensitySlicePass {
public:
  static constexpr const char* kName = "cloud_density_slice";
  static constexpr uint32_t kWidth = 512, kHeight = 128;
  struct Inputs {
    shared::CloudParams params{};  // slice.x: length ahead (m); slice.y: top altitude (m)
    CloudTextures textures;
  };
  struct Outputs {
    ImageId slice;  // RGBA16F kWidth x kHeight: r density, g cover, b type, a layer (0/1, -1)
  };

  CloudDensitySlicePass(const Context& ctx, ShaderCompiler& compiler);
  Outputs setup(GraphBuilder& builder, const Inputs& inputs);
  void execute(PassContext& ctx) const;

private:
  // Every frame with clouds adds this pass for the debug view, and nearly every frame culls
  // it: its variant is compiled when it first runs, in execute(), not in setup().
  mutable CloudPipelines mPipelines;
  Inputs mInputs{};
  Outputs mOutputs;
};

// Calibrated coverage thresholds (CloudParams.coverageLut): [layer][type key][cover entry].
using CoverageTables =
    std::array<std::array<std::array<float, CLOUD_COVERAGE_LUT_SIZE>, CLOUD_COVERAGE_TYPE_KEYS>, 2>;

// What the clouds take from the scene, built once per frame by engine/render
// (volumetricCloudsSettings in engine/render/cloud_layers.h), not the whole Scene.
struct VolumetricCloudsSettings {
  CloudSettings clouds;  // clouds.*, with a forecast's layer altitudes in low and mid
  WeatherRegion region;  // where the weather map lies
  // The observer (camera.latitude, longitude, altitude_m), unless topDown: camera.mode
  // geographic_topdown, rays straight down from above the region's centre.
  double cameraLatDeg = 0.0, cameraLonDeg = 0.0, cameraAltitudeM = 0.0;
  bool topDown = false;
  IsoTime timeStart;       // time's start: the wind drifts the noise from this instant
  double turbidity = 0.1;  // lighting.turbidity: the air the light crosses to each layer
};

// Where the frame's rays start: the observer, or for a top-down camera the region's centre
// above the clouds.
struct CloudFrameGeometry {
  double latDeg, lonDeg, altitudeM;
  bool topDown;
};
CloudFrameGeometry cloudFrameGeometry(const VolumetricCloudsSettings& settings);

// The mean of each channel of the baked noise textures (CloudParams.shapeMean, .detailMean):
// what the octaves finer than a pixel's footprint fade to at a distance.
struct NoiseMeans {
  glm::vec4 shape{0.5f};
  glm::vec4 detail{0.5f};
};

// What a product of the cloud field made once and kept over frames (the light volume, the
// shadow map) was made from. A frame whose key differs in anything but the drift, or whose
// drift has gone further than `maxShiftM` (the cover the noise drifts through stays put),
// makes it again; within that, the product is read shifted by the drift since.
struct CloudFieldKey {
  std::string clouds;      // the scene written out but for the camera's pose and the time
  uint64_t mapRevision = 0;
  glm::dvec3 camera{0.0};           // latitude, longitude (degrees), altitude (m)
  glm::vec3 sun{0.0f}, moon{0.0f};  // directions (ENU)
  uint32_t lights = 0;              // which are marched: bit 0 the sun, bit 1 the moon
  glm::dvec2 drift{0.0};            // the wind's drift of the clouds (east, north, m)
};
// Whether what was made for `made` serves `now` (lights turned by under 0.05 degrees, the
// camera moved by under 50 m, the drift within maxShiftM).
bool cloudFieldReusable(const CloudFieldKey& made, const CloudFieldKey& now, double maxShiftM);

// The bookkeeping of one such product (the pass owns the image): what it was made from.
class KeptCloudProduct {
public:
  explicit KeptCloudProduct(double maxShiftM) : mMaxShiftM(maxShiftM) {}
  // Whether a frame with `key` must make the product again; if so it is recorded as made
  // for `key` (a frame that then fails calls invalidate()).
  bool needsMaking(const CloudFieldKey& key) {
    if (mValid && cloudFieldReusable(mMade, key, mMaxShiftM)) return false;
    mMade = key;
    mValid = true;
    return true;
  }
  // How far (east, north, m) the clouds drifted from where they were when it was made.
  glm::dvec2 shift(const CloudFieldKey& key) const { return key.drift - mMade.drift; }
  void invalidate() { mValid = false; }

private:
  double mMaxShiftM;
  CloudFieldKey mMade;
  bool mValid = false;
};

// How far (east, north, m) the wind has carried the clouds' noise `elapsedS` seconds after the
// scene's start (clouds.wind_speed_ms toward wind_from + 180 degrees).
glm::dvec2 cloudWindDriftM(const CloudSettings& clouds, double elapsedS);

// The pass's uniforms for one frame at `time`: the layers and shells, the frame, the wind's
// drift of the noise since settings.timeStart, the key light and its illuminance at each
// layer's altitude, the ambient light, the coverage tables and the noise means. `maxCover` is
// the map's largest (low, mid) cover; `weatherSize` its texel counts; `lowRolls` whether any
// of its low cloud has rolls (cloudRollWeight, CloudLayers::Frame::lowRolls).
shared::CloudParams cloudParams(const VolumetricCloudsSettings& settings,
                                const LightingState& lighting, const IsoTime& time,
                                const shared::ViewState& view, const glm::vec2& maxCover,
                                const glm::uvec2& weatherSize, const CoverageTables& coverage,
                                const NoiseMeans& noiseMeans, bool lowRolls);

}  // namespace sky
