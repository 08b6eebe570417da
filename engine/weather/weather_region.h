#pragma once
// Where the weather map lies when the scene does not say: weather.region when given, else a
// square of weather.camera_region_km centred on the camera, and for forecast data never past
// the data's own extent. See docs/weather.md, "The region".
#include "engine/scene/scene.h"
#include "engine/weather/weather_fields.h"

namespace sky {

// The square of `weather.cameraRegionKm` on a side (north-south along a meridian, east-west
// along the parallel through its middle) centred on (latDeg, lonDeg). The centre is snapped to
// the pitch of the map's texels (weather.resolution across), so a camera that moves less than
// a texel keeps the same map, and texel centres stay on one grid fixed to the ground. Clipped
// at the poles; a square wider than the parallel spans all 360 degrees. West may lie below
// -180 (regionUv takes longitudes modulo 360).
WeatherRegion cameraRegion(double latDeg, double lonDeg, const WeatherSettings& weather);

// The lat/lon rectangle a forecast grid covers. A regular lat/lon grid: its rows' and columns'
// range (a global grid all longitudes, and the poles when its outer rows lie within a row and
// a half of them). Any other grid (Lambert conformal, ...): the largest rectangle inside its
// four edges, so every texel of the map lies on the data; a grid stored as one list: the
// range of its points.
WeatherRegion dataRegion(const GridGeometry& grid);

// The region of the weather map for `in`: weather.region when given; else cameraRegion()
// around the camera, clipped to `data` (a forecast's dataRegion, found once per file) when
// given. BadInput naming weather.region when the data do not reach the camera's square.
WeatherRegion mapRegion(const WeatherInputs& in, const WeatherRegion* data = nullptr);

// The region of a scene whose map has been made (the renderer sets it from the map):
// weather.region, which must be set by then.
const WeatherRegion& resolvedRegion(const WeatherSettings& weather);

}  // namespace sky
