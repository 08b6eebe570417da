#pragma once
// What the volumetric clouds need besides their pass, kept across frames: the baked noise
// (passes/cloud_noise), the weather map built from the scene (engine/weather) and put on the
// GPU (WeatherTextures), and the calibrated coverage tables (engine/clouds), each remade only
// when its inputs change.
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "engine/clouds/coverage_calibration.h"
#include "engine/render/weather_textures.h"
#include "engine/weather/weather_map.h"
#include "engine/weather/weather_source.h"
#include "passes/cloud_noise/cloud_noise.h"
#include "passes/cloud_field/cloud_field.h"

namespace sky {

// The volumetric pass's settings from `cloudScene`, the scene with the weather map's region
// and a forecast's layer altitudes filled in (as the renderer makes it for each frame).
// Internal error when the scene has no weather.region.
VolumetricCloudsSettings volumetricCloudsSettings(const Scene& cloudScene);

class CloudLayers {
public:
  CloudLayers(const Context& ctx, ShaderCompiler& compiler, GraphRuntime& runtime);

  // The weather map of `scene` in the frame at `time` (engine/weather/weather_source.h: rebuilt
  // only when its settings, files or, for a map that moves, the time change). BadInput for bad
  // settings or files, naming weather.<key>.
  const WeatherMap& weatherMap(const Scene& scene, const IsoTime& time);
  const WeatherSource& weatherSource() const { return mSource; }
  // Counts the weather maps weatherMap() has built: a texture of the map is current while
  // this is unchanged.
  uint64_t mapRevision() const { return mMapRevision; }

  struct Frame {
    CloudTextures textures;
    CoverageTables coverage{};
    NoiseMeans noiseMeans;
    glm::vec2 maxCover{0.0f};
    bool lowRolls = false;  // some low cloud of the map has rolls (cloudRollWeight)
    bool cumulus = false;   // some cloud of the map is cumulus (cloudCumulusWeight)
  };
  // Imports the noise and weather textures into `graph` (baking or loading the noise on first
  // use of a model) and returns them with the coverage tables for `scene`. Call only when
  // weatherMap(scene) has cover.
  Frame addTo(FrameGraph& graph, const Scene& scene, const IsoTime& time);
  // The high layer's cover of the last weatherMap() `map` on the GPU (WeatherTextures), for
  // the high clouds' regional cover. Internal error when the map has no high layer.
  ImageId addHighCover(FrameGraph& graph, const WeatherMap& map) {
    return mWeather.addHighCover(graph, map, mMapRevision);
  }
  // The sampler of the weather textures (linear, clamp to edge).
  const Sampler& weatherSampler() const { return mWeather.sampler(); }

  const CloudNoise::Activity& noiseActivity() const { return mNoise.lastActivity(); }
  // The noise as it is now (its CPU copies: engine/render/cloud_field.h reads them).
  const CloudNoise& noise() const { return mNoise; }
  // How many coverage tables were calibrated in the last addTo (0 when cached).
  int lastCalibrations() const { return mLastCalibrations; }

private:
  CoverageTables coverageTables(const Scene& scene, const WeatherMap& map);

  CloudNoise mNoise;
  WeatherTextures mWeather;
  WeatherSource mSource;
  uint64_t mMapRevision = 0;
  struct Calibration {
    clouds::CoverageLut thresholds{};
    clouds::FarMeanTable farMean{};
  };
  std::map<std::string, Calibration> mLuts;  // by model, layer, type and column
  int mLastCalibrations = 0;
};

}  // namespace sky
