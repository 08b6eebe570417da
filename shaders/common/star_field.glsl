// The reader side of the star field (passes/star_field): the flux a pixel received and the
// solid angle it covers, so a composite can turn flux into resolution-independent radiance,
// L = starFlux(p) * (radiance scale of a V = 0 star) / pixelSolidAngle(view, centre of p).
// The includer defines STAR_FLUX_BINDING (descriptor set 0) before including this file and
// declares that buffer as read in its pass (Access::StorageReadCompute). Without the define
// only pixelSolidAngle exists (so the header still compiles on its own; a call to starFlux
// then fails with "no matching overloaded function").
#ifndef SKY_STAR_FIELD_GLSL
#define SKY_STAR_FIELD_GLSL
#include "star_field_shared.h"
#include "view_shared.h"

#ifdef STAR_FLUX_BINDING
layout(std430, set = 0, binding = STAR_FLUX_BINDING) readonly buffer StarFluxBuffer {
  uvec4 starFluxSize;  // width, height
  uint starFluxCounts[];
};

// Star flux that landed in `pixel`, relative to one V = 0 star above the atmosphere;
// 0 outside the image.
float starFlux(ivec2 pixel) {
  if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, ivec2(starFluxSize.xy))))
    return 0.0;
  return float(starFluxCounts[pixel.y * int(starFluxSize.x) + pixel.x]) / STAR_FLUX_FIXED_ONE;
}
#endif

// atan(t) for t >= 0. Vulkan lets atan() be off by 4096 ulp (lavapipe: ~2e-5 relative),
// too coarse for solid angles that are summed over a whole image. A pixel's t is about a
// quarter of its solid angle, far below 0.1 for any image more than a few pixels wide, and
// there the Taylor series to t^9 is exact in float (remainder < t^11 / 11 < 1e-12).
float starAtanPositive(float t) {
  if (t >= 0.1) return atan(t);
  float t2 = t * t;
  return t * (1.0 - t2 * (1.0 / 3.0 - t2 * (1.0 / 5.0 - t2 * (1.0 / 7.0 - t2 * (1.0 / 9.0)))));
}

// Solid angle of the triangle a, b, c seen from the origin, given the triple product
// a . (b x c): Van Oosterom & Strackee (1983), tan(omega / 2) = |a.(b x c)| /
// (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|). The vectors need not be unit length; the
// denominator is positive for any triangle within a hemisphere (a pinhole's field of view).
float starTriangleSolidAngle(vec3 a, vec3 b, vec3 c, float tripleProduct) {
  float la = length(a), lb = length(b), lc = length(c);
  float denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2.0 * starAtanPositive(abs(tripleProduct) / denominator);
}

// Exact solid angle (steradians) of the pixel whose centre is `pixel` (integer + 0.5, as
// for viewDirection). A pinhole pixel (common/view.glsl) is a rectangle
// du x dv on the image plane at unit distance, split into two triangles; on that plane each
// triangle's triple product is exactly du * dv, so no difference of nearly equal angles is
// taken and the result keeps float precision even for tiny pixels.
// An equirectangular pixel is a band of latitude: (2 pi / width) (sin top - sin bottom).
float pixelSolidAngle(ViewState view, vec2 pixel) {
  // A top-down view sees no sky; any positive size keeps the (zero) star term finite.
  if (view.size.z == VIEW_PROJECTION_TOPDOWN) return view.forward.w * view.forward.w;
  if (view.size.z == VIEW_PROJECTION_EQUIRECTANGULAR) {
    const float pi = 3.14159265358979;
    float top = (0.5 - (pixel.y - 0.5) / float(view.size.y)) * pi;
    float bottom = (0.5 - (pixel.y + 0.5) / float(view.size.y)) * pi;
    // sin a - sin b = 2 cos((a + b) / 2) sin((a - b) / 2): no cancellation for thin bands.
    return 2.0 * pi / float(view.size.x) * 2.0 * cos(0.5 * (top + bottom)) *
           sin(0.5 * (top - bottom));
  }
  vec2 tanHalf = vec2(view.right.w, view.up.w);
  vec2 pixelSize = 2.0 * tanHalf / vec2(view.size.xy);  // du, dv: one pixel on the image plane
  // Image-plane coordinates of the pixel's lower-left corner (v grows upward, rows downward).
  float u0 = (pixel.x - 0.5) * pixelSize.x - tanHalf.x;
  float v0 = tanHalf.y - (pixel.y + 0.5) * pixelSize.y;
  vec3 a = vec3(u0, v0, 1.0);
  vec3 b = vec3(u0 + pixelSize.x, v0, 1.0);
  vec3 c = vec3(u0 + pixelSize.x, v0 + pixelSize.y, 1.0);
  vec3 d = vec3(u0, v0 + pixelSize.y, 1.0);
  float det = pixelSize.x * pixelSize.y;
  return starTriangleSolidAngle(a, b, c, det) + starTriangleSolidAngle(a, c, d, det);
}

#endif
