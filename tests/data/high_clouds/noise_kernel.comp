#version 460
// Kernel test of shaders/common/noise.glsl (tests/high_clouds/noise_kernel_test.cpp): each
// invocation evaluates the noise functions at one point p of a grid that spans negative and
// beyond-period coordinates, and again at p moved by whole periods.
#include <common/noise.glsl>

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) writeonly uniform image2D atPoint;
layout(rgba32f, binding = 1) writeonly uniform image2D atShifted;
layout(rgba32f, binding = 2) writeonly uniform image2D fbmAtPoint;

const ivec2 kPeriod = ivec2(5, 3);
const uint kSeed = 77u;

// gradient, value, Worley F1, Worley F2
vec4 noises(vec2 p) {
  vec2 f = worley2(p, kPeriod, kSeed, 0.8);
  return vec4(gradientNoise2(p, kPeriod, kSeed), valueNoise2(p, kPeriod, kSeed), f);
}

void main() {
  ivec2 i = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(i, ivec2(64)))) return;
  vec2 p = vec2(i) * 0.173 - vec2(2.7, 1.9);
  imageStore(atPoint, i, noises(p));
  imageStore(atShifted, i, noises(p + vec2(kPeriod * ivec2(3, -2))));
  imageStore(fbmAtPoint, i,
             vec4(fbmGradient2(p, kPeriod, kSeed, 4, 0.5), fbmValue2(p, kPeriod, kSeed, 3, 0.6),
                  fbmRidged2(p, kPeriod, kSeed, 3, 0.5),
                  fbmGradient2(p + vec2(kPeriod * ivec2(-1, 4)), kPeriod, kSeed, 4, 0.5)));
}
