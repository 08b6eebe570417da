// The GPU display path (passes/display_transform, shaders/display_transform.comp): the
// beauty's physical scene-linear values through the night look, the exposure and the OCIO
// view baked into a 3D table (engine/color/display_lut.h), into 8-bit display codes.
#ifndef SKY_DISPLAY_TRANSFORM_SHARED_H
#define SKY_DISPLAY_TRANSFORM_SHARED_H
#include "shared_prelude.h"

#define DISPLAY_TRANSFORM_GROUP_X 8
#define DISPLAY_TRANSFORM_GROUP_Y 8
#define DISPLAY_TRANSFORM_BINDING_PARAMS 0
#define DISPLAY_TRANSFORM_BINDING_BEAUTY 1   // rgba32f, scene-linear, physical
#define DISPLAY_TRANSFORM_BINDING_LUT 2      // the baked view: sampled 3D, linear, clamp
#define DISPLAY_TRANSFORM_BINDING_DISPLAY 3  // out: rgba8, display-referred

SKY_SHARED_BEGIN

struct DisplayTransformParams {
  float exposureScale;  // 2^ev of the frame's exposure (output.exposure auto or fixed)
  uint nightLook;       // 1: output.night_look, on the physical values before the exposure
  float lutMinLog2;     // the table's log2 shaper range (DisplayLut::kMinLog2, kMaxLog2)
  float lutMaxLog2;
  float lutSize;  // points a side
  float unused0;
  float unused1;
  float unused2;
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::DisplayTransformParams) == 32,
              "std140 layout of DisplayTransformParams");
#endif
#endif
