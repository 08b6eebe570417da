// The cloud light volume (passes/cloud_light_volume, shaders/cloud_light_volume.comp): the
// optical depth toward the sun and the moon from points of the cloud shells around the
// camera, made once and read by every view sample of the raymarch (cloud_light_volume.glsl)
// instead of a march toward the light at each (Lu (24)). docs/clouds.md, "Light volume".
#ifndef SKY_CLOUD_LIGHT_VOLUME_SHARED_H
#define SKY_CLOUD_LIGHT_VOLUME_SHARED_H
#include "shared_prelude.h"

#define CLOUD_LIGHT_VOLUME_SIZE 256      // texels across and down (east, north)
#define CLOUD_LIGHT_VOLUME_SLICES 32     // texels from the shells' base to their top
#define CLOUD_LIGHT_VOLUME_GROUP_X 8
#define CLOUD_LIGHT_VOLUME_GROUP_Y 8
#define CLOUD_LIGHT_VOLUME_GROUP_Z 1
// The cloud field's bindings (volumetric_clouds_shared.h, 0-9) come first.
#define CLOUD_LIGHT_VOLUME_BINDING_IMAGE 10  // the volume pass's output; the march samples it
// How many sub-steps each step of the light schedule takes in the volume's march (the long
// step twice as many): the reference's refinement, done once per texel instead of per sample.
#define CLOUD_LIGHT_VOLUME_SPLIT 4
// A view sample marches the first this many short steps of the light schedule itself (the
// cloud's detail shadowing it) and reads the rest from the volume (CloudLightVolume.startM).
#define CLOUD_LIGHT_VOLUME_NEAR 2

SKY_SHARED_BEGIN

// The volume's place. Texel coordinate u in [-1, 1] across it stands for the ground distance
// radiusM u |u| east (v likewise north) of the point below the camera, as the cloud shadow
// map's; slices are spaced evenly in altitude from baseM to topM. Each texel holds the optical
// depth (r: toward the sun, g: toward the moon) along the light from its centre over the
// light march's reach (lightMarchReach), as the clouds were when it was made.
struct CloudLightVolume {
  float radiusM;    // ground distance from the centre to the edge (m)
  float baseM;      // altitude of the bottom of the first slice (m above sea level)
  float topM;       // altitude of the top of the last slice
  float startM;     // a view sample marches the light itself up to here, then reads the volume

  float shiftEastM;   // how far the clouds drifted east since the volume was made (m)
  float shiftNorthM;  // and north
  float padding0;     // std140: the rest of the row
  float padding1;
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::CloudLightVolume) == 32, "std140 layout of CloudLightVolume");
#endif
#endif
