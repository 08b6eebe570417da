// The distance to what a host drew (host_depth_shared.h), for the composite and the
// volumetric clouds: one formula, so the clouds stop where the composite finds the host's pixel.
#ifndef SKY_HOST_DEPTH_GLSL
#define SKY_HOST_DEPTH_GLSL
#include "host_depth_shared.h"

// The distance (m) along unit ray `V` to the host's pixel of depth value `d`, for a camera
// whose view axis is `forward`; -1 where the host drew nothing.
float hostDistance(HostDepth hd, float d, vec3 V, vec3 forward) {
  float along = hd.depthB / (d + hd.depthA);  // metres along the view axis
  if (d == hd.emptyDepth || !(along > 0.0)) return -1.0;
  return along / max(dot(V, forward), 1e-6);
}

#endif
