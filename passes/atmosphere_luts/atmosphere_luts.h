#pragma once
// The physically based atmosphere of Hillaire 2020 ("A Scalable and Production Ready Sky and
// Atmosphere Rendering Technique") as frame-graph passes: the transmittance and
// multiple-scattering LUTs (persistent, remade when the atmosphere changes), the sky-view LUTs
// lit by the sun and by the moon, and the aerial-perspective froxel volume (both every
// frame). Shaders sample them through shaders/common/atmosphere.glsl; docs/atmosphere.md
// describes their contents, parametrisations and units.
#include <cstdint>
#include <optional>
#include <utility>

#include <glm/vec3.hpp>

#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/sampler.h"
#include "engine/graph/frame_graph.h"
#include "engine/scene/scene.h"
#include "shaders/common/atmosphere_shared.h"
#include "shaders/common/view_shared.h"

namespace sky {

class Context;
class ShaderCompiler;

// The camera is kept this far inside the atmosphere (above the ground, below the top), so
// every ray from it is well defined (Hillaire's PLANET_RADIUS_OFFSET).
inline constexpr double kAtmosphereCameraMarginKm = 0.01;

// GPU parameters from the scene's settings: km and 1/km (1/Mm = 1e-3/km). The camera sits at
// the ground (plus the margin), the lights are off and the view is empty; AtmosphereLuts::addTo
// fills those per frame. Input error for settings no atmosphere can have (non-positive sizes,
// Mie extinction below its scattering).
shared::AtmosphereParams atmosphereParams(const AtmosphereSettings& s);

// `params` with the camera at `altitudeM` above the ground, clamped into the atmosphere.
void setAtmosphereCamera(shared::AtmosphereParams& params, double altitudeM);

class AtmosphereLuts {
public:
  struct Frame {
    AtmosphereSettings atmosphere;
    double cameraAltitudeM = 0.0;  // above sea level (= ground radius)
    shared::ViewState view;        // the camera (shaders/common/view_shared.h) for the AP froxels
    glm::vec3 sunDirection{0, 0, 1};  // unit, east-north-up (z up)
    glm::vec3 moonDirection{0, 0, -1};
    glm::vec3 sunIlluminance{0.0f};  // rgb above the atmosphere, renderer units
    glm::vec3 moonIlluminance{0.0f};
    // Where the volumetric clouds are (above sea level): their sky, a second pair of sky-view
    // LUTs seen from there (passes/cloud_ambient). Unset: none.
    std::optional<double> cloudAltitudeM;
  };
  struct Outputs {
    ImageId transmittance;    // 256x64, rgb transmittance to the top of the atmosphere
    ImageId multiScattering;  // 160x32: Hillaire's Psi_ms and the second order's moments
                              // (per unit illuminance; packing in atmosphere_shared.h)
    ImageId skyViewSun;       // 192x108, sky radiance lit by the sun (illuminance applied)
    ImageId skyViewMoon;      // 192x108, the same lit by the moon
    // The same two seen from Frame::cloudAltitudeM (invalid without one): from the clouds the
    // low sky is bluer and brighter than from the ground, and below the horizon lies the air
    // between them and the ground.
    ImageId skyViewSunClouds, skyViewMoonClouds;
    ImageId aerialPerspective;  // 32x32x32 RGBA: rgb in-scattered radiance from camera to the
                                // slice (sun + moon), a: mean transmittance
  };

  // Pass names (FrameResult timings, graph dumps).
  static constexpr const char* kTransmittanceName = "atmosphere_transmittance";
  static constexpr const char* kMultiScatteringName = "atmosphere_multiscattering";
  // The sky-view LUTs: one pass per light and per place seen from (the camera, the clouds).
  static constexpr const char* kSkyViewName = "atmosphere_sky_view";
  static constexpr const char* kSkyViewMoonName = "atmosphere_sky_view_moon";
  static constexpr const char* kSkyViewCloudsName = "atmosphere_sky_view_clouds";
  static constexpr const char* kSkyViewCloudsMoonName = "atmosphere_sky_view_clouds_moon";
  static constexpr const char* kAerialPerspectiveName = "atmosphere_aerial_perspective";
  static constexpr const char* kSkyProbeName = "atmosphere_sky_probe";

