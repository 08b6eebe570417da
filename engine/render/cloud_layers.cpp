#include "engine/render/cloud_layers.h"

#include <algorithm>
#include <sstream>

#include "engine/clouds/cloud_math.h"
#include "engine/clouds/coverage_calibration.h"
#include "engine/weather/cloud_layers_from_fields.h"
#include "engine/weather/weather_region.h"

namespace sky {

static_assert(clouds::kCoverageLutSize == CLOUD_COVERAGE_LUT_SIZE &&
                  clouds::kFarMeanCovers == CLOUD_FAR_MEAN_COVERS &&
                  clouds::kFarMeanHeights == CLOUD_FAR_MEAN_HEIGHTS,
              "the calibration's tables are the shader's (volumetric_clouds_shared.h)");

VolumetricCloudsSettings volumetricCloudsSettings(const Scene& cloudScene) {
  VolumetricCloudsSettings s;
  s.clouds = cloudScene.clouds;
  s.region = resolvedRegion(cloudScene.weather);
  s.cameraLatDeg = cloudScene.camera.latitude;
  s.cameraLonDeg = cloudScene.camera.longitude;
  s.cameraAltitudeM = cloudScene.camera.altitudeM;
  s.topDown = cloudScene.camera.mode == CameraMode::GeographicTopdown;
  s.timeStart = cloudScene.time.start;
  s.turbidity = cloudScene.lighting.turbidity;
  return s;
}

CloudLayers::CloudLayers(const Context& ctx, ShaderCompiler& compiler, GraphRuntime& runtime)
    : mNoise(ctx, compiler, runtime), mWeather(ctx) {}

const WeatherMap& CloudLayers::weatherMap(const Scene& scene, const IsoTime& time) {
  const uint64_t before = mSource.revision();
  const WeatherMap& map = mSource.map(weatherInputs(scene), time);
  if (mSource.revision() != before) ++mMapRevision;
  return map;
}

CoverageTables CloudLayers::coverageTables(const Scene& scene, const WeatherMap& map) {
  const CloudSettings& c = scene.clouds;
  CoverageTables tables{};
  // Until calibrated (and for the paper's remap) each entry is Lu's 1 - CMc.
  for (auto& layer : tables.thresholds)
    for (auto& type : layer)
      for (int i = 0; i < CLOUD_COVERAGE_LUT_SIZE; ++i)
        type[static_cast<size_t>(i)] = 1.0f - static_cast<float>(i) / (CLOUD_COVERAGE_LUT_SIZE - 1);
  mLastCalibrations = 0;
  if (c.coverage != CloudCoverageMode::Calibrated) return tables;

  // Only the layers with cover, and only the type keys the map comes near.
  const glm::vec2 maxCover = map.maxCover();
  bool typeUsed[CLOUD_COVERAGE_TYPE_KEYS] = {};
  for (const glm::vec4& t : map.texels) {
    const float k = glm::clamp(t.b, 0.0f, 1.0f) * (CLOUD_COVERAGE_TYPE_KEYS - 1);
    typeUsed[static_cast<int>(std::floor(k))] = true;
    typeUsed[std::min(static_cast<int>(std::ceil(k)), CLOUD_COVERAGE_TYPE_KEYS - 1)] = true;
  }
  for (int layer = 0; layer < 2; ++layer) {
    if ((layer == 0 ? maxCover.x : maxCover.y) <= 0.0f) continue;
    const CloudLayerSettings& l = layer == 0 ? c.low : c.mid;
    for (int k = 0; k < CLOUD_COVERAGE_TYPE_KEYS; ++k) {
      if (!typeUsed[k]) continue;
      clouds::CoverageColumn column;
      column.thicknessM = l.topM - l.baseM;
      column.shapeScaleM = c.shapeScaleKm * 1000.0;
      column.detailScaleM = c.detailScaleKm * 1000.0;
      column.extinction = c.extinction;
      column.type = static_cast<float>(k) / (CLOUD_COVERAGE_TYPE_KEYS - 1);
      column.typeRange = clouds::cloudTypeRange(layer, column.type);
      column.model = c.model;
      // As the shader does in calibrated mode (shaders/common/cloud_field.glsl): Lu's height
      // profile and erosion at full cover, the cover carried by the threshold alone.
      column.profileCover = 1.0f;
      // And as it does for the type: the fine structure kept, the boundary sharpened with it.
      column.textureKeep = clouds::cloudTypeTexture(column.type);
      column.edgeSharpness =
          glm::mix(1.0f, static_cast<float>(c.edgeSharpness), column.textureKeep);
      // And the cumulus' outline, profile and billows (cumulusShape, cumulusCloudDensity).
      column.cumulus = clouds::cloudCumulusWeight(column.type);
      std::ostringstream key;
      key.precision(17);
      key << enumName(column.model) << '|' << layer << '|' << column.type << '|'
          << column.thicknessM << '|' << column.shapeScaleM << '|' << column.detailScaleM << '|'
          << column.extinction << '|' << column.profileCover << '|' << column.edgeSharpness << '|'
          << column.textureKeep << '|' << column.cumulus;
      auto it = mLuts.find(key.str());
      if (it == mLuts.end()) {
        Calibration calibration;
        calibration.thresholds =
            clouds::calibrateCoverage(mNoise.shapeVolume(), mNoise.detailVolume(), column);
        calibration.farMean = clouds::farMeanDensity(mNoise.shapeVolume(), mNoise.detailVolume(),
                                                     column, calibration.thresholds);
        it = mLuts.emplace(key.str(), calibration).first;
        ++mLastCalibrations;
      }
      const size_t li = static_cast<size_t>(layer), ti = static_cast<size_t>(k);
      std::copy(it->second.thresholds.begin(), it->second.thresholds.end(),
                tables.thresholds[li][ti].begin());
      tables.farMean[li][ti] = it->second.farMean;
    }
  }
  return tables;
}

CloudLayers::Frame CloudLayers::addTo(FrameGraph& graph, const Scene& scene, const IsoTime& time) {
  const WeatherMap& map = weatherMap(scene, time);
  Frame f;
  const CloudNoise::Outputs noise = mNoise.addTo(graph, scene.clouds.model);
  const WeatherTextures::Clouds weather = mWeather.addClouds(graph, map, mMapRevision);
  f.textures = {noise.shape, noise.detail,   noise.curl,         &mNoise.sampler(),
                weather.map, weather.coarse, &mWeather.sampler()};
  f.coverage = coverageTables(scene, map);
  f.noiseMeans = {mNoise.shapeMean(), mNoise.detailMean()};
  f.maxCover = map.maxCover();
  for (const glm::vec4& t : map.texels) {
    f.lowRolls = f.lowRolls || (t.r > 0.0f && clouds::cloudRollWeight(0, t.b) > 0.0f);
    f.cumulus =
        f.cumulus || ((t.r > 0.0f || t.g > 0.0f) && clouds::cloudCumulusWeight(t.b) > 0.0f);
  }
  return f;
}

}  // namespace sky
