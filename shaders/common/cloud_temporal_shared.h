// Temporal reuse of the volumetric clouds (passes/cloud_temporal, shaders/cloud_temporal.comp):
// the frame's sparse march (one pixel of every block x block square) merged with last frame's
// clouds, reprojected through the camera's motion and the wind, into this frame's full-size
// clouds, which become the next frame's history.
#ifndef SKY_CLOUD_TEMPORAL_SHARED_H
#define SKY_CLOUD_TEMPORAL_SHARED_H
#include "shared_prelude.h"
#include "view_shared.h"

#define CLOUD_TEMPORAL_GROUP_X 8
#define CLOUD_TEMPORAL_GROUP_Y 8
#define CLOUD_TEMPORAL_BINDING_PARAMS 0
#define CLOUD_TEMPORAL_BINDING_MARCHED 1        // this frame's march: rgba32f, the view / block
#define CLOUD_TEMPORAL_BINDING_MARCHED_DEPTH 2  // its depth (m): r32f
#define CLOUD_TEMPORAL_BINDING_HISTORY 3        // last frame's clouds: sampled (linear, clamp)
#define CLOUD_TEMPORAL_BINDING_HISTORY_DEPTH 4  // last frame's depth: r32f
#define CLOUD_TEMPORAL_BINDING_CLOUDS 5         // out: this frame's clouds, rgba32f, full size
#define CLOUD_TEMPORAL_BINDING_DEPTH 6          // out: this frame's depth, r32f, full size

SKY_SHARED_BEGIN

// std140; positions in metres, directions unit. "This frame's ENU" is the east-north-up frame
// at this frame's camera, as the view's axes are.
struct CloudTemporalParams {
  ViewState view;          // this frame's camera
  ViewState previousView;  // last frame's, its axes in last frame's ENU frame
  vec4 previousPosition;   // xyz: last frame's camera in this frame's ENU frame
  // The rotation from this frame's ENU axes to last frame's, by rows: a vector v of this
  // frame is (dot(toPreviousX.xyz, v), dot(toPreviousY.xyz, v), dot(toPreviousZ.xyz, v)) there.
  vec4 toPreviousX;
  vec4 toPreviousY;
  vec4 toPreviousZ;
  vec4 windShift;  // xyz: how far the clouds drifted with the wind since last frame

  uint block;         // the march's block (CloudParams.marchBlock)
  uint offsetX;       // the pixel of every block marched this frame
  uint offsetY;
  uint historyValid;  // 1: the history holds last frame's clouds; 0: a cut

  float planetRadiusM;    // the sphere the ground and the shells are measured on (m)
  float cameraAltitudeM;  // this frame's camera above that sphere (m)
  float shellBaseM;       // the marched shells (CloudParams.shellBaseM, shellTopM)
  float shellTopM;
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::CloudTemporalParams) == 2 * 64 + 5 * 16 + 2 * 16,
              "std140 layout of CloudTemporalParams");
#endif
#endif
