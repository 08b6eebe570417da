#version 460
// The tileable 3D cloud-noise volumes (docs/cloud-noise.md): the shape texture (Lu Table 1,
// Tang: 128^3) or the detail texture (Lu: 32^3, Tang: 64^3), one texel per invocation.
// CloudNoiseParams.size.z picks which (CLOUD_NOISE_VOLUME_*), size.y the model.
#include "common/cloud_noise_shared.h"
#include "common/noise3d.glsl"

layout(local_size_x = CLOUD_NOISE_GROUP_3D, local_size_y = CLOUD_NOISE_GROUP_3D,
       local_size_z = CLOUD_NOISE_GROUP_3D) in;

layout(push_constant) uniform Push {
  CloudNoiseParams params;
};
layout(rgba8, binding = CLOUD_NOISE_BINDING_OUT) writeonly uniform image3D volume;

// Lu (11): fbm(n1, n2, n3) = 0.625 n1 + 0.25 n2 + 0.125 n3. An octave that the texture cannot
// resolve is left out (weight 0) and the others renormalised.
float luFbm(float n1, float n2, float n3, vec3 use) {
  vec3 w = vec3(0.625, 0.25, 0.125) * use;
  return dot(w, vec3(n1, n2, n3)) / (w.x + w.y + w.z);
}

// Linear remap, Lu (3): R(v, lo, ho, ln, hn) = ln + (v - lo) (hn - ln) / (ho - lo).
float remap(float v, float lo, float ho, float ln, float hn) {
  return ln + (v - lo) * (hn - ln) / (ho - lo);  // Lu (3)
}

// Where each channel's raw value lands on [0, 1]: the fbm of a few octaves has a narrower
// spread than its parts, so each channel is stretched linearly from the span [x, y] that holds
// all but about 0.5 % of its texels at either end (measured on the baked textures) onto
// [0, 1], and clamped.
const vec2 kWorleySpan3 = vec2(0.185, 0.78);  // Worley fbm of three octaves
const vec2 kWorleySpan2 = vec2(0.15, 0.815);  // of two (the finest octave left out)
const float kPerlinSpan = 0.42;               // Perlin fbm, 4 octaves: [-0.42, 0.42]
const float kSimplexSpan = 0.56;              // simplex fbm, 4 octaves: [-0.56, 0.56]
const vec2 kPerlinWorleySpan = vec2(0.29, 1.0);  // Perlin-Worley: [0.29, 1]

float stretch(float v, vec2 span) {
  return clamp((v - span.x) / (span.y - span.x), 0.0, 1.0);
}

// Inverted Worley "layers": layer k has 2^k times the base frequency (cells per tile) and a
// seed of its own. Channel c takes Lu (11)'s three consecutive octaves from layers c, c + 1,
// c + 2 (shape: R's Worley part low, G medium, B high, A highest; detail: R low, G medium,
// B high), shared between channels as in Schneider's and Hillaire's reference bakes, so a
// volume costs 5 Worley evaluations a texel rather than 11. Layers finer than 2 texels a cell
// would only alias: their weight is 0 (use[k]), and layer 5 never exists.
const int kLayers = 5;

void main() {
  uint n = params.size.x;
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(uvec3(texel), uvec3(n)))) return;
  bool shape = params.size.z == CLOUD_NOISE_VOLUME_SHAPE;
  bool tang = params.size.y == CLOUD_NOISE_MODEL_TANG2019;
  vec3 uvw = (vec3(texel) + 0.5) / float(n);  // texel centres in the tile [0, 1)^3

  // Shape layers at 4, 8, ..., 64 cells a tile; detail layers from n / 16 cells a tile: 2 for
  // the 32^3 detail (16 texels a cell), 4 for the 64^3 one.
  int base = shape ? 4 : int(n) / 16;
  uint seed = noiseSeed(shape ? 0x73686170u : 0x64657461u, params.size.y);
  float layer[kLayers + 1];
  float use[kLayers + 1];
  // Tang's shape R is simplex noise alone: its Worley layer 0 would go unused.
  int first = shape && tang ? 1 : 0;
  for (int k = 0; k <= kLayers; ++k) {
    int f = base << k;
    use[k] = k < kLayers && 2 * f <= int(n) ? 1.0 : 0.0;
    layer[k] = use[k] > 0.0 && k >= first
                   ? worleyInverted3(uvw * float(f), ivec3(f), noiseSeed(seed, uint(k)))
                   : 0.0;
  }
  vec4 worley;
  for (int c = 0; c < 4; ++c) {
    float raw = luFbm(layer[c], layer[c + 1], layer[c + 2], vec3(use[c], use[c + 1], use[c + 2]));
    worley[c] = stretch(raw, use[c + 2] > 0.0 ? kWorleySpan3 : kWorleySpan2);
  }

  vec4 result;
  if (shape) {
    float r;
    if (tang) {
      // Tang: simplex fbm, Tang (1), 4 octaves from 4 to 32 cells a tile (4 texels a cell).
      float s = simplexFbm3(uvw * 4.0, ivec3(4), noiseSeed(seed, 16u), 4, 0.5);
      r = clamp(0.5 + 0.5 * s / kSimplexSpan, 0.0, 1.0);
    } else {
      // Perlin-Worley (Schneider 2015, Nubis): Perlin fbm dilated by the low Worley fbm,
      // remap(perlin, worley - 1, 1, 0, 1): the Worley cells make billows, the Perlin
      // noise connects them.
      float p = perlinFbm3(uvw * 4.0, ivec3(4), noiseSeed(seed, 17u), 4, 0.5);
      float p01 = clamp(0.5 + 0.5 * p / kPerlinSpan, 0.0, 1.0);
      r = stretch(remap(p01, worley.r - 1.0, 1.0, 0.0, 1.0), kPerlinWorleySpan);  // Lu (3)
    }
    result = vec4(r, worley.gba);
  } else {
    // Lu (14): NDfbm = fbm(dnr, dng, dnb), precomputed for the raymarcher.
    result = vec4(worley.rgb, luFbm(worley.r, worley.g, worley.b, vec3(1.0)));
  }
  imageStore(volume, texel, result);
}
