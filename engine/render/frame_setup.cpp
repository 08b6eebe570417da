#include "engine/render/frame_setup.h"

#include <chrono>

#include "engine/render/frame_inputs.h"

namespace sky {

FrameSetup frameSetup(CloudLayers& weather, const Scene& scene, const IsoTime& time) {
  const WeatherMap& map = weather.weatherMap(scene, time);
  FrameSetup s{scene, {}, {}, {}, {}, &map};
  // The map's region, resolved from the camera when the scene gives none.
  s.cloudScene.weather.region = map.region;
  // A forecast file places the layers at the altitudes of its pressure levels (from gh); the
  // scene's clouds.low/mid apply otherwise.
  if (map.layerAltitudesM) {
    const glm::dvec4& a = *map.layerAltitudesM;
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
      localWeather(map, s.geometry.latDeg, s.geometry.lonDeg, scene.weather.localRadiusKm);
  applyOvercast(s.lighting, scene.sky, s.localWeather.overcast);
  return s;
}

CloudFieldFrame cloudFieldFrame(FrameGraph& graph, CloudLayers& weather, const FrameSetup& setup,
                                const IsoTime& time, const shared::ViewState& view,
                                uint64_t settingsRevision, const CloudLayers::Frame* made) {
  CloudFieldFrame c;
  const auto start = std::chrono::steady_clock::now();
  c.frame = made ? *made : weather.addTo(graph, setup.cloudScene, time);
  c.texturesMs = msSince(start);
  c.params = cloudParams(setup.volumetric, setup.lighting, time, view, c.frame.maxCover,
                         c.frame.coverage, c.frame.noiseMeans);
  c.variant = cloudVariant(setup.volumetric, c.frame.lowRolls, c.frame.cumulus);
  const Scene& scene = setup.cloudScene;
  c.key.settings = settingsRevision;
  c.key.mapRevision = weather.mapRevision();
  c.key.camera = glm::dvec3(setup.geometry.latDeg, setup.geometry.lonDeg, setup.geometry.altitudeM);
  c.key.sun = glm::vec3(c.params.sunDirection);
  c.key.moon = glm::vec3(c.params.moonDirection);
  c.key.lights =
      (c.params.sunMarched != 0.0f ? 1u : 0u) | (c.params.moonMarched != 0.0f ? 2u : 0u);
  c.key.drift = cloudWindDriftM(scene.clouds, time.secondsSince(scene.time.start));
  return c;
}

}  // namespace sky
