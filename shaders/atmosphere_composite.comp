#version 460
// The final image: for now the Kozlov 3.1 clear sky plus the sun disc, in scene-linear
// Rec.709. Later layers (high clouds, volumetric clouds, aerial perspective) join here.
#include "common/atmosphere_composite_shared.h"
#include "common/view.glsl"
#include "common/kozlov_sky.glsl"

layout(local_size_x = ATMOSPHERE_COMPOSITE_GROUP_X, local_size_y = ATMOSPHERE_COMPOSITE_GROUP_Y) in;

layout(std140, binding = ATMOSPHERE_COMPOSITE_BINDING_PARAMS) uniform Params {
  AtmosphereCompositeParams params;
};
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_BEAUTY, rgba16f) uniform writeonly image2D beautyImage;
layout(binding = ATMOSPHERE_COMPOSITE_BINDING_SKY, rgba16f) uniform writeonly image2D skyImage;

// Fraction of a pixel of angular size `pixel` covered by a disc of angular radius `radius`
// whose centre is `distance` away (a box-filtered edge). A disc smaller than a pixel is
// spread over one pixel's width with its radiance scaled by the area ratio, so its energy
// stays within ~8 % of pi r^2 L instead of flickering in and out at test sizes like 64x36.
float discCoverage(float distance, float radius, float pixel) {
  float spread = max(radius, pixel);
  float inside = clamp((spread - distance) / pixel + 0.5, 0.0, 1.0);
  return inside * (radius * radius) / (spread * spread);
}

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, params.view.size.xy))) return;
  vec3 V = viewDirection(params.view, vec2(p) + 0.5);
  vec3 S = params.sunDirection.xyz;

  vec3 sky = kozlovClearSky(V, S, params.skyColor.rgb, params.fogColor.rgb, params.glowColor.rgb,
                            params.skyColor.w, params.fogColor.w);

  // A pinhole pixel spans p cos^2 (radially) by p cos (tangentially) at angle theta off axis.
  float cosOffAxis = dot(V, params.view.forward.xyz);
  float pixelAngle = params.view.forward.w * pow(cosOffAxis, 1.5);
  float distance = acos(clamp(dot(V, S), -1.0, 1.0));
  // The ground hides whatever part of the disc lies below the horizon: the share of the
  // disc above it (linear in elevation across the diameter), drawn only above the horizon.
  float radius = params.sunDirection.w;
  float discAbove = clamp((asin(clamp(S.z, -1.0, 1.0)) + radius) / (2.0 * radius), 0.0, 1.0);
  float aboveHorizon = clamp(V.z / pixelAngle + 0.5, 0.0, 1.0);
  vec3 disc = params.sunDisc.rgb * discCoverage(distance, radius, pixelAngle) * discAbove * aboveHorizon;

  imageStore(skyImage, ivec2(p), vec4(sky, 1.0));
  imageStore(beautyImage, ivec2(p), vec4(sky + disc, 1.0));
}
