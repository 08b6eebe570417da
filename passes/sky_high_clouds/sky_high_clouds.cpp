#include "passes/sky_high_clouds/sky_high_clouds.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/gpu/sampler.h"
#include "engine/lighting/light_model.h"
#include "engine/shader/shader_compiler.h"

namespace sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kEarthRadiusM = 6371000.0;  // for the kozlov model, which has no planet

ComputePipeline buildPipeline(const Context& ctx, ShaderCompiler& compiler, bool physical) {
  CompiledShader shader =
      compiler.compile("sky_high_clouds.comp", {{"SKY_PHYSICAL_SKY", physical ? "1" : "0"}});
  return ComputePipeline(ctx, SkyHighCloudsPass::kName, shader.spirv, shader.reflection);
}

}  // namespace

glm::vec3 illuminanceAtAltitude(const glm::vec3& aboveAtmosphere, double elevationDeg,
                                double radiusDeg, double altitudeM, double turbidity) {
  const double h = std::max(altitudeM, 0.0);
  const double dipDeg = std::acos(kEarthRadiusM / (kEarthRadiusM + h)) / kDeg;
  const double visible = light::discAboveHorizon(elevationDeg + dipDeg, radiusDeg);
  if (visible <= 0.0) return glm::vec3(0.0f);
  glm::dvec3 t;
  if (elevationDeg >= 0.0) {
    t = light::atmosphereTransmittance(elevationDeg, h, turbidity);
  } else {
    // Below the point's horizontal the ray dips to a tangent height ht before climbing out:
    // roughly a horizontal path out from ht, plus the descent from h to ht (the horizontal
    // path from ht less the one from h). Equal to the path from h at elevation 0.
    const double c = std::cos(std::min(-elevationDeg, dipDeg) * kDeg);
    const double ht = (kEarthRadiusM + h) * c - kEarthRadiusM;
    const glm::dvec3 fromTangent = light::atmosphereTransmittance(0.0, ht, turbidity);
    const glm::dvec3 fromPoint = light::atmosphereTransmittance(0.0, h, turbidity);
    t = fromTangent * fromTangent / fromPoint;
  }
  return glm::vec3(glm::dvec3(aboveAtmosphere) * t * visible);
}

shared::SkyHighCloudsParams skyHighCloudsParams(const Scene& scene, const LightingState& lighting,
                                                const IsoTime& time, const shared::ViewState& view,
                                                bool cloudsPresent, uint32_t textureSize,
                                                uint32_t coarseSize,
                                                const glm::vec4& meanCoefficients) {
  const HighCloudSettings& hc = scene.highClouds;
  const bool physical = scene.sky.model == "physical";
  const double planetR = physical ? scene.atmosphere.groundRadiusKm * 1000.0 : kEarthRadiusM;
  shared::SkyHighCloudsParams p{};
  p.view = view;
  // Altitudes are above sea level; the camera may not sit below the ground sphere.
  p.layer = glm::vec4(static_cast<float>(planetR),
                      static_cast<float>(planetR + std::max(scene.camera.altitudeM, 1.0)),
                      static_cast<float>(planetR + hc.altitudeM), cloudsPresent ? 1.0f : 0.0f);

  // The wind blows from `windFrom`: the clouds drift toward windFrom + 180 degrees. The drift
  // is measured from the start of the scene's time so a time-lapse moves smoothly; the texture
  // moves against it (a cloud at ground point x now was at x - drift at the start).
  const double elapsed = time.secondsSince(scene.time.start);
  const double toward = (hc.windFrom + 180.0) * kDeg;
  const double tileM = hc.tileSizeKm * 1000.0;
  double driftEast = hc.windSpeedMs * elapsed * std::sin(toward);
  double driftNorth = hc.windSpeedMs * elapsed * std::cos(toward);
  // Wrapped to one tile: the texture repeats, and floats keep their precision.
  driftEast = std::fmod(driftEast, tileM);
  driftNorth = std::fmod(driftNorth, tileM);
  p.texture = glm::vec4(static_cast<float>(-driftEast), static_cast<float>(-driftNorth),
                        static_cast<float>(tileM), static_cast<float>(textureSize));
  p.shading =
      glm::vec4(static_cast<float>(hc.brightness), static_cast<float>(hc.edgeGlowDeg * kDeg),
                static_cast<float>(coarseSize), 0.0f);
  p.meanCoefficients = meanCoefficients;

  const double turbidity = scene.lighting.turbidity;
  p.sunAtLayer =
      glm::vec4(illuminanceAtAltitude(glm::vec3(lighting.gpu.sunSpace), lighting.sun.elevationDeg,
                                      lighting.sun.angularRadiusDeg, hc.altitudeM, turbidity),
                0.0f);
  p.moonAtLayer =
      glm::vec4(illuminanceAtAltitude(glm::vec3(lighting.gpu.moonSpace), lighting.moon.elevationDeg,
                                      lighting.moon.angularRadiusDeg, hc.altitudeM, turbidity),
                0.0f);
  return p;
}

