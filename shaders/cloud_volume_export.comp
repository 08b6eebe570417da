#version 460
// skyrender export-volume: the cloud density at the centre of every voxel of a box, for the
// path-traced reference (scripts/pathtrace). The density is the raymarch's own: the same
// cloud_field.glsl function with the same parameters and textures, so the grid holds exactly
// the field the clouds pass marches through (the CPU multiplies by the extinction), at full
// detail or at the level of detail the raymarch resolves at each voxel's distance.
#include "common/volumetric_clouds_shared.h"
#include "common/cloud_volume_export_shared.h"
#include "common/geo.glsl"
#include "common/cloud_density.glsl"
#include "common/cloud_field.glsl"

layout(local_size_x = CLOUD_VOLUME_EXPORT_GROUP_X, local_size_y = CLOUD_VOLUME_EXPORT_GROUP_Y,
       local_size_z = CLOUD_VOLUME_EXPORT_GROUP_Z) in;

layout(std140, binding = CLOUD_VOLUME_EXPORT_BINDING_PARAMS) uniform CloudVolumeExportBlock {
  CloudVolumeExportParams boxBlock[1];
};
#define box boxBlock[SKY_PARAMS_INDEX]

layout(binding = CLOUD_VOLUME_EXPORT_BINDING_GRID, r32f) uniform writeonly image3D grid;

void main() {
  uvec3 id = gl_GlobalInvocationID;
  if (any(greaterThanEqual(id, box.voxels.xyz))) return;
  vec3 p = box.firstVoxelCentreM.xyz + vec3(id) * box.voxelM.xyz;
  // The field as a sample of the raymarch's footprint at this distance sees it (0: full detail).
  float footprintM = max(box.footprintPerM * length(p), box.footprintMinM);
  CloudSample s;
  cloudSampleAt(p, footprintM, s);
  imageStore(grid, ivec3(id), vec4(s.density, 0.0, 0.0, 0.0));
}
