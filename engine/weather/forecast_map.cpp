#include "engine/weather/forecast_map.h"

#include <string>

#include "engine/weather/cloud_layers_from_fields.h"

namespace sky {

std::vector<std::string> forecastFileOverrides(const std::filesystem::path& file) {
  std::string quoted;
  for (char c : std::filesystem::absolute(file).string())
    quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return {"weather.source=file", "weather.file=\"" + quoted + "\""};
}

ForecastMap forecastMap(const Scene& scene, WeatherSource& source) {
  ForecastMap out;
  // Without weather.region the map shows the file's whole grid.
  source.setWholeDataRegion(true);
  out.inputs = weatherInputs(scene);
  out.map = source.map(out.inputs, scene.time.start);
  out.timeUnix = weatherTimeUnix(out.inputs, scene.time.start);
  out.altitudes = layerAltitudeMaps(*source.fields(), out.timeUnix, scene.weather, out.map.region);

  const WeatherMap& map = out.map;
  LayeredImage& image = out.image;
  image.width = int(map.width);
  image.height = int(map.height);
  ImageLayer layer{"",
                   {"cover_low", "cover_mid", "cover_high", "type", "low_base_m", "low_top_m",
                    "mid_base_m", "mid_top_m", "high_base_m", "high_top_m"},
                   {},
                   true};  // FLOAT: altitudes in metres want more than half's 11 bits
  const size_t channels = layer.channels.size();
  layer.pixels.resize(map.texels.size() * channels);
  for (size_t i = 0; i < map.texels.size(); ++i) {
    float* p = &layer.pixels[i * channels];
    p[0] = map.texels[i].r;
    p[1] = map.texels[i].g;
    p[2] = map.coverHigh.empty() ? 0.0f : map.coverHigh[i];
    p[3] = map.texels[i].b;
    for (size_t a = 0; a < 6; ++a) p[4 + a] = out.altitudes[a][i];
  }
  image.layers.push_back(std::move(layer));
  if (map.layerAltitudesM && map.highAltitudeM) {
    const glm::dvec4& a = *map.layerAltitudesM;
    const double means[6] = {a.x, a.y, a.z, a.w, map.highAltitudeM->x, map.highAltitudeM->y};
    for (size_t i = 0; i < 6; ++i)
      image.attributes["skylayers:" + image.layers[0].channels[4 + i]] = std::to_string(means[i]);
  }
  return out;
}

}  // namespace sky
