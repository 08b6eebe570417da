#include "passes/atmosphere_composite/atmosphere_composite.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "engine/core/error.h"
#include "engine/lighting/light_model.h"
#include "engine/shader/shader_compiler.h"

namespace sky {
namespace {

glm::vec4 v4(const glm::dvec3& v, double w = 0.0) {
  return glm::vec4(glm::vec3(v), static_cast<float>(w));
}

// The world direction through `pixel`: viewDirection() of shaders/common/view.glsl on the
// CPU, for planning the bands.
glm::dvec3 viewDirection(const shared::ViewState& view, glm::dvec2 pixel) {
  constexpr double kPi = 3.14159265358979323846;
  const glm::dvec2 uv = pixel / glm::dvec2(view.size.x, view.size.y);
  const glm::dvec3 forward(view.forward), right(view.right), up(view.up);
  if (view.size.z == VIEW_PROJECTION_TOPDOWN) return glm::dvec3(0.0, 0.0, -1.0);
  if (view.size.z == VIEW_PROJECTION_EQUIRECTANGULAR) {
    const double azimuth = (uv.x - 0.5) * 2.0 * kPi, elevation = (0.5 - uv.y) * kPi;
    const glm::dvec3 horizontal = std::cos(azimuth) * forward + std::sin(azimuth) * right;
    return std::cos(elevation) * horizontal + std::sin(elevation) * up;
  }
  const glm::dvec2 ndc = uv * 2.0 - 1.0;
  return glm::normalize(forward + ndc.x * double(view.right.w) * right -
                        ndc.y * double(view.up.w) * up);
}

}  // namespace

std::vector<ShaderDefine> compositeVariantDefines(const CompositeVariant& v) {
  auto flag = [](const char* name, bool on) { return ShaderDefine{name, on ? "1" : "0"}; };
  return {flag("ATMOSPHERE_COMPOSITE_PHYSICAL", v.sky == CompositeSky::Physical),
          flag("ATMOSPHERE_COMPOSITE_CLOUDS", v.clouds),
          flag("ATMOSPHERE_COMPOSITE_STARS", v.stars),
          flag("ATMOSPHERE_COMPOSITE_SUN_DISC", v.sunDisc),
          flag("ATMOSPHERE_COMPOSITE_MOON_DISC", v.moonDisc),
          flag("ATMOSPHERE_COMPOSITE_GROUND", v.ground),
          flag("ATMOSPHERE_COMPOSITE_CLOUD_AIR", v.cloudAir),
          flag("ATMOSPHERE_COMPOSITE_HOST", v.host),
          flag("ATMOSPHERE_COMPOSITE_HOST_DEPTH", v.hostDepth),
          {"ATMOSPHERE_COMPOSITE_HOST_FORMAT",
           v.hostFormat == HostColourFormat::Rgba32f ? "rgba32f" : "rgba16f"},
          flag("ATMOSPHERE_COMPOSITE_PERCEPTION", v.perception)};
}

shared::AtmosphereCompositeParams atmosphereCompositeParams(const AtmosphereCompositeSettings& s,
                                                            const LightingState& lighting,
                                                            const shared::ViewState& view) {
  shared::AtmosphereCompositeParams p{};
  p.view = view;
  p.aboveHighClouds = s.aboveHighClouds ? 1u : 0u;
  p.observer = s.observer ? 1u : 0u;
  p.highCloudsAltitudeM = static_cast<float>(s.highCloudsAltitudeM);
  // The camera may not sit below the ground sphere (sky_high_clouds places it the same way).
  p.planetRadiusM = static_cast<float>(s.planetRadiusM);
  p.cameraRadiusM = static_cast<float>(s.planetRadiusM + std::max(s.cameraAltitudeM, 1.0));
  p.overcast = static_cast<float>(lighting.overcast);
  // Below the clouds the air, like the ground, gets the share of the clear sky's light that
  // Kasten & Czeplak give for the overcast, where the sky models know only the clear sky:
  // broken cumulus barely dim it, a full overcast takes three quarters.
  p.airLight =
      static_cast<float>(s.belowClouds ? light::overcastGlobalShare(lighting.overcast) : 1.0);
  p.groundAlbedo = glm::vec4(s.ground.albedo, 0.0f);
  // The kozlov ground's sunlight and moonlight: the lighting model's air down to sea level.
  const glm::vec3 sunSpace(lighting.gpu.sunSpace), moonSpace(lighting.gpu.moonSpace);
  p.sunAtGround =
      glm::vec4(light::illuminanceAtAltitude(sunSpace, lighting.sun.elevationDeg,
                                             lighting.sun.angularRadiusDeg, 0.0, s.turbidity),
                0.0f);
  p.moonAtGround =
      glm::vec4(light::illuminanceAtAltitude(moonSpace, lighting.moon.elevationDeg,
                                             lighting.moon.angularRadiusDeg, 0.0, s.turbidity),
                0.0f);
  const light::HazeMedium haze = light::hazeMedium(s.turbidity);
  p.hazeRayleigh = v4(haze.rayleighPerM, haze.rayleighHeightM);
  p.hazeAerosol = v4(haze.aerosolPerM, haze.aerosolHeightM);
  p.shadow.valid = 0.0f;
  p.shadow.lightIsSun = 1.0f;
  p.shadow.radiusM = 1.0f;
  return p;
}

bool discReachesView(const shared::ViewState& view, const glm::vec3& direction, float radius) {
  if (view.size.z != VIEW_PROJECTION_PERSPECTIVE) return true;  // the whole sphere, or no sky
  // The widest angle a pixel centre lies from the view axis (the image's corner), and the
  // reach of discCoverage past a disc's centre: its spread max(radius, pixel) plus half a
  // pixel, with a whole pixel (the largest, at the centre: forward.w) and a margin for
  // rounding.
  const double corner = std::atan(std::hypot(double(view.right.w), double(view.up.w)));
  const double pixel = view.forward.w;
  const double reach = std::max(double(radius), pixel) + pixel + 1e-3;
  const double fromAxis = std::acos(
      std::clamp(double(glm::dot(glm::normalize(direction), glm::vec3(view.forward))), -1.0, 1.0));
  return fromAxis <= corner + reach;
}

std::vector<CompositeBand> compositeBands(const shared::AtmosphereCompositeParams& params,
                                          bool clouds, bool cloudsAboveHorizon, uint32_t bandRows) {
  const shared::ViewState& view = params.view;
  const uint32_t width = view.size.x, height = view.size.y;
  std::vector<CompositeBand> bands;
  if (height == 0 || bandRows == 0) return bands;
  if (params.observer == 0u) {
    // No ground and no aerial perspective anywhere (the shader's params.observer).
    bands.push_back({0, height, false, false});
    return bands;
  }
  // The horizon's cosine of zenith, as the shader takes it.
  const double planetR = params.planetRadiusM, cameraR = params.cameraRadiusM;
  const double h = cameraR - planetR;
  const double horizonZ = -std::sqrt(std::max(h * (2.0 * planetR + h), 0.0)) / cameraR;
  // Wider than any pixel's reach: the shader's ground blends over half a pixel at the
  // horizon, and the reduced-resolution clouds' filters reach a pixel or two of the source
  // (two of the view's) across it. The largest pixel of a pinhole is the centre's
  // (forward.w); of an equirectangular image, a row's (pi / height).
  const double pixel = view.size.z == VIEW_PROJECTION_EQUIRECTANGULAR
                           ? 3.14159265358979323846 / height
                           : double(view.forward.w);
  const double margin = 8.0 * pixel;
  // Each band's lowest and highest view direction, from its top and bottom pixel edges
  // every few pixels across and at both ends: a straight line of the image is an arc of a
  // great circle, along which z is smooth, and the margin covers what lies between samples.
  const uint32_t stepX = std::max(1u, std::min(8u, width / 8u));
  for (uint32_t first = 0; first < height; first += bandRows) {
    const uint32_t rows = std::min(bandRows, height - first);
    double zMin = 1.0, zMax = -1.0;
    for (double y : {double(first), double(first + rows)})
      for (uint32_t x = 0;; x = std::min(x + stepX, width)) {
        const double z = viewDirection(view, glm::dvec2(x, y)).z;
        zMin = std::min(zMin, z);
        zMax = std::max(zMax, z);
        if (x == width) break;
      }
    CompositeBand b{first, rows, zMin < horizonZ + margin,
                    clouds && (!cloudsAboveHorizon || zMax > horizonZ - margin)};
    if (!bands.empty() && bands.back().ground == b.ground && bands.back().cloudAir == b.cloudAir)
      bands.back().rows += rows;
    else
      bands.push_back(b);
  }
  return bands;
}

AtmosphereCompositePass::AtmosphereCompositePass(const Context& ctx, ShaderCompiler& compiler)
    : mVariants(ctx, compiler, "atmosphere_composite.comp", kName) {}

AtmosphereCompositePass::Outputs AtmosphereCompositePass::setup(GraphBuilder& b, const Inputs& in,
                                                                Data& d) {
  d.inputs = in;
  d.inputs.params.clouds = in.clouds ? 1u : 0u;
  const shared::LightingState& L = in.lighting;
  CompositeVariant frame;
  frame.sky = in.atmosphere ? CompositeSky::Physical : CompositeSky::Kozlov;
  frame.clouds = in.clouds.has_value();
  frame.stars = in.starFlux.has_value();
  frame.sunDisc = discReachesView(in.params.view, glm::vec3(L.sun.direction), L.sun.direction.w);
  frame.moonDisc =
      discReachesView(in.params.view, glm::vec3(L.moon.direction), L.moon.direction.w);
  frame.perception = in.perception.has_value();
  if (in.host) {
    frame.host = true;
    frame.hostDepth = in.host->depth.has_value();
    if (in.host->colourFormat == VK_FORMAT_R32G32B32A32_SFLOAT)
      frame.hostFormat = HostColourFormat::Rgba32f;
    else if (in.host->colourFormat != VK_FORMAT_R16G16B16A16_SFLOAT)
      internalError("atmosphere_composite: a host colour format other than rgba16f or rgba32f");
    if (in.host->depth && !in.host->depthSampler)
      internalError("atmosphere_composite: no host depth sampler");
    d.inputs.params.host = in.host->depthMapping;
    d.inputs.params.host.present = in.host->depth ? 1u : 0u;
  }
  d.bands.clear();
  for (const CompositeBand& band :
       compositeBands(d.inputs.params, in.clouds.has_value(), in.clouds && in.clouds->belowBase,
                      ATMOSPHERE_COMPOSITE_GROUP_Y)) {
    CompositeVariant v = frame;
    v.ground = band.ground;
    v.cloudAir = band.cloudAir;
    d.bands.emplace_back(band, &mVariants.get(compositeVariantDefines(v)));
  }
  if (in.starFlux) b.read(*in.starFlux, Access::StorageReadCompute);
  b.read(in.sky, Access::StorageReadCompute);
  b.read(in.highClouds, Access::StorageReadCompute);
  if (in.clouds) {
    if (!in.clouds->shadowSampler) internalError("atmosphere_composite: no shadow sampler");
    b.read(in.clouds->clouds, Access::StorageReadCompute);
    b.read(in.clouds->depth, Access::StorageReadCompute);
    b.read(in.clouds->shadow, Access::SampledCompute);
    d.inputs.params.shadow = in.clouds->shadowMap;
  }
  if (in.atmosphere) {
    if (!in.atmosphere->sampler) internalError("atmosphere_composite: no LUT sampler");
    b.read(in.atmosphere->transmittance, Access::SampledCompute);
    b.read(in.atmosphere->aerialPerspective, Access::SampledCompute);
  }
  ImageDesc desc;
  // 32-bit: physical radiance, from the sun's disc to a moonless night's 1e-8.
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.width = in.params.view.size.x;
  desc.height = in.params.view.size.y;
  desc.name = "beauty";
  desc.about = "the frame: sky, clouds and ground through the atmosphere (scene-linear)";
  d.outputs.beauty = b.write(b.create(desc), Access::StorageWriteCompute);
  d.outputs.host = {};
  d.outputs.perception = {};
  if (in.perception) {
    if (in.clouds.has_value() != in.perception->cloudHit.has_value())
      internalError("atmosphere_composite: the perception layers need the clouds' hits with clouds");
    if (in.perception->cloudHit) b.read(*in.perception->cloudHit, Access::StorageReadCompute);
    ImageDesc p = desc;
    p.name = "perception";
    p.about =
        "the perception layers: R label (0 sky, 1 ground, 2 low, 3 mid, 4 high cloud, 5 sun, 6 "
        "moon), G cloud type, B the air's transmittance to what the ray meets, A the ground's "
        "cloud shadow";
    p.view = DebugView::Heat;  // the label: a small count of classes in false colour
    p.channels = "label,cloud_type,air_transmittance,cloud_shadow";
    d.outputs.perception = b.write(b.create(p), Access::StorageWriteCompute);
  }
  if (in.host) {
    if (in.host->depth) b.read(*in.host->depth, Access::SampledCompute);
    d.outputs.host = b.write(in.host->colour, Access::StorageReadWriteCompute);
    b.sideEffect();  // the host reads it, after the frame
  }
  return d.outputs;
}

void AtmosphereCompositePass::execute(PassContext& ctx, const Data& d) const {
  const auto& size = d.inputs.params.view.size;
  // Each variant's shader declares exactly these: the common ones, the stars', the clouds'
  // and, for the physical sky, the atmosphere's.
  std::vector<Binding> bindings = {
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_BEAUTY, d.outputs.beauty),
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_SKY, d.inputs.sky),
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_HIGH_CLOUDS, d.inputs.highClouds),
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_LIGHTING, ctx.uniform(d.inputs.lighting))};
  if (d.inputs.starFlux)
    bindings.push_back(Binding::of(ATMOSPHERE_COMPOSITE_BINDING_STARS, *d.inputs.starFlux));
  if (const auto& c = d.inputs.clouds) {
    bindings.push_back(Binding::of(ATMOSPHERE_COMPOSITE_BINDING_CLOUDS, c->clouds));
    bindings.push_back(Binding::of(ATMOSPHERE_COMPOSITE_BINDING_CLOUD_DEPTH, c->depth));
    bindings.push_back(
        Binding::of(ATMOSPHERE_COMPOSITE_BINDING_CLOUD_SHADOW, c->shadow, c->shadowSampler));
  }
  if (const auto& a = d.inputs.atmosphere) {
    bindings.push_back(
        Binding::of(ATMOSPHERE_COMPOSITE_BINDING_ATMOSPHERE, ctx.uniform(a->params)));
    bindings.push_back(
        Binding::of(ATMOSPHERE_COMPOSITE_BINDING_TRANSMITTANCE, a->transmittance, a->sampler));
    bindings.push_back(Binding::of(ATMOSPHERE_COMPOSITE_BINDING_AERIAL_PERSPECTIVE,
                                   a->aerialPerspective, a->sampler));
  }
  if (const auto& h = d.inputs.host) {
    bindings.push_back(Binding::of(ATMOSPHERE_COMPOSITE_BINDING_HOST_COLOUR, d.outputs.host));
    if (h->depth)
      bindings.push_back(
          Binding::of(ATMOSPHERE_COMPOSITE_BINDING_HOST_DEPTH, *h->depth, h->depthSampler));
  }
  if (const auto& p = d.inputs.perception) {
    if (p->cloudHit)
      bindings.push_back(Binding::of(ATMOSPHERE_COMPOSITE_BINDING_CLOUD_HIT, *p->cloudHit));
    bindings.push_back(Binding::of(ATMOSPHERE_COMPOSITE_BINDING_PERCEPTION, d.outputs.perception));
  }
  for (const auto& [band, pipeline] : d.bands) {
    const shared::AtmosphereCompositeBand rows{glm::uvec4(band.firstRow, band.rows, 0u, 0u)};
    ctx.dispatch(*pipeline, bindings, pipeline->groupsX(size.x), pipeline->groupsY(band.rows), 1,
                 &rows, sizeof rows);
  }
}

}  // namespace sky
