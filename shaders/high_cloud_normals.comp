#version 460
// The high-cloud normal map from the coefficient texture: the height field is the opacity
// 1 - B (the clear-sky channel), scaled to HIGH_CLOUD_NORMAL_RELIEF of the tile, and the normal
// of that surface comes from central differences that wrap around the tile's edges, so the
// normal map tiles like the texture. Tangent space: x east (+u, the columns), y north (image
// up, towards row 0), z up out of the layer (the OpenGL convention); w = 0.
#include "common/high_cloud_bake_shared.h"

layout(local_size_x = HIGH_CLOUD_GROUP_X, local_size_y = HIGH_CLOUD_GROUP_Y) in;

layout(push_constant) uniform Push {
  HighCloudNormalsParams params;
};
layout(rgba16f, binding = HIGH_CLOUD_NORMALS_BINDING_COEFFICIENTS) readonly uniform image2D
    coefficients;
layout(rgba16f, binding = HIGH_CLOUD_NORMALS_BINDING_NORMALS) writeonly uniform image2D normals;

float heightAt(ivec2 p, int n) {
  return 1.0 - imageLoad(coefficients, (p + n) % n).b;  // p >= -1: +n keeps it non-negative
}

void main() {
  int n = int(params.size.x);
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(n)))) return;
  // Per texel; north is the previous row.
  float dhdx = 0.5 * (heightAt(p + ivec2(1, 0), n) - heightAt(p - ivec2(1, 0), n));
  float dhdy = 0.5 * (heightAt(p - ivec2(0, 1), n) - heightAt(p + ivec2(0, 1), n));
  // Surface z = relief * h(x, y): normal (-dz/dx, -dz/dy, 1), normalised.
  float relief = params.relief.x;
  vec3 normal = normalize(vec3(-relief * dhdx, -relief * dhdy, 1.0));
  imageStore(normals, p, vec4(normal, 0.0));
}
