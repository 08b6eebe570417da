#version 460
// The per-cover coarse high-cloud texture, for the far field of a layer whose cover varies per
// pixel (regional cover from the weather map): layer k holds the coefficients the rank/shape
// texture gives at cover c_k = k / (STEPS - 1), box-filtered over (N / C)^2 texels, exactly
// what high_cloud_reduce.comp makes of a texture baked at cover c_k. The draw interpolates
// between the layers in c; the means of the layers are the far-field table.
#include "common/high_cloud_bake_shared.h"
#include "common/high_cloud_coverage.glsl"

layout(local_size_x = HIGH_CLOUD_GROUP_X, local_size_y = HIGH_CLOUD_GROUP_Y) in;

layout(push_constant) uniform Push {
  HighCloudCoverReduceParams params;
};
layout(rgba16f, binding = HIGH_CLOUD_COVER_REDUCE_BINDING_RANK_SHAPE) readonly uniform image2D
    rankShape;
layout(rgba16f, binding = HIGH_CLOUD_COVER_REDUCE_BINDING_COARSE) writeonly uniform image3D
    coverCoarse;

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  int c = int(params.size.y), steps = int(params.size.w);
  if (any(greaterThanEqual(p.xy, ivec2(c))) || p.z >= steps) return;
  float cover = float(p.z) / float(steps - 1);
  float w = params.ramp.x;
  int box = int(params.size.z);
  vec4 sum = vec4(0.0);
  for (int y = 0; y < box; ++y)
    for (int x = 0; x < box; ++x)
      sum += highCloudCoefficients(imageLoad(rankShape, p.xy * box + ivec2(x, y)).rg, cover, w);
  imageStore(coverCoarse, p, sum / float(box * box));
}