SkyHighCloudsPass::SkyHighCloudsPass(const Context& ctx, ShaderCompiler& compiler)
    : mKozlov(buildPipeline(ctx, compiler, false)), mPhysical(buildPipeline(ctx, compiler, true)) {}

SkyHighCloudsPass::Outputs SkyHighCloudsPass::setup(GraphBuilder& b, const Inputs& in) {
  if (!in.textures.sampler) internalError("sky_high_clouds: no texture sampler");
  if (in.physical && !in.atmosphere.sampler) internalError("sky_high_clouds: no LUT sampler");
  mInputs = in;
  b.read(in.textures.coefficients, Access::SampledCompute);
  b.read(in.textures.normals, Access::SampledCompute);
  b.read(in.textures.coarse, Access::SampledCompute);
  if (in.physical) {
    b.read(in.atmosphere.transmittance, Access::SampledCompute);
    b.read(in.atmosphere.skyViewSun, Access::SampledCompute);
    b.read(in.atmosphere.skyViewMoon, Access::SampledCompute);
  }
  ImageDesc desc;
  desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  desc.width = in.params.view.size.x;
  desc.height = in.params.view.size.y;
  desc.name = "sky";
  mOutputs.sky = b.write(b.create(desc), Access::StorageWriteCompute);
  desc.name = "high_clouds";
  mOutputs.highClouds = b.write(b.create(desc), Access::StorageWriteCompute);
  return mOutputs;
}

void SkyHighCloudsPass::execute(PassContext& ctx) const {
  const auto& size = mInputs.params.view.size;
  const Textures& tex = mInputs.textures;
  const UniformRange params = ctx.uniform(mInputs.params);
  const UniformRange lighting = ctx.uniform(mInputs.lighting);
  if (!mInputs.physical) {
    ctx.dispatch(mKozlov,
                 {Binding::of(SKY_HIGH_CLOUDS_BINDING_PARAMS, params),
                  Binding::of(SKY_HIGH_CLOUDS_BINDING_LIGHTING, lighting),
                  Binding::of(SKY_HIGH_CLOUDS_BINDING_SKY, mOutputs.sky),
                  Binding::of(SKY_HIGH_CLOUDS_BINDING_CLOUDS, mOutputs.highClouds),
                  Binding::of(SKY_HIGH_CLOUDS_BINDING_COEFFICIENTS, tex.coefficients, tex.sampler),
                  Binding::of(SKY_HIGH_CLOUDS_BINDING_NORMALS, tex.normals, tex.sampler),
                  Binding::of(SKY_HIGH_CLOUDS_BINDING_COARSE, tex.coarse, tex.sampler)},
                 mKozlov.groupsX(size.x), mKozlov.groupsY(size.y));
    return;
  }
  const Atmosphere& atm = mInputs.atmosphere;
  ctx.dispatch(mPhysical,
               {Binding::of(SKY_HIGH_CLOUDS_BINDING_PARAMS, params),
                Binding::of(SKY_HIGH_CLOUDS_BINDING_LIGHTING, lighting),
                Binding::of(SKY_HIGH_CLOUDS_BINDING_SKY, mOutputs.sky),
                Binding::of(SKY_HIGH_CLOUDS_BINDING_CLOUDS, mOutputs.highClouds),
                Binding::of(SKY_HIGH_CLOUDS_BINDING_COEFFICIENTS, tex.coefficients, tex.sampler),
                Binding::of(SKY_HIGH_CLOUDS_BINDING_NORMALS, tex.normals, tex.sampler),
                Binding::of(SKY_HIGH_CLOUDS_BINDING_COARSE, tex.coarse, tex.sampler),
                Binding::of(SKY_HIGH_CLOUDS_BINDING_ATMOSPHERE, ctx.uniform(atm.params)),
                Binding::of(SKY_HIGH_CLOUDS_BINDING_TRANSMITTANCE, atm.transmittance, atm.sampler),
                Binding::of(SKY_HIGH_CLOUDS_BINDING_SKY_VIEW_SUN, atm.skyViewSun, atm.sampler),
                Binding::of(SKY_HIGH_CLOUDS_BINDING_SKY_VIEW_MOON, atm.skyViewMoon, atm.sampler)},
               mPhysical.groupsX(size.x), mPhysical.groupsY(size.y));
}

}  // namespace sky
