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

// ---- Cirrus ------------------------------------------------------------------------------
// Cirrus fibratus and uncinus: wisps drawn out by wind shear, striated by fine fibres, in
// groups whose direction wanders across the sky, some curling into hooks at their heads,
// broken into patches with clear sky between. Both wisps and fibres are line integral
// convolutions (Cabral and Leedom 1993) of sparse random spots along one smoothly varying
// flow: each texel sums the spots on a path that leaves it downstream, so every spot is
// smeared upstream into a streak, brightest at its head and fading along its tail. The spots
// fall at random points, so the streaks are sharp across, long along and at random offsets from
// each other: no comb of evenly spaced lines, and no lattice direction preferred.

// A 32-bit hash of lattice point c wrapped to a power-of-two period of `cells` (Wellons'
// lowbias32 mix). The wrap is a bit mask, far cheaper than noise.glsl's general periods for the
// thousands of lookups along each texel's path.
uint cirrusHash(ivec2 c, int cells, uint seed) {
  uvec2 q = uvec2(c & ivec2(cells - 1));
  uint h = (q.x + (q.y << 13u)) ^ seed;
  h ^= h >> 16u;
  h *= 0x7feb352du;
  h ^= h >> 15u;
  h *= 0x846ca68bu;
  h ^= h >> 16u;
  return h;
}

// Value noise in [0, 1] on a lattice of `cells` (a power of two) cells a tile, periodic.
float cirrusValueNoise(vec2 uv, int cells, uint seed) {
  vec2 p = uv * float(cells);
  vec2 i = floor(p);
  vec2 f = p - i;
  ivec2 c = ivec2(i);
  vec4 v = vec4(uvec4(cirrusHash(c, cells, seed), cirrusHash(c + ivec2(1, 0), cells, seed),
                      cirrusHash(c + ivec2(0, 1), cells, seed),
                      cirrusHash(c + ivec2(1, 1), cells, seed)) >> 8u) *
           (1.0 / 16777216.0);
  vec2 u = f * f * (3.0 - 2.0 * f);
  return mix(mix(v.x, v.y, u.x), mix(v.z, v.w, u.x), u.y);
}

// Sparse round spots, the heads of the streaks: in each cell of a lattice of `cells` (a power
// of two) cells a tile, with probability q, one spot at a uniformly random point, of radius
// half a cell and a random brightness in [0.5, 1]. Every spot within half a cell of uv lies in
// the 2 x 2 cells nearest to it, so four lookups find them all. Unlike thresholded lattice
// noise the spots are round and nowhere aligned with the lattice: no streak starts square or
// lines up with its neighbours.
float cirrusSpots(vec2 uv, int cells, uint seed, float q) {
  vec2 p = uv * float(cells);
  ivec2 c = ivec2(floor(p - 0.5));
  float sum = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 cell = c + ivec2(k & 1, k >> 1);
    uint h = cirrusHash(cell, cells, seed);
    // Four 8-bit numbers: the spot's position in its cell, whether it is there, its brightness.
    vec4 r = vec4(uvec4(h, h >> 8u, h >> 16u, h >> 24u) & 255u) * (1.0 / 256.0);
    vec2 d = p - (vec2(cell) + r.xy);
    float x = min(4.0 * dot(d, d), 1.0);  // (distance / radius)^2
    sum += (r.z < q ? 0.5 + 0.5 * r.w : 0.0) * (1.0 - x) * (1.0 - x);
  }
  return sum;
}

// The flow's direction at uv, radians from +u (east) toward +v: a slow field turns the wisps
// of each part of the sky (most directions somewhere in the tile, each over several km), a
// faster one bends them. A continuous angle, not a vector field, so the flow never stalls or
// reverses. Periodic, so the streaks tile.
float cirrusFlowAngle(vec2 uv, uint seed) {
  float regions = fbmGradient2(uv * 2.0, ivec2(2), noiseSeed(seed, 70u), 3, 0.5);
  float bends = fbmGradient2(uv * 6.0, ivec2(6), noiseSeed(seed, 71u), 2, 0.5);
  return 3.0 * regions + 0.4 * bends;
}

// The mean of cirrusValueNoise over the tile: the mean of its cells x cells lattice values.
float cirrusValueNoiseMean(int cells, uint seed) {
  float sum = 0.0;
  for (int y = 0; y < cells; ++y)
    for (int x = 0; x < cells; ++x) sum += float(cirrusHash(ivec2(x, y), cells, seed) >> 8u);
  return sum * (1.0 / 16777216.0) / float(cells * cells);
}

// Where the wisps gather (the patches): three octaves of value noise, 4 to 16 cells a tile,
// about 0.5. `offset` recentres the tile's mean on 0.5: with only 16 lattice values in the
// first octave the mean would wander by seed, and the cover with it.
float cirrusPatchNoise(vec2 uv, uint seed, float offset) {
  return 0.55 * cirrusValueNoise(uv, 4, seed) + 0.3 * cirrusValueNoise(uv, 8, seed + 1u) +
         0.15 * cirrusValueNoise(uv, 16, seed + 2u) + offset;
}

// Quantiles of the cirrus field x (cirrusRankShape) at 0, 5, ..., 100 %, measured over the
// tile at N = 512 and averaged over seeds 1, 3, 7 and 42 (one seed's median lies within 0.1
// of the average; N = 128 and 1024 shift them by less than 0.04): cirrusRank() interpolates
// them, so the rank is about uniform and cover c clouds about a fraction c of the sky, as
// rankOf() does for fbm.
const float kCirrusQuantiles[21] = float[21](
    -0.8446, -0.3690, -0.2171, -0.1003, -0.0016, 0.0847, 0.1606, 0.2336, 0.3039, 0.3744,
    0.4462, 0.5196, 0.5943, 0.6764, 0.7632, 0.8589, 0.9678, 1.1008, 1.2713, 1.5288, 3.4858);

