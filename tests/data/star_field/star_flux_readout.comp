#version 460
// Test shader for shaders/common/star_field.glsl: per pixel, r = starFlux(p),
// g = pixelSolidAngle(view, centre of p), b = starFlux of the same pixel shifted one image
// width to the right (outside the image, so it must read 0).
#include "common/view_shared.h"
#define STAR_FLUX_BINDING 1
#include "common/star_field.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std140, binding = 0) uniform Params {
  ViewState view;
};
layout(binding = 2, rgba32f) uniform writeonly image2D outImage;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(view.size.xy)))) return;
  imageStore(outImage, p, vec4(starFlux(p), pixelSolidAngle(view, vec2(p) + 0.5),
                               starFlux(p + ivec2(view.size.x, 0)), 0.0));
}
