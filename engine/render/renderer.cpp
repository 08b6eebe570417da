#include "engine/render/renderer.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/paths.h"
#include "engine/gpu/context.h"
#include "engine/lighting/light_model.h"
#include "engine/render/camera.h"
#include "engine/scene/scene_io.h"
#include "engine/weather/geo.h"

namespace sky {
namespace {

// Splits interleaved read-back into a layer with the first `channels` channels. A 3D image
// is laid out with its depth slices side by side (width * depth across).
ImageLayer toLayer(const ReadbackImage& img, std::string name, std::vector<std::string> channels,
                   bool fullFloat = false) {
  ImageLayer layer{std::move(name), std::move(channels), {}, fullFloat};
  const size_t w = img.width, h = img.height, d = img.depth, c = layer.channels.size();
  layer.pixels.resize(w * h * d * c);
  for (size_t z = 0; z < d; ++z)
    for (size_t y = 0; y < h; ++y)
      for (size_t x = 0; x < w; ++x) {
        const size_t src = ((z * h + y) * w + x) * img.channels;
        const size_t dst = (y * w * d + z * w + x) * c;
        for (size_t k = 0; k < c; ++k) layer.pixels[dst + k] = img.pixels[src + k];
      }
  return layer;
}

const std::vector<std::string> kRgb = {"R", "G", "B"};
const std::vector<std::string> kRgba = {"R", "G", "B", "A"};
const std::vector<std::string> kSteps = {"view", "light"};
const std::vector<std::string> kShadow = {"transmittance"};

// The "clouds" layer: premultiplied radiance, opacity and the transmittance-weighted depth
// (m); all zero when the scene has no volumetric clouds.
ImageLayer cloudLayer(const ReadbackImage* clouds, const ReadbackImage* depth, uint32_t width,
                      uint32_t height) {
  // FLOAT: the depth of horizon clouds (up to ~200 km) is past half's 65504, and moonlit
  // clouds' radiance (1e-7) below its normal range.
  ImageLayer layer{"clouds", {"R", "G", "B", "A", "depth"}, {}, true};
  const size_t n = size_t(width) * height;
  layer.pixels.assign(n * 5, 0.0f);
  if (!clouds || !depth) return layer;
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < 4; ++k)
      layer.pixels[i * 5 + k] = clouds->pixels[i * clouds->channels + k];
    layer.pixels[i * 5 + 4] = depth->pixels[i * depth->channels];
  }
  return layer;
}

// The "weather" layer of a top-down render: the map's low and mid cover at each pixel's
// centre (row 0 the north edge, column 0 the west edge), for `skyrender dsc`.
ImageLayer weatherCoverLayer(const WeatherMap& map, const WeatherRegion& region, uint32_t width,
                             uint32_t height) {
  ImageLayer layer{"weather", {"cover_low", "cover_mid"}, {}};
  layer.pixels.resize(size_t(width) * height * 2);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const double lat = region.lat[1] + (region.lat[0] - region.lat[1]) * (y + 0.5) / height;
      const double lon = region.lon[0] + (region.lon[1] - region.lon[0]) * (x + 0.5) / width;
      const glm::vec4 w = map.sample(lat, lon);
      const size_t i = (size_t(y) * width + x) * 2;
      layer.pixels[i] = w.r;
      layer.pixels[i + 1] = w.g;
    }
  return layer;
}

}  // namespace

