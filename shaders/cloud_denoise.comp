#version 460
// A still's clouds with their march's grain filtered out (passes/cloud_denoise; clouds.denoise,
// frames with no temporal reuse). One march per pixel starts at a random offset into its first
// step (volumetric_clouds.comp, pixelHash), so neighbouring pixels of one lit face differ by
// the step's sampling and its light march's: grain a time-lapse averages out over frames and
// a still keeps (the lit faces of a 640 x 360 frame held 1.5 times the reference march's
// high-frequency energy, those of its nearest cloud 2.6 times; docs/clouds.md, "Grain").
// Each pixel becomes the binomial 3 x 3 mean (1 2 1 by 1 2 1) of its neighbours alike in what
// they show:
// - only where the finest detail is several pixels wide (CLOUD_DENOISE_FINE_PIXELS): there the
//   cloud has no texture of a pixel's size, and what differs from pixel to pixel is grain;
// - two that both hold cloud mix as far as their depths agree (a near cloud keeps its outline
//   against a far one), the more so the narrower the pixel (CLOUD_DENOISE_NEAR_PIXELS);
// - across a cloud's edge the pair mixes by distance alone, so the edge's grain goes too;
// - a ray that meets the ground is left as it is and lends nothing to one that reaches the
//   shells; rays that reach them far apart mix less (cloudShellAlike, as the upsampling has).
// The depth is the mean of the cloudy ones.
#include "common/cloud_denoise_shared.h"
#include "common/params_block.glsl"
#include "common/cloud_shells.glsl"

layout(local_size_x = CLOUD_DENOISE_GROUP_X, local_size_y = CLOUD_DENOISE_GROUP_Y) in;

layout(std140, binding = CLOUD_DENOISE_BINDING_PARAMS) uniform CloudDenoiseBlock {
  CloudDenoiseParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = CLOUD_DENOISE_BINDING_CLOUDS, rgba32f) uniform readonly image2D clouds;
layout(binding = CLOUD_DENOISE_BINDING_DEPTH, rg32f) uniform readonly image2D depth;
layout(binding = CLOUD_DENOISE_BINDING_OUT_CLOUDS, rgba32f) uniform writeonly image2D outClouds;
layout(binding = CLOUD_DENOISE_BINDING_OUT_DEPTH, rg32f) uniform writeonly image2D outDepth;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(params.view.size.xy);
  if (any(greaterThanEqual(p, size))) return;
  vec4 centre = imageLoad(clouds, p);
  vec2 centreZ = imageLoad(depth, p).rg;
  // A ray that meets the ground before the shells has no cloud, and takes none from the
  // neighbours that reach them.
  if (centreZ.g < 0.0) {
    imageStore(outClouds, p, centre);
    imageStore(outDepth, p, vec4(centreZ, 0.0, 0.0));
    return;
  }
  // A pixel much narrower than the finest detail (a near cloud) shows none of it: its
  // neighbours mix whatever their grainy depths say, bar a cloud in front of another.
  float footprintM = max(centreZ.r, 1.0) * params.view.forward.w;
  float spread = params.depthSpread +
                 min(params.detailCellM / (CLOUD_DENOISE_NEAR_PIXELS * footprintM), 1.0);
  vec4 sum = vec4(0.0);
  float weightSum = 0.0, depthSum = 0.0, depthWeight = 0.0;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) {
      ivec2 q = clamp(p + ivec2(i, j), ivec2(0), size - 1);
      vec4 c = imageLoad(clouds, q);
      vec2 z = imageLoad(depth, q).rg;
      if (z.g < 0.0) continue;
      float w = float((2 - abs(i)) * (2 - abs(j))) * cloudShellAlike(z.g, centreZ.g);
      // Only where a pixel is much narrower than the finest detail, so that the cloud has no
      // texture of a pixel's size (CLOUD_DENOISE_FINE_PIXELS).
      if (i != 0 || j != 0) {
        float pairFootprintM = max(max(z.r, centreZ.r), 1.0) * params.view.forward.w;
        w *= clamp((params.detailCellM / pairFootprintM - CLOUD_DENOISE_FINE_PIXELS) /
                       CLOUD_DENOISE_FINE_PIXELS, 0.0, 1.0);
      }
      if (centre.a > CLOUD_DENOISE_CLOUDY && c.a > CLOUD_DENOISE_CLOUDY) {
        float rel = abs(z.r - centreZ.r) / max(max(z.r, centreZ.r), 1.0) / spread;
        w *= exp(-rel * rel);
      }
      sum += w * c;
      weightSum += w;
      depthSum += w * c.a * z.r;
      depthWeight += w * c.a;
    }
  imageStore(outClouds, p, sum / weightSum);
  imageStore(outDepth, p,
             vec4(depthWeight > 0.0 ? depthSum / depthWeight : 0.0, centreZ.g, 0.0, 0.0));
}
