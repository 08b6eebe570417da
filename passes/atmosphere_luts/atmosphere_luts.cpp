#include "passes/atmosphere_luts/atmosphere_luts.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <tuple>

#include "engine/core/error.h"
#include "engine/lighting/light_model.h"
#include "engine/graph/pass_context.h"
#include "engine/shader/shader_compiler.h"

namespace sky {
namespace {

// Settings are in 1/Mm (1e-6 per metre); the GPU works in km, so 1/Mm = 1e-3 per km.
constexpr double kPerMmToPerKm = 1e-3;
// Every LUT is RGBA32F: transmittance reaches 1e-5 along the horizon and twilight radiance
// 1e-6 renderer units, both below what half floats keep (lavapipe and every desktop GPU
// filter RGBA32F linearly).
constexpr VkFormat kLutFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

// The pass's pipeline from shaders/NAME.comp.
ComputePipeline buildPipeline(const Context& ctx, ShaderCompiler& compiler, const char* name) {
  return buildComputePipeline(ctx, compiler, std::string(name) + ".comp", name);
}

ImageDesc lutDesc(const char* name, const char* about, uint32_t width, uint32_t height,
                  uint32_t depth = 1) {
  ImageDesc d;
  d.name = name;
  d.about = about;
  d.dim = depth > 1 ? ImageDim::Tex3D : ImageDim::Tex2D;
  d.format = kLutFormat;
  d.width = width;
  d.height = height;
  d.depth = depth;
  return d;
}

PersistentImage persistentLut(const Context& ctx, const char* name, const char* about,
                              uint32_t width, uint32_t height) {
  ImageDesc d = lutDesc(name, about, width, height);
  // Written by its own pass, sampled by the others, readable as a debug output.
  d.usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  return PersistentImage{Image(ctx, d), {}};
}

glm::vec4 perKm(glm::vec3 perMm, double w) {
  return glm::vec4(glm::dvec3(perMm) * kPerMmToPerKm, w);
}

void checkPositive(double value, const char* key) {
  if (!(value > 0.0))
    inputError("atmosphere." + std::string(key) + ": " + std::to_string(value) +
               " must be greater than 0");
}

}  // namespace

shared::AtmosphereParams atmosphereParams(const AtmosphereSettings& s) {
  checkPositive(s.groundRadiusKm, "ground_radius_km");
  checkPositive(s.thicknessKm, "thickness_km");
  checkPositive(s.rayleighScaleHeightKm, "rayleigh_scale_height_km");
  checkPositive(s.mieScaleHeightKm, "mie_scale_height_km");
  checkPositive(s.ozoneHalfWidthKm, "ozone_half_width_km");
  if (s.mieExtinction < s.mieScattering)
    inputError("atmosphere.mie_extinction: " + std::to_string(s.mieExtinction) +
               " must be at least mie_scattering (" + std::to_string(s.mieScattering) + ")");
  if (std::abs(s.mieAnisotropy) >= 1.0)
    inputError("atmosphere.mie_anisotropy: " + std::to_string(s.mieAnisotropy) +
               " must lie strictly between -1 and 1");

  shared::AtmosphereParams p{};
  p.radii = glm::vec4(s.groundRadiusKm, s.groundRadiusKm + s.thicknessKm, 0.0f, 0.0f);
  p.rayleighScattering = perKm(s.rayleighScattering, s.rayleighScaleHeightKm);
  // The coefficients stand for 550 nm; Angstrom's law at each channel's aerosol wavelength
  // (light_model.h: where the law gives the channel's average) scales them.
  glm::vec3 angstrom(1.0f);
  for (int c = 0; c < 3; ++c)
    angstrom[c] = static_cast<float>(
        std::pow(light::kChannelAerosolWavelengthsNm[c] / 550.0, -s.mieAngstrom));
  p.mieScattering = perKm(glm::vec3(s.mieScattering) * angstrom, s.mieScaleHeightKm);
  p.mieExtinction = perKm(glm::vec3(s.mieExtinction) * angstrom, s.mieAnisotropy);
  p.ozoneAbsorption = perKm(s.ozoneAbsorption, 0.0);
  p.ozoneProfile = glm::vec4(s.ozoneCenterKm, s.ozoneHalfWidthKm, 0.0f, 0.0f);
  p.groundAlbedo = glm::vec4(s.groundAlbedo, 0.0f);
  p.sunDirection = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
  p.moonDirection = glm::vec4(0.0f, 0.0f, -1.0f, 0.0f);
  p.aerialPerspective = glm::vec4(ATMOSPHERE_AP_DEPTH_KM, ATMOSPHERE_AP_SLICES, 0.0f, 0.0f);
  setAtmosphereCamera(p, 0.0);
  return p;
}

void setAtmosphereCamera(shared::AtmosphereParams& params, double altitudeM) {
  const float ground = params.radii.x, top = params.radii.y;
  const double thickness = double(top) - double(ground);
  // A thin atmosphere (under twice the margin) keeps the camera in its middle.
  const double margin = std::min(kAtmosphereCameraMarginKm, 0.5 * thickness);
  const double altitudeKm = std::clamp(altitudeM * 1e-3, margin, thickness - margin);
  const float radius = static_cast<float>(double(ground) + altitudeKm);
  params.radii.z = radius;
  // The altitude as the float radius has it (exact: Sterbenz), so the horizon the shaders
  // derive from it and the rays they march from the radius agree.
  params.radii.w = radius - ground;
}

AtmosphereLuts::AtmosphereLuts(const Context& ctx, ShaderCompiler& compiler)
    : mTransmittance(buildPipeline(ctx, compiler, kTransmittanceName)),
      mMultiScattering(buildPipeline(ctx, compiler, kMultiScatteringName)),
      mSkyView(buildPipeline(ctx, compiler, kSkyViewName)),
      mAerialPerspective(buildPipeline(ctx, compiler, kAerialPerspectiveName)),
      mSkyProbe(buildPipeline(ctx, compiler, kSkyProbeName)),
      mSampler(ctx, SamplerWrap::Clamp, true),
      mTransmittanceLut(persistentLut(ctx, "atmosphere_transmittance",
                                      "transmittance to the top of the atmosphere (Hillaire 2020)",
                                      ATMOSPHERE_TRANSMITTANCE_WIDTH,
                                      ATMOSPHERE_TRANSMITTANCE_HEIGHT)),
      mMultiScatteringLut(persistentLut(
          ctx, "atmosphere_multiscattering",
          "multiple scattering: Psi_ms (Hillaire 2020) and the second order's dipole and "
          "quadrupole, packed in blocks side by side",
          ATMOSPHERE_MULTISCATTERING_SIZE * ATMOSPHERE_MS_TEXELS, ATMOSPHERE_MULTISCATTERING_SIZE)),
      mCameraSkyView{{persistentLut(ctx, "atmosphere_sky_view_sun",
                                    "sky radiance lit by the sun (Hillaire 2020)",
                                    ATMOSPHERE_SKY_VIEW_WIDTH, ATMOSPHERE_SKY_VIEW_HEIGHT),
                      std::nullopt},
                     {persistentLut(ctx, "atmosphere_sky_view_moon", "sky radiance lit by the moon",
                                    ATMOSPHERE_SKY_VIEW_WIDTH, ATMOSPHERE_SKY_VIEW_HEIGHT),
                      std::nullopt}},
      mCloudSkyView{{persistentLut(ctx, "atmosphere_sky_view_clouds_sun",
                                   "sky radiance lit by the sun, seen from the clouds",
                                   ATMOSPHERE_SKY_VIEW_WIDTH, ATMOSPHERE_SKY_VIEW_HEIGHT),
                     std::nullopt},
                    {persistentLut(ctx, "atmosphere_sky_view_clouds_moon",
                                   "sky radiance lit by the moon, seen from the clouds",
                                   ATMOSPHERE_SKY_VIEW_WIDTH, ATMOSPHERE_SKY_VIEW_HEIGHT),
                     std::nullopt}} {}

ImageId AtmosphereLuts::addSkyView(FrameGraph& graph, const char* name, SkyViewLut& lut,
                                   const shared::AtmosphereParams& p, uint32_t light,
                                   const SkyViewKey& key, ImageId transmittance,
                                   ImageId multiScattering) {
  struct Handles {
    ImageId transmittance, multiScattering, lut;
  };
  auto h = std::make_shared<Handles>(
      Handles{transmittance, multiScattering, graph.importImage(lut.image)});
  // A new transmittance or multiple scattering changes the atmosphere, hence the key.
  if (lut.key && *lut.key == key) return h->lut;
  GraphBuilder s = graph.addPass(name, [this, h, p, light, key, &lut](PassContext& ctx) {
    const shared::AtmosphereSkyViewLight which{glm::uvec4(light, 0u, 0u, 0u)};
    ctx.dispatch(
        mSkyView,
        {Binding::of(ATMOSPHERE_BINDING_PARAMS, ctx.uniform(p)),
         Binding::of(ATMOSPHERE_SKY_VIEW_BINDING_TRANSMITTANCE, h->transmittance, &mSampler),
         Binding::of(ATMOSPHERE_SKY_VIEW_BINDING_MULTISCATTERING, h->multiScattering, &mSampler),
         Binding::of(ATMOSPHERE_SKY_VIEW_BINDING_OUT, h->lut)},
        mSkyView.groupsX(ATMOSPHERE_SKY_VIEW_WIDTH), mSkyView.groupsY(ATMOSPHERE_SKY_VIEW_HEIGHT),
        1, &which, sizeof which);
    // Recorded: later frames with the same light and altitude keep the LUT. A frame that
    // culls the pass (nothing reads the LUT) records nothing, so the next reader remakes it.
    lut.key = key;
  });
  s.read(h->transmittance, Access::SampledCompute);
  s.read(h->multiScattering, Access::SampledCompute);
  h->lut = s.write(h->lut, Access::StorageWriteCompute);
  return h->lut;
}

AtmosphereLuts::Outputs AtmosphereLuts::addTo(FrameGraph& graph, const Frame& frame) {
  shared::AtmosphereParams p = atmosphereParams(frame.atmosphere);
  setAtmosphereCamera(p, frame.cameraAltitudeM);
  p.sunDirection = glm::vec4(frame.sunDirection, 0.0f);
  p.moonDirection = glm::vec4(frame.moonDirection, 0.0f);
  p.sunIlluminance = glm::vec4(frame.sunIlluminance, 0.0f);
  p.moonIlluminance = glm::vec4(frame.moonIlluminance, 0.0f);
  p.view = frame.view;
  mParams = p;

  // The handles each pass binds are only known once its builder has declared them, after
  // addPass took the execute function: they travel in this block, shared by the closures.
  struct Handles {
    Outputs out;
  };
  auto h = std::make_shared<Handles>();
  Outputs& out = h->out;
  out.transmittance = graph.importImage(mTransmittanceLut);
  out.multiScattering = graph.importImage(mMultiScatteringLut);

  if (!mBaked || *mBaked != frame.atmosphere) {
    const AtmosphereSettings settings = frame.atmosphere;
    GraphBuilder t = graph.addPass(kTransmittanceName, [this, h, p, settings](PassContext& ctx) {
      ctx.dispatch(mTransmittance,
                   {Binding::of(ATMOSPHERE_BINDING_PARAMS, ctx.uniform(p)),
                    Binding::of(ATMOSPHERE_TRANSMITTANCE_BINDING_OUT, h->out.transmittance)},
                   mTransmittance.groupsX(ATMOSPHERE_TRANSMITTANCE_WIDTH),
                   mTransmittance.groupsY(ATMOSPHERE_TRANSMITTANCE_HEIGHT));
      // Recorded: later frames with the same atmosphere reuse the LUTs.
      mBaked = settings;
    });
    // Persistent: kept even when nothing reads the LUT this frame.
    t.sideEffect();
    out.transmittance = t.write(out.transmittance, Access::StorageWriteCompute);

    GraphBuilder m = graph.addPass(kMultiScatteringName, [this, h, p](PassContext& ctx) {
      ctx.dispatch(mMultiScattering,
                   {Binding::of(ATMOSPHERE_BINDING_PARAMS, ctx.uniform(p)),
                    Binding::of(ATMOSPHERE_MULTISCATTERING_BINDING_TRANSMITTANCE,
                                h->out.transmittance, &mSampler),
                    Binding::of(ATMOSPHERE_MULTISCATTERING_BINDING_OUT, h->out.multiScattering)},
                   ATMOSPHERE_MULTISCATTERING_SIZE, ATMOSPHERE_MULTISCATTERING_SIZE);
    });
    m.sideEffect();
    m.read(out.transmittance, Access::SampledCompute);
    out.multiScattering = m.write(out.multiScattering, Access::StorageWriteCompute);
  }

  auto addPair = [&](SkyView& luts, const shared::AtmosphereParams& params, double altitudeM,
                     const char* sunName, const char* moonName) {
    const SkyViewKey sunKey{frame.atmosphere, altitudeM, frame.sunDirection.z,
                            frame.sunIlluminance};
    const SkyViewKey moonKey{frame.atmosphere, altitudeM, frame.moonDirection.z,
                             frame.moonIlluminance};
    return std::pair{addSkyView(graph, sunName, luts.sun, params, ATMOSPHERE_SKY_VIEW_LIGHT_SUN,
                                sunKey, out.transmittance, out.multiScattering),
                     addSkyView(graph, moonName, luts.moon, params, ATMOSPHERE_SKY_VIEW_LIGHT_MOON,
                                moonKey, out.transmittance, out.multiScattering)};
  };
  std::tie(out.skyViewSun, out.skyViewMoon) =
      addPair(mCameraSkyView, p, frame.cameraAltitudeM, kSkyViewName, kSkyViewMoonName);
  mCloudParams = p;
  if (frame.cloudAltitudeM) {
    setAtmosphereCamera(mCloudParams, *frame.cloudAltitudeM);
    std::tie(out.skyViewSunClouds, out.skyViewMoonClouds) =
        addPair(mCloudSkyView, mCloudParams, *frame.cloudAltitudeM, kSkyViewCloudsName,
                kSkyViewCloudsMoonName);
  }

  out.aerialPerspective = addAerialPerspective(graph, out, frame.view);
  return out;
}

ImageId AtmosphereLuts::addAerialPerspective(FrameGraph& graph, const Outputs& luts,
                                             const shared::ViewState& view) {
  shared::AtmosphereParams p = mParams;
  p.view = view;
  struct Handles {
    ImageId transmittance, multiScattering, aerialPerspective;
  };
  auto h = std::make_shared<Handles>(Handles{luts.transmittance, luts.multiScattering, {}});
  GraphBuilder a = graph.addPass(kAerialPerspectiveName, [this, h, p](PassContext& ctx) {
    ctx.dispatch(mAerialPerspective,
                 {Binding::of(ATMOSPHERE_BINDING_PARAMS, ctx.uniform(p)),
                  Binding::of(ATMOSPHERE_AP_BINDING_TRANSMITTANCE, h->transmittance, &mSampler),
                  Binding::of(ATMOSPHERE_AP_BINDING_MULTISCATTERING, h->multiScattering, &mSampler),
                  Binding::of(ATMOSPHERE_AP_BINDING_OUT, h->aerialPerspective)},
                 mAerialPerspective.groupsX(ATMOSPHERE_AP_SIZE),
                 mAerialPerspective.groupsY(ATMOSPHERE_AP_SIZE));
  });
  a.read(luts.transmittance, Access::SampledCompute);
  a.read(luts.multiScattering, Access::SampledCompute);
  h->aerialPerspective =
      a.write(a.create(lutDesc("atmosphere_aerial_perspective",
                               "in-scattering (RGB) and transmittance (A) along view rays, 3D",
                               ATMOSPHERE_AP_SIZE, ATMOSPHERE_AP_SIZE, ATMOSPHERE_AP_SLICES)),
              Access::StorageWriteCompute);
  return h->aerialPerspective;
}

ImageId AtmosphereLuts::addSkyProbe(FrameGraph& graph, const Outputs& luts, uint32_t width,
                                    uint32_t height) {
  if (width == 0 || height == 0) internalError("atmosphere_sky_probe: empty image size");
  struct Handles {
    ImageId sun, moon, probe;
  };
  auto h = std::make_shared<Handles>(Handles{luts.skyViewSun, luts.skyViewMoon, {}});
  GraphBuilder b =
      graph.addPass(kSkyProbeName, [this, h, p = mParams, width, height](PassContext& ctx) {
        ctx.dispatch(mSkyProbe,
                     {Binding::of(ATMOSPHERE_BINDING_PARAMS, ctx.uniform(p)),
                      Binding::of(ATMOSPHERE_SKY_PROBE_BINDING_SUN, h->sun, &mSampler),
                      Binding::of(ATMOSPHERE_SKY_PROBE_BINDING_MOON, h->moon, &mSampler),
                      Binding::of(ATMOSPHERE_SKY_PROBE_BINDING_OUT, h->probe)},
                     mSkyProbe.groupsX(width), mSkyProbe.groupsY(height));
      });
  b.read(h->sun, Access::SampledCompute);
  b.read(h->moon, Access::SampledCompute);
  ImageDesc d =
      lutDesc("atmosphere_sky_probe",
              "the whole sky, equirectangular (north at column 0, zenith at row 0)", width, height);
  h->probe = b.write(b.create(d), Access::StorageWriteCompute);
  return h->probe;
}

}  // namespace sky
