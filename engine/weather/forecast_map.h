#pragma once
// A forecast file's cloud map as `skyrender weather` writes it and the public API's
// weatherMap returns it: the map the renderer would draw at the scene's first instant
// (weather.time, advection and evolution included), over weather.region or, without one,
// the file's whole grid, with each layer's base and top altitude per texel.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/io/exr.h"
#include "engine/scene/scene.h"
#include "engine/weather/weather_map.h"
#include "engine/weather/weather_source.h"

namespace sky {

struct ForecastMap {
  WeatherInputs inputs;
  double timeUnix = 0.0;  // the forecast instant the map is for
  WeatherMap map;
  // Per texel, m above sea level: low base, low top, mid base, mid top, high base, high top.
  std::array<std::vector<float>, 6> altitudes;
  // One layer of FLOAT channels cover_low, cover_mid, cover_high, type, low_base_m, low_top_m,
  // mid_base_m, mid_top_m, high_base_m, high_top_m (row 0 north), and the layers' region
  // mean altitudes, which the renderer uses, as "skylayers:<channel>" attributes.
  LayeredImage image;
};

// The overrides that read `file` as the scene's forecast: weather.source file and
// weather.file, its absolute path quoted so any path reads as a YAML string.
std::vector<std::string> forecastFileOverrides(const std::filesystem::path& file);

// `scene` must have weather.source file. `source` reads the file and keeps its fields
// (source.fields()) for the caller. BadInput naming weather.<key> and the file.
ForecastMap forecastMap(const Scene& scene, WeatherSource& source);

}  // namespace sky
