#version 460
// Kernel for atmosphere_api_test.cpp: calls the sampling functions of
// shaders/common/atmosphere.glsl that other passes use, one query per column.
// Row 0: transmittanceToTop(r, mu); row 1: transmittanceAlong(V, distance);
// row 2: aerialPerspective(uv, distance).
#include <common/atmosphere.glsl>

#define KERNEL_QUERIES 64
layout(local_size_x = KERNEL_QUERIES) in;

layout(std140, binding = 0) uniform Params {
  AtmosphereParams params;
};
// [2i]: xyz the view direction, w the distance (km); [2i + 1]: r (km), mu, screen u, v.
layout(std140, binding = 1) uniform Queries {
  vec4 queries[2 * KERNEL_QUERIES];
};
layout(binding = 2) uniform sampler2D transmittanceLut;
layout(binding = 3) uniform sampler3D apLut;
layout(binding = 4, rgba32f) uniform writeonly image2D results;

void main() {
  uint i = gl_LocalInvocationIndex;
  vec4 a = queries[2 * i], b = queries[2 * i + 1];
  AtmosphereParams p = params;
  imageStore(results, ivec2(i, 0), vec4(transmittanceToTop(p, transmittanceLut, b.x, b.y), 1.0));
  imageStore(results, ivec2(i, 1), vec4(transmittanceAlong(p, transmittanceLut, a.xyz, a.w), 1.0));
  imageStore(results, ivec2(i, 2), aerialPerspective(p, apLut, b.zw, a.w));
}
