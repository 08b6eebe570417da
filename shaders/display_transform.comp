#version 460
// The GPU display path (passes/display_transform): each pixel of the physical beauty through
// the night look (output.night_look), the exposure and the OCIO view baked into a 3D table
// over a log2 shaper (engine/color/display_lut.h), to 8-bit display codes. What a window
// shows and a benchmark frame reads back; skyrender's PNG keeps the exact CPU transform.
#include "common/display_transform_shared.h"
#include "common/params_block.glsl"
#include "common/night_look.glsl"

layout(local_size_x = DISPLAY_TRANSFORM_GROUP_X, local_size_y = DISPLAY_TRANSFORM_GROUP_Y) in;

layout(std140, binding = DISPLAY_TRANSFORM_BINDING_PARAMS) uniform DisplayTransformBlock {
  DisplayTransformParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = DISPLAY_TRANSFORM_BINDING_BEAUTY, rgba32f) uniform readonly image2D beauty;
layout(binding = DISPLAY_TRANSFORM_BINDING_LUT) uniform sampler3D lut;
layout(binding = DISPLAY_TRANSFORM_BINDING_DISPLAY, rgba8) uniform writeonly image2D display;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(display)))) return;
  vec3 c = imageLoad(beauty, p).rgb;
  if (params.nightLook != 0u) c = nightLook(c);
  c = max(c, vec3(0.0)) * params.exposureScale;
  // The shaper (displayLutShaper), then the grid point i / (n - 1) at texel centre
  // (i + 0.5) / n.
  float range = params.lutMaxLog2 - params.lutMinLog2;
  vec3 s = clamp((log2(max(c, vec3(exp2(params.lutMinLog2)))) - params.lutMinLog2) / range, 0.0,
                 1.0);
  vec3 coord = (s * (params.lutSize - 1.0) + 0.5) / params.lutSize;
  imageStore(display, p, vec4(clamp(textureLod(lut, coord, 0.0).rgb, 0.0, 1.0), 1.0));
}
