// Where a ground point falls in the cloud shadow map (cloud_shadow_shared.h).
#ifndef SKY_CLOUD_SHADOW_GLSL
#define SKY_CLOUD_SHADOW_GLSL
#include "cloud_shadow_shared.h"

// Map coordinate u (-1..1 across the map, beyond it outside) of the ground point at ground
// distance `metres` (east, north) from the point below the camera: the inverse of the map's
// u |u| spacing. The texture coordinate is u * 0.5 + 0.5.
vec2 cloudShadowU(CloudShadowMap map, vec2 metres) {
  return sign(metres) * sqrt(abs(metres) / map.radiusM);
}

// The ground distance (east, north) of map coordinate u in [-1, 1].
vec2 cloudShadowGround(CloudShadowMap map, vec2 u) {
  return map.radiusM * u * abs(u);
}

#endif
