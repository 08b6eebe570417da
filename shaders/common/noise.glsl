// Tileable (periodic) procedural noise for baked textures.
//
// Every function takes a lattice `period` (in lattice cells, per axis): the result repeats
// exactly when p moves by `period`, because the lattice hash sees cell coordinates modulo the
// period. To tile a texture over uv in [0, 1), evaluate at p = uv * f with an integer
// frequency f and period f; different integer frequencies along the axes give anisotropic
// noise that still tiles. Octave i of fbm runs at 2^i times the frequency with 2^i times the
// period, so fbm tiles too. A `seed` picks an independent field.
//
// 2D only for now: gradient (Perlin) noise, value noise, fbm of both, ridged fbm and
// Worley/cellular (F1, F2). Cell coordinates must stay above -64 periods, far beyond any
// domain warp.
#ifndef SKY_NOISE_GLSL
#define SKY_NOISE_GLSL

// pcg3d from Jarzynski and Olano, "Hash Functions for GPU Rendering" (JCGT 9(3), 2020): a
// cheap integer hash with good avalanche in all three outputs.
uvec3 noiseHash3(uvec3 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

// A hash in [0, 1) per component.
vec3 noiseHashUnit3(uvec3 v) {
  return vec3(noiseHash3(v) >> 8u) * (1.0 / 16777216.0);
}

// A new seed for the field number `index` derived from `seed` (independent fields of one bake).
uint noiseSeed(uint seed, uint index) {
  return noiseHash3(uvec3(seed, index, 0x5bd1e995u)).x;
}

// The lattice cell `cell` folded into [0, period): what makes the noise periodic.
uvec2 noiseWrap2(ivec2 cell, ivec2 period) {
  return uvec2(cell + period * 64) % uvec2(period);
}

// A unit gradient at a random angle. The angle stays in [-pi, pi), where Vulkan bounds the
// error of sin and cos (2^-11).
vec2 noiseGradient2(ivec2 cell, ivec2 period, uint seed) {
  float h = noiseHashUnit3(uvec3(noiseWrap2(cell, period), seed)).x;
  float angle = 6.28318530718 * h - 3.14159265359;
  return vec2(cos(angle), sin(angle));
}

// Perlin's quintic fade 6t^5 - 15t^4 + 10t^3 (Perlin 2002, "Improving Noise"): C2 across cells.
vec2 noiseFade2(vec2 t) {
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// Gradient noise in about [-1, 1] (unit gradients reach at most sqrt(1/2); scaled by sqrt(2)).
float gradientNoise2(vec2 p, ivec2 period, uint seed) {
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec2 c = ivec2(i);
  float n00 = dot(noiseGradient2(c, period, seed), f);
  float n10 = dot(noiseGradient2(c + ivec2(1, 0), period, seed), f - vec2(1.0, 0.0));
  float n01 = dot(noiseGradient2(c + ivec2(0, 1), period, seed), f - vec2(0.0, 1.0));
  float n11 = dot(noiseGradient2(c + ivec2(1, 1), period, seed), f - vec2(1.0, 1.0));
  vec2 u = noiseFade2(f);
  return 1.41421356 * mix(mix(n00, n10, u.x), mix(n01, n11, u.x), u.y);
}

// Value noise in [0, 1]: random values at the lattice points, quintic interpolation.
float valueNoise2(vec2 p, ivec2 period, uint seed) {
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec2 c = ivec2(i);
  float v00 = noiseHashUnit3(uvec3(noiseWrap2(c, period), seed)).x;
  float v10 = noiseHashUnit3(uvec3(noiseWrap2(c + ivec2(1, 0), period), seed)).x;
  float v01 = noiseHashUnit3(uvec3(noiseWrap2(c + ivec2(0, 1), period), seed)).x;
  float v11 = noiseHashUnit3(uvec3(noiseWrap2(c + ivec2(1, 1), period), seed)).x;
  vec2 u = noiseFade2(f);
  return mix(mix(v00, v10, u.x), mix(v01, v11, u.x), u.y);
}

// Fractional Brownian motion of gradient noise: `octaves` octaves, each at twice the
// frequency (and period) of the last and `gain` times its amplitude, each with its own seed.
// Normalised by the sum of the amplitudes, so the result stays in about [-1, 1].
float fbmGradient2(vec2 p, ivec2 period, uint seed, int octaves, float gain) {
  float sum = 0.0, amplitude = 1.0, norm = 0.0;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * gradientNoise2(p, period, noiseSeed(seed, uint(i)));
    norm += amplitude;
    amplitude *= gain;
    p *= 2.0;
    period *= 2;
  }
  return sum / norm;
}

// fbm of value noise, in [0, 1].
float fbmValue2(vec2 p, ivec2 period, uint seed, int octaves, float gain) {
  float sum = 0.0, amplitude = 1.0, norm = 0.0;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * valueNoise2(p, period, noiseSeed(seed, uint(i)));
    norm += amplitude;
    amplitude *= gain;
    p *= 2.0;
    period *= 2;
  }
  return sum / norm;
}

// Ridged fbm in [0, 1]: 1 - |noise| per octave turns the zero crossings of gradient noise into
// thin bright ridges (filaments, fibres); squared to sharpen them.
float fbmRidged2(vec2 p, ivec2 period, uint seed, int octaves, float gain) {
  float sum = 0.0, amplitude = 1.0, norm = 0.0;
  for (int i = 0; i < octaves; ++i) {
    float r = 1.0 - abs(gradientNoise2(p, period, noiseSeed(seed, uint(i))));
    sum += amplitude * r * r;
    norm += amplitude;
    amplitude *= gain;
    p *= 2.0;
    period *= 2;
  }
  return sum / norm;
}

// Worley (cellular) noise, Worley 1996: one feature point per cell, displaced from the cell's
// centre by up to `jitter` / 2 of a cell (jitter 1: anywhere in the cell; 0: a regular grid).
// Returns (F1, F2), the distances to the nearest and second-nearest feature points, in cells.
// The 3x3 neighbourhood is exact for jitter <= 1.
vec2 worley2(vec2 p, ivec2 period, uint seed, float jitter) {
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec2 c = ivec2(i);
  float f1 = 8.0, f2 = 8.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 o = ivec2(dx, dy);
      vec2 h = noiseHashUnit3(uvec3(noiseWrap2(c + o, period), seed)).xy;
      vec2 feature = vec2(o) + 0.5 + jitter * (h - 0.5);
      float d = length(feature - f);
      if (d < f1) {
        f2 = f1;
        f1 = d;
      } else if (d < f2) {
        f2 = d;
      }
    }
  }
  return vec2(f1, f2);
}

#endif
