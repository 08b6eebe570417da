#include "passes/sky_high_clouds/sky_high_clouds.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "engine/core/error.h"
#include "engine/gpu/sampler.h"
#include "engine/lighting/light_model.h"
#include "engine/shader/shader_compiler.h"
#include "engine/weather/geo.h"

namespace sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
ShaderDefine flag(const char* name, bool on) {
  return {name, on ? "1" : "0"};
}

}  // namespace

double skyPlanetRadiusM(const Scene& scene) {
  return scene.sky.model == SkyModel::Physical ? scene.atmosphere.groundRadiusKm * 1000.0
                                               : kEarthRadiusM;
}

shared::SkyHighCloudsParams skyHighCloudsParams(const Scene& scene, const LightingState& lighting,
                                                const IsoTime& time, const shared::ViewState& view,
                                                bool cloudsPresent, uint32_t textureSize,
                                                uint32_t coarseSize,
                                                const glm::vec4& meanCoefficients,
                                                std::optional<double> layerAltitudeM) {
  const HighCloudSettings& hc = scene.highClouds;
  const double altitudeM = layerAltitudeM.value_or(hc.altitudeM);
  shared::SkyHighCloudsParams p{};
  p.view = view;
  // Altitudes are above sea level; the camera may not sit below the ground sphere (setRegionalCover
  // places it the same way).
  const double planetR = skyPlanetRadiusM(scene);
  p.layer = glm::vec4(static_cast<float>(planetR),
                      static_cast<float>(planetR + std::max(scene.camera.altitudeM, 1.0)),
                      static_cast<float>(planetR + altitudeM), cloudsPresent ? 1.0f : 0.0f);

  // The wind blows from `windFrom`: the clouds drift toward windFrom + 180 degrees. The drift
  // is measured from the start of the scene's time so a time-lapse moves smoothly; the texture
  // moves against it (a cloud at ground point x now was at x - drift at the start).
  const double elapsed = time.secondsSince(scene.time.start);
  const double toward = (hc.windFrom + 180.0) * kDeg;
  const glm::dvec2 downwind(std::sin(toward), std::cos(toward));  // east, north
  // A procedural texture's +u axis is laid downwind: its cirrus streaks run along +u, and real
  // ones are drawn out along the upper-level wind, so in perspective they converge toward the
  // horizon where the wind blows to and comes from. An image keeps north up, as it was drawn.
  // Rotating the draw, not the bake, keeps the baked texture (and its cache entry) the same
  // whatever the wind.
  const glm::dvec2 tileU =
      hc.source == HighCloudSource::Procedural ? downwind : glm::dvec2(1.0, 0.0);
  const glm::dvec2 tileV(tileU.y, -tileU.x);  // +u turned 90 degrees clockwise
  const double tileM = hc.tileSizeKm * 1000.0;
  const glm::dvec2 drift = hc.windSpeedMs * elapsed * downwind;
  // Wrapped to one tile along the texture's own axes, its periods (the texture repeats, and
  // floats keep their precision), then back to east and north.
  const double driftU = std::fmod(glm::dot(drift, tileU), tileM);
  const double driftV = std::fmod(glm::dot(drift, tileV), tileM);
  const glm::dvec2 wrapped = driftU * tileU + driftV * tileV;
  p.texture = glm::vec4(static_cast<float>(-wrapped.x), static_cast<float>(-wrapped.y),
                        static_cast<float>(tileM), static_cast<float>(textureSize));
  p.tileUEast = static_cast<float>(tileU.x);
  p.tileUNorth = static_cast<float>(tileU.y);
  p.shading =
      glm::vec4(static_cast<float>(hc.brightness), static_cast<float>(hc.edgeGlowDeg * kDeg),
                static_cast<float>(coarseSize), 0.0f);
  p.meanCoefficients = meanCoefficients;

  const double turbidity = scene.lighting.turbidity;
  p.sunAtLayer = glm::vec4(
      light::illuminanceAtAltitude(glm::vec3(lighting.gpu.sunSpace), lighting.sun.elevationDeg,
                                   lighting.sun.angularRadiusDeg, altitudeM, turbidity),
      0.0f);
  p.moonAtLayer = glm::vec4(
      light::illuminanceAtAltitude(glm::vec3(lighting.gpu.moonSpace), lighting.moon.elevationDeg,
                                   lighting.moon.angularRadiusDeg, altitudeM, turbidity),
      0.0f);
  return p;
}

