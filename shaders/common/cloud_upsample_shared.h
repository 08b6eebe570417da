// The clouds marched at reduced resolution brought to the view's (passes/cloud_upsample,
// shaders/cloud_upsample.comp): clouds.temporal.resolution half.
#ifndef SKY_CLOUD_UPSAMPLE_SHARED_H
#define SKY_CLOUD_UPSAMPLE_SHARED_H
#include "shared_prelude.h"
#include "view_shared.h"

#define CLOUD_UPSAMPLE_GROUP_X 8
#define CLOUD_UPSAMPLE_GROUP_Y 8
#define CLOUD_UPSAMPLE_BINDING_PARAMS 0
#define CLOUD_UPSAMPLE_BINDING_CLOUDS 1        // rgba32f, the reduced view's size
#define CLOUD_UPSAMPLE_BINDING_DEPTH 2         // rg32f: depth (m), where the ray reaches the shells
#define CLOUD_UPSAMPLE_BINDING_OUT_CLOUDS 3    // out: rgba32f, the view's size
#define CLOUD_UPSAMPLE_BINDING_OUT_DEPTH 4     // out: rg32f

SKY_SHARED_BEGIN

struct CloudUpsampleParams {
  ViewState view;    // the full view
  ViewState source;  // the same camera at the reduced size the clouds were marched at
  float planetRadiusM;    // the sphere the ground and the shells are measured on (m)
  float cameraAltitudeM;
  float shellBaseM;       // the marched shells (CloudParams.shellBaseM, shellTopM)
  float shellTopM;
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::CloudUpsampleParams) == 2 * 64 + 16,
              "std140 layout of CloudUpsampleParams");
#endif
#endif
