// Geography on a spherical Earth, as the cloud shaders and engine/weather/geo.h see it.
// A pass works in the camera's local east-north-up frame (metres, x east, y north, z up, the
// camera at the origin); GeoFrame ties that frame to latitude, longitude and altitude.
// Filled on the CPU by sky::geoFrame() and sky::geoRegion() (engine/weather/geo.h).
#ifndef SKY_GEO_SHARED_H
#define SKY_GEO_SHARED_H
#include "shared_prelude.h"

// The mean Earth radius (IUGG), metres: the one radius of every geographic mapping.
#define GEO_EARTH_RADIUS_M 6371000.0

SKY_SHARED_BEGIN

// The camera's ENU axes in Earth-centred, Earth-fixed coordinates (x toward 0N 0E, y toward
// 0N 90E, z toward the north pole) and where the camera stands. The Earth's centre lies at
// (0, 0, -(radius + altitude)) in the ENU frame.
struct GeoFrame {
  vec4 east;    // xyz: unit east at the camera (ECEF); w: cos(camera latitude)
  vec4 north;   // xyz: unit north; w: sin(camera latitude)
  vec4 up;      // xyz: unit up (the geocentric vertical); w unused (0)
  vec4 origin;  // x: camera latitude, y: longitude (degrees), z: altitude (m), w: Earth radius (m)
};

// A lat/lon rectangle (a weather region).
struct GeoRegion {
  vec4 bounds;  // x: south, y: north, z: west, w: east (degrees; west < east, at most 360 apart)
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::GeoFrame) == 64, "std140 layout of GeoFrame");
static_assert(sizeof(sky::shared::GeoRegion) == 16, "std140 layout of GeoRegion");
#endif
#endif
