#version 460
// Kernel for weather_texture_test.cpp: the weather map and its coarse max-cover map sampled
// the way the cloud pass samples them, at WEATHER_KERNEL_SIZE^2 points spread over the map.
// results: (map.r, map.g) linear, (coarse.r, coarse.g) linear; nearest: coarse by texelFetch.
#define WEATHER_KERNEL_SIZE 64
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D weatherMap;
layout(binding = 1) uniform sampler2D coarseMap;
layout(binding = 2, rgba32f) uniform writeonly image2D results;
layout(binding = 3, rgba32f) uniform writeonly image2D nearest;

void main() {
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  // Irrational offsets: the points fall at every phase between texel centres.
  vec2 uv = (vec2(id) + vec2(0.3183, 0.6180)) / float(WEATHER_KERNEL_SIZE);
  vec2 m = texture(weatherMap, uv).rg;
  vec2 c = texture(coarseMap, uv).rg;
  imageStore(results, id, vec4(m, c));
  ivec2 size = textureSize(coarseMap, 0);
  ivec2 texel = clamp(ivec2(floor(uv * vec2(size))), ivec2(0), size - 1);
  imageStore(nearest, id, texelFetch(coarseMap, texel, 0));
}
