#include "passes/cloud_field/cloud_field.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "engine/clouds/cloud_math.h"
#include "engine/core/error.h"
#include "engine/gpu/sampler.h"
#include "engine/lighting/light_model.h"
#include "engine/shader/shader_compiler.h"
#include "engine/weather/geo.h"
#include "shaders/common/cloud_light_march_shared.h"

namespace sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// Tang's curl noise bends the detail lookup by up to this many detail repeats.
constexpr float kCurlStrength = 0.1f;
// Stratocumulus rolls are this many times longer (along the wind) than wide: the shape's
// 1.25 km cells become streets about 5 km long at the default scale (real cloud streets
// run tens of kilometres; the noise's repeat bounds them).
constexpr double kRollStretch = 4.0;
// A light is marched toward when it gives more than this share of the light at the clouds.
constexpr float kLightShare = 1e-3f;
// Top-down rays start this far above the highest layer.
constexpr double kTopDownMarginM = 500.0;
// clouds.quality reference: the longest first step and the most steps a view ray takes.
constexpr double kReferenceStepM = 10.0;
constexpr uint32_t kReferenceMaxSteps = 16384;
// The reference's light march splits each short step this many ways (its long step's parts are
// CLOUD_LIGHT_REFERENCE_LONG_PART_M long).
constexpr int kReferenceLightSplit = 4;
// The reference stops a ray only where what is left of it (below 1e-4 of the pixel) is far
// under one 8-bit code of any display: no exit to speak of, at a fraction of the cost of
// marching every opaque cloud to the far end of the shells.
constexpr float kReferenceCutoff = 1e-4f;

float luminance(const glm::vec3& c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

}  // namespace

CloudImages writeCloudImages(GraphBuilder& b, uint32_t width, uint32_t height,
                             const CloudImageNames& names) {
  ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.name = names.clouds;
  desc.about = names.cloudsAbout;
  CloudImages out;
  out.clouds = b.write(b.create(desc), Access::StorageWriteCompute);
  desc.format = VK_FORMAT_R32G32_SFLOAT;
  desc.name = names.depth;
  desc.about = names.depthAbout;
  desc.view = DebugView::Depth;
  desc.channels = "depth,shell_entry";
  out.depth = b.write(b.create(desc), Access::StorageWriteCompute);
  return out;
}

void readCloudTextures(GraphBuilder& b, const CloudTextures& t) {
  if (!t.noiseSampler || !t.weatherSampler) internalError("cloud textures: no sampler");
  for (ImageId id : {t.shape, t.detail, t.curl, t.weather, t.weatherCoarse})
    b.read(id, Access::SampledCompute);
}

std::vector<Binding> cloudTextureBindings(const CloudTextures& t) {
  return {Binding::of(VOLUMETRIC_CLOUDS_BINDING_SHAPE, t.shape, t.noiseSampler),
          Binding::of(VOLUMETRIC_CLOUDS_BINDING_DETAIL, t.detail, t.noiseSampler),
          Binding::of(VOLUMETRIC_CLOUDS_BINDING_CURL, t.curl, t.noiseSampler),
          Binding::of(VOLUMETRIC_CLOUDS_BINDING_WEATHER, t.weather, t.weatherSampler),
          Binding::of(VOLUMETRIC_CLOUDS_BINDING_WEATHER_COARSE, t.weatherCoarse, t.weatherSampler)};
}

CloudVariant cloudVariant(const VolumetricCloudsSettings& settings, bool lowRolls,
                          bool cumulus) {
  const CloudSettings& c = settings.clouds;
  CloudVariant v;
  v.frame = settings.topDown ? CloudFrame::TopDown : CloudFrame::Observer;
  v.model = c.model;
  v.phase = c.phase;
  v.integral = c.energyConserving ? CloudStepIntegral::Exact : CloudStepIntegral::Riemann;
  v.coverage = c.coverage;
  v.rolls = lowRolls ? CloudRolls::On : CloudRolls::Off;
  v.cumulus = cumulus ? CloudCumulus::On : CloudCumulus::Off;
  v.quality = c.quality;
  v.light = c.quality == CloudQuality::Reference ? CloudLight::March : c.light;
  return v;
}

std::vector<ShaderDefine> cloudVariantDefines(const CloudVariant& v) {
  const auto flag = [](bool on) { return std::string(on ? "1" : "0"); };
  return {{"CLOUD_TOPDOWN", flag(v.frame == CloudFrame::TopDown)},
          {"CLOUD_TANG", flag(v.model == CloudModel::Tang2019)},
          {"CLOUD_DUAL_LOBE", flag(v.phase == CloudPhase::DualLobe)},
          {"CLOUD_ENERGY_CONSERVING", flag(v.integral == CloudStepIntegral::Exact)},
          {"CLOUD_CALIBRATED", flag(v.coverage == CloudCoverageMode::Calibrated)},
          {"CLOUD_ROLLS", flag(v.rolls == CloudRolls::On)},
          {"CLOUD_CUMULUS", flag(v.cumulus == CloudCumulus::On)},
          {"CLOUD_REFERENCE", flag(v.quality == CloudQuality::Reference)},
          {"CLOUD_LIGHT_VOLUME", flag(v.light == CloudLight::Volume)}};
}

