// Parameters and bindings of passes/cloud_volume_export (shaders/cloud_volume_export.comp):
// the cloud density field of passes/volumetric_clouds sampled at the centres of a voxel grid
// (skyrender export-volume). The cloud parameters and textures bind at the slots
// cloud_field.glsl declares (volumetric_clouds_shared.h); the grid's own block and image
// take two of the slots the raymarch uses for its outputs.
#ifndef SKY_CLOUD_VOLUME_EXPORT_SHARED_H
#define SKY_CLOUD_VOLUME_EXPORT_SHARED_H
#include "shared_prelude.h"

#define CLOUD_VOLUME_EXPORT_GROUP_X 4
#define CLOUD_VOLUME_EXPORT_GROUP_Y 4
#define CLOUD_VOLUME_EXPORT_GROUP_Z 4
#define CLOUD_VOLUME_EXPORT_BINDING_GRID 2    // out: r32f 3D image, density at each voxel centre
#define CLOUD_VOLUME_EXPORT_BINDING_PARAMS 3  // CloudVolumeExportParams

SKY_SHARED_BEGIN

struct CloudVolumeExportParams {
  vec4 firstVoxelCentreM;  // xyz: voxel (0, 0, 0)'s centre in the camera's ENU frame (m); w: unused
  vec4 voxelM;             // xyz: a voxel's edge along east, north, up (m); w: unused
  uvec4 voxels;            // xyz: voxels along east, north, up; w: unused
  // The width each voxel's sample stands for, as the raymarch's level of detail takes it
  // (cloudSampleAt's footprintM, docs/clouds.md): max(footprintPerM x the voxel's distance
  // from the camera, footprintMinM). Both 0: full detail.
  float footprintPerM;  // metres of footprint per metre of distance (the view's pixel width)
  float footprintMinM;  // the least footprint (m): the voxel, so no noise finer than it aliases
  float unused0;
  float unused1;
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::CloudVolumeExportParams) == 64,
              "std140 layout of CloudVolumeExportParams");
#endif
#endif
