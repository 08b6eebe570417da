#version 460
// The procedural high-cloud coefficient texture (Kozlov et al. section 3, fig. 3): an optical
// depth tau per texel from tileable noise in one of three styles, turned into the four
// channels (docs/high-clouds.md, "The coefficient texture"). Each style gives a texel a rank r
// and a cover-independent optical depth factor `shape`, tau = shape * presence(r, c, w); the
// rank/shape texture keeps both so the draw can apply any cover per pixel (regional cover from
// the weather map). One dispatch fills one band of rows, so a large bake is split into several
// submits with progress in between.
#include "common/params_block.glsl"
#include "common/high_cloud_bake_shared.h"
#include "common/high_cloud_coverage.glsl"
#include "common/noise.glsl"
#include "common/cirrus.glsl"

layout(local_size_x = HIGH_CLOUD_GROUP_X, local_size_y = HIGH_CLOUD_GROUP_Y) in;

layout(std140, binding = HIGH_CLOUD_BAKE_BINDING_PARAMS) uniform Params {
  HighCloudBakeParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
// Greyscale, sampled bilinearly with wrap over one tile; multiplies the cover when used.
layout(binding = HIGH_CLOUD_BAKE_BINDING_COVER_MAP) uniform sampler2D coverMap;
layout(rgba16f, binding = HIGH_CLOUD_BAKE_BINDING_COEFFICIENTS) writeonly uniform image2D
    coefficients;
layout(rgba16f, binding = HIGH_CLOUD_BAKE_BINDING_RANK_SHAPE) writeonly uniform image2D rankShape;

// The spread of fbmGradient2 at gain 0.5, measured over many seeds and tiles: mean 0 (exactly,
// over whole periods), standard deviation 0.19 for 3 or more octaves (0.31 for one).
// rankOf() maps it to an about uniform [0, 1] with the logistic approximation of the normal
// CDF, Phi(z) ~ 1 / (1 + exp(-1.702 z)), so a cover fraction c can be a threshold at 1 - c.
const float kFbmSigma = 0.19;

float rankOf(float fbm) {
  return 1.0 / (1.0 + exp(-1.702 * fbm / kFbmSigma));
}

// Octaves of base frequency `frequency` (cycles per tile) whose highest stays at or below
// N / 4 cycles (4 texels a cycle): finer octaves would only alias.
int octavesFor(float frequency, float n) {
  return clamp(1 + int(floor(log2(max(n * 0.25 / frequency, 1.0)))), 1, 8);
}

// A displacement field of two independent fbm fields (domain warping): periodic, so the
// warped noise still tiles.
vec2 warpField(vec2 uv, float frequency, uint seed, float n) {
  ivec2 period = ivec2(frequency);
  int oct = octavesFor(frequency, n);
  return vec2(fbmGradient2(uv * frequency, period, noiseSeed(seed, 0u), oct, 0.5),
              fbmGradient2(uv * frequency, period, noiseSeed(seed, 1u), oct, 0.5));
}

// Cirrostratus: a thin, wide, low-contrast veil with faint fibres stretched 8:1 along u; at
// full cover it covers the whole tile with tau between about 0.3 and 0.8. Returns (rank,
// shape); ramp width HIGH_CLOUD_RAMP_CIRROSTRATUS.
vec2 cirrostratusRankShape(vec2 uv, uint seed, float n) {
  float veil = fbmGradient2(uv * 2.0, ivec2(2), noiseSeed(seed, 20u), octavesFor(2.0, n), 0.5);
  vec2 q = uv + 0.04 * warpField(uv, 2.0, noiseSeed(seed, 21u), n);
  float fibres = fbmGradient2(q * vec2(4.0, 32.0), ivec2(4, 32), noiseSeed(seed, 22u),
                              octavesFor(32.0, n), 0.5);
  return vec2(rankOf(veil), 0.55 * clamp(1.0 + 0.6 * fibres, 0.5, 1.5));
}

// Cirrocumulus: small lumpy cloudlets (Worley F1, roughened by fbm) on a grid of 40 x 32 cells
// a tile, modulated by sinusoidal ripples whose 32 crests a tile run along u through the cell
// centres, so the cloudlets line up in rows (undulatus); gently warped so the rows undulate.
// The patches' edges follow the cells, so they break up into single cloudlets. Returns (rank,
// shape); ramp width HIGH_CLOUD_RAMP_CIRROCUMULUS.
const float kRippleRows = 32.0;
vec2 cirrocumulusRankShape(vec2 uv, uint seed, float n) {
  vec2 q = uv + 0.01 * warpField(uv, 3.0, noiseSeed(seed, 31u), n);
  vec2 f = worley2(q * vec2(40.0, kRippleRows), ivec2(40, int(kRippleRows)),
                   noiseSeed(seed, 32u), 0.7);
  float lumps = fbmGradient2(q * 80.0, ivec2(80), noiseSeed(seed, 33u), octavesFor(80.0, n), 0.5);
  float cell = 1.0 - smoothstep(0.1, 0.6, f.x + 0.3 * lumps);
  // Crests at v = (j + 1/2) / rows, the unjittered cell centres.
  float ripple = 0.5 - 0.5 * cos(6.28318530718 * kRippleRows * q.y);
  float puff = cell * (0.15 + 0.85 * ripple);
  float patches = fbmGradient2(uv * vec2(3.0, 4.0), ivec2(3, 4), noiseSeed(seed, 30u),
                               octavesFor(4.0, n), 0.5);
  return vec2(rankOf(patches + 0.15 * (puff - 0.4)), 2.0 * puff);
}

void main() {
  uint n = params.size.x;
  uvec2 p = uvec2(gl_GlobalInvocationID.x, gl_GlobalInvocationID.y + params.size.y);
  if (p.x >= n || p.y >= params.size.y + params.size.z || p.y >= n) return;
  // Texel centres; v grows southwards with the rows (row 0 = north edge).
  vec2 uv = (vec2(p) + 0.5) / float(n);
  float c = params.cover.x;
  if (params.cover.y > 0.5) c *= clamp(textureLod(coverMap, uv, 0.0).r, 0.0, 1.0);
  uint seed = noiseHash3(uvec3(params.seed.x, 0x68636c64u, 1u)).x;
  uint style = params.size.w;
  vec2 rs;
  if (style == HIGH_CLOUD_STYLE_CIRROSTRATUS)
    rs = cirrostratusRankShape(uv, seed, float(n));
  else if (style == HIGH_CLOUD_STYLE_CIRROCUMULUS)
    rs = cirrocumulusRankShape(uv, seed, float(n));
  else
    rs = cirrusRankShape(uv, seed, float(n));
  // c = 0 gives tau = 0: every style's rank stays below 1, under the threshold 1 - 0 (1 + w).
  imageStore(coefficients, ivec2(p), highCloudCoefficients(rs, c, highCloudRampWidth(style)));
  imageStore(rankShape, ivec2(p), vec4(rs, 0.0, 0.0));
}