CloudPipelines::CloudPipelines(const Context& ctx, ShaderCompiler& compiler, const char* file,
                               const char* name)
    : mVariants(ctx, compiler, file, name) {}

const ComputePipeline& CloudPipelines::get(const CloudVariant& variant,
                                           const std::vector<ShaderDefine>& extra) {
  std::vector<ShaderDefine> defines = cloudVariantDefines(variant);
  defines.insert(defines.end(), extra.begin(), extra.end());
  return mVariants.get(defines);
}

bool cloudFieldReusable(const CloudFieldKey& m, const CloudFieldKey& k, double maxShiftM) {
  // The lights may turn this far (degrees), and the camera move this far (m).
  constexpr double kMaxLightTurnDeg = 0.05, kMaxCameraMoveM = 50.0;
  if (k.settings != m.settings || k.mapRevision != m.mapRevision || k.lights != m.lights)
    return false;
  if (glm::length(k.drift - m.drift) > maxShiftM) return false;
  auto turned = [](const glm::vec3& a, const glm::vec3& b) {
    return std::acos(std::clamp(static_cast<double>(glm::dot(a, b)), -1.0, 1.0)) / kDeg;
  };
  if (((k.lights & 1u) && turned(k.sun, m.sun) > kMaxLightTurnDeg) ||
      ((k.lights & 2u) && turned(k.moon, m.moon) > kMaxLightTurnDeg))
    return false;
  const double kMPerDeg = 111195.0;  // on the mean sphere
  const glm::dvec3 d = k.camera - m.camera;
  const double east = d.y * kMPerDeg * std::cos(k.camera.x * kDeg);
  return std::hypot(d.x * kMPerDeg, east, d.z) <= kMaxCameraMoveM;
}

glm::dvec2 cloudWindDriftM(const CloudSettings& c, double elapsedS) {
  const double toward = (c.windFrom + 180.0) * kDeg;
  return c.windSpeedMs * elapsedS * glm::dvec2(std::sin(toward), std::cos(toward));
}

CloudFrameGeometry cloudFrameGeometry(const VolumetricCloudsSettings& s) {
  if (s.topDown) {
    const WeatherRegion& r = s.region;
    const double top = std::max(s.clouds.low.topM, s.clouds.mid.topM);
    return {0.5 * (r.lat[0] + r.lat[1]), 0.5 * (r.lon[0] + r.lon[1]), top + kTopDownMarginM, true};
  }
  return {s.cameraLatDeg, s.cameraLonDeg, s.cameraAltitudeM, false};
}

