#version 460
// Kernel test of shaders/common/noise3d.glsl (tests/cloud_noise/noise3d_kernel_test.cpp): each
// invocation evaluates the noise functions at one point p of a grid that spans negative and
// beyond-period coordinates, and again at p moved by whole periods.
#include <common/noise3d.glsl>

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) writeonly uniform image2D perlinAt;       // value, gradient
layout(rgba32f, binding = 1) writeonly uniform image2D perlinShifted;  // the same, moved
layout(rgba32f, binding = 2) writeonly uniform image2D cellular;       // simplex, F1, both moved
layout(rgba32f, binding = 3) writeonly uniform image2D fbms;  // Perlin fbm, simplex fbm, moved
layout(rgba32f, binding = 4) writeonly uniform image2D curls;  // curl xyz, curl.x moved

const ivec3 kPeriod = ivec3(5, 3, 4);
const uint kSeed = 77u;

// The grid point of invocation i: a plane slanted through all three axes.
vec3 pointOf(ivec2 i) {
  return vec3(i.x, i.y, 0.5 * float(i.x) - 0.3 * float(i.y)) * 0.173 - vec3(2.7, 1.9, 0.6);
}

void main() {
  ivec2 i = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(i, ivec2(64)))) return;
  vec3 p = pointOf(i);
  vec3 moved = p + vec3(kPeriod * ivec3(3, -2, 1));
  imageStore(perlinAt, i, perlinNoise3d(p, kPeriod, kSeed));
  imageStore(perlinShifted, i, perlinNoise3d(moved, kPeriod, kSeed));
  imageStore(cellular, i,
             vec4(simplexNoise3(p, kPeriod, kSeed), worleyF1(p, kPeriod, kSeed),
                  simplexNoise3(moved, kPeriod, kSeed), worleyF1(moved, kPeriod, kSeed)));
  imageStore(fbms, i,
             vec4(perlinFbm3(p, kPeriod, kSeed, 4, 0.5), simplexFbm3(p, kPeriod, kSeed, 3, 0.6),
                  perlinFbm3(moved, kPeriod, kSeed, 4, 0.5),
                  simplexFbm3(moved, kPeriod, kSeed, 3, 0.6)));
  vec3 c = curlNoise3(p, kPeriod, kSeed, 2, 0.5);
  imageStore(curls, i, vec4(c, curlNoise3(moved, kPeriod, kSeed, 2, 0.5).x));
}
