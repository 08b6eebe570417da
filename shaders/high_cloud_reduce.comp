#version 460
// The coarse high-cloud texture: the coefficients box-filtered over (N / C)^2 texels per
// coarse texel, for the far field (the layer near the horizon, where one pixel covers many
// texels and the full texture would alias). Its mean is the whole texture's mean.
#include "common/high_cloud_bake_shared.h"

layout(local_size_x = HIGH_CLOUD_GROUP_X, local_size_y = HIGH_CLOUD_GROUP_Y) in;

layout(push_constant) uniform Push {
  HighCloudReduceParams params;
};
layout(rgba16f, binding = HIGH_CLOUD_REDUCE_BINDING_COEFFICIENTS) readonly uniform image2D
    coefficients;
layout(rgba16f, binding = HIGH_CLOUD_REDUCE_BINDING_COARSE) writeonly uniform image2D coarse;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  int c = int(params.size.y);
  if (any(greaterThanEqual(p, ivec2(c)))) return;
  int box = int(params.size.z);
  vec4 sum = vec4(0.0);
  for (int y = 0; y < box; ++y)
    for (int x = 0; x < box; ++x) sum += imageLoad(coefficients, p * box + ivec2(x, y));
  imageStore(coarse, p, sum / float(box * box));
}