AtmosphereSettings physicalAtmosphere(const Scene& scene) {
  AtmosphereSettings a = scene.atmosphere;
  a.groundAlbedo = scene.ground.albedo;  // one ground for the sky and the composite
  if (a.aerosols == AerosolSource::Turbidity) {
    // Hillaire 2020's Earth: 3.996 of 4.4 /Mm scatters, the rest is absorbed.
    constexpr double kMieSingleScatteringAlbedo = 3.996 / 4.4;
    // tau = beta H for an exponential profile; 1/km to 1/Mm.
    a.mieExtinction = scene.lighting.turbidity / a.mieScaleHeightKm * 1000.0;
    a.mieScattering = a.mieExtinction * kMieSingleScatteringAlbedo;
    a.mieAngstrom = light::kAerosolAngstrom;
    // Cornette-Shanks g 0.6 has the mean cosine 3g(4 + g^2) / (5(2 + g^2)) = 0.665, the
    // asymmetry parameter of continental aerosol at 550 nm (AERONET: about 0.62-0.72,
    // Dubovik et al. 2002). Hillaire's 0.8 (mean cosine 0.84) belongs to coarse maritime
    // particles; it made the aureole several times too bright against the CIE standard
    // clear sky (AtmosphereTest.PhysicalSkyAgainstCieAndPreetham, docs/atmosphere.md).
    a.mieAnisotropy = kContinentalAerosolG;
  }
  return a;
}

const std::vector<DebugOutputInfo>& debugOutputs() {
  static const std::vector<DebugOutputInfo> outputs = {
      {"coefficients", "high-cloud coefficient texture (R thin lit, G dense, B clear, A edges)",
       false, false},
      {"normals", "high-cloud tangent-space normal map (xyz in -1..1)", false, false},
      {"transmittance_lut", "transmittance to the top of the atmosphere, 256x64", true, false},
      {"multiscattering_lut", "multiple-scattering contribution Psi_ms, 32x32", true, false},
      {"sky_view_sun_lut", "sky radiance lit by the sun, 192x108", true, false},
      {"sky_view_moon_lut", "sky radiance lit by the moon, 192x108", true, false},
      {"aerial_perspective",
       "in-scattering (rgb) and transmittance (a), 32x32x32, slices "
       "side by side",
       true, false},
      {"cloud_steps",
       "volumetric clouds: density samples per pixel along the view ray (R) and in the light "
       "marches (G), a heat map of the raymarch's cost",
       false, true},
      {"cloud_density_slice",
       "volumetric clouds: a vertical cut along the camera's heading, 60 km ahead (across) by "
       "sea level to above the clouds (down), 512x128: R density, G cover, B type, A layer",
       false, true},
      {"weather_map",
       "the weather map over its region: R low cover, G mid cover, B type, A density", false, true},
      {"cloud_shadow",
       "volumetric clouds: transmittance toward the key light from the ground, 384x384 around "
       "the point below the camera (east right, north up; ground distance r u|u| from the "
       "centre, r in the report's cloud_shadow.radius_m)",
       false, true},
  };
  return outputs;
}

void checkDebugOutputs(const Scene& scene, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    auto it = std::find_if(debugOutputs().begin(), debugOutputs().end(),
                           [&](const DebugOutputInfo& o) { return name == o.name; });
    if (it == debugOutputs().end()) {
      std::string known;
      for (const DebugOutputInfo& o : debugOutputs())
        known += (known.empty() ? "" : ", ") + std::string(o.name);
      inputError("--debug-output " + name + ": unknown (known: " + known + ")");
    }
    if (it->physicalOnly && scene.sky.model != SkyModel::Physical)
      inputError("--debug-output " + name + ": needs sky.model physical (the scene uses " +
                 enumName(scene.sky.model) + ")");
  }
}

Renderer::Renderer(const Context& ctx, ShaderCompiler& compiler)
    : mRuntime(ctx),
      mStars(ctx, compiler, loadStarCatalog(configDir() / "stars" / "bright_star_catalogue.txt")),
      mHighCloudTextures(ctx, compiler, mRuntime),
      mRegionalCover(ctx),
      mAtmosphere(ctx, compiler),
      mSky(ctx, compiler),
      mClouds(ctx, compiler, mRuntime),
      mVolumetric(ctx, compiler),
      mShadow(ctx, compiler),
      mTemporal(ctx, compiler),
      mUpsample(ctx, compiler),
      mLightVolume(ctx, compiler),
      mDisplay(ctx, compiler),
      mHistorySampler(ctx, SamplerWrap::Clamp),
      mSlice(ctx, compiler),
      mVolumeExport(ctx, compiler),
      mComposite(ctx, compiler) {}

