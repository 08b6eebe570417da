#version 460
// Kernel tests of shaders/common/cirrus.glsl (tests/high_clouds/cirrus_kernel_test.cpp).
// CIRRUS_KERNEL_FLOW: over a 256 x 256 grid of the tile for each of four seeds (the image's
// quadrants), the flow's angle, the angle of the flow this one replaced, the largest turn of
// the path a streak is drawn along and the path's length.
// CIRRUS_KERNEL_FIELD: the field x the rank is taken of, over a 512 x 512 texture for each of
// the four seeds of the quantile table (the quadrants), as the bake computes it.
#include <common/cirrus.glsl>

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) writeonly uniform image2D result;

// The bake's seed for a scene's seed (high_cloud_bake.comp).
uint bakeSeed(uint sceneSeed) {
  return noiseHash3(uvec3(sceneSeed, 0x68636c64u, 1u)).x;
}

// The flow before issue 46: 3 fbm at 2 cycles a tile plus 0.4 fbm at 6, an angle that
// wanders over +-2 rad and more across the tile.
float oldCirrusFlowAngle(vec2 uv, uint seed) {
  float regions = fbmGradient2(uv * 2.0, ivec2(2), noiseSeed(seed, 70u), 3, 0.5);
  float bends = fbmGradient2(uv * 6.0, ivec2(6), noiseSeed(seed, 71u), 2, 0.5);
  return 3.0 * regions + 0.4 * bends;
}

void main() {
  ivec2 i = ivec2(gl_GlobalInvocationID.xy);
#if CIRRUS_KERNEL_FLOW
  const int n = 256;
  const uint seeds[4] = uint[4](1u, 2u, 3u, 4u);
#else
  const int n = 512;
  const uint seeds[4] = uint[4](1u, 3u, 7u, 42u);
#endif
  if (any(greaterThanEqual(i, ivec2(2 * n)))) return;
  uint seed = bakeSeed(seeds[(i.y / n) * 2 + i.x / n]);
  vec2 uv = (vec2(i % n) + 0.5) / float(n);
#if CIRRUS_KERNEL_FLOW
  CirrusPath path = cirrusPath(uv, seed);
  float turn = 0.0;
  for (int k = 0; k <= 32; ++k) turn = max(turn, abs(cirrusPathAngle(path, float(k) / 32.0)));
  imageStore(result, i,
             vec4(cirrusFlowAngle(uv, seed), oldCirrusFlowAngle(uv, seed), turn, path.len));
#else
  CirrusField field = cirrusField(uv, seed, float(n));
  imageStore(result, i, vec4(field.x, field.shape, 0.0, 0.0));
#endif
}
