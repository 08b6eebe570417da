// Where a point falls in the cloud light volume (cloud_light_volume_shared.h), for the pass
// that makes it and the raymarch that reads it.
#ifndef SKY_CLOUD_LIGHT_VOLUME_GLSL
#define SKY_CLOUD_LIGHT_VOLUME_GLSL
#include "cloud_light_volume_shared.h"
#include "geo.glsl"

// The texture coordinate of point p (the camera's ENU frame): the ground distance east and
// north of the point below the camera along the sphere (less the drift since the volume was
// made) through the u |u| spacing, and the altitude between its base and top.
vec3 cloudLightVolumeCoord(CloudLightVolume v, GeoFrame geo, vec3 p) {
  vec3 q = p - geoCentre(geo);
  float horizontal = length(q.xy);
  float angle = atan(horizontal, q.z);
  vec2 metres = horizontal > 0.0 ? q.xy * (geo.origin.w * angle / horizontal) : vec2(0.0);
  metres -= vec2(v.shiftEastM, v.shiftNorthM);
  vec2 u = sign(metres) * sqrt(abs(metres) / v.radiusM);
  float w = (geoAltitude(geo, p) - v.baseM) / (v.topM - v.baseM);
  return vec3(u * 0.5 + 0.5, w);
}

// The point (ENU) at ground distance `metres` (east, north) from the point below the camera
// and altitude `h`: its drop below the camera's horizon plane as 2 (R + h) sin^2(angle / 2),
// which keeps its precision near the camera (as cloud_shadow.comp places its ground).
vec3 cloudLightVolumePoint(GeoFrame geo, vec2 metres, float h) {
  float R = geo.origin.w;
  float distance = length(metres);
  vec2 heading = distance > 0.0 ? metres / distance : vec2(0.0, 1.0);
  float angle = distance / R;
  float sh = sin(0.5 * angle);
  return vec3((R + h) * sin(angle) * heading, (h - geo.origin.z) - 2.0 * (R + h) * sh * sh);
}

#endif
