// Spherical-Earth geography for passes working in the camera's east-north-up frame (metres,
// camera at the origin): the twin of engine/weather/geo.h, checked against it by
// tests/weather/geo_test.cpp (kernel geo_kernel.comp). Written for float: nothing subtracts
// two Earth-sized numbers and angles are offsets from the camera's, so altitudes stay good to
// millimetres, positions to a metre and lat/lon to a few 1e-5 of the distance from the
// camera, hundreds of kilometres out (docs/weather.md).
#ifndef SKY_GEO_GLSL
#define SKY_GEO_GLSL
#include "geo_shared.h"

#define GEO_DEG_PER_RAD 57.295779513082321
#define GEO_RAD_PER_DEG 0.017453292519943296

// The Earth's centre in the ENU frame.
vec3 geoCentre(GeoFrame f) {
  return vec3(0.0, 0.0, -(f.origin.w + f.origin.z));
}

// Altitude above the sphere of point p: |c + p| - |c| with c = -geoCentre, written as
// (2 c.p + p.p) / (|c + p| + |c|) so it does not cancel in float.
float geoAltitude(GeoFrame f, vec3 p) {
  float rc = f.origin.w + f.origin.z;
  vec3 q = p + vec3(0.0, 0.0, rc);
  return f.origin.z + (2.0 * rc * p.z + dot(p, p)) / (length(q) + rc);
}

// The local vertical (unit, pointing away from the centre) at p.
vec3 geoUp(GeoFrame f, vec3 p) {
  return normalize(p - geoCentre(f));
}

// (latitude, longitude in (-180, 180], altitude in metres) of point p.
// Latitude and longitude are found as small angles from the camera's, never as atan of an
// Earth-sized vector: GPU atan is good to a relative error, so an absolute angle near 1 rad
// would carry errors of metres while an offset of a few degrees stays well below one.
// In the frame (east, the camera meridian's equatorial direction, the pole), the point
// q = p - centre has components (q.x, h, z) with h = q.z cos(lat0) - q.y sin(lat0) and
// z = q.y cos(lat0) + q.z sin(lat0); its longitude offset is atan(q.x, h) and, with
// rho = |(q.x, h)| and d = rho - h, its latitude offset is
// atan(q.y - d sin(lat0), q.z + d cos(lat0)): the angle between (rho, z) and
// (cos lat0, sin lat0), rearranged so nothing cancels.
vec3 latLonAltitude(GeoFrame f, vec3 p) {
  float c0 = f.east.w, s0 = f.north.w;
  vec3 q = p - geoCentre(f);
  float h = q.z * c0 - q.y * s0;
  float rho = length(vec2(q.x, h));
  // rho - h: as q.x^2 / (rho + h) where h > 0 (no cancellation), directly otherwise.
  float d = h > 0.0 ? q.x * q.x / (rho + h) : rho - h;
  float dLat = atan(q.y - d * s0, q.z + d * c0);
  float dLon = atan(q.x, h);
  float lon = f.origin.y + dLon * GEO_DEG_PER_RAD;
  lon -= 360.0 * ceil((lon - 180.0) / 360.0);  // into (-180, 180]
  return vec3(f.origin.x + dLat * GEO_DEG_PER_RAD, lon, geoAltitude(f, p));
}

// The point at a latitude, longitude (degrees) and altitude (metres), in the ENU frame: the
// inverse of latLonAltitude, again from the small offsets to the camera's latitude and
// longitude. The unit vector l toward the place has l.x = cos(lat) sin(dLon) and
// l.y = sin(dLat) + 2 cos(lat) sin(lat0) sin^2(dLon / 2).
vec3 geoPosition(GeoFrame f, float latDeg, float lonDeg, float altitudeM) {
  float c0 = f.east.w, s0 = f.north.w;
  float dLat = (latDeg - f.origin.x) * GEO_RAD_PER_DEG;
  float dLon = lonDeg - f.origin.y;
  dLon = (dLon - 360.0 * floor((dLon + 180.0) / 360.0)) * GEO_RAD_PER_DEG;
  float lat = latDeg * GEO_RAD_PER_DEG;
  float cl = cos(lat), sh = sin(0.5 * dLon);
  vec3 l = vec3(cl * sin(dLon), sin(dLat) + 2.0 * cl * s0 * sh * sh,
                cl * cos(dLon) * c0 + sin(lat) * s0);
  float r = f.origin.w + altitudeM;
  // l.z - 1 = -(l.x^2 + l.y^2) / (1 + l.z): the drop below the camera's horizon plane
  // without cancelling.
  float drop = -(l.x * l.x + l.y * l.y) / (1.0 + l.z);
  return vec3(r * l.x, r * l.y, r * drop + (altitudeM - f.origin.z));
}

// Latitude and longitude along a straight line, taken linear in the distance through the
// exact values at its origin and `lengthM` metres on. The line's ground track bends away
// from that by under s^2 / 2R: 3 m at the cloud light march's 6 km reach, where the weather
// map's texels are kilometres. The light march takes its samples' latitudes and longitudes
// from here: latLonAltitude's two arctangents in every light sample were 5 % of the cloud pass.
struct LatLonLine {
  vec3 origin;
  vec3 direction;  // unit
  vec2 latLon;     // at the origin (degrees)
  vec2 rate;       // change per metre along the line
};

LatLonLine latLonLine(GeoFrame f, vec3 origin, vec2 latLonAtOrigin, vec3 direction,
                      float lengthM) {
  vec2 change = latLonAltitude(f, origin + direction * lengthM).xy - latLonAtOrigin;
  change.y -= 360.0 * round(change.y / 360.0);  // across 180 E the short way
  return LatLonLine(origin, direction, latLonAtOrigin, change / lengthM);
}

// (latitude, longitude, altitude) of a point p on the line; the altitude is exact (the cloud
// layers and their height profiles need it to the metre).
vec3 latLonAltitudeOn(GeoFrame f, LatLonLine line, vec3 p) {
  float along = dot(p - line.origin, line.direction);
  return vec3(line.latLon + line.rate * along, geoAltitude(f, p));
}

// The longitude among lon + k 360 nearest the region's centre: a region may run past 180E.
float geoRegionLongitude(GeoRegion r, float lonDeg) {
  float centre = 0.5 * (r.bounds.z + r.bounds.w);
  return lonDeg - 360.0 * floor((lonDeg - centre + 180.0) / 360.0);
}

// The weather map coordinate of a latitude/longitude: u from the west edge (0) to the east
// edge (1), v from the north edge (0) to the south edge (1), so texel (i, j) of a W x H map
// has its centre at ((i + 0.5) / W, (j + 0.5) / H). uv is set even outside; returns whether
// the point lies inside the region (edges included).
bool regionUv(GeoRegion r, float latDeg, float lonDeg, out vec2 uv) {
  float lon = geoRegionLongitude(r, lonDeg);
  uv = vec2((lon - r.bounds.z) / (r.bounds.w - r.bounds.z),
            (r.bounds.y - latDeg) / (r.bounds.y - r.bounds.x));
  return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
}

#endif
