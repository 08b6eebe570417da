#include "engine/weather/geo.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "engine/scene/scene.h"

namespace sky {

glm::dmat3 enuToEcefRotation(double latDeg, double lonDeg) {
  const double lat = glm::radians(latDeg), lon = glm::radians(lonDeg);
  const double sLat = std::sin(lat), cLat = std::cos(lat), sLon = std::sin(lon),
               cLon = std::cos(lon);
  const glm::dvec3 east(-sLon, cLon, 0.0);
  const glm::dvec3 north(-sLat * cLon, -sLat * sLon, cLat);
  const glm::dvec3 up(cLat * cLon, cLat * sLon, sLat);
  return glm::dmat3(east, north, up);
}

glm::dvec2 latLonFromEcef(const glm::dvec3& p) {
  // atan2 of the polar height over the equatorial distance: well conditioned at the poles,
  // where asin(z / r) is not.
  return {glm::degrees(std::atan2(p.z, std::hypot(p.x, p.y))), glm::degrees(std::atan2(p.y, p.x))};
}

glm::dvec3 ecefFromLatLonAltitude(double latDeg, double lonDeg, double altitudeM) {
  return (kEarthRadiusM + altitudeM) * enuToEcefRotation(latDeg, lonDeg)[2];
}

glm::dvec3 latLonAltitude(const GeoPosition& camera, const glm::dvec3& enu) {
  const double rc = kEarthRadiusM + camera.altitudeM;
  const glm::dvec3 fromCentre = enu + glm::dvec3(0.0, 0.0, rc);
  const glm::dvec3 ecef = enuToEcefRotation(camera.latDeg, camera.lonDeg) * fromCentre;
  const glm::dvec2 latLon = latLonFromEcef(ecef);
  // |c + p| - |c| without cancelling (the form the float shader needs; same here).
  const double altitude =
      camera.altitudeM + (2.0 * rc * enu.z + glm::dot(enu, enu)) / (glm::length(fromCentre) + rc);
  return {latLon, altitude};
}

glm::dvec3 geoPosition(const GeoPosition& camera, double latDeg, double lonDeg, double altitudeM) {
  const glm::dvec3 d = enuToEcefRotation(latDeg, lonDeg)[2];
  // The rotation is orthonormal: its transpose takes ECEF to the camera's ENU.
  const glm::dvec3 l = glm::transpose(enuToEcefRotation(camera.latDeg, camera.lonDeg)) * d;
  const double r = kEarthRadiusM + altitudeM;
  const double drop = -(l.x * l.x + l.y * l.y) / (1.0 + l.z);  // l.z - 1, without cancelling
  return {r * l.x, r * l.y, r * drop + (altitudeM - camera.altitudeM)};
}

bool regionUv(const WeatherRegion& region, double latDeg, double lonDeg, glm::dvec2& uv) {
  const double centre = 0.5 * (region.lon[0] + region.lon[1]);
  const double lon = lonDeg - 360.0 * std::floor((lonDeg - centre + 180.0) / 360.0);
  uv = {(lon - region.lon[0]) / (region.lon[1] - region.lon[0]),
        (region.lat[1] - latDeg) / (region.lat[1] - region.lat[0])};
  return uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0;
}

glm::dvec2 regionSizeKm(const WeatherRegion& region) {
  const double kmPerDegree = kEarthRadiusM * 1e-3 * glm::radians(1.0);
  const double midLat = glm::radians(0.5 * (region.lat[0] + region.lat[1]));
  return {(region.lon[1] - region.lon[0]) * kmPerDegree * std::cos(midLat),
          (region.lat[1] - region.lat[0]) * kmPerDegree};
}

shared::GeoFrame geoFrame(const GeoPosition& camera) {
  const glm::dmat3 m = enuToEcefRotation(camera.latDeg, camera.lonDeg);
  shared::GeoFrame f;
  const double lat = glm::radians(camera.latDeg);
  f.east = glm::vec4(glm::vec3(m[0]), float(std::cos(lat)));
  f.north = glm::vec4(glm::vec3(m[1]), float(std::sin(lat)));
  f.up = glm::vec4(glm::vec3(m[2]), 0.0f);
  f.origin = glm::vec4(float(camera.latDeg), float(camera.lonDeg), float(camera.altitudeM),
                       float(kEarthRadiusM));
  return f;
}

shared::GeoRegion geoRegion(const WeatherRegion& region) {
  return {glm::vec4(float(region.lat[0]), float(region.lat[1]), float(region.lon[0]),
                    float(region.lon[1]))};
}

}  // namespace sky