  // Compiles the five shaders and creates the persistent LUT images (once, at start-up).
  AtmosphereLuts(const Context& ctx, ShaderCompiler& compiler);

  // Adds the passes to `graph`. Transmittance and multiple scattering live in persistent
  // images and are recomputed (their passes added) only when `frame.atmosphere` differs from
  // the settings they were last recorded with. The sky-view LUTs are persistent too, one per
  // light: each depends on the atmosphere, the camera's altitude, its light's elevation and
  // illuminance, not on where the camera looks or the light's azimuth, so a pan (a window, a
  // benchmark) keeps them, and a moon that moves with the clock remakes only the moon's. A
  // LUT no pass of the frame reads (the moon's by day) is culled with its pass. Aerial
  // perspective follows the view and runs every frame. Must outlive graph.execute().
  Outputs addTo(FrameGraph& graph, const Frame& frame);
  // Another view's aerial-perspective volume from the LUTs of this frame's addTo (a frame of
  // several views at one place: the other LUTs do not depend on where the camera looks).
  ImageId addAerialPerspective(FrameGraph& graph, const Outputs& luts,
                               const shared::ViewState& view);

  // Adds the sky probe: a width x height RGBA32F equirectangular image of the whole sphere
  // (column 0 north, azimuth eastward; row 0 the zenith) made by skyViewRadiance() from
  // `luts` (sun + moon) with the parameters of the last addTo. A debug view.
  ImageId addSkyProbe(FrameGraph& graph, const Outputs& luts, uint32_t width, uint32_t height);

  const shared::AtmosphereParams& params() const { return mParams; }  // those of the last addTo
  // The last addTo's with the camera at Frame::cloudAltitudeM: what skyViewRadiance() needs to
  // read the clouds' sky-view LUTs.
  const shared::AtmosphereParams& cloudParams() const { return mCloudParams; }
  const Sampler& sampler() const { return mSampler; }  // linear clamp, for every LUT

private:
  ComputePipeline mTransmittance;
  ComputePipeline mMultiScattering;
  ComputePipeline mSkyView;
  ComputePipeline mAerialPerspective;
  ComputePipeline mSkyProbe;
  Sampler mSampler;
  PersistentImage mTransmittanceLut;
  PersistentImage mMultiScatteringLut;
  // The settings the persistent LUTs were last recorded for (set when their passes record).
  std::optional<AtmosphereSettings> mBaked;
  // What a sky-view LUT was last recorded for, likewise: what the shader reads of the frame
  // (its light's direction only through the elevation, atmosphere_sky_view.comp).
  struct SkyViewKey {
    AtmosphereSettings atmosphere;
    double cameraAltitudeM = 0.0;
    float lightElevation = 0.0f;  // the light direction's up component
    glm::vec3 illuminance{0.0f};
    bool operator==(const SkyViewKey&) const = default;
  };
  // One light's sky-view LUT and what it was last recorded for.
  struct SkyViewLut {
    PersistentImage image;
    std::optional<SkyViewKey> key;
  };
  // The pair of one place.
  struct SkyView {
    SkyViewLut sun, moon;
  };
  // Adds the pass `name` that remakes `lut` for `light` (ATMOSPHERE_SKY_VIEW_LIGHT_*) unless
  // it holds `key` already; returns the LUT.
  ImageId addSkyView(FrameGraph& graph, const char* name, SkyViewLut& lut,
                     const shared::AtmosphereParams& p, uint32_t light, const SkyViewKey& key,
                     ImageId transmittance, ImageId multiScattering);
  SkyView mCameraSkyView;  // seen from the camera
  SkyView mCloudSkyView;   // seen from the clouds
  shared::AtmosphereParams mParams{};
  shared::AtmosphereParams mCloudParams{};
};

}  // namespace sky
