#pragma once
// What every pass that samples the cloud field shares (issue 46: its own room, so the raymarch
// pass is one pass among them): the textures they read, the shader variant and its pipelines,
// the settings the clouds take from the scene, the frame's uniforms (cloudParams), the key of
// a product kept over frames and the key light. The raymarch (passes/volumetric_clouds), the
// light volume, the shadow map, the perception, the density slice and the volume export
// include this; docs/clouds.md.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/clouds/coverage_calibration.h"
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
  ImageId weather, weatherCoarse;           // engine/render WeatherTextures
  const Sampler* weatherSampler = nullptr;  // linear, clamp
};

// The width (m) of the detail noise's coarsest cells for a repeat of `detailRepeatM` metres:
// its R channel holds 2 cells a repeat (lu2023) or 4 (tang2019), G and B twice and four times
// as many (docs/cloud-noise.md; cloud_field.glsl's detailCellM).
inline double cloudDetailCellM(double detailRepeatM, CloudModel model) {
  return detailRepeatM / (model == CloudModel::Tang2019 ? 4.0 : 2.0);
}

// The clouds' two images as the raymarch, the upsampling and the still's filter write them:
// premultiplied radiance and opacity (RGBA32F: physical radiance, ~1e-7 by moonlight, is below
// half float's normal range), and the transmittance-weighted distance with where the ray
// enters the shells (RG32F). Each pass names them and says what they hold.
struct CloudImages {
  ImageId clouds, depth;
};
struct CloudImageNames {
  const char* clouds;
  const char* cloudsAbout;
  const char* depth;
  const char* depthAbout;
};
CloudImages writeCloudImages(GraphBuilder& b, uint32_t width, uint32_t height,
                             const CloudImageNames& names);

// Every pass that samples the cloud field (the raymarch, the density slice, the volume
// export) reads these textures in setup and binds them at the same slots in execute
// (cloud_field.glsl declares them).
void readCloudTextures(GraphBuilder& b, const CloudTextures& t);
// The five sampler bindings; the caller appends its own parameters and images.
std::vector<Binding> cloudTextureBindings(const CloudTextures& t);

// Where a frame's cloud rays start: the observer's camera, or straight down from above the
// clouds over every pixel's latitude and longitude (camera.mode geographic_topdown).
enum class CloudFrame { Observer, TopDown };
// How a view step's scattering is integrated: exactly for a homogeneous step (Hillaire 2016,
// clouds.energy_conserving true) or as the Riemann sum S dt.
enum class CloudStepIntegral { Exact, Riemann };
// Whether the shape noise's second lookup, stretched along the wind, is compiled in: only when
// some low cloud of the map is stratocumulus (cloudRollWeight). On lavapipe the lookup costs a
// fifth of the pass wherever it is compiled in, even where no sample reads it.
enum class CloudRolls { Off, On };
// Whether the cumulus' two slower lookups of the shape noise are compiled in: only when some
// cloud of the map is cumulus or convective (cloudCumulusWeight).
enum class CloudCumulus { Off, On };

// The cloud shaders' variant: the scene's discrete choices, compiled in as constants
// (cloudVariantDefines), one pipeline per combination, so the compiler drops the unused model
// and lookups (lavapipe runs both sides of every branch; no test at run time can). Nothing in
// it comes from a continuous setting: light steps, splits, octaves and the noise each light
// step reads are uniforms, so moving a slider never compiles a pipeline. A time-lapse uses
// one; changing a choice costs one compile.
struct CloudVariant {
  CloudFrame frame = CloudFrame::Observer;
  CloudModel model = CloudModel::Lu2023;
  CloudPhase phase = CloudPhase::DualLobe;
  CloudStepIntegral integral = CloudStepIntegral::Exact;
  CloudCoverageMode coverage = CloudCoverageMode::Calibrated;
  CloudRolls rolls = CloudRolls::On;
  CloudCumulus cumulus = CloudCumulus::On;
  CloudQuality quality = CloudQuality::Standard;
  CloudLight light = CloudLight::March;

  bool operator==(const CloudVariant&) const = default;
};

struct VolumetricCloudsSettings;
// The variant of a frame: the scene's choices, the frame's kind, whether the map has rolls
// (CloudLayers::Frame::lowRolls). The reference always marches its light.
CloudVariant cloudVariant(const VolumetricCloudsSettings& settings, bool lowRolls,
                          bool cumulus);
// The GLSL defines that compile `v` (cloud_field.glsl and volumetric_clouds.comp read them).
std::vector<ShaderDefine> cloudVariantDefines(const CloudVariant& v);

// The cloud shaders compiled for each variant, built on first use and kept.
class CloudPipelines {
public:
  CloudPipelines(const Context& ctx, ShaderCompiler& compiler, const char* file, const char* name);
  // `extra`: a pass's own defines beside the variant's (the raymarch's host depth).
  const ComputePipeline& get(const CloudVariant& variant,
                             const std::vector<ShaderDefine>& extra = {});

private:
  ComputePipelineVariants mVariants;
};

// Calibrated coverage: the thresholds (CloudParams.coverageLut), [layer][type key][cover
// entry], and the far field's mean density and cloud share per height (CloudParams.farMeanLut),
// [layer][type key][cover entry][height].
struct CoverageTables {
  template <class T>
  using PerLayerAndType = std::array<std::array<T, CLOUD_COVERAGE_TYPE_KEYS>, 2>;
  PerLayerAndType<std::array<float, CLOUD_COVERAGE_LUT_SIZE>> thresholds{};
  PerLayerAndType<
      std::array<std::array<clouds::FarMean, CLOUD_FAR_MEAN_HEIGHTS>, CLOUD_FAR_MEAN_COVERS>>
      farMean{};
};

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
  double turbidity = 0.15;  // lighting.turbidity: the air the light crosses to each layer
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
  uint64_t settings = 0;  // the scene but for the camera's pose and the time, as a revision
                          // number (engine/render/cloud_reuse.h, SettingsRevisions)
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
// the map's largest (low, mid) cover.
shared::CloudParams cloudParams(const VolumetricCloudsSettings& settings,
                                const LightingState& lighting, const IsoTime& time,
                                const shared::ViewState& view, const glm::vec2& maxCover,
                                const CoverageTables& coverage, const NoiseMeans& noiseMeans);

// The key light at the clouds: the brighter of the sun and the moon there (the shadow map is
// cast by it), from the uniforms' illuminance at the layers.
struct CloudKeyLight {
  glm::vec3 direction{0.0f, 0.0f, 1.0f};  // unit, ENU
  bool isSun = true;
};
CloudKeyLight cloudKeyLight(const shared::CloudParams& params);

}  // namespace sky
