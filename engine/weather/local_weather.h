#pragma once
// Local weather (Kozlov et al. section 5): the weather map is not only where clouds are drawn
// but also "what the weather is" where the camera stands, as the map's cover filtered over a
// radius of a few km. The filter is smooth in position, so the weather changes smoothly as the
// camera moves or the map changes with time. The lighting model turns it into ambient light
// and haze (engine/lighting/lighting_state.h applyLocalWeather). See docs/weather.md.
#include "engine/weather/weather_map.h"

namespace sky {

struct LocalWeather {
  float low = 0.0f, mid = 0.0f, high = 0.0f;  // the layers' filtered cover, 0..1
  // The fraction of the sky hidden by any layer, the layers overlapping at random:
  // 1 - (1 - low)(1 - mid)(1 - high).
  float overcast = 0.0f;
};

// The cover of `map` around (latDeg, lonDeg), weighted by (1 - (r / radius)^2)^2 over a disc
// of `radiusKm` (61 bilinear samples on rings, continuous in the position). Beyond the map's
// region the cover is 0, as the volumetric clouds draw none there, fading over half a texel.
// coverHigh counts when the map has it.
LocalWeather localWeather(const WeatherMap& map, double latDeg, double lonDeg, double radiusKm);

}  // namespace sky
