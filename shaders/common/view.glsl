// View rays for full-screen compute passes. Row 0 is the top of the image.
#ifndef SKY_VIEW_GLSL
#define SKY_VIEW_GLSL
#include "view_shared.h"

// World (east-north-up) direction through `pixel` (pixel centre = integer + 0.5).
vec3 viewDirection(ViewState view, vec2 pixel) {
  vec2 ndc = pixel / vec2(view.size.xy) * 2.0 - 1.0;
  return normalize(view.forward.xyz + ndc.x * view.right.w * view.right.xyz -
                   ndc.y * view.up.w * view.up.xyz);
}

#endif
