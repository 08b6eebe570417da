#version 460
// The high-cloud normal map from the coefficient texture: the height field is the opacity
// 1 - B (the clear-sky channel), scaled to the relief (relief.x, in texels), and the normal
// of that surface comes from central differences that wrap around the tile's edges, so the
// normal map tiles like the texture. Tangent space: x east (+u, the columns), y north (image
// up, towards row 0), z up out of the layer (the OpenGL convention); w = 0.
// With size.y = l > 0 the height is read from mip level l (common/high_cloud_levels.glsl) and
// differenced over one of its texels: the normals of the layer's relief at that scale, without
// the finer detail. Cirrus takes them so: a fibre a few tens of metres wide is no surface with
// a lit and a shadowed side, and per-fibre normals would stripe every wisp with light and dark
// lines.
#include "common/high_cloud_bake_shared.h"
#include "common/high_cloud_levels.glsl"

layout(local_size_x = HIGH_CLOUD_GROUP_X, local_size_y = HIGH_CLOUD_GROUP_Y) in;

layout(push_constant) uniform Push {
  HighCloudNormalsParams params;
};
layout(rgba16f, binding = HIGH_CLOUD_NORMALS_BINDING_COEFFICIENTS) readonly uniform image2D
    coefficients;
layout(rgba16f, binding = HIGH_CLOUD_NORMALS_BINDING_NORMALS) writeonly uniform image2D normals;
layout(binding = HIGH_CLOUD_NORMALS_BINDING_LEVELS) uniform sampler2D levels;

float heightAt(ivec2 p, int n) {
  return 1.0 - imageLoad(coefficients, (p + n) % n).b;  // p >= -1: +n keeps it non-negative
}

// The height of level l at uv (bilinear, wrapping).
float levelHeightAt(int level, vec2 uv) {
  return 1.0 - highCloudLevelSample(levels, params.size.x, level, uv).b;
}

void main() {
  int n = int(params.size.x);
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(n)))) return;
  int level = int(params.size.y);
  // Per texel; north is the previous row.
  float dhdx, dhdy;
  if (level == 0) {
    dhdx = 0.5 * (heightAt(p + ivec2(1, 0), n) - heightAt(p - ivec2(1, 0), n));
    dhdy = 0.5 * (heightAt(p - ivec2(0, 1), n) - heightAt(p + ivec2(0, 1), n));
  } else {
    // Central differences over one texel of level l, 2^l texels of level 0, either side.
    vec2 uv = (vec2(p) + 0.5) / float(n);
    float step = float(1 << level);
    vec2 e = vec2(step / float(n), 0.0);
    dhdx = 0.5 * (levelHeightAt(level, uv + e.xy) - levelHeightAt(level, uv - e.xy)) / step;
    dhdy = 0.5 * (levelHeightAt(level, uv - e.yx) - levelHeightAt(level, uv + e.yx)) / step;
  }
  // Surface z = relief * h(x, y): normal (-dz/dx, -dz/dy, 1), normalised.
  float relief = params.relief.x;
  vec3 normal = normalize(vec3(-relief * dhdx, -relief * dhdy, 1.0));
  imageStore(normals, p, vec4(normal, 0.0));
}
