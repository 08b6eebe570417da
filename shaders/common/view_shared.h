// The camera as every full-screen pass sees it. Directions are in the local
// east-north-up frame at the camera (x east, y north, z up).
#ifndef SKY_VIEW_SHARED_H
#define SKY_VIEW_SHARED_H
#include "shared_prelude.h"

// ViewState.size.z: how pixels map to directions.
#define VIEW_PROJECTION_PERSPECTIVE 0u      // a pinhole camera
#define VIEW_PROJECTION_EQUIRECTANGULAR 1u  // the whole sphere: azimuth across, elevation down
#define VIEW_PROJECTION_TOPDOWN 2u          // every pixel looks straight down (camera.mode
                                            // geographic_topdown: the cloud pass places the rays)

SKY_SHARED_BEGIN

// Perspective: right/up/forward are the camera axes. Equirectangular: forward is the horizontal
// heading (the image centre), right is 90 degrees clockwise from it and up is the zenith; the
// width spans 360 degrees of azimuth and the height 180 degrees of elevation (+90 at the top).
struct ViewState {
  vec4 right;    // xyz: camera right; w: tan(horizontal fov / 2) (perspective)
  vec4 up;       // xyz: camera up;    w: tan(vertical fov / 2) (perspective)
  vec4 forward;  // xyz: view axis;    w: angular size of one pixel at the centre (radians)
  uvec4 size;    // x, y: image size in pixels; z: VIEW_PROJECTION_*
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::ViewState) == 64, "std140 layout of ViewState");
#endif
#endif
