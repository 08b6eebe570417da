#pragma once
// Geography on a spherical Earth (radius kEarthRadiusM), in double, for the CPU: the reference
// of shaders/common/geo.glsl (same functions, same conventions) and what fills its GeoFrame
// and GeoRegion. ECEF: x toward 0N 0E, y toward 0N 90E, z toward the north pole. ENU: the
// local frame at a place, x east, y north, z up (the geocentric vertical). Angles in degrees.
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "shaders/common/geo_shared.h"

namespace sky {

struct WeatherRegion;

constexpr double kEarthRadiusM = GEO_EARTH_RADIUS_M;

// Where a camera (or any ENU frame's origin) stands.
struct GeoPosition {
  double latDeg = 0.0;
  double lonDeg = 0.0;
  double altitudeM = 0.0;
};

// The rotation from the ENU frame at (lat, lon) to ECEF: columns east, north, up.
glm::dmat3 enuToEcefRotation(double latDeg, double lonDeg);
// (latitude, longitude in (-180, 180]) of an ECEF point (any length > 0).
glm::dvec2 latLonFromEcef(const glm::dvec3& p);
// The ECEF point (metres) at a latitude, longitude and altitude above the sphere.
glm::dvec3 ecefFromLatLonAltitude(double latDeg, double lonDeg, double altitudeM);

// (latitude, longitude, altitude m) of point `enu` in the ENU frame of `camera`, whose origin
// is the camera and in which the Earth's centre lies at (0, 0, -(R + camera altitude)).
glm::dvec3 latLonAltitude(const GeoPosition& camera, const glm::dvec3& enu);
// The inverse: the point in the camera's ENU frame at a latitude, longitude and altitude.
glm::dvec3 geoPosition(const GeoPosition& camera, double latDeg, double lonDeg, double altitudeM);

// The weather map coordinate of a latitude/longitude (see regionUv in geo.glsl): u west (0)
// to east (1), v north (0) to south (1); `uv` is set even outside. Returns whether the point
// lies inside the region (edges included). Longitudes are taken modulo 360 nearest the
// region's centre, so regions that run past 180E work.
bool regionUv(const WeatherRegion& region, double latDeg, double lonDeg, glm::dvec2& uv);

// Ground size of a region, km: x east-west along the parallel through the region's middle
// latitude, y north-south along a meridian.
glm::dvec2 regionSizeKm(const WeatherRegion& region);

// The GPU forms of the above.
shared::GeoFrame geoFrame(const GeoPosition& camera);
shared::GeoRegion geoRegion(const WeatherRegion& region);

}  // namespace sky
