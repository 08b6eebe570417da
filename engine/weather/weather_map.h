#pragma once
// The weather map the volumetric clouds read: a lat/lon grid over a region whose texels hold
// R = low-layer cover (Lu's CMc, 0..1), G = mid-layer cover, B = cloud type (0 stratiform,
// 0.5 cellular, 1 convective), A = density scale (1 = normal). Row 0 is the north edge,
// column 0 the west edge, equal lat/lon spacing, texel (i, j) centred at
// ((i + 0.5) / width, (j + 0.5) / height) of the region (engine/weather/geo.h regionUv).
// Every source (procedural, image, GRIB2/NetCDF forecast files) produces this.
// See docs/weather.md.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "engine/scene/scene.h"
#include "engine/weather/weather_fields.h"

namespace sky {

struct WeatherMap {
  WeatherRegion region;
  uint32_t width = 0, height = 0;  // texels
  std::vector<glm::vec4> texels;   // row-major, row 0 north
  // From forecast data (source "file") only, empty or absent otherwise: the high layer's
  // cover per texel (the volumetric clouds do not draw it), and the layers' altitudes above
  // sea level from the data, m: (low base, low top, mid base, mid top).
  std::vector<float> coverHigh;
  std::optional<glm::dvec4> layerAltitudesM;
  std::optional<glm::dvec2> highAltitudeM;  // the high layer's (base, top), m

  // Bilinear between texel centres, clamped at the edges (what a linear clamp-to-edge
  // sampler returns); points outside the region take the nearest edge. An empty map gives 0.
  glm::vec4 sample(double latDeg, double lonDeg) const;
  // The largest low (x) and mid (y) cover anywhere on the map: a layer whose maximum is 0 has
  // no clouds at all.
  glm::vec2 maxCover() const;
  const glm::vec4& at(uint32_t x, uint32_t y) const { return texels[size_t(y) * width + x]; }
};

// The type channel's value of a cloud type: stratus and altostratus 0 (stratiform),
// stratocumulus and altocumulus 0.5 (cellular), cumulus 1 (convective).
float cloudTypeValue(CloudType type);

// The map of `in.settings` over `region` (mapRegion(in) for the scene's own):
// "procedural" (fbm cover, see weather_map.cpp and docs/weather.md), "image" (the RGBA
// PNG/EXR `in.image` over the region) or "file" (a GRIB2/NetCDF forecast at the scene's
// start, through engine/weather/cloud_layers_from_fields.h).
// Bad settings or files are BadInput errors naming weather.<key> and the file.
WeatherMap makeWeatherMap(const WeatherInputs& in, const WeatherRegion& region);
// The same over the scene's region (weather_region.h mapRegion, clipped to a forecast's data).
WeatherMap makeWeatherMap(const WeatherInputs& in);

// The forecast file(s) of source "file" (`in.file`: weather.file resolved against the
// scene's folder), read whole: callers that render several times keep it and build each frame's map
// with weatherMapFromFields (engine/weather/cloud_layers_from_fields.h). A file name with
// '*' or '?' (e.g. "gfs.t00z.f0*.grib2") reads every matching file in that folder, sorted by
// name, and merges their steps by valid time; they must share one grid. BadInput naming
// weather.file for a missing, unknown or broken file, a pattern that matches nothing, grids
// that differ or two files with the same valid time.
WeatherFields readWeatherFile(const WeatherInputs& in);

// The files weather.file names (one, or a pattern's matches sorted by name); none when a
// pattern matches nothing.
std::vector<std::filesystem::path> weatherFiles(const WeatherInputs& in);

// The map's size: `weather.resolution` texels along the region's longer side in km, the
// other side in proportion (at least 2).
glm::uvec2 proceduralMapSize(const WeatherSettings& weather, const WeatherRegion& region);

}  // namespace sky
