#version 460
// The high-cloud coefficients' mip levels 1 .. L - 1 in one image (common/high_cloud_levels.glsl):
// each texel of level l is the box mean of its 2^l x 2^l texels of the coefficient texture, so
// the draw can filter the texture by the pixel's footprint instead of aliasing its fibres.
#include "common/high_cloud_bake_shared.h"
#include "common/high_cloud_levels.glsl"

layout(local_size_x = HIGH_CLOUD_GROUP_X, local_size_y = HIGH_CLOUD_GROUP_Y) in;

layout(push_constant) uniform Push {
  HighCloudLevelsParams params;
};
layout(rgba16f, binding = HIGH_CLOUD_LEVELS_BINDING_COEFFICIENTS) readonly uniform image2D
    coefficients;
layout(rgba16f, binding = HIGH_CLOUD_LEVELS_BINDING_LEVELS) writeonly uniform image2D levels;

void main() {
  uint n = params.size.x, coarse = params.size.y;
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), highCloudLevelsSize(n, coarse)))) return;
  // The level this column belongs to: level l spans [N - 2N / 2^l, N - N / 2^l).
  int level = 1;
  while (p.x >= int(n) - int(n >> uint(level))) ++level;
  int size = int(n >> uint(level));
  ivec2 local = ivec2(p.x - highCloudLevelColumn(n, level), p.y);
  if (local.y >= size) {
    imageStore(levels, p, vec4(0.0));  // below a level: unused
    return;
  }
  int box = 1 << level;
  vec4 sum = vec4(0.0);
  for (int y = 0; y < box; ++y)
    for (int x = 0; x < box; ++x) sum += imageLoad(coefficients, local * box + ivec2(x, y));
  imageStore(levels, p, sum / float(box * box));
}
