// The high-cloud coefficients' mip levels (docs/high-clouds.md, "Filtering"): the levels
// texture holds levels 1 .. L - 1 of an N x N texture side by side in one image, level l
// (N / 2^l on a side, each texel the box mean of 2^l x 2^l texels of level 0) at column
// N - 2N / 2^l, row 0; level L = log2(N / C) is the coarse texture. One image keeps the
// bindings fixed whatever N is; the cost is a bilinear lookup by hand, since the sampler's
// repeat would wrap over the whole image instead of one level.
#ifndef SKY_HIGH_CLOUD_LEVELS_GLSL
#define SKY_HIGH_CLOUD_LEVELS_GLSL

// The number of the coarse level, L = log2(N / C).
int highCloudCoarseLevel(uint n, uint coarse) {
  return findMSB(n / coarse);
}

// Width and height of the levels texture for an N x N texture with a C x C coarse level.
uvec2 highCloudLevelsSize(uint n, uint coarse) {
  return uvec2(n - 2u * coarse, n / 2u);
}

// Column of level l (1 .. L - 1) in the levels texture.
int highCloudLevelColumn(uint n, int level) {
  return int(n) - int(2u * n >> uint(level));
}

// Level l (1 .. L - 1) at uv, bilinear between its texel centres, wrapping within the level
// like the tile it filters.
vec4 highCloudLevelSample(sampler2D levels, uint n, int level, vec2 uv) {
  int size = int(n >> uint(level));
  ivec2 origin = ivec2(highCloudLevelColumn(n, level), 0);
  vec2 p = uv * float(size) - 0.5;
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec2 c = ivec2(i) & ivec2(size - 1);  // size is a power of two: & wraps negatives too
  ivec2 c1 = (c + 1) & ivec2(size - 1);
  vec4 v00 = texelFetch(levels, origin + c, 0);
  vec4 v10 = texelFetch(levels, origin + ivec2(c1.x, c.y), 0);
  vec4 v01 = texelFetch(levels, origin + ivec2(c.x, c1.y), 0);
  vec4 v11 = texelFetch(levels, origin + c1, 0);
  return mix(mix(v00, v10, f.x), mix(v01, v11, f.x), f.y);
}

#endif