void setRegionalCover(shared::SkyHighCloudsParams& params, const Scene& scene,
                      const WeatherRegion& region, const HighCloudTextures::Outputs& textures) {
  if (!textures.rankShape.valid() || !textures.coverCoarse.valid())
    internalError("sky_high_clouds: regional cover needs textures made with regionalCover");
  // The pass puts the camera at (0, 0, layer.y) from the centre of a sphere of radius layer.x
  // and the layer point at t V in the camera's ENU frame: a geographic frame on that same
  // sphere maps t V to the latitude and longitude below it.
  shared::GeoFrame geo = geoFrame(
      {scene.camera.latitude, scene.camera.longitude, std::max(scene.camera.altitudeM, 1.0)});
  geo.origin.w = static_cast<float>(skyPlanetRadiusM(scene));
  params.geo = geo;
  params.region = geoRegion(region);
  params.regional = glm::vec4(1.0f, textures.rampWidth, 0.0f, 0.0f);
  for (uint32_t k = 0; k < HIGH_CLOUD_COVER_STEPS; ++k) params.farField[k] = textures.farField[k];
}

bool highCloudsFromWeather(const Scene& scene, const WeatherMap& map) {
  const HighCloudSettings& hc = scene.highClouds;
  const bool hasHighLayer =
      map.width > 0 && map.height > 0 && map.coverHigh.size() == size_t(map.width) * map.height;
  const bool procedural = hc.source == HighCloudSource::Procedural;
  switch (hc.coverSource) {
    case HighCloudCoverSource::Scene:
      return false;
    case HighCloudCoverSource::Auto:
      return procedural && hasHighLayer;
    case HighCloudCoverSource::Weather:
      break;
  }
  if (!procedural)
    inputError("high_clouds.cover_source: weather needs high_clouds.source procedural, not '" +
               std::string(enumName(hc.source)) + "'");
  if (!hasHighLayer)
    inputError(
        "high_clouds.cover_source: weather needs a weather map with a high layer "
        "(weather.source file); this map has none");
  return true;
}

SkyHighCloudsPass::SkyHighCloudsPass(const Context& ctx, ShaderCompiler& compiler)
    : mVariants(ctx, compiler, "sky_high_clouds.comp", kName) {}

SkyHighCloudsPass::Outputs SkyHighCloudsPass::setup(GraphBuilder& b, const Inputs& in, Data& d) {
  if (!in.textures.sampler) internalError("sky_high_clouds: no texture sampler");
  if (in.physical && !in.atmosphere.sampler) internalError("sky_high_clouds: no LUT sampler");
  d.inputs = in;
  d.moon = !moonLightNegligible(in.lighting);
  d.pipeline = &mVariants.get(
      {flag("SKY_PHYSICAL_SKY", in.physical), flag("SKY_HIGH_CLOUDS_REGIONAL", d.regional()),
       flag("SKY_HIGH_CLOUDS_LAYER", in.params.layer.w > 0.0f), flag("LIGHTING_MOON", d.moon)});
  b.read(in.textures.normals, Access::SampledCompute);
  if (d.regional()) {
    const Regional& r = in.regional;
    if (!r.cover.valid() || !r.coverSampler || !r.rankShape.valid() || !r.coverCoarse.valid())
      internalError("sky_high_clouds: regional cover without its textures");
    b.read(r.cover, Access::SampledCompute);
    b.read(r.rankShape, Access::SampledCompute);
    b.read(r.coverCoarse, Access::SampledCompute);
  } else {
    if (!in.textures.levels.valid()) internalError("sky_high_clouds: no mip levels");
    b.read(in.textures.coefficients, Access::SampledCompute);
    b.read(in.textures.levels, Access::SampledCompute);
    b.read(in.textures.coarse, Access::SampledCompute);
  }
  if (in.physical) {
    b.read(in.atmosphere.transmittance, Access::SampledCompute);
    b.read(in.atmosphere.skyViewSun, Access::SampledCompute);
    if (d.moon) b.read(in.atmosphere.skyViewMoon, Access::SampledCompute);
  }
  ImageDesc desc;
  // 32-bit: the images are physical, and a moonlit night's 1e-7 (renderer units) is below
  // half float's normal range.
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.width = in.params.view.size.x;
  desc.height = in.params.view.size.y;
  desc.name = "sky";
  desc.about = "the clear sky's radiance, without clouds";
  d.outputs.sky = b.write(b.create(desc), Access::StorageWriteCompute);
  desc.name = "high_clouds";
  desc.about = "the high clouds: premultiplied radiance (RGB) and opacity (A)";
  d.outputs.highClouds = b.write(b.create(desc), Access::StorageWriteCompute);
  return d.outputs;
}

