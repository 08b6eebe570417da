#version 460
// The tileable 2D curl-noise texture (Tang et al. 2019; docs/cloud-noise.md): the curl of a
// Perlin vector potential on the plane z = kSliceZ of its 3D domain, which perturbs the detail
// lookup. Divergence-free as a 3D field; the texture keeps all three components.
#include "common/cloud_noise_shared.h"
#include "common/noise3d.glsl"

layout(local_size_x = CLOUD_NOISE_GROUP_2D, local_size_y = CLOUD_NOISE_GROUP_2D) in;

layout(push_constant) uniform Push {
  CloudNoiseParams params;
};
layout(rgba8, binding = CLOUD_NOISE_BINDING_OUT) writeonly uniform image2D curl;

// The potential's base frequency (cells a tile) and octaves: 4, 8, 16 cells, the finest 8
// texels a cell. Differentiation multiplies octave i by 2^i, so the potential's gain of 1/4
// leaves the velocity a gain of 1/2: large swirls with smaller ones on them, not grain.
const int kFrequency = 4;
const int kOctaves = 3;
const float kGain = 0.25;
// A plane off the lattice: at integer z, Perlin noise loses the corner terms of one axis.
const float kSliceZ = 0.37;
// |v| per component stays below this for all but a fraction of a percent of the texels
// (measured); v / kCurlSpan is clamped to [-1, 1].
const float kCurlSpan = 2.5;

void main() {
  uint n = params.size.x;
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(n)))) return;
  vec2 uv = (vec2(texel) + 0.5) / float(n);
  vec3 p = vec3(uv * float(kFrequency), kSliceZ);
  vec3 v = curlNoise3(p, ivec3(kFrequency), noiseSeed(0x6375726cu, 0u), kOctaves, kGain);
  imageStore(curl, texel, vec4(0.5 + 0.5 * clamp(v / kCurlSpan, -1.0, 1.0), 1.0));
}
