// View rays for full-screen compute passes. Row 0 is the top of the image.
#ifndef SKY_VIEW_GLSL
#define SKY_VIEW_GLSL
#include "view_shared.h"

#define VIEW_PI 3.14159265358979

// World (east-north-up) direction through `pixel` (pixel centre = integer + 0.5).
vec3 viewDirection(ViewState view, vec2 pixel) {
  vec2 uv = pixel / vec2(view.size.xy);
  if (view.size.z == VIEW_PROJECTION_TOPDOWN) return vec3(0.0, 0.0, -1.0);
  if (view.size.z == VIEW_PROJECTION_EQUIRECTANGULAR) {
    float azimuth = (uv.x - 0.5) * 2.0 * VIEW_PI;  // clockwise from the heading
    float elevation = (0.5 - uv.y) * VIEW_PI;
    vec3 horizontal = cos(azimuth) * view.forward.xyz + sin(azimuth) * view.right.xyz;
    return cos(elevation) * horizontal + sin(elevation) * view.up.xyz;
  }
  vec2 ndc = uv * 2.0 - 1.0;
  return normalize(view.forward.xyz + ndc.x * view.right.w * view.right.xyz -
                   ndc.y * view.up.w * view.up.xyz);
}

// The continuous pixel position (centres at integer + 0.5) that viewDirection() maps to `d`
// (unit); false when no pixel sees it (behind a pinhole camera).
bool viewPixel(ViewState view, vec3 d, out vec2 pixel) {
  vec2 size = vec2(view.size.xy);
  if (view.size.z == VIEW_PROJECTION_TOPDOWN) {
    pixel = vec2(0.0);
    return false;  // the sky is never in view
  }
  if (view.size.z == VIEW_PROJECTION_EQUIRECTANGULAR) {
    float azimuth = atan(dot(d, view.right.xyz), dot(d, view.forward.xyz));
    float elevation = asin(clamp(dot(d, view.up.xyz), -1.0, 1.0));
    pixel = vec2(azimuth / (2.0 * VIEW_PI) + 0.5, 0.5 - elevation / VIEW_PI) * size;
    return true;
  }
  float depth = dot(d, view.forward.xyz);
  pixel = vec2(0.0);
  if (depth <= 0.0) return false;
  vec2 ndc = vec2(dot(d, view.right.xyz) / (depth * view.right.w),
                  -dot(d, view.up.xyz) / (depth * view.up.w));
  pixel = (ndc + 1.0) * 0.5 * size;
  return true;
}

// The angular size (radians) of the pixel that sees direction V, as the square root of its
// solid angle: the scale below which a disc or an edge is sub-pixel. A pinhole pixel spans
// p cos^2 (radially) by p cos (tangentially) at an angle off the axis; an equirectangular one
// spans (2 pi / width) cos(elevation) by (pi / height).
float viewPixelAngle(ViewState view, vec3 V) {
  if (view.size.z == VIEW_PROJECTION_TOPDOWN) return view.forward.w;
  if (view.size.z == VIEW_PROJECTION_EQUIRECTANGULAR) {
    float across = 2.0 * VIEW_PI / float(view.size.x) * max(sqrt(1.0 - V.z * V.z), 1e-3);
    return sqrt(across * VIEW_PI / float(view.size.y));
  }
  return view.forward.w * pow(max(dot(V, view.forward.xyz), 1e-3), 1.5);
}

#endif