float cirrusRank(float x) {
  if (x <= kCirrusQuantiles[0]) return 0.0;
  for (int k = 1; k < 21; ++k)
    if (x < kCirrusQuantiles[k])
      return (float(k - 1) + (x - kCirrusQuantiles[k - 1]) /
                                 (kCirrusQuantiles[k] - kCirrusQuantiles[k - 1])) / 20.0;
  return 0.9999;
}

// Returns (rank, shape); ramp width HIGH_CLOUD_RAMP_CIRRUS. Lengths are in tiles (30 km in the
// default scene): wisps 0.12 to 0.3 long from spots 1/32 across, fibres up to 0.06 long from
// spots 4 texels across (at most 256 a tile).
vec2 cirrusRankShape(vec2 uv, uint seed, float n) {
  float lengthField = fbmGradient2(uv * 4.0, ivec2(4), noiseSeed(seed, 73u), 2, 0.5);
  float len = mix(0.12, 0.3, clamp(0.5 + 2.0 * lengthField, 0.0, 1.0));
  // The path: the flow's direction here, turning at the rate the flow turns over the first
  // half of the wisp, so it follows the streamline as an arc without sampling the flow at
  // every step. Texels nearby take nearly the same arc, so their streaks stay parallel.
  float theta = cirrusFlowAngle(uv, seed);
  vec2 dir = vec2(cos(theta), sin(theta));
  float kappa = (cirrusFlowAngle(uv + 0.5 * len * dir, seed) - theta) / (0.5 * len);
  // A wisp bends by at most about 70 degrees along its length: where the flow turns faster
  // (near a vortex of the angle field) the arc would close into a ring.
  kappa = clamp(kappa, -1.2 / len, 1.2 / len);
  // Hooks (cirrus uncinus): in some regions the path turns by up to about 90 degrees more,
  // most of it within its first third, all one way within a region. Seen from the spot, its
  // streak curls near the head and trails straight.
  float hookField = fbmGradient2(uv * 3.0, ivec2(3), noiseSeed(seed, 72u), 2, 0.5);
  float hookTurn = 1.6 * sign(hookField) * clamp((abs(hookField) - 0.2) / 0.2, 0.0, 1.0);
  float hook = hookTurn * 3.0 / (0.95 * len);  // rad per tile at the start; the total is hookTurn

  // Wisps: 33 steps along the whole path, over sparse spots 1/32 of the tile across; the
  // patch noise is averaged along it too, so the patches are drawn out along the wisps.
  const int kWispSteps = 32;
  float h = len / float(kWispSteps);
  uint wispSeed = noiseSeed(seed, 77u), patchSeed = noiseSeed(seed, 76u);
  float patchOffset = 0.5 - 0.55 * cirrusValueNoiseMean(4, patchSeed) -
                      0.3 * cirrusValueNoiseMean(8, patchSeed + 1u) - 0.15 * 0.5;
  float wisp = 0.0, weights = 0.0, patches = 0.0;
  vec2 p = uv, d = dir;
  for (int i = 0; i <= kWispSteps; ++i) {
    float s = float(i) / float(kWispSteps);
    float w = 1.0 - s;  // the head brightest, the tail fading
    wisp += w * cirrusSpots(p, 32, wispSeed, 0.25);
    weights += w;
    if ((i & 3) == 0) patches += cirrusPatchNoise(p, patchSeed, patchOffset) / 9.0;
    float turn = (kappa + hook * exp(-3.0 * s)) * h;
    d = normalize(d + turn * vec2(-d.y, d.x));
    p += d * h;
  }
  wisp /= weights;

  // Fibres: 41 steps along the start of the same path, over sparser spots 4 texels across,
  // each head softened so it does not show as a dot.
  int cells = int(min(0.25 * n, 256.0));
  const int kFibreSteps = 40;
  float lf = min(len, 0.06);
  h = lf / float(kFibreSteps);
  uint fibreSeed = noiseSeed(seed, 75u);
  float fibre = 0.0;
  weights = 0.0;
  p = uv;
  d = dir;
  for (int i = 0; i <= kFibreSteps; ++i) {
    float s = float(i) / float(kFibreSteps);
    float w = (1.0 - s) * min(0.3 + s * 10.0, 1.0);
    fibre += w * cirrusSpots(p, cells, fibreSeed, 0.1);
    weights += w;
    float turn = (kappa + hook * exp(-3.0 * s * lf / len)) * h;
    d = normalize(d + turn * vec2(-d.y, d.x));
    p += d * h;
  }
  fibre /= weights;

  // Wisps and fibres in units of their 95th percentiles (0.15 and 0.05); the patch noise's
  // spread along a path is about 0.1 around 0.5. The rank follows all three, so cover first
  // fills the strongest wisps in the densest patches and their edges fray into fibres; the
  // optical depth follows wisp and fibre, so a wisp is brighter in its core and striated.
  float wn = wisp / 0.15, fn = min(fibre / 0.05, 2.0);
  float x = wn + 0.5 * fn + 0.35 * (patches - 0.5) / 0.1;
  return vec2(cirrusRank(x), 1.8 * clamp(0.35 + 0.5 * wn, 0.0, 1.0) * (0.6 + 0.2 * fn));
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
