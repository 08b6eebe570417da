#include "passes/atmosphere_composite/atmosphere_composite.h"

#include <algorithm>

#include "engine/core/error.h"
#include "engine/lighting/light_model.h"
#include "engine/shader/shader_compiler.h"

namespace sky {
namespace {

ComputePipeline buildPipeline(const Context& ctx, ShaderCompiler& compiler, bool physical,
                              bool clouds) {
  CompiledShader shader = compileForDevice(ctx, compiler, "atmosphere_composite.comp",
                                           {{"ATMOSPHERE_COMPOSITE_PHYSICAL", physical ? "1" : "0"},
                                            {"ATMOSPHERE_COMPOSITE_CLOUDS", clouds ? "1" : "0"}});
  return ComputePipeline(ctx, AtmosphereCompositePass::kName, shader.spirv, shader.reflection);
}

glm::vec4 v4(const glm::dvec3& v, double w = 0.0) {
  return glm::vec4(glm::vec3(v), static_cast<float>(w));
}

}  // namespace

shared::AtmosphereCompositeParams atmosphereCompositeParams(const AtmosphereCompositeSettings& s,
                                                            const LightingState& lighting,
                                                            const shared::ViewState& view) {
  shared::AtmosphereCompositeParams p{};
  p.view = view;
  p.aboveHighClouds = s.aboveHighClouds ? 1u : 0u;
  p.observer = s.observer ? 1u : 0u;
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

AtmosphereCompositePass::AtmosphereCompositePass(const Context& ctx, ShaderCompiler& compiler)
    : mKozlov(buildPipeline(ctx, compiler, false, false)),
      mPhysical(buildPipeline(ctx, compiler, true, false)),
      mKozlovClouds(buildPipeline(ctx, compiler, false, true)),
      mPhysicalClouds(buildPipeline(ctx, compiler, true, true)) {}

const ComputePipeline& AtmosphereCompositePass::pipeline() const {
  const bool clouds = mInputs.clouds.has_value();
  if (mInputs.atmosphere) return clouds ? mPhysicalClouds : mPhysical;
  return clouds ? mKozlovClouds : mKozlov;
}

AtmosphereCompositePass::Outputs AtmosphereCompositePass::setup(GraphBuilder& b, const Inputs& in) {
  mInputs = in;
  mInputs.params.clouds = in.clouds ? 1u : 0u;
  b.read(in.starFlux, Access::StorageReadCompute);
  b.read(in.sky, Access::StorageReadCompute);
  b.read(in.highClouds, Access::StorageReadCompute);
  if (in.clouds) {
    if (!in.clouds->shadowSampler) internalError("atmosphere_composite: no shadow sampler");
    b.read(in.clouds->clouds, Access::StorageReadCompute);
    b.read(in.clouds->depth, Access::StorageReadCompute);
    b.read(in.clouds->shadow, Access::SampledCompute);
    mInputs.params.shadow = in.clouds->shadowMap;
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
  mOutputs.beauty = b.write(b.create(desc), Access::StorageWriteCompute);
  return mOutputs;
}

void AtmosphereCompositePass::execute(PassContext& ctx) const {
  const auto& size = mInputs.params.view.size;
  // Each variant's shader declares exactly these: the common ones, the clouds' and, for the
  // physical sky, the atmosphere's.
  std::vector<Binding> bindings = {
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_PARAMS, ctx.uniform(mInputs.params)),
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_BEAUTY, mOutputs.beauty),
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_SKY, mInputs.sky),
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_HIGH_CLOUDS, mInputs.highClouds),
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_LIGHTING, ctx.uniform(mInputs.lighting)),
      Binding::of(ATMOSPHERE_COMPOSITE_BINDING_STARS, mInputs.starFlux)};
  if (const auto& c = mInputs.clouds) {
    bindings.push_back(Binding::of(ATMOSPHERE_COMPOSITE_BINDING_CLOUDS, c->clouds));
    bindings.push_back(Binding::of(ATMOSPHERE_COMPOSITE_BINDING_CLOUD_DEPTH, c->depth));
    bindings.push_back(
        Binding::of(ATMOSPHERE_COMPOSITE_BINDING_CLOUD_SHADOW, c->shadow, c->shadowSampler));
  }
  if (const auto& a = mInputs.atmosphere) {
    bindings.push_back(
        Binding::of(ATMOSPHERE_COMPOSITE_BINDING_ATMOSPHERE, ctx.uniform(a->params)));
    bindings.push_back(
        Binding::of(ATMOSPHERE_COMPOSITE_BINDING_TRANSMITTANCE, a->transmittance, a->sampler));
    bindings.push_back(Binding::of(ATMOSPHERE_COMPOSITE_BINDING_AERIAL_PERSPECTIVE,
                                   a->aerialPerspective, a->sampler));
  }
  const ComputePipeline& p = pipeline();
  ctx.dispatch(p, bindings, p.groupsX(size.x), p.groupsY(size.y));
}

}  // namespace sky
