#version 460
// The benchmark harness's empty full-screen pass (benchmarks/skybench, op "empty"): one
// invocation per pixel that writes a constant to an RGBA32F image, the format of the frame's
// full-screen images, and does nothing else. Its time is the floor a full-screen pass of that
// size pays on a device (launching the groups, the stores), the yardstick the harness
// measures the frame's other passes against (benchmarks/README.md).
#include "common/empty_pass_shared.h"

layout(local_size_x = EMPTY_PASS_GROUP_X, local_size_y = EMPTY_PASS_GROUP_Y) in;

layout(binding = EMPTY_PASS_BINDING_OUT, rgba32f) uniform writeonly image2D outImage;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(outImage)))) return;
  imageStore(outImage, p, vec4(0.5, 0.5, 0.5, 1.0));
}
