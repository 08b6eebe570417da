#version 460
// The clouds marched (and temporally resolved) at reduced resolution, brought to the view's
// (passes/cloud_upsample; clouds.temporal.resolution half): each pixel a bilinear blend of
// the four nearest reduced pixels, weighted by how alike their rays are for the clouds
// (cloudShellAlike: a ray that meets the ground before the shells takes nothing from one
// that reaches them, so the horizon stays sharp), the depth from the cloudy ones alone.
#include "common/cloud_upsample_shared.h"
#include "common/params_block.glsl"
#include "common/view.glsl"
#include "common/cloud_shells.glsl"

layout(local_size_x = CLOUD_UPSAMPLE_GROUP_X, local_size_y = CLOUD_UPSAMPLE_GROUP_Y) in;

layout(std140, binding = CLOUD_UPSAMPLE_BINDING_PARAMS) uniform CloudUpsampleBlock {
  CloudUpsampleParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = CLOUD_UPSAMPLE_BINDING_CLOUDS, rgba32f) uniform readonly image2D clouds;
layout(binding = CLOUD_UPSAMPLE_BINDING_DEPTH, rg32f) uniform readonly image2D depth;
layout(binding = CLOUD_UPSAMPLE_BINDING_OUT_CLOUDS, rgba32f) uniform writeonly image2D outClouds;
layout(binding = CLOUD_UPSAMPLE_BINDING_OUT_DEPTH, rg32f) uniform writeonly image2D outDepth;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(params.view.size.xy)))) return;
  vec3 d = viewDirection(params.view, vec2(p) + 0.5);
  float entry = cloudShellEntry(params.planetRadiusM, params.cameraAltitudeM, params.shellBaseM,
                                params.shellTopM, d);
  vec2 size = vec2(params.source.size.xy);
  // This pixel's centre among the reduced pixels' centres.
  vec2 f = (vec2(p) + 0.5) * size / vec2(params.view.size.xy) - 0.5;
  ivec2 q0 = ivec2(floor(f));
  vec2 t = f - vec2(q0);
  vec4 sum = vec4(0.0);
  float weightSum = 0.0, depthSum = 0.0, depthWeight = 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      ivec2 q = clamp(q0 + ivec2(i, j), ivec2(0), ivec2(size) - 1);
      float w = (i == 0 ? 1.0 - t.x : t.x) * (j == 0 ? 1.0 - t.y : t.y);
      vec4 c = imageLoad(clouds, q);
      vec2 z = imageLoad(depth, q).rg;
      w = max(w, 1e-4) * cloudShellAlike(z.g, entry);
      sum += w * c;
      weightSum += w;
      depthSum += w * c.a * z.r;
      depthWeight += w * c.a;
    }
  imageStore(outClouds, p, sum / weightSum);
  imageStore(outDepth, p, vec4(depthWeight > 0.0 ? depthSum / depthWeight : 0.0, entry, 0.0, 0.0));
}
