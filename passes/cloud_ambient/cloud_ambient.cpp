#include "passes/cloud_ambient/cloud_ambient.h"

#include <algorithm>

#include "engine/core/error.h"
#include "engine/lighting/light_model.h"

namespace sky {

shared::CloudAmbientParams cloudAmbientParams(const CloudAmbientSettings& s) {
  shared::CloudAmbientParams p{};
  p.groundAlbedo = glm::vec4(s.groundAlbedo, 0.0f);
  // The air between the ground and the clouds' base, straight up (the shader takes it along
  // each slant path below the horizon).
  const glm::dvec3 toBase =
      light::atmosphereTransmittance(90.0, 0.0, s.turbidity) /
      light::atmosphereTransmittance(90.0, std::max(s.cloudBaseM, 0.0), s.turbidity);
  p.airDepth = glm::vec4(glm::vec3(-glm::log(glm::max(toBase, glm::dvec3(1e-30)))), 0.0f);
  p.groundLight = static_cast<float>(light::overcastGlobalShare(std::clamp(s.overcast, 0.0, 1.0)));
  p.skyOcclusion = static_cast<float>(CLOUD_AMBIENT_OCCLUSION_PER_COVER * std::clamp(s.overcast, 0.0, 1.0));
  p.phaseG = static_cast<float>(s.phaseG);
  p.phaseGBack = static_cast<float>(s.phaseGBack);
  p.phaseBackWeight = static_cast<float>(s.phaseBackWeight);
  return p;
}

CloudAmbientPass::CloudAmbientPass(const Context& ctx, ShaderCompiler& compiler)
    : mVariants(ctx, compiler, "cloud_ambient.comp", kName) {}

CloudAmbientPass::Outputs CloudAmbientPass::setup(GraphBuilder& b, const Inputs& in, Data& d) {
  d.inputs = in;
  const bool physical = in.atmosphere.has_value();
  d.pipeline = &mVariants.get(
      {{"SKY_PHYSICAL_SKY", physical ? "1" : "0"}, {"LIGHTING_MOON", in.moon ? "1" : "0"}});
  if (physical) {
    const Atmosphere& a = *in.atmosphere;
    if (!a.sampler) internalError("cloud_ambient: no LUT sampler");
    b.read(a.transmittance, Access::SampledCompute);
    b.read(a.skyViewSun, Access::SampledCompute);
    if (in.moon) b.read(a.skyViewMoon, Access::SampledCompute);
  }
  ImageDesc desc;
  desc.width = CLOUD_AMBIENT_MAP_WIDTH;
  desc.height = CLOUD_AMBIENT_IMAGE_HEIGHT;
  // 32-bit: a moonlit night's sky is 1e-7 in renderer units, below half float's normal range.
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.name = "cloud_ambient";
  desc.about =
      "the clouds' ambient light from the frame's sky: the sky's light on a surface by its "
      "normal (azimuth across from east, elevation up from the nadir; below the horizon the "
      "ground through the air), the ground's own radiance in the next row's first texel, then "
      "the sky scattered once toward each view direction less an isotropic phase's share (same "
      "grid)";
  d.outputs.ambient = b.write(b.create(desc), Access::StorageWriteCompute);
  return d.outputs;
}

void CloudAmbientPass::execute(PassContext& ctx, const Data& d) const {
  std::vector<Binding> bindings = {
      Binding::of(CLOUD_AMBIENT_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
      Binding::of(CLOUD_AMBIENT_BINDING_LIGHTING, ctx.uniform(d.inputs.lighting)),
      Binding::of(CLOUD_AMBIENT_BINDING_OUT, d.outputs.ambient)};
  if (d.inputs.atmosphere) {
    const Atmosphere& a = *d.inputs.atmosphere;
    bindings.push_back(Binding::of(CLOUD_AMBIENT_BINDING_ATMOSPHERE, ctx.uniform(a.params)));
    bindings.push_back(
        Binding::of(CLOUD_AMBIENT_BINDING_TRANSMITTANCE, a.transmittance, a.sampler));
    bindings.push_back(Binding::of(CLOUD_AMBIENT_BINDING_SKY_VIEW_SUN, a.skyViewSun, a.sampler));
    if (d.inputs.moon)
      bindings.push_back(
          Binding::of(CLOUD_AMBIENT_BINDING_SKY_VIEW_MOON, a.skyViewMoon, a.sampler));
  }
  ctx.dispatch(*d.pipeline, bindings, 1, 1);
}

}  // namespace sky
