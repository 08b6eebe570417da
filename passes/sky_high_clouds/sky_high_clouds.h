#pragma once
// The sky and high-cloud layer (Kozlov et al. §3): the clear sky (Kozlov 3.1 or, with
// sky.model physical, Hillaire's sky-view LUTs) and the high clouds from a coefficient texture
// and normal map mapped onto a sphere at the layer's altitude, scrolled by the wind and shaded
// by Kozlov 3.2-3.4 for the sun and the moon (shaders/sky_high_clouds.comp). The textures come
// from passes/high_cloud_textures, the LUTs from passes/atmosphere_luts; nothing here depends on
// the time of day except the uniforms, so moving the light never re-bakes anything.
// With regional cover (high_clouds.cover_source weather) the cover comes per pixel from the
// weather map's high layer where the ray meets the layer, applied to the bake's rank/shape
// texture, so the cirrus lies where the forecast puts it (docs/high-clouds.md).
#include <optional>

#include <glm/vec3.hpp>

#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "engine/lighting/lighting_state.h"
#include "engine/scene/scene.h"
#include "engine/weather/weather_map.h"
#include "passes/high_cloud_textures/high_cloud_textures.h"
#include "shaders/common/atmosphere_shared.h"
#include "shaders/common/lighting_shared.h"
#include "shaders/common/sky_high_clouds_shared.h"

namespace sky {

class Context;
class Sampler;
class ShaderCompiler;

class SkyHighCloudsPass {
public:
  static constexpr const char* kName = "sky_high_clouds";
  struct Textures {  // passes/high_cloud_textures
    ImageId coefficients, normals, coarse;
    const Sampler* sampler = nullptr;  // linear, repeat
    ImageId levels;  // the mip levels between coefficients and coarse (not read regionally)
  };
  struct Atmosphere {  // passes/atmosphere_luts; sky.model physical only
    shared::AtmosphereParams params{};
    ImageId transmittance, skyViewSun, skyViewMoon;
    const Sampler* sampler = nullptr;  // linear, clamp
  };
  // params.regional.x = 1 only (setRegionalCover): all three must be set, and `coefficients`,
  // `levels` and `coarse` of `textures` are not read (normals still are).
  struct Regional {
    ImageId cover;                          // R16F, WeatherTextures::addHighCover (the high cover)
    const Sampler* coverSampler = nullptr;  // linear, clamp (WeatherTextures::sampler)
    ImageId rankShape;    // HighCloudTextures::Outputs::rankShape, with `textures.sampler`
    ImageId coverCoarse;  // HighCloudTextures::Outputs::coverCoarse, with `textures.sampler`
  };
  struct Inputs {
    shared::SkyHighCloudsParams params{};
    shared::LightingState lighting{};
    Textures textures;
    bool physical = false;  // sky.model physical: `atmosphere` must be set
    Atmosphere atmosphere;
    Regional regional;
  };
  struct Outputs {
    ImageId sky;         // RGBA16F: the clear sky radiance alone (no discs, stars or clouds)
    ImageId highClouds;  // RGBA16F: cloud radiance premultiplied, a = coverage
  };

  // The shader's variants (kozlov or physical; regional cover; a high-cloud layer or none;
  // moonlight or, by day, none) are compiled on first use: setup picks the frame's.
  SkyHighCloudsPass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add): once per view.
  struct Data {
    const ComputePipeline* pipeline = nullptr;  // this view's variant
    bool moon = true;                           // the moon's light is in this frame
    Inputs inputs{};
    Outputs outputs;
    bool regional() const { return inputs.params.regional.x > 0.5f; }
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  ComputePipelineVariants mVariants;
};

// The sphere the sky passes put the ground on: the physical atmosphere's ground, or for the
// kozlov model, which has no planet of its own, the geographic Earth.
double skyPlanetRadiusM(const Scene& scene);

// The layer's uniforms for one frame: geometry from the scene and camera, the wind's drift
// since the start of the scene's time, the texture's orientation (a procedural one's +u
// downwind) and each light's illuminance at the layer's altitude.
// `textureSize`/`coarseSize` are the texel counts across the fine and coarse textures.
// `layerAltitudeM`, when given, places the layer (m above sea level) instead of
// high_clouds.altitude_m: the forecast's high-layer altitude when the cover comes from it.
// Regional cover stays off (regional.x = 0) until setRegionalCover.
shared::SkyHighCloudsParams skyHighCloudsParams(const Scene& scene, const LightingState& lighting,
                                                const IsoTime& time, const shared::ViewState& view,
                                                bool cloudsPresent, uint32_t textureSize,
                                                uint32_t coarseSize,
                                                const glm::vec4& meanCoefficients,
                                                std::optional<double> layerAltitudeM = {});

// Turns regional cover on in `params` (made by skyHighCloudsParams for the same scene): the
// camera's geographic frame on the pass's planet, the weather map's `region`, and the ramp
// width and far-field table of `textures` (HighCloudTextures::addTo with regionalCover).
// Internal error if `textures` has no rank/shape or per-cover coarse texture.
void setRegionalCover(shared::SkyHighCloudsParams& params, const Scene& scene,
                      const WeatherRegion& region, const HighCloudTextures::Outputs& textures);

// Whether the high clouds take their cover per pixel from the weather map's high layer
// (regional cover) rather than from high_clouds.cover, by high_clouds.cover_source:
//  - scene: never;
//  - weather: always; BadInput unless the source is procedural and the map has a high layer
//    (WeatherMap::coverHigh, from a forecast file);
//  - auto: when the source is procedural and the map has a high layer.
// When true, the caller passes
// regionalCover to HighCloudTextures::addTo (which then bakes even at cover 0), uploads the
// high layer with WeatherTextures::addHighCover and calls setRegionalCover.
bool highCloudsFromWeather(const Scene& scene, const WeatherMap& map);

}  // namespace sky
