#include "engine/render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/paths.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/context.h"
#include "engine/lighting/light_model.h"
#include "engine/render/camera.h"
#include "engine/render/frame_layers.h"
#include "engine/scene/scene_io.h"
#include "engine/weather/geo.h"

namespace sky {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

DebugImageInfo debugImageInfo(const GraphImage& g) {
  const ImageDesc& d = g.desc;
  return {g.name,
          g.writer,
          d.about,
          d.view,
          d.width,
          d.height,
          d.dim == ImageDim::Tex3D ? d.depth : 1u,
          d.format};
}

// A read-back debug image with what its view needs: how to show it, its channels' names and
// the pass that wrote it with that pass's GPU time.
DebugImage debugImage(const ReadbackImage& readback, const GraphImage& g,
                      const FrameResult& result) {
  DebugImage d;
  d.info = debugImageInfo(g);
  for (const PassTiming& t : result.passes)
    if (t.name == g.writer) d.gpuMs += t.gpuMs;
  d.image.width = static_cast<int>(readback.width * readback.depth);
  d.image.height = static_cast<int>(readback.height);
  d.image.layers.push_back(imageLayer(readback, "", channelNames(g.desc)));
  return d;
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

Renderer::Renderer(const Context& ctx, ShaderCompiler& compiler)
    : mRuntime(ctx),
      mStars(ctx, compiler, loadStarCatalog(configDir() / "stars" / "bright_star_catalogue.txt")),
      mHighCloudTextures(ctx, compiler, mRuntime),
      mAtmosphere(ctx, compiler),
      mSky(ctx, compiler),
      mClouds(ctx, compiler, mRuntime),
      mAmbient(ctx, compiler),
      mVolumetric(ctx, compiler),
      mShadow(ctx, compiler),
      mReuse(ctx, compiler),
      mUpsample(ctx, compiler),
      mLightVolume(ctx, compiler),
      mDisplay(ctx, compiler),
      mHostDepthSampler(ctx, SamplerWrap::Clamp, false),
      mSlice(ctx, compiler),
      mVolumeExport(ctx, compiler),
      mComposite(ctx, compiler) {
  FrameCosts c;
  c.rendererMs = msSince(mCreated);
  c.rendererPipelinesMs = pipelineBuildMs() - mPipelinesAtCreation;
  mConstruction = c;
}

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

// What every part of a frame's graph is built from: the scene, the time, the clouds' setup
// and the view.
struct Renderer::FrameInputs {
  const Scene& scene;
  const IsoTime& time;
  const CloudSetup& setup;
  shared::ViewState view;
  uint32_t width, height;
  bool physical, topDown;
  SharedFrame* shared;  // a frame of several views: what they share; null for one view
  // What the passes read of the frame, never write: the lights after the local weather, and
  // whether the weather map has low or mid cover.
  const LightingState& lighting;
  bool clouds;
};

// What the views of a frame of several share, made by the first view's passes.
struct Renderer::SharedFrame {
  std::optional<HighCloudTextures::Outputs> textures;
  std::optional<ImageId> highCover;
  std::optional<AtmosphereLuts::Outputs> luts;
  struct Clouds {
    CloudLayers::Frame frame;
    ImageId ambient;
    std::optional<CloudLightVolumePass::Outputs> volume;
    CloudShadowPass::Outputs shadow;
  };
  std::optional<Clouds> clouds;
};

// The sky, the high clouds and the stars of a frame, as the composite reads them.
struct Renderer::SkyImages {
  SkyHighCloudsPass::Outputs sky;
  AtmosphereLuts::Outputs luts{};
  std::optional<StarFieldPass::Outputs> stars;
  std::optional<double> highAltitudeM;  // a forecast's high layer (the middle of its gh range)
};

// The volumetric clouds of a frame at the view's size, their shadow map and their textures.
struct Renderer::CloudImages {
  ImageId clouds, depth;
  CloudShadowPass::Outputs shadow{};
  CloudLayers::Frame frame;
};

Renderer::SkyImages Renderer::addSky(FrameGraph& graph, const FrameInputs& f, RenderedFrame& out) {
  const Scene& scene = f.scene;
  const WeatherMap& weather = *f.setup.weather;
  SkyImages s;
  StarFieldPass::Frame stars;
  stars.view = f.view;
  stars.j2000ToEnu = glm::mat3(f.lighting.ephemeris.equatorialJ2000ToEnu);
  stars.extinction = static_cast<float>(scene.lighting.starExtinction);
  // No star passes by day: the brightest star over a pixel of this view against the sky.
  const glm::vec3 skyColor = glm::vec3(f.lighting.gpu.palette.sky);
  const double skyLuminance = 0.2126 * skyColor.r + 0.7152 * skyColor.g + 0.0722 * skyColor.b;
  const bool starsShow =
      f.lighting.dayFactor < 1.0 ||
      starsVisible(mStars.brightestVmag(), f.lighting.gpu.night.z,
                   double(f.view.forward.w) * double(f.view.forward.w), skyLuminance);
  s.stars = mStars.addTo(graph, stars, starsShow);

  // The high-cloud textures: kept from the last frame, loaded, or baked (before this graph).
  // With a forecast's high layer the cover comes from the map per pixel, at the data's
  // altitude (the middle of the layer's gh range).
  const bool highFromWeather = highCloudsFromWeather(scene, weather);
  const auto texturesStart = std::chrono::steady_clock::now();
  SharedFrame* shared = f.shared;
  const HighCloudTextures::Outputs textures =
      shared && shared->textures ? *shared->textures
                                 : mHighCloudTextures.addTo(graph, scene, highFromWeather);
  if (shared) shared->textures = textures;
  out.costs.texturesMs += msSince(texturesStart);
  out.highClouds = mHighCloudTextures.lastActivity();
  if (highFromWeather && weather.highAltitudeM)
    s.highAltitudeM = 0.5 * (weather.highAltitudeM->x + weather.highAltitudeM->y);

  SkyHighCloudsPass::Inputs sky{};
  const bool cloudsPresent = highFromWeather || scene.highClouds.source == HighCloudSource::Image ||
                             scene.highClouds.cover > 0.0;
  const ImageDesc& fine = graph.desc().resources[textures.coefficients.id].image;
  const ImageDesc& coarse = graph.desc().resources[textures.coarse.id].image;
  sky.params = skyHighCloudsParams(scene, f.lighting, f.time, f.view, cloudsPresent, fine.width,
                                   coarse.width, textures.mean, s.highAltitudeM);
  if (highFromWeather) {
    setRegionalCover(sky.params, scene, weather.region, textures);
    const ImageId cover =
        shared && shared->highCover ? *shared->highCover : mClouds.addHighCover(graph, weather);
    if (shared) shared->highCover = cover;
    sky.regional = {cover, &mClouds.weatherSampler(), textures.rankShape, textures.coverCoarse};
  }
  sky.lighting = f.lighting.gpu;
  sky.textures = {textures.coefficients, textures.normals, textures.coarse,
                  &mHighCloudTextures.sampler(), textures.levels};
  if (f.physical) {
    AtmosphereLuts::Frame a;
    a.atmosphere = physicalAtmosphere(scene);
    a.cameraAltitudeM = scene.camera.altitudeM;
    a.view = f.view;
    a.sunDirection = glm::vec3(f.lighting.sun.direction);
    a.moonDirection = glm::vec3(f.lighting.moon.direction);
    a.sunIlluminance = glm::vec3(f.lighting.gpu.sunSpace);
    a.moonIlluminance = glm::vec3(f.lighting.gpu.moonSpace);
    // The volumetric clouds' sky, from the middle of the low layer (where their sunlight is
    // taken too, cloudParams): seen from the ground, the low sky was a third dimmer and less
    // blue than the clouds see it, and a backlit core came out too dark and too warm against
    // Cycles lit by the sky at the clouds (docs/cloud-model.md).
    if (f.clouds) {
      const CloudSettings& c = f.setup.volumetric.clouds;
      a.cloudAltitudeM = 0.5 * (c.low.baseM + c.low.topM);
    }
    if (shared && shared->luts) {
      // Another view at the same place: its own aerial perspective, the same other LUTs.
      s.luts = *shared->luts;
      s.luts.aerialPerspective = mAtmosphere.addAerialPerspective(graph, s.luts, f.view);
    } else {
      s.luts = mAtmosphere.addTo(graph, a);
      if (shared) shared->luts = s.luts;
    }
    sky.physical = true;
    sky.atmosphere = {mAtmosphere.params(), s.luts.transmittance, s.luts.skyViewSun,
                      s.luts.skyViewMoon, &mAtmosphere.sampler()};
  }
  s.sky = graph.add(mSky, sky);
  return s;
}

Renderer::CloudImages Renderer::addClouds(FrameGraph& graph, const FrameInputs& f,
                                          const SkyImages& sky, RenderedFrame& out,
                                          bool& reuseStep) {
  const Scene& scene = f.scene;
  const Scene& cloudScene = f.setup.cloudScene;
  const CloudFrameGeometry& geometry = f.setup.geometry;
  CloudImages c;
  SharedFrame* shared = f.shared;
  const SharedFrame::Clouds* made = shared && shared->clouds ? &*shared->clouds : nullptr;
  const auto texturesStart = std::chrono::steady_clock::now();
  c.frame = made ? made->frame : mClouds.addTo(graph, cloudScene, f.time);
  out.costs.texturesMs += msSince(texturesStart);
  out.cloudNoise = mClouds.noiseActivity();
  // Temporal reuse: a sequence's frames march a share of the pixels and reproject the rest,
  // at the view's size or at half its width and height. Not in a frame of several views.
  const bool temporal = scene.clouds.temporal.mode == CloudTemporalMode::On &&
                        scene.clouds.quality == CloudQuality::Standard && !f.topDown && !shared;
  const bool half = temporal && scene.clouds.temporal.resolution == CloudTemporalResolution::Half;
  const uint32_t cloudWidth = half ? (f.width + 1) / 2 : f.width;
  const uint32_t cloudHeight = half ? (f.height + 1) / 2 : f.height;
  const shared::ViewState cloudView =
      half ? makeViewState(scene.camera, cloudWidth, cloudHeight) : f.view;
  VolumetricCloudsPass::Inputs in;
  in.params = cloudParams(f.setup.volumetric, f.lighting, f.time, cloudView, c.frame.maxCover,
                          c.frame.coverage, c.frame.noiseMeans);
  in.variant = cloudVariant(f.setup.volumetric, c.frame.lowRolls);
  in.lighting = f.lighting.gpu;
  in.textures = c.frame.textures;
  // The ambient light from the sky the frame draws (either model) and the ground under it.
  CloudAmbientPass::Inputs ambient;
  const bool dualLobe = in.variant.phase == CloudPhase::DualLobe;
  ambient.params = cloudAmbientParams({scene.ground.albedo, scene.lighting.turbidity,
                                       in.params.shellBaseM, f.lighting.overcast, in.params.g,
                                       in.params.gBack, dualLobe ? in.params.backWeight : 0.0f});
  ambient.lighting = f.lighting.gpu;
  ambient.moon = !moonLightNegligible(f.lighting.gpu);
  if (f.physical)
    ambient.atmosphere = CloudAmbientPass::Atmosphere{
        mAtmosphere.cloudParams(), sky.luts.transmittance, sky.luts.skyViewSunClouds,
        sky.luts.skyViewMoonClouds, &mAtmosphere.sampler()};
  in.ambient = made ? made->ambient : graph.add(mAmbient, ambient).ambient;
  std::optional<CloudLightVolumePass::Outputs> lightVolume;
  // What the light volume and the shadow map are made from: kept while it holds.
  CloudFieldKey field;
  field.settings = mFieldSettings.of(cloudScene);
  field.mapRevision = mClouds.mapRevision();
  field.camera = glm::dvec3(geometry.latDeg, geometry.lonDeg, geometry.altitudeM);
  field.sun = glm::vec3(in.params.sunDirection);
  field.moon = glm::vec3(in.params.moonDirection);
  field.lights =
      (in.params.sunMarched != 0.0f ? 1u : 0u) | (in.params.moonMarched != 0.0f ? 2u : 0u);
  field.drift = cloudWindDriftM(scene.clouds, f.time.secondsSince(scene.time.start));
  // The light through the clouds from the light volume (the reference marches it).
  if (in.variant.light == CloudLight::Volume) {
    CloudLightVolumePass::Inputs v;
    v.params = in.params;
    v.variant = in.variant;
    v.params.lightVolume = cloudLightVolumePlace(in.params, geometry.altitudeM);
    v.textures = in.textures;
    v.key = field;
    const CloudLightVolumePass::Outputs volume =
        made && made->volume ? *made->volume : mLightVolume.addTo(graph, v);
    if (shared) lightVolume = volume;
    in.params.lightVolume = volume.place;
    in.lightVolume = volume.volume;
    in.lightVolumeSampler = &mLightVolume.sampler();
  }
  std::optional<CloudReuse::Step> step;
  if (temporal) {
    step = mReuse.step(scene, f.time, cloudView, mClouds.mapRevision());
    in.params.marchBlock = step->block;
    in.params.marchOffsetX = step->offset.x;
    in.params.marchOffsetY = step->offset.y;
    // A new jitter every frame, so a pixel marched again averages differently.
    in.params.frameIndex =
        (in.params.frameIndex + static_cast<uint32_t>(step->frame) * 0x9E3779B9u) & 0x7fffffffu;
  }
  const VolumetricCloudsPass::Outputs marched = graph.add(mVolumetric, in);
  c.clouds = marched.clouds;
  c.depth = marched.depth;
  if (temporal) {
    const CloudTemporalPass::Outputs resolved =
        mReuse.addTo(graph, *step, c.clouds, c.depth,
                     {in.params.geo.origin.w, scene.camera.altitudeM, in.params.shellBaseM,
                      in.params.shellTopM});
    c.clouds = resolved.clouds;
    c.depth = resolved.depth;
    reuseStep = true;
  }
  if (half) {
    CloudUpsamplePass::Inputs u;
    u.params.view = f.view;
    u.params.source = cloudView;
    u.params.planetRadiusM = in.params.geo.origin.w;
    u.params.cameraAltitudeM = static_cast<float>(scene.camera.altitudeM);
    u.params.shellBaseM = in.params.shellBaseM;
    u.params.shellTopM = in.params.shellTopM;
    u.clouds = c.clouds;
    u.depth = c.depth;
    const CloudUpsamplePass::Outputs full = graph.add(mUpsample, u);
    c.clouds = full.clouds;
    c.depth = full.depth;
  }
  // The clouds' shadows on the ground around the observer (a top-down render draws no
  // ground, but the composite's cloud variant binds a map all the same).
  if (made) {
    c.shadow = made->shadow;
  } else {
    c.shadow =
        mShadow.addTo(graph, CloudShadowPass::Inputs{in.params, in.variant,
                                                     cloudShadowMap(in.params, geometry.altitudeM),
                                                     in.textures, field});
    // A cut through the density field for the debug view: culled unless it is asked for.
    graph.add(mSlice, CloudDensitySlicePass::Inputs{in.params, in.variant, in.textures});
    if (shared) shared->clouds = SharedFrame::Clouds{c.frame, in.ambient, lightVolume, c.shadow};
  }
  out.cloudShadow = c.shadow.map;
  return c;
}

Renderer::FramePlan Renderer::buildFrame(FrameGraph& graph, const Scene& scene, const IsoTime& time,
                                         const RenderOptions& options, RenderedFrame& out,
                                         SharedFrame* shared) {
  const CloudSetup setup = cloudSetup(scene, time);
  const WeatherMap& weather = *setup.weather;
  out.lighting = setup.lighting;
  out.localWeather = setup.localWeather;
  out.weatherRegion = weather.region;
  out.weatherTexels = glm::uvec2(weather.width, weather.height);
  const glm::vec2 maxCover = weather.maxCover();
  out.clouds = maxCover.x > 0.0f || maxCover.y > 0.0f;
  const uint32_t width = static_cast<uint32_t>(scene.output.width);
  const uint32_t height = static_cast<uint32_t>(scene.output.height);
  const FrameInputs f{scene,
                      time,
                      setup,
                      makeViewState(scene.camera, width, height),
                      width,
                      height,
                      scene.sky.model == SkyModel::Physical,
                      setup.geometry.topDown,
                      shared,
                      setup.lighting,
                      out.clouds};
  FramePlan plan;
  const SkyImages sky = addSky(graph, f, out);
  std::optional<CloudImages> clouds;
  if (out.clouds) clouds = addClouds(graph, f, sky, out, plan.reuseStep);

  AtmosphereCompositeSettings compositeSettings;
  compositeSettings.ground = scene.ground;
  compositeSettings.planetRadiusM = skyPlanetRadiusM(scene);
  compositeSettings.cameraAltitudeM = scene.camera.altitudeM;
  compositeSettings.turbidity = scene.lighting.turbidity;
  compositeSettings.observer = !f.topDown;
  // High clouds lie in front of the volumetric ones when the camera flies above them.
  compositeSettings.aboveHighClouds =
      !f.topDown && scene.camera.altitudeM > sky.highAltitudeM.value_or(scene.highClouds.altitudeM);
  compositeSettings.belowClouds = scene.camera.altitudeM < setup.volumetric.clouds.low.baseM;
  AtmosphereCompositePass::Inputs composite{};
  composite.params = atmosphereCompositeParams(compositeSettings, f.lighting, f.view);
  if (clouds)
    composite.clouds = AtmosphereCompositePass::Clouds{clouds->clouds,
                                                       clouds->depth,
                                                       clouds->shadow.shadow,
                                                       clouds->shadow.map,
                                                       clouds->frame.textures.weatherSampler,
                                                       compositeSettings.belowClouds};
  if (f.physical)
    composite.atmosphere =
        AtmosphereCompositePass::Atmosphere{mAtmosphere.params(), sky.luts.transmittance,
                                            sky.luts.aerialPerspective, &mAtmosphere.sampler()};
  composite.lighting = f.lighting.gpu;
  if (sky.stars) composite.starFlux = sky.stars->flux;
  composite.sky = sky.sky.sky;
  composite.highClouds = sky.sky.highClouds;
  if (const HostTarget* host = options.host) {
    AtmosphereCompositePass::Host h;
    h.colour = graph.importExternal(*host->colour, host->colourLayout);
    h.colourFormat = host->colour->image.desc().format;
    if (host->depth) h.depth = graph.importExternal(*host->depth, host->depthLayout);
    h.depthMapping = host->depthMapping;
    h.depthSampler = &mHostDepthSampler;
    composite.host = h;
  }
  plan.beauty = graph.add(mComposite, composite).beauty;
  plan.sky = sky.sky.sky;
  plan.highClouds = sky.sky.highClouds;
  if (clouds) {
    plan.clouds = clouds->clouds;
    plan.cloudsDepth = clouds->depth;
  }
  if (options.gpuDisplay && !options.host) {
    if (scene.output.exposure == ExposureMode::Histogram)
      internalError("the GPU display path has no histogram exposure (it meters the frame)");
    DisplayTransformPass::Inputs d;
    d.settings = {options.gpuDisplay, scene.output.display, scene.output.view,
                  (scene.output.exposure == ExposureMode::Auto ? f.lighting.nightLiftEv : 0.0) +
                      scene.output.exposureEv,
                  scene.output.nightLook};
    d.beauty = plan.beauty;
    d.width = width;
    d.height = height;
    if (PersistentImage* target = options.displayTarget) {
      const ImageDesc& t = target->image.desc();
      if (t.format != VK_FORMAT_R8G8B8A8_UNORM || t.width != width || t.height != height ||
          !(t.usage & VK_IMAGE_USAGE_STORAGE_BIT))
        internalError("RenderOptions::displayTarget is not an RGBA8 storage image of the " +
                      std::to_string(width) + "x" + std::to_string(height) + " output");
      d.target = graph.importExternal(*target, options.displayTargetLayout);
    }
    out.displayEv = d.settings.exposureEv;
    plan.display = mDisplay.addTo(graph, d).display;
  }
  if (f.topDown && options.readBack == ReadBack::Layers) plan.weather = &weather;
  return plan;
}

void Renderer::requestOutputs(FrameGraph& graph, FramePlan& plan, const RenderOptions& options,
                              const std::string& prefix) {
  FramePlan::Outputs& o = plan.outputs;
  if (options.readBack != ReadBack::Display)
    o.beauty = graph.requestOutput(plan.beauty, prefix + "beauty");
  if (options.readBack == ReadBack::Layers) {
    o.sky = graph.requestOutput(plan.sky, prefix + "sky");
    o.highClouds = graph.requestOutput(plan.highClouds, prefix + "high_clouds");
    if (plan.clouds.valid()) {
      o.clouds = graph.requestOutput(plan.clouds, prefix + "clouds");
      o.cloudsDepth = graph.requestOutput(plan.cloudsDepth, prefix + "clouds_depth");
    }
  }
  if (plan.display.valid() && !options.displayTarget)
    o.display = graph.requestOutput(plan.display, prefix + "display");
  // The debug images, by the names their passes gave them (the graph is the registry).
  std::vector<std::string> names = options.debugOutputs;
  if (options.allDebugOutputs)
    for (const GraphImage& image : graph.images())
      if (std::find(names.begin(), names.end(), image.name) == names.end())
        names.push_back(image.name);
  for (const std::string& name : names) {
    const GraphImage image = graph.image(name);
    o.debug.emplace_back(graph.requestOutput(image, prefix + "debug " + name), image);
  }
}

void Renderer::collectOutputs(RenderedFrame& out, const FrameResult& result,
                              const FrameGraph& graph, const FramePlan& plan,
                              const RenderOptions& options) {
  const FramePlan::Outputs& o = plan.outputs;
  const uint32_t width = graph.desc().resources[plan.beauty.id].image.width;
  const uint32_t height = graph.desc().resources[plan.beauty.id].image.height;
  out.image.width = static_cast<int>(width);
  out.image.height = static_cast<int>(height);
  if (options.readBack != ReadBack::Display)
    out.image.layers.push_back(beautyLayer(result.output(o.beauty)));
  if (options.readBack == ReadBack::Layers) {
    const bool clouds = o.clouds.valid();
    appendAovLayers(out.image, result.output(o.sky), result.output(o.highClouds),
                    clouds ? &result.output(o.clouds) : nullptr,
                    clouds ? &result.output(o.cloudsDepth) : nullptr);
    if (plan.weather)
      out.image.layers.push_back(
          weatherCoverLayer(*plan.weather, plan.weather->region, width, height));
  }
  for (const GraphImage& g : graph.images()) out.images.push_back(debugImageInfo(g));
  for (const auto& [id, image] : o.debug)
    out.debug.push_back(debugImage(result.output(id), image, result));
  if (o.display.valid()) {
    const std::vector<float>& codes = result.output(o.display).pixels;
    out.display.resize(codes.size());
    for (size_t i = 0; i < codes.size(); ++i)
      out.display[i] = static_cast<uint8_t>(std::lround(codes[i] * 255.0f));
  }
}

RenderedFrame Renderer::render(const Scene& scene, const IsoTime& time,
                               const RenderOptions& options) {
  if (options.readBack == ReadBack::Display && !options.gpuDisplay)
    internalError("ReadBack::Display without RenderOptions::gpuDisplay");
  if (options.displayTarget && (options.readBack != ReadBack::Display || options.host))
    internalError("RenderOptions::displayTarget without ReadBack::Display, or with a host target");
  const auto start = std::chrono::steady_clock::now();
  const double pipelinesBefore = pipelineBuildMs();
  RenderedFrame out;
  FrameGraph graph(mRuntime);
  FramePlan plan = buildFrame(graph, scene, time, options, out);
  try {
    if (options.host) {
      out.frame = graph.record(options.host->cmd);
    } else {
      requestOutputs(graph, plan, options);
      out.frame = graph.execute();
    }
  } catch (...) {
    mLightVolume.invalidate();  // they may not have been made
    mShadow.invalidate();
    throw;
  }
  if (plan.reuseStep) mReuse.commit();
  out.graphDot = graph.toDot(&out.frame);
  if (!options.host) {
    collectOutputs(out, out.frame, graph, plan, options);
    for (ReadbackImage& o : out.frame.outputs) o.pixels = {};  // the layers hold the data now
  }
  finishCosts(out, start, pipelinesBefore);
  return out;
}

void Renderer::finishCosts(RenderedFrame& out, std::chrono::steady_clock::time_point start,
                           double pipelinesBefore) {
  for (const PassTiming& t : out.frame.passes)
    if (t.name == AtmosphereLuts::kTransmittanceName ||
        t.name == AtmosphereLuts::kMultiScatteringName)
      out.costs.lutBakeGpuMs += t.gpuMs;
  out.costs.pipelinesMs = pipelineBuildMs() - pipelinesBefore;
  out.costs.renderMs = msSince(start);
  if (mConstruction) {
    out.costs.rendererMs = mConstruction->rendererMs;
    out.costs.rendererPipelinesMs = mConstruction->rendererPipelinesMs;
    mConstruction.reset();
  }
}

std::vector<RenderedFrame> Renderer::render(const Scene& scene, const IsoTime& time,
                                            const std::vector<FrameView>& views,
                                            const RenderOptions& options) {
  if (views.empty()) inputError("render: no view to render");
  if (scene.camera.mode != CameraMode::Observer)
    inputError("render: several views need an observer camera (camera.mode observer)");
  if (options.gpuDisplay || options.displayTarget || options.host ||
      !options.debugOutputs.empty() || options.allDebugOutputs)
    internalError("a frame of several views has no GPU display, host target or debug output");
  const auto start = std::chrono::steady_clock::now();
  const double pipelinesBefore = pipelineBuildMs();
  std::vector<RenderedFrame> outs(views.size());
  std::vector<FramePlan> plans;
  FrameGraph graph(mRuntime);
  SharedFrame shared;
  for (size_t i = 0; i < views.size(); ++i) {
    const FrameView& v = views[i];
    if (v.width == 0 || v.height == 0)
      inputError("render: view " + std::to_string(i) + " has no size");
    Scene view = scene;
    view.camera.heading = v.headingDeg;
    view.camera.pitch = v.pitchDeg;
    view.camera.roll = v.rollDeg;
    view.camera.verticalFov = v.verticalFovDeg;
    view.camera.projection = v.projection;
    view.output.width = static_cast<int>(v.width);
    view.output.height = static_cast<int>(v.height);
    // Each view's images by their names, "view1/beauty" after the first view's "beauty".
    graph.setNamePrefix(i == 0 ? "" : "view" + std::to_string(i) + "/");
    plans.push_back(buildFrame(graph, view, time, options, outs[i], &shared));
  }
  graph.setNamePrefix("");
  const auto label = [](size_t i) {
    return i == 0 ? std::string() : "view" + std::to_string(i) + "/";
  };
  FrameResult result;
  try {
    for (size_t i = 0; i < views.size(); ++i) requestOutputs(graph, plans[i], options, label(i));
    result = graph.execute();
  } catch (...) {
    mLightVolume.invalidate();
    mShadow.invalidate();
    throw;
  }
  // The views marched every pixel; a later sequence frame starts afresh.
  mReuse.invalidate();
  const std::string dot = graph.toDot(&result);
  // Each view holds the frame's timings; its images come from the one read-back, not copies.
  FrameResult timings = result;
  timings.outputs.clear();
  for (size_t i = 0; i < views.size(); ++i) {
    outs[i].frame = timings;
    collectOutputs(outs[i], result, graph, plans[i], options);
    outs[i].graphDot = dot;
    finishCosts(outs[i], start, pipelinesBefore);
  }
  return outs;
}

std::vector<DebugImageInfo> Renderer::debugImages(const Scene& scene, const IsoTime& time,
                                                  const RenderOptions& options) {
  RenderedFrame out;
  FrameGraph graph(mRuntime);
  buildFrame(graph, scene, time, options, out);
  // Built, never run: what the light volume and the shadow map think they hold is not made.
  mLightVolume.invalidate();
  mShadow.invalidate();
  std::vector<DebugImageInfo> list;
  for (const GraphImage& g : graph.images()) list.push_back(debugImageInfo(g));
  return list;
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
                          cloudFrame.coverage, cloudFrame.noiseMeans);
  in.variant = cloudVariant(setup.volumetric, cloudFrame.lowRolls);
  in.box = grid.params;
  in.textures = cloudFrame.textures;
  graph.requestOutput(graph.add(mVolumeExport, in).grid, "cloud_volume");
  FrameResult result = graph.execute();
  return makeCloudVolume(setup.cloudScene, setup.lighting, time, view, grid,
                         std::move(result.output("cloud_volume").pixels));
}

CloudField Renderer::cloudField(const Scene& scene, const IsoTime& time) {
  const CloudSetup setup = cloudSetup(scene, time);
  if (setup.geometry.topDown)
    inputError(
        "cloud queries: camera.mode geographic_topdown has no observer to place the clouds "
        "around (use camera.mode observer)");
  CloudFieldInputs in;
  in.camera = {setup.geometry.latDeg, setup.geometry.lonDeg, setup.geometry.altitudeM};
  in.weather = *setup.weather;
  in.air = atmosphereParams(physicalAtmosphere(scene));
  const glm::vec2 maxCover = setup.weather->maxCover();
  in.anyCover = maxCover.x > 0.0f || maxCover.y > 0.0f;
  if (in.anyCover) {
    // As exportCloudVolume: the textures and tables a frame would import, then the
    // raymarch's own uniforms.
    FrameGraph graph(mRuntime);
    const CloudLayers::Frame cloudFrame = mClouds.addTo(graph, setup.cloudScene, time);
    const shared::ViewState view =
        makeViewState(scene.camera, static_cast<uint32_t>(scene.output.width),
                      static_cast<uint32_t>(scene.output.height));
    in.params = cloudParams(setup.volumetric, setup.lighting, time, view, cloudFrame.maxCover,
                            cloudFrame.coverage, cloudFrame.noiseMeans);
    const CloudVariant variant = cloudVariant(setup.volumetric, cloudFrame.lowRolls);
    in.tang = variant.model == CloudModel::Tang2019;
    in.calibrated = variant.coverage == CloudCoverageMode::Calibrated;
    in.rolls = variant.rolls == CloudRolls::On;
    in.shape = mClouds.noise().shapeVolume();
    in.detail = mClouds.noise().detailVolume();
    in.curl = mClouds.noise().curlPlane();
  }
  return CloudField(std::move(in));
}

}  // namespace sky