void Renderer::setBakeProgress(std::function<void(double)> progress) {
  mHighCloudTextures.setProgress(std::move(progress));
}

Renderer::CloudSetup Renderer::cloudSetup(const Scene& scene, const IsoTime& time) {
  const WeatherMap& weather = mClouds.weatherMap(scene, time);
  CloudSetup s{scene, {}, {}, {}, {}, &weather};
  // The map's region, resolved from the camera when the scene gives none.
  s.cloudScene.weather.region = weather.region;
  // A forecast file places the layers at the altitudes of its pressure levels (from gh); the
  // scene's clouds.low/mid apply otherwise.
  if (weather.layerAltitudesM) {
    const glm::dvec4& a = *weather.layerAltitudesM;
    s.cloudScene.clouds.low = {a.x, a.y};
    s.cloudScene.clouds.mid = {a.z, a.w};
  }
  // A top-down view is lit as seen from the middle of the weather region.
  s.volumetric = volumetricCloudsSettings(s.cloudScene);
  s.geometry = cloudFrameGeometry(s.volumetric);
  Scene litScene = scene;
  litScene.camera.latitude = s.geometry.latDeg;
  litScene.camera.longitude = s.geometry.lonDeg;
  s.lighting = computeLighting(litScene, time);
  // The weather where the camera stands sets the ambient light and the haze.
  s.localWeather =
      localWeather(weather, s.geometry.latDeg, s.geometry.lonDeg, scene.weather.localRadiusKm);
  applyOvercast(s.lighting, scene.sky, s.localWeather.overcast);
  return s;
}

namespace {

// A history older than this, or a camera moved further, is a cut: the clouds have changed
// too much for reprojection (a time-lapse's steps, a jump).
constexpr double kHistoryMaxGapS = 60.0;
constexpr double kHistoryMaxMoveM = 5000.0;

// The scene written out without the camera's pose and the time: what temporal reuse and the
// light volume compare to see whether anything else changed.
std::string settingsWithoutPose(const Scene& scene) {
  Scene s = scene;
  s.camera.heading = s.camera.pitch = 0.0;
  s.camera.latitude = s.camera.longitude = s.camera.altitudeM = 0.0;
  s.time.start = IsoTime{};
  s.time.end.reset();
  s.time.stepSeconds = 0.0;
  return writeScene(s, ConfigFormat::Json);
}

}  // namespace

Renderer::HistoryStep Renderer::stepHistory(const Scene& scene, const IsoTime& time,
                                            const shared::ViewState& view, uint32_t width,
                                            uint32_t height) {
  const Context& ctx = mRuntime.gpu();
  ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.name = "clouds";
  mCloudHistory.ensure(ctx, desc);
  desc.format = VK_FORMAT_R32G32_SFLOAT;
  desc.name = "clouds_depth";
  mDepthHistory.ensure(ctx, desc);

  HistoryStep step;
  CloudHistory& next = step.next;
  next.settings = settingsWithoutPose(scene);
  next.view = view;
  next.latDeg = scene.camera.latitude;
  next.lonDeg = scene.camera.longitude;
  next.altitudeM = scene.camera.altitudeM;
  next.time = time;
  next.mapRevision = mClouds.mapRevision();

  const CloudHistory& last = mHistory;
  const glm::dvec3 here = ecefFromLatLonAltitude(next.latDeg, next.lonDeg, next.altitudeM);
  const glm::dvec3 there = ecefFromLatLonAltitude(last.latDeg, last.lonDeg, last.altitudeM);
  const double gap = time.secondsSince(last.time);
  step.valid = mCloudHistory.valid() && mDepthHistory.valid() &&
               next.settings == last.settings && next.mapRevision == last.mapRevision &&
               std::abs(gap) <= kHistoryMaxGapS && glm::length(here - there) <= kHistoryMaxMoveM;
  next.frame = step.valid ? last.frame + 1 : 0;
  // A cut marches every pixel, so the first frame of a sequence is the still.
  if (step.valid) {
    step.block = static_cast<uint32_t>(scene.clouds.temporal.block);
    step.offset = cloudMarchOffset(step.block, next.frame - 1);
    const glm::dmat3 enuHere = enuToEcefRotation(next.latDeg, next.lonDeg);
    const glm::dmat3 enuThere = enuToEcefRotation(last.latDeg, last.lonDeg);
    step.motion.previousPosition = glm::vec3(glm::transpose(enuHere) * (there - here));
    step.motion.toPrevious = glm::mat3(glm::transpose(enuThere) * enuHere);
    step.motion.windShift = glm::vec3(glm::vec2(cloudWindDriftM(scene.clouds, gap)), 0.0f);
  }
  return step;
}

