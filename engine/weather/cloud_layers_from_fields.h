#pragma once
// Cloud layers from forecast fields (Lu et al. 2023, section 3): per layer (low, mid, high) of
// pressure levels, cover from relative humidity by Lu (1) with Lu (2)'s critical humidity, or
// the model's own layer cloud cover; the layers' altitudes from geopotential height; and the
// resampling of a field on the file's grid onto the weather map's lat/lon texels. The result
// is the same WeatherMap the procedural and image sources give. See docs/weather.md,
// "From forecast data".
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "engine/scene/scene.h"
#include "engine/weather/weather_fields.h"
#include "engine/weather/weather_map.h"

namespace sky {

// Lu (1): ((rh - rhcr) / (1 - rhcr))^2 where rh > rhcr, else 0; rh and the result are
// fractions (rh above 1 counts as 1, NaN as 0).
float humidityCover(float rh, float rhCritical);

// Geopotential altitude (m) of a pressure in the ICAO standard atmosphere (troposphere and
// the isothermal layer above 11 km).
double standardAtmosphereAltitudeM(double pressureHpa);

// The cover of the three layers on the file's grid at one time, and their altitudes.
struct LayerCover {
  std::vector<float> low, mid, high;  // grid.size() values each, 0..1
  // (base, top) above sea level, m: the region mean of gh at the layer's bottomHpa and topHpa
  // (log-pressure interpolation between the file's gh levels), or the standard atmosphere
  // there when the file has no gh bracketing that pressure. Never below 0.
  glm::dvec2 lowAltM{0.0}, midAltM{0.0}, highAltM{0.0};
};

// The layers of `fields` at `timeUnix` (seconds since 1970 UTC): cover linearly interpolated
// between the two steps that bracket it, the nearest step outside them. weather.cover "rh":
// per point the largest Lu (1) cover over the layer's r levels within [topHpa, bottomHpa];
// "tcc": tcc_low / tcc_mid / tcc_high as they are. Missing values count as clear. BadInput
// naming weather.<layer> (no r level in its range; the file's levels listed), weather.cover
// (no tcc field) or weather.file (no steps). `region` only sets the
// altitudes' means.
LayerCover layerCover(const WeatherFields& fields, double timeUnix, const WeatherSettings& weather,
                      const WeatherRegion& region);

// `values` (on `grid`) at the centres of a width x height lat/lon map of `region` (row 0
// north, texel (i, j) at ((i + 0.5) / width, (j + 0.5) / height)). Regular lat/lon grids:
// Catmull-Rom bicubic in index space, wrapping in longitude on a global grid, clamped to
// [0, 1] when `clampUnit`; other grids: modified Shepard (Franke-Little) weights of the points
// within a radius of a few grid spacings on the sphere. Both reproduce the data at data
// points. NaN values must be replaced before. BadInput "weather.region: lies outside the
// data (...)" when the region is not covered by the grid.
std::vector<float> resampleToRegion(const GridGeometry& grid, std::span<const float> values,
                                    const WeatherRegion& region, uint32_t width, uint32_t height,
                                    bool clampUnit);

// The weather map of `fields` at `timeUnix` over `region`: proceduralMapSize texels,
// R low cover, G mid cover, B cloudTypeValue(weather.cloudType) (the data carry no type),
// A 1, coverHigh the high layer's cover and layerAltitudesM the low and mid altitudes. With
// weather.advection "data", a time before the first step or after the last (any time, for a
// single step) carries the nearest step's map with its wind at weather.steeringHpa
// (advectMap); BadInput naming weather.advection when the file has no u/v there. With
// advection "wind" the same, with the uniform `sceneWindMs` (east, north; sceneWindMs()).
WeatherMap weatherMapFromFields(const WeatherFields& fields, double timeUnix,
                                const WeatherSettings& weather, const WeatherRegion& region,
                                glm::dvec2 sceneWindMs = glm::dvec2(0.0));

// The layers' base and top altitudes (m above sea level) at each texel of the map
// weatherMapFromFields makes: gh at the layer's bottom_hpa and top_hpa per grid point (log-
// pressure interpolation, the standard atmosphere beyond the file's levels), resampled and
// interpolated in time like the cover. In order low base, low top, mid base, mid top, high
// base, high top. (The renderer uses their region means, layerAltitudesM.)
std::array<std::vector<float>, 6> layerAltitudeMaps(const WeatherFields& fields, double timeUnix,
                                                    const WeatherSettings& weather,
                                                    const WeatherRegion& region);

// Moves the map's cover (all channels and coverHigh) with a wind given per texel (m/s east,
// north; row-major like the texels) over `seconds`, semi-Lagrangian: each texel takes the
// map's bilinear value upstream. Values from beyond the region are its edge's.
void advectMap(WeatherMap& map, std::span<const float> eastMs, std::span<const float> northMs,
               double seconds);
// The same with one wind everywhere (east, north, m/s), e.g. sceneWindMs().
void advectMap(WeatherMap& map, glm::dvec2 windMs, double seconds);

}  // namespace sky
