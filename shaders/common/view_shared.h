// The camera as every full-screen pass sees it. Directions are in the local
// east-north-up frame at the camera (x east, y north, z up).
#ifndef SKY_VIEW_SHARED_H
#define SKY_VIEW_SHARED_H
#include "shared_prelude.h"

SKY_SHARED_BEGIN

struct ViewState {
  vec4 right;    // xyz: camera right; w: tan(horizontal fov / 2)
  vec4 up;       // xyz: camera up;    w: tan(vertical fov / 2)
  vec4 forward;  // xyz: view axis;    w: angular size of one pixel at the centre (radians)
  uvec4 size;    // x, y: image size in pixels
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::ViewState) == 64, "std140 layout of ViewState");
#endif
#endif