RenderedFrame Renderer::render(const Scene& scene, const IsoTime& time,
                               const RenderOptions& options) {
  checkDebugOutputs(scene, options.debugOutputs);
  if (options.readBack == ReadBack::Display && !options.gpuDisplay)
    internalError("ReadBack::Display without RenderOptions::gpuDisplay");
  const bool layers = options.readBack == ReadBack::Layers;
  RenderedFrame out;
  const CloudSetup setup = cloudSetup(scene, time);
  const WeatherMap& weather = *setup.weather;
  const Scene& cloudScene = setup.cloudScene;
  const CloudFrameGeometry& geometry = setup.geometry;
  out.lighting = setup.lighting;
  out.localWeather = setup.localWeather;
  out.weatherRegion = weather.region;
  out.weatherTexels = glm::uvec2(weather.width, weather.height);
  const uint32_t width = static_cast<uint32_t>(scene.output.width);
  const uint32_t height = static_cast<uint32_t>(scene.output.height);
  const shared::ViewState view = makeViewState(scene.camera, width, height);
  const bool physical = scene.sky.model == SkyModel::Physical;
  const bool topDown = geometry.topDown;
  const glm::vec2 maxCover = weather.maxCover();
  out.clouds = maxCover.x > 0.0f || maxCover.y > 0.0f;
  for (const std::string& name : options.debugOutputs)
    for (const DebugOutputInfo& info : debugOutputs())
      if (name == info.name && info.cloudsOnly && !out.clouds)
        inputError("--debug-output " + name +
                   ": the scene has no low or mid clouds (weather cover is 0 everywhere)");

  FrameGraph graph(mRuntime);
  StarFieldPass::Frame stars;
  stars.view = view;
  stars.j2000ToEnu = glm::mat3(out.lighting.ephemeris.equatorialJ2000ToEnu);
  stars.extinction = static_cast<float>(scene.lighting.starExtinction);
  // No star passes by day: the brightest star over a pixel of this view against the sky.
  const glm::vec3 skyColor = glm::vec3(out.lighting.gpu.palette.sky);
  const double skyLuminance = 0.2126 * skyColor.r + 0.7152 * skyColor.g + 0.0722 * skyColor.b;
  const bool starsShow =
      out.lighting.dayFactor < 1.0 ||
      starsVisible(mStars.brightestVmag(), out.lighting.gpu.night.z,
                   double(view.forward.w) * double(view.forward.w), skyLuminance);
  const std::optional<StarFieldPass::Outputs> starOut = mStars.addTo(graph, stars, starsShow);

  // The high-cloud textures: kept from the last frame, loaded, or baked (before this graph).
  // With a forecast's high layer the cover comes from the map per pixel, at the data's
  // altitude (the middle of the layer's gh range).
  const bool highFromWeather = highCloudsFromWeather(scene, weather);
  const HighCloudTextures::Outputs textures =
      mHighCloudTextures.addTo(graph, scene, highFromWeather);
  out.highClouds = mHighCloudTextures.lastActivity();
  std::optional<double> highAltitudeM;
  if (highFromWeather && weather.highAltitudeM)
    highAltitudeM = 0.5 * (weather.highAltitudeM->x + weather.highAltitudeM->y);

  SkyHighCloudsPass::Inputs sky{};
  const bool cloudsPresent = highFromWeather || scene.highClouds.source == HighCloudSource::Image ||
                             scene.highClouds.cover > 0.0;
  const ImageDesc& fine = graph.desc().resources[textures.coefficients.id].image;
  const ImageDesc& coarse = graph.desc().resources[textures.coarse.id].image;
  sky.params = skyHighCloudsParams(scene, out.lighting, time, view, cloudsPresent, fine.width,
                                   coarse.width, textures.mean, highAltitudeM);
  if (highFromWeather) {
    setRegionalCover(sky.params, scene, weather.region, textures);
    sky.regional = {mRegionalCover.addTo(graph, weather, mClouds.mapRevision()),
                    &mRegionalCover.sampler(), textures.rankShape, textures.coverCoarse};
  }
  sky.lighting = out.lighting.gpu;
  sky.textures = {textures.coefficients, textures.normals, textures.coarse,
                  &mHighCloudTextures.sampler()};
  AtmosphereLuts::Outputs luts{};
  if (physical) {
    AtmosphereLuts::Frame f;
    f.atmosphere = physicalAtmosphere(scene);
    f.cameraAltitudeM = scene.camera.altitudeM;
    f.view = view;
    f.sunDirection = glm::vec3(out.lighting.sun.direction);
    f.moonDirection = glm::vec3(out.lighting.moon.direction);
    f.sunIlluminance = glm::vec3(out.lighting.gpu.sunSpace);
    f.moonIlluminance = glm::vec3(out.lighting.gpu.moonSpace);
    luts = mAtmosphere.addTo(graph, f);
    sky.physical = true;
    sky.atmosphere = {mAtmosphere.params(), luts.transmittance, luts.skyViewSun, luts.skyViewMoon,
                      &mAtmosphere.sampler()};
  }
  const SkyHighCloudsPass::Outputs skyOut = graph.add(mSky, sky);

  // The volumetric clouds, when the map has any low or mid cover.
  VolumetricCloudsPass::Outputs clouds{};
  CloudShadowPass::Outputs shadow{};
  shared::CloudShadowMap shadowMap{};
  CloudLayers::Frame cloudFrame;
  std::optional<CloudHistory> pendingHistory;  // becomes mHistory once the frame has run
  if (out.clouds) {
    cloudFrame = mClouds.addTo(graph, cloudScene, time);
    out.cloudNoise = mClouds.noiseActivity();
    // Temporal reuse: a sequence's frames march a share of the pixels and reproject the rest,
    // at the view's size or at half its width and height.
    const bool temporal = scene.clouds.temporal.mode == CloudTemporalMode::On &&
                          scene.clouds.quality == CloudQuality::Standard && !topDown;
    const bool half =
        temporal && scene.clouds.temporal.resolution == CloudTemporalResolution::Half;
    const uint32_t cloudWidth = half ? (width + 1) / 2 : width;
    const uint32_t cloudHeight = half ? (height + 1) / 2 : height;
    const shared::ViewState cloudView =
        half ? makeViewState(scene.camera, cloudWidth, cloudHeight) : view;
    VolumetricCloudsPass::Inputs in;
    in.params = cloudParams(setup.volumetric, out.lighting, time, cloudView, cloudFrame.maxCover,
                            cloudFrame.weatherSize, cloudFrame.coverage, cloudFrame.noiseMeans,
                            cloudFrame.lowRolls);
    in.lighting = out.lighting.gpu;
    in.textures = cloudFrame.textures;
    // What the light volume and the shadow map are made from: kept while it holds.
    CloudFieldKey field;
    field.clouds = settingsWithoutPose(cloudScene);
    field.mapRevision = mClouds.mapRevision();
    field.camera = glm::dvec3(geometry.latDeg, geometry.lonDeg, geometry.altitudeM);
    field.sun = glm::vec3(in.params.sunDirection);
    field.moon = glm::vec3(in.params.moonDirection);
    field.lights =
        (in.params.sunMarched != 0.0f ? 1u : 0u) | (in.params.moonMarched != 0.0f ? 2u : 0u);
    field.drift = cloudWindDriftM(scene.clouds, time.secondsSince(scene.time.start));
    // The light through the clouds from the light volume (the reference marches it).
    if (scene.clouds.light == CloudLight::Volume &&
        scene.clouds.quality == CloudQuality::Standard) {
      CloudLightVolumePass::Inputs v;
      v.params = in.params;
      v.params.lightVolume = cloudLightVolumePlace(in.params, geometry.altitudeM);
      v.textures = in.textures;
      v.key = field;
      const CloudLightVolumePass::Outputs volume = mLightVolume.addTo(graph, v);
      in.params.lightVolume = volume.place;
      in.lightVolume = volume.volume;
      in.lightVolumeSampler = &mLightVolume.sampler();
    }
    std::optional<HistoryStep> step;
    if (temporal) {
      step = stepHistory(scene, time, cloudView, cloudWidth, cloudHeight);
      in.params.marchBlock = step->block;
      in.params.marchOffsetX = step->offset.x;
      in.params.marchOffsetY = step->offset.y;
      // A new jitter every frame, so a pixel marched again averages differently.
      in.params.frameIndex = (in.params.frameIndex + static_cast<uint32_t>(step->next.frame) *
                                                         0x9E3779B9u) & 0x7fffffffu;
    }
    clouds = graph.add(mVolumetric, in);
    if (temporal) {
      CloudTemporalPass::Inputs t;
      t.params = cloudTemporalParams(cloudView, mHistory.view, step->motion, step->block,
                                     step->offset, step->valid, in.params.geo.origin.w,
                                     scene.camera.altitudeM, in.params.shellBaseM,
                                     in.params.shellTopM);
      t.marched = clouds.clouds;
      t.marchedDepth = clouds.depth;
      t.clouds = graph.importHistory(mCloudHistory);
      t.depth = graph.importHistory(mDepthHistory);
      t.historySampler = &mHistorySampler;
      const CloudTemporalPass::Outputs resolved = graph.add(mTemporal, t);
      clouds.clouds = resolved.clouds;
      clouds.depth = resolved.depth;
      pendingHistory = std::move(step->next);
    }
    if (half) {
      CloudUpsamplePass::Inputs u;
      u.params.view = view;
      u.params.source = cloudView;
      u.params.planetRadiusM = in.params.geo.origin.w;
      u.params.cameraAltitudeM = static_cast<float>(scene.camera.altitudeM);
      u.params.shellBaseM = in.params.shellBaseM;
      u.params.shellTopM = in.params.shellTopM;
      u.clouds = clouds.clouds;
      u.depth = clouds.depth;
      const CloudUpsamplePass::Outputs full = graph.add(mUpsample, u);
      clouds.clouds = full.clouds;
      clouds.depth = full.depth;
    }
    if (layers) {
      graph.requestOutput(clouds.clouds, "clouds");
      graph.requestOutput(clouds.depth, "clouds_depth");
    }
    // The clouds' shadows on the ground around the observer (a top-down render draws no
    // ground, but the composite's cloud variant binds a map all the same).
    shadow = mShadow.addTo(graph, CloudShadowPass::Inputs{
                                      in.params, cloudShadowMap(in.params, geometry.altitudeM),
                                      in.textures, field});
    shadowMap = shadow.map;
    out.cloudShadow = shadowMap;
    for (const std::string& name : options.debugOutputs) {
      if (name == "cloud_steps") graph.requestOutput(clouds.steps, "debug:" + name);
      if (name == "weather_map") graph.requestOutput(cloudFrame.textures.weather, "debug:" + name);
      if (name == "cloud_shadow") graph.requestOutput(shadow.shadow, "debug:" + name);
      if (name == "cloud_density_slice") {
        CloudDensitySlicePass::Inputs slice{in.params, in.textures};
        graph.requestOutput(graph.add(mSlice, slice).slice, "debug:" + name);
      }
    }
  }

  AtmosphereCompositeSettings compositeSettings;
  compositeSettings.ground = scene.ground;
  compositeSettings.planetRadiusM = skyPlanetRadiusM(scene);
  compositeSettings.cameraAltitudeM = scene.camera.altitudeM;
  compositeSettings.turbidity = scene.lighting.turbidity;
  compositeSettings.observer = !topDown;
  // High clouds lie in front of the volumetric ones when the camera flies above them.
  compositeSettings.aboveHighClouds =
      !topDown && scene.camera.altitudeM > highAltitudeM.value_or(scene.highClouds.altitudeM);
  compositeSettings.belowClouds = scene.camera.altitudeM < setup.volumetric.clouds.low.baseM;
  AtmosphereCompositePass::Inputs composite{};
  composite.params = atmosphereCompositeParams(compositeSettings, out.lighting, view);
  if (out.clouds)
    composite.clouds = AtmosphereCompositePass::Clouds{clouds.clouds, clouds.depth, shadow.shadow,
                                                       shadowMap,
                                                       cloudFrame.textures.weatherSampler};
  if (physical)
    composite.atmosphere = AtmosphereCompositePass::Atmosphere{
        mAtmosphere.params(), luts.transmittance, luts.aerialPerspective, &mAtmosphere.sampler()};
  composite.lighting = out.lighting.gpu;
  if (starOut) composite.starFlux = starOut->flux;
  composite.sky = skyOut.sky;
  composite.highClouds = skyOut.highClouds;
  AtmosphereCompositePass::Outputs composited = graph.add(mComposite, composite);
  if (options.readBack != ReadBack::Display) graph.requestOutput(composited.beauty, "beauty");
  if (options.gpuDisplay) {
    if (scene.output.exposure == ExposureMode::Histogram)
      internalError("the GPU display path has no histogram exposure (it meters the frame)");
    DisplayTransformPass::Inputs d;
    d.settings = {options.gpuDisplay, scene.output.display, scene.output.view,
                  (scene.output.exposure == ExposureMode::Auto ? out.lighting.nightLiftEv : 0.0) +
                      scene.output.exposureEv,
                  scene.output.nightLook};
    d.beauty = composited.beauty;
    d.width = width;
    d.height = height;
    out.displayEv = d.settings.exposureEv;
    graph.requestOutput(mDisplay.addTo(graph, d).display, "display");
  }
  if (layers) {
    graph.requestOutput(skyOut.sky, "sky");
    graph.requestOutput(skyOut.highClouds, "high_clouds");
  }

  struct DebugSource {
    const char* name;
    ImageId image;
    const std::vector<std::string>* channels;
    bool requested = false;  // already requested where its pass was added
  };
  // The cloud debug images were requested above (they exist only with clouds).
  const DebugSource sources[] = {
      {"coefficients", textures.coefficients, &kRgba},
      {"normals", textures.normals, &kRgb},
      {"transmittance_lut", luts.transmittance, &kRgb},
      {"multiscattering_lut", luts.multiScattering, &kRgb},
      {"sky_view_sun_lut", luts.skyViewSun, &kRgb},
      {"sky_view_moon_lut", luts.skyViewMoon, &kRgb},
      {"aerial_perspective", luts.aerialPerspective, &kRgba},
      {"cloud_steps", clouds.steps, &kSteps, true},
      {"cloud_density_slice", ImageId{}, &kRgba, true},
      {"weather_map", cloudFrame.textures.weather, &kRgba, true},
      {"cloud_shadow", shadow.shadow, &kShadow, true},
  };
  for (const std::string& name : options.debugOutputs)
    for (const DebugSource& s : sources)
      if (name == s.name && !s.requested) graph.requestOutput(s.image, "debug:" + name);

  try {
    out.frame = graph.execute();
  } catch (...) {
    mLightVolume.invalidate();  // they may not have been made
    mShadow.invalidate();
    throw;
  }
  if (pendingHistory) mHistory = std::move(*pendingHistory);
  out.graphDot = graph.toDot(&out.frame);

  out.image.width = static_cast<int>(width);
  out.image.height = static_cast<int>(height);
  // FLOAT: physical values span from a moonless night (1e-8) to the sun's disc (1e5), past
  // both ends of half's range.
  if (options.readBack != ReadBack::Display)
    out.image.layers.push_back(toLayer(out.frame.output("beauty"), "", kRgba, true));
  if (layers) {
    out.image.layers.push_back(toLayer(out.frame.output("sky"), "sky", kRgb, true));
    out.image.layers.push_back(
        toLayer(out.frame.output("high_clouds"), "high_clouds", kRgba, true));
    out.image.layers.push_back(cloudLayer(
        out.clouds ? &out.frame.output("clouds") : nullptr,
        out.clouds ? &out.frame.output("clouds_depth") : nullptr, width, height));
  }
  if (topDown && layers)
    out.image.layers.push_back(weatherCoverLayer(weather, weather.region, width, height));
  for (const std::string& name : options.debugOutputs)
    for (const DebugSource& s : sources)
      if (name == s.name) {
        const ReadbackImage& img = out.frame.output("debug:" + name);
        DebugImage d{name, {}};
        d.image.width = static_cast<int>(img.width * img.depth);
        d.image.height = static_cast<int>(img.height);
        d.image.layers.push_back(toLayer(img, "", *s.channels));
        out.debug.push_back(std::move(d));
      }
  if (options.gpuDisplay) {
    const std::vector<float>& codes = out.frame.output("display").pixels;
    out.display.resize(codes.size());
    for (size_t i = 0; i < codes.size(); ++i)
      out.display[i] = static_cast<uint8_t>(std::lround(codes[i] * 255.0f));
  }
  for (ReadbackImage& o : out.frame.outputs) o.pixels = {};  // the layers hold the data now
  return out;
}

