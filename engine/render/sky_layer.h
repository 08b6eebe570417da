#pragma once
// The first layer of a frame: the clear sky (Kozlov's, or Hillaire's physical atmosphere with
// its LUTs), the high clouds from their coefficient textures and the stars, lit by the frame's
// one sun and moon. One of the Renderer's jobs, beside the volumetric clouds
// (volumetric_cloud_layer.h), the cloud history (cloud_reuse.h) and the outputs
// (frame_outputs.h). It owns those passes, the star catalogue, the high-cloud textures and the
// atmosphere LUTs, which persist from frame to frame.
#include <functional>
#include <optional>

#include "engine/render/frame_inputs.h"
#include "passes/atmosphere_luts/atmosphere_luts.h"
#include "passes/high_cloud_textures/high_cloud_textures.h"
#include "passes/sky_high_clouds/sky_high_clouds.h"
#include "passes/star_field/star_field.h"

namespace sky {

class Context;
class GraphRuntime;
class ShaderCompiler;

// The physical sky's atmosphere for `scene`: its atmosphere settings with the ground's albedo
// and, with atmosphere.aerosols turbidity, the Mie coefficients of lighting.turbidity: the
// aerosol optical depth at 550 nm spread over the Mie scale height, Hillaire's single-
// scattering albedo, the lighting model's Angstrom exponent and continental aerosol's phase
// (kContinentalAerosolG, in place of atmosphere.mie_anisotropy), so the sky and the sunlight
// cross the same aerosols.
AtmosphereSettings physicalAtmosphere(const Scene& scene);
// Cornette-Shanks g of the aerosol that atmosphere.aerosols turbidity stands for.
inline constexpr double kContinentalAerosolG = 0.6;

class SkyLayer {
public:
  // Loads the star catalogue from configs/stars/ (under dataRoot()). `weather` is the frame's
  // weather map and its textures (a forecast's high layer gives the high clouds' cover).
  SkyLayer(const Context& ctx, ShaderCompiler& compiler, GraphRuntime& runtime,
           CloudLayers& weather);

  // The sky, the high clouds and the stars of a frame, as the composite reads them, and what
  // the layer reports of the frame.
  struct Images {
    SkyHighCloudsPass::Outputs sky;
    AtmosphereLuts::Outputs luts{};
    std::optional<StarFieldPass::Outputs> stars;
    std::optional<double> highAltitudeM;     // a forecast's high layer (the middle of its gh range)
    double texturesMs = 0.0;                 // keeping, loading or baking the high-cloud textures
    HighCloudTextures::Activity highClouds;  // which of those it was
  };
  Images addTo(FrameGraph& graph, const FrameInputs& f);

  // The physical sky's parameters, LUT sampler and the clouds' view of it (the volumetric
  // clouds' ambient and the composite read them).
  const AtmosphereLuts& atmosphere() const { return mAtmosphere; }
  // Called with the share done (0..1) while a high-cloud texture bakes.
  void setBakeProgress(std::function<void(double)> progress);

private:
  CloudLayers& mWeather;
  StarFieldPass mStars;
  HighCloudTextures mHighCloudTextures;
  AtmosphereLuts mAtmosphere;
  SkyHighCloudsPass mSky;
};

}  // namespace sky