shared::CloudParams cloudParams(const VolumetricCloudsSettings& settings,
                                const LightingState& lighting, const IsoTime& time,
                                const shared::ViewState& view, const glm::vec2& maxCover,
                                const CoverageTables& coverage, const NoiseMeans& noiseMeans) {
  const CloudSettings& c = settings.clouds;
  const WeatherRegion& region = settings.region;
  const CloudFrameGeometry g = cloudFrameGeometry(settings);
  shared::CloudParams p{};
  p.view = view;
  p.geo = geoFrame({g.latDeg, g.lonDeg, g.altitudeM});
  p.region = geoRegion(region);
  const bool reference = c.quality == CloudQuality::Reference;
  p.lightSteps = static_cast<uint32_t>(c.lightSteps);
  p.lightSplit = static_cast<uint32_t>(reference ? kReferenceLightSplit : c.lightSplit);
  p.lightLongPartM = reference ? CLOUD_LIGHT_REFERENCE_LONG_PART_M : CLOUD_LIGHT_LONG_PART_M;
  p.octaves = static_cast<uint32_t>(c.scatteringOctaves);
  p.maxSteps = static_cast<uint32_t>(c.maxSteps);
  p.marchBlock = 1;
  p.samplesPerPixel = static_cast<uint32_t>(std::clamp(c.samples, 1, 64));
  p.lowBaseM = static_cast<float>(c.low.baseM);
  p.lowTopM = static_cast<float>(c.low.topM);
  p.midBaseM = static_cast<float>(c.mid.baseM);
  p.midTopM = static_cast<float>(c.mid.topM);
  // March only through the layers that have cover somewhere on the map.
  const bool low = maxCover.x > 0.0f, mid = maxCover.y > 0.0f;
  p.shellBaseM = static_cast<float>(low ? c.low.baseM : c.mid.baseM);
  p.shellTopM = static_cast<float>(mid ? c.mid.topM : c.low.topM);
  p.topDownStartM = static_cast<float>(std::max(c.low.topM, c.mid.topM) + kTopDownMarginM);
  p.anyCover = low || mid ? 1.0f : 0.0f;

  // The noise is tied to the ground: it tiles Earth-fixed (ECEF) space, whatever the region or
  // the camera, and drifts with the wind from the start of the scene's time (a cloud at x now
  // was at x - drift then). Each texture's origin is the camera's ECEF position less the drift,
  // reduced in double by whole repeats of that texture, so floats keep their precision and the
  // lookups equal those of the unreduced position exactly.
  const double shapeM = c.shapeScaleKm * 1000.0, detailM = c.detailScaleKm * 1000.0;
  const glm::dvec3 camera = ecefFromLatLonAltitude(g.latDeg, g.lonDeg, g.altitudeM);
  const glm::dmat3 enu = enuToEcefRotation(g.latDeg, g.lonDeg);
  const double elapsed = time.secondsSince(settings.timeStart);
  const double toward = (c.windFrom + 180.0) * kDeg;
  const glm::dvec2 windDrift = cloudWindDriftM(c, elapsed);
  const glm::dvec3 drift = windDrift.x * enu[0] + windDrift.y * enu[1];
  const glm::dvec3 noise = camera - drift;
  p.shapeOrigin = glm::vec4(glm::vec3(glm::mod(noise, shapeM)), 0.0f);
  p.detailOrigin = glm::vec4(glm::vec3(glm::mod(noise, detailM)), 0.0f);
  // The curl texture lies on the ground plane at the camera (east, north): its origin is the
  // noise position's east and north coordinates, reduced by whole repeats (shapeM) likewise.
  const glm::dvec2 ground(glm::dot(noise, enu[0]), glm::dot(noise, enu[1]));
  p.curlOrigin = glm::vec4(glm::vec2(glm::mod(ground, shapeM)), 0.0f, 0.0f);
  // Stratocumulus rolls run along the wind (cloudRollWeight): the shape noise is stretched
  // kRollStretch times along it. The stretch is linear, so the camera's stretched position
  // is reduced by whole repeats in double like the others; it moves columns of the texture
  // to other columns, so the cover calibration (which reads columns) still holds.
  const glm::dvec3 axis = std::sin(toward) * enu[0] + std::cos(toward) * enu[1];
  const double compression = 1.0 - 1.0 / kRollStretch;
  const glm::dvec3 rolled = noise - compression * glm::dot(noise, axis) * axis;
  p.rollOrigin = glm::vec4(glm::vec3(glm::mod(rolled, shapeM)), 0.0f);
  // Cumulus read the shape noise at a half and a quarter of its frequency too (cumulusOutline):
  // their origin is reduced by whole repeats of the slowest, or the pattern would jump wherever
  // shapeOrigin wraps.
  p.cumulusOrigin =
      glm::vec4(glm::vec3(glm::mod(noise, shapeM * CLOUD_CUMULUS_REPEAT_SHAPES)), 0.0f);
  p.rollAxis = glm::vec4(glm::vec3(axis), 0.0f);
  p.rollCompression = static_cast<float>(compression);
  // The short light steps whose samples may resolve the detail noise (CloudParams.
  // lightNearSteps): a prefix, as the steps grow. A sample stands for its sub-step (the step
  // split light_split ways) and sees a quarter of it (lightFootprint); noiseKeep resolves
  // nothing from half a cell. The 0.1 % spares float rounding. The reference reads it all.
  const double detailCellM = cloudDetailCellM(detailM, c.model);
  uint32_t near = 0;
  for (int i = 0; i < c.lightSteps; ++i) {
    const double sub =
        clouds::lightStepLength(i, c.lightSteps, static_cast<float>(c.lightDistanceM)) /
        static_cast<double>(p.lightSplit);
    if (0.25 * sub >= 0.5 * detailCellM * 1.001) break;
    near = static_cast<uint32_t>(i + 1);
  }
  p.lightNearSteps = reference ? p.lightSteps : near;
  p.shapeRepeatsPerM = static_cast<float>(1.0 / shapeM);
  p.detailRepeatsPerM = static_cast<float>(1.0 / detailM);
  p.curlRepeatsPerM = static_cast<float>(1.0 / shapeM);
  p.curlStrength = kCurlStrength;
  // Each frame of a time-lapse jitters its rays differently (whole seconds since the start).
  p.frameIndex = static_cast<uint32_t>(static_cast<int64_t>(std::floor(elapsed)) & 0x7fffffff);
  p.jitter = 1.0f;
  p.stepM = static_cast<float>(c.stepM);
  p.stepGrowth = static_cast<float>(c.stepGrowth);
  p.transmittanceCutoff = static_cast<float>(c.transmittanceCutoff);
  if (reference) {
    // The reference: steps half as long (and never over kReferenceStepM near the camera),
    // no early exit to speak of, and room for every step to the end of the shells.
    p.stepM = static_cast<float>(std::min(0.5 * c.stepM, kReferenceStepM));
    p.stepGrowth = static_cast<float>(0.5 * c.stepGrowth);
    p.transmittanceCutoff = kReferenceCutoff;
    p.maxSteps = kReferenceMaxSteps;
  }
  p.lightDistanceM = static_cast<float>(c.lightDistanceM);
  p.attenuationClamp = static_cast<float>(c.attenuationClamp);
  p.extinction = static_cast<float>(c.extinction);
  p.g = static_cast<float>(c.g);
  p.gBack = static_cast<float>(c.gBack);
  p.backWeight = static_cast<float>(c.backWeight);
  p.edgeSharpness = static_cast<float>(c.edgeSharpness);
  p.multipleScattering = static_cast<float>(c.multipleScattering);
  p.shapeMean = noiseMeans.shape;
  p.detailMean = noiseMeans.detail;

  // Both lights are marched toward where each gives a visible share of the light at the
  // clouds (the moon by day does not), so the change from sun to moon at dusk is a blend, not
  // a switch. Each layer gets the light that reaches its base, middle and top altitudes, so
  // clouds stay lit a while after sunset at the ground, their tops longest, and a low sun
  // lights their bases with less and redder light than their tops.
  const double turbidity = settings.turbidity;
  auto through = [&](const BodyLight& body, const glm::vec4& space, const CloudLayerSettings& l) {
    const light::LayerIlluminance e = light::illuminanceAcrossLayer(
        glm::vec3(space), body.elevationDeg, body.angularRadiusDeg, l.baseM, l.topM, turbidity);
    return shared::CloudLayerLight{glm::vec4(e.base, 0.0f), glm::vec4(e.middle, 0.0f),
                                   glm::vec4(e.top, 0.0f)};
  };
  const BodyLight* bodies[2] = {&lighting.sun, &lighting.moon};
  const glm::vec4* space[2] = {&lighting.gpu.sunSpace, &lighting.gpu.moonSpace};
  shared::CloudLayerLight* atLow[2] = {&p.sunAtLow, &p.moonAtLow};
  shared::CloudLayerLight* atMid[2] = {&p.sunAtMid, &p.moonAtMid};
  float share[2];
  for (int i = 0; i < 2; ++i) {
    *atLow[i] = through(*bodies[i], *space[i], c.low);
    *atMid[i] = through(*bodies[i], *space[i], c.mid);
    share[i] = std::max(luminance(glm::vec3(atLow[i]->middle)),
                        luminance(glm::vec3(atMid[i]->middle)));
  }
  const float total = share[0] + share[1];
  float* marched[2] = {&p.sunMarched, &p.moonMarched};
  for (int i = 0; i < 2; ++i)
    *marched[i] = total > 0.0f && share[i] > kLightShare * total ? 1.0f : 0.0f;
  p.sunDirection = glm::vec4(glm::vec3(lighting.sun.direction), 0.0f);
  p.moonDirection = glm::vec4(glm::vec3(lighting.moon.direction), 0.0f);
  p.sliceLengthM = 60000.0f;
  p.sliceTopM = static_cast<float>(std::max(c.low.topM, c.mid.topM) + 500.0);

  int i = 0;
  for (const auto& layer : coverage.thresholds)
    for (const auto& type : layer)
      for (float threshold : type) {
        p.coverageLut[i / 4][i % 4] = threshold;
        ++i;
      }
  i = 0;
  for (const auto& layer : coverage.farMean)
    for (const auto& type : layer)
      for (const auto& cover : type)
        for (const clouds::FarMean& mean : cover) {
          p.farMeanLut[i / 2][2 * (i % 2)] = mean.density;
          p.farMeanLut[i / 2][2 * (i % 2) + 1] = mean.fraction;
          ++i;
        }
  return p;
}

CloudKeyLight cloudKeyLight(const shared::CloudParams& p) {
  const auto share = [](const shared::CloudLayerLight& low, const shared::CloudLayerLight& mid) {
    return std::max(luminance(glm::vec3(low.middle)), luminance(glm::vec3(mid.middle)));
  };
  const bool sun = share(p.sunAtLow, p.sunAtMid) >= share(p.moonAtLow, p.moonAtMid);
  return {glm::vec3(sun ? p.sunDirection : p.moonDirection), sun};
}

}  // namespace sky