CloudVolume Renderer::exportCloudVolume(const Scene& scene, const IsoTime& time,
                                        const std::optional<CloudVolumeBox>& box, double voxelM) {
  const CloudSetup setup = cloudSetup(scene, time);
  if (setup.geometry.topDown)
    inputError(
        "export-volume: camera.mode geographic_topdown has no camera to export the "
        "clouds around (use camera.mode observer)");
  const glm::vec2 maxCover = setup.weather->maxCover();
  if (maxCover.x <= 0.0f && maxCover.y <= 0.0f)
    inputError("export-volume: the scene has no low or mid clouds (weather cover is 0 everywhere)");
  const CloudVolumeGrid grid =
      cloudVolumeGrid(box.value_or(defaultCloudVolumeBox(setup.cloudScene, maxCover)), voxelM);

  FrameGraph graph(mRuntime);
  const CloudLayers::Frame cloudFrame = mClouds.addTo(graph, setup.cloudScene, time);
  const shared::ViewState view =
      makeViewState(scene.camera, static_cast<uint32_t>(scene.output.width),
                    static_cast<uint32_t>(scene.output.height));
  // The raymarch's own parameters, so the grid holds the very field it marches through.
  CloudVolumeExportPass::Inputs in;
  in.params = cloudParams(setup.volumetric, setup.lighting, time, view, cloudFrame.maxCover,
                          cloudFrame.weatherSize, cloudFrame.coverage, cloudFrame.noiseMeans,
                          cloudFrame.lowRolls);
  in.box = grid.params;
  in.textures = cloudFrame.textures;
  graph.requestOutput(graph.add(mVolumeExport, in).grid, "cloud_volume");
  FrameResult result = graph.execute();
  return makeCloudVolume(setup.cloudScene, setup.lighting, time, view, grid,
                         std::move(result.output("cloud_volume").pixels));
}

}  // namespace sky