void SkyHighCloudsPass::execute(PassContext& ctx, const Data& d) const {
  const auto& size = d.inputs.params.view.size;
  const Textures& tex = d.inputs.textures;
  const Regional& r = d.inputs.regional;
  const UniformRange params = ctx.uniform(d.inputs.params);
  const UniformRange lighting = ctx.uniform(d.inputs.lighting);
  const Atmosphere& atm = d.inputs.atmosphere;
  // Each variant's shader declares exactly these: the common ones, the cloud textures of its
  // cover mode and, for the physical sky, the atmosphere LUTs (the moon's when it shines).
  std::vector<Binding> bindings = {
      Binding::of(SKY_HIGH_CLOUDS_BINDING_PARAMS, params),
      Binding::of(SKY_HIGH_CLOUDS_BINDING_LIGHTING, lighting),
      Binding::of(SKY_HIGH_CLOUDS_BINDING_SKY, d.outputs.sky),
      Binding::of(SKY_HIGH_CLOUDS_BINDING_CLOUDS, d.outputs.highClouds),
      Binding::of(SKY_HIGH_CLOUDS_BINDING_NORMALS, tex.normals, tex.sampler)};
  if (d.regional()) {
    bindings.push_back(
        Binding::of(SKY_HIGH_CLOUDS_BINDING_REGIONAL_COVER, r.cover, r.coverSampler));
    bindings.push_back(Binding::of(SKY_HIGH_CLOUDS_BINDING_RANK_SHAPE, r.rankShape, tex.sampler));
    bindings.push_back(
        Binding::of(SKY_HIGH_CLOUDS_BINDING_COVER_COARSE, r.coverCoarse, tex.sampler));
  } else {
    bindings.push_back(
        Binding::of(SKY_HIGH_CLOUDS_BINDING_COEFFICIENTS, tex.coefficients, tex.sampler));
    bindings.push_back(Binding::of(SKY_HIGH_CLOUDS_BINDING_LEVELS, tex.levels, tex.sampler));
    bindings.push_back(Binding::of(SKY_HIGH_CLOUDS_BINDING_COARSE, tex.coarse, tex.sampler));
  }
  if (d.inputs.physical) {
    bindings.push_back(Binding::of(SKY_HIGH_CLOUDS_BINDING_ATMOSPHERE, ctx.uniform(atm.params)));
    bindings.push_back(
        Binding::of(SKY_HIGH_CLOUDS_BINDING_TRANSMITTANCE, atm.transmittance, atm.sampler));
    bindings.push_back(
        Binding::of(SKY_HIGH_CLOUDS_BINDING_SKY_VIEW_SUN, atm.skyViewSun, atm.sampler));
    if (d.moon)
      bindings.push_back(
          Binding::of(SKY_HIGH_CLOUDS_BINDING_SKY_VIEW_MOON, atm.skyViewMoon, atm.sampler));
  }
  ctx.dispatch(*d.pipeline, bindings, d.pipeline->groupsX(size.x), d.pipeline->groupsY(size.y));
}

}  // namespace sky
