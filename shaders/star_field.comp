#version 460
// The star field: every catalogue star rotated from J2000 into the camera's east-north-up
// frame, dimmed by atmospheric extinction, projected into the image and splatted with
// bilinear (tent) weights onto the four nearest pixel centres as fixed-point flux. The tent
// conserves each star's flux and moves its centroid linearly with the star, so a star
// drifting across the image in a time-lapse neither flickers nor jumps.
#include "common/params_block.glsl"
#include "common/star_field_shared.h"
#include "common/view.glsl"

layout(local_size_x = STAR_FIELD_GROUP_SIZE) in;

layout(std140, binding = STAR_FIELD_BINDING_PARAMS) uniform Params {
  StarFieldParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(std430, binding = STAR_FIELD_BINDING_STARS) readonly buffer Stars {
  vec4 stars[];  // xyz: J2000 direction; w: flux relative to V = 0
};
layout(std430, binding = STAR_FIELD_BINDING_FLUX) buffer Flux {
  uvec4 fluxSize;  // written by star_clear.comp
  uint flux[];
};

// Relative air mass at elevation `elevationDeg`: Kasten & Young (1989, Appl. Opt. 28, 4735),
// X = 1 / (sin h + 0.50572 (h + 6.07995)^-1.6364), h in degrees; 1 at the zenith, ~38 at
// the horizon and still finite (~46) at the -0.5 degrees where stars have faded out. The
// formula wants the apparent elevation; we pass the geometric one (no refraction model yet),
// which changes X noticeably only within a few degrees of the horizon.
float airMass(float elevationDeg) {
  float h = max(elevationDeg, -STAR_FIELD_HORIZON_FADE_DEG);
  return 1.0 / (sin(radians(h)) + 0.50572 * pow(h + 6.07995, -1.6364));
}

void addFlux(ivec2 pixel, float amount) {
  // An equirectangular image wraps around in azimuth.
  if (params.view.size.z == VIEW_PROJECTION_EQUIRECTANGULAR)
    pixel.x = (pixel.x + int(params.view.size.x)) % int(params.view.size.x);
  if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, ivec2(params.view.size.xy))))
    return;
  uint counts = uint(amount * STAR_FLUX_FIXED_ONE + 0.5);
  if (counts != 0u) atomicAdd(flux[pixel.y * params.view.size.x + pixel.x], counts);
}

void splat(vec4 star) {
  mat3 toEnu = mat3(params.j2000ToEnu0.xyz, params.j2000ToEnu1.xyz, params.j2000ToEnu2.xyz);
  vec3 d = toEnu * star.xyz;
  float elevationDeg = degrees(asin(clamp(d.z, -1.0, 1.0)));
  if (elevationDeg <= -STAR_FIELD_HORIZON_FADE_DEG) return;

  // The exact inverse of viewDirection() in common/view.glsl.
  vec2 pixel;
  if (!viewPixel(params.view, d, pixel)) return;  // behind the camera
  vec2 size = vec2(params.view.size.xy);
  vec2 p = pixel - 0.5;  // relative to the centre of pixel (0, 0)
  vec2 base = floor(p);
  // Keeps stars whose footprint still touches the image at the border; written so that a
  // NaN also lands here.
  if (!(all(greaterThanEqual(base, vec2(-1.0))) && all(lessThan(base, size)))) return;

  // Extinction: m = m0 + k X, so flux *= 10^(-0.4 k X); then the fade below the horizon.
  float f = star.w * pow(10.0, -0.4 * params.extinction.x * airMass(elevationDeg));
  f *= smoothstep(-STAR_FIELD_HORIZON_FADE_DEG, 0.0, elevationDeg);
  f = min(f, STAR_FLUX_MAX_PER_STAR);

  vec2 w = p - base;  // bilinear weights of the far neighbours
  ivec2 i = ivec2(base);
  addFlux(i, f * (1.0 - w.x) * (1.0 - w.y));
  addFlux(i + ivec2(1, 0), f * w.x * (1.0 - w.y));
  addFlux(i + ivec2(0, 1), f * (1.0 - w.x) * w.y);
  addFlux(i + ivec2(1, 1), f * w.x * w.y);
}

void main() {
  // A grid-stride loop: the dispatch is capped at the 65535 workgroups every device allows.
  uint stride = gl_NumWorkGroups.x * STAR_FIELD_GROUP_SIZE;
  for (uint s = gl_GlobalInvocationID.x; s < params.counts.x; s += stride) splat(stars[s]);
}
