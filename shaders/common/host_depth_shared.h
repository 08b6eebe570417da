// A host's depth image as distances (skylayers::Sky::record): the composite sees the host's
// pixels through the air by it, and the volumetric clouds stop marching at it.
#ifndef SKY_HOST_DEPTH_SHARED_H
#define SKY_HOST_DEPTH_SHARED_H
#include "shared_prelude.h"

SKY_SHARED_BEGIN

// How the host's depth buffer maps to distance. A perspective projection P in Vulkan's clip
// space (depth 0..1, w = -z of the view; column-major) stores
// d = B / z - A for a point z metres in front of the camera along its axis, with A = P[2][2]
// and B = P[3][2]; so z = B / (d + A), and the distance along a pixel's ray is
// z / dot(ray, forward). Standard depth (near 0, far 1) and reverse-Z alike, an infinite far
// plane included.
struct HostDepth {
  float depthA;
  float depthB;
  float emptyDepth;  // the value where the host drew nothing (its far plane: 1, or 0 reverse-Z)
  uint present;      // 1: a depth image is bound; 0: the host drew nothing yet, all is sky
};

SKY_SHARED_END

#endif
