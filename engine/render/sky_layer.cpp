#include "engine/render/sky_layer.h"

#include <chrono>

#include "engine/core/paths.h"
#include "engine/lighting/light_model.h"
#include "engine/render/camera.h"
#include "engine/weather/weather_map.h"

namespace sky {

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

SkyLayer::SkyLayer(const Context& ctx, ShaderCompiler& compiler, GraphRuntime& runtime,
                   CloudLayers& weather)
    : mWeather(weather),
      mStars(ctx, compiler, loadStarCatalog(configDir() / "stars" / "bright_star_catalogue.txt")),
      mHighCloudTextures(ctx, compiler, runtime),
      mAtmosphere(ctx, compiler),
      mSky(ctx, compiler) {}

void SkyLayer::setBakeProgress(std::function<void(double)> progress) {
  mHighCloudTextures.setProgress(std::move(progress));
}

SkyLayer::Images SkyLayer::addTo(FrameGraph& graph, const FrameInputs& f) {
  const Scene& scene = f.scene;
  const WeatherMap& weather = *f.setup.weather;
  Images s;
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
  s.texturesMs = msSince(texturesStart);
  s.highClouds = mHighCloudTextures.lastActivity();
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
        shared && shared->highCover ? *shared->highCover : mWeather.addHighCover(graph, weather);
    if (shared) shared->highCover = cover;
    sky.regional = {cover, &mWeather.weatherSampler(), textures.rankShape, textures.coverCoarse};
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

}  // namespace sky
