// The cloud shadow map (passes/cloud_shadow, shaders/cloud_shadow.comp): how much of the key
// light reaches the ground through the volumetric clouds, over a square of ground centred
// below the camera. Read by the composite for the lit ground (cloudShadowUv) and meant for
// the clouds' own light later.
#ifndef SKY_CLOUD_SHADOW_SHARED_H
#define SKY_CLOUD_SHADOW_SHARED_H
#include "shared_prelude.h"

#define CLOUD_SHADOW_SIZE 384  // texels across and down
#define CLOUD_SHADOW_STEPS 24  // density samples along each texel's ray toward the light
#define CLOUD_SHADOW_GROUP_X 8
#define CLOUD_SHADOW_GROUP_Y 8
// The cloud field's bindings (volumetric_clouds_shared.h) come first.
#define CLOUD_SHADOW_BINDING_MAP_PARAMS 10
#define CLOUD_SHADOW_BINDING_IMAGE 11

SKY_SHARED_BEGIN

// The map's ground square: texel coordinate u in [-1, 1] across it stands for the ground
// distance radiusM u |u| east (v likewise north) of the point below the camera, measured
// along the ground. Texels are small under the camera and grow outward as a ground pixel's
// footprint does (it grows with the square of the distance seen from above the ground).
struct CloudShadowMap {
  vec4 lightDirection;  // xyz: unit ENU direction to the light the map is made for; w: unused
  float radiusM;        // ground distance from the centre to the map's edge (m)
  float lightIsSun;     // 1: made for the sun, 0: for the moon
  float maxPathM;       // the march toward the light stops after this distance (m)
  float valid;          // 1 when the frame has a map (0: no volumetric clouds)

  // How far the clouds drifted (east, north, m) since the map was made: a map kept from an
  // earlier frame (passes/cloud_shadow) is read where its clouds were.
  float shiftEastM;
  float shiftNorthM;
  float unused0;
  float unused1;
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::CloudShadowMap) == 48, "std140 layout of CloudShadowMap");
#endif
#endif
