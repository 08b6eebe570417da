// The procedural cirrus of the high-cloud bake (high_cloud_bake.comp), shared with its kernel
// tests (tests/data/high_clouds/cirrus_kernel.comp), which check the flow and the cover
// calibration on the GPU. See docs/high-clouds.md, "Cirrus".
//
// Cirrus fibratus and uncinus: wisps drawn out by the upper-level wind shear, striated by fine
// fibres, some curling into hooks at their heads, broken into patches with clear sky between.
// The streaks of one sky run roughly parallel along the shear, wandering a little, so in
// perspective they converge toward a vanishing point on the horizon. The tile's +u axis is the
// mean direction; the draw lays it downwind (sky_high_clouds.comp).
//
// Both wisps and fibres are line integral convolutions (Cabral and Leedom 1993) of sparse
// random spots along one smoothly varying flow: each texel sums the spots on a path that
// leaves it downstream, so every spot is smeared upstream into a streak, brightest at its head
// and fading along its tail. The spots fall at random points, so the streaks are sharp across,
// long along and at random offsets from each other: no comb of evenly spaced lines.
#ifndef SKY_CIRRUS_GLSL
#define SKY_CIRRUS_GLSL
#include "high_cloud_bake_shared.h"
#include "noise.glsl"

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

// The flow's direction at uv, radians from +u (east on the tile, downwind in the sky) toward
// +v: the mean direction plus a bounded wander. The streaks of a sky are drawn out by one
// upper-level wind shear, so they run about one way, turned a little from part to part of the
// sky (a slow field, 2 cycles a tile) and bent gently (a faster one, 6 cycles a tile). The
// wander passes through a soft clamp, CIRRUS_FLOW_MAX_WANDER tanh(x / CIRRUS_FLOW_MAX_WANDER),
// so the flow never turns more than that from +u anywhere: every streamline advances along +u
// and none can curl around a point. (An angle of 3 fbm, +-2 rad over the tile, closed
// streamlines into rings, which perspective squeezed into concentric arcs toward the horizon.)
// A continuous angle, not a vector field, so the flow never stalls or reverses. Periodic, so
// the streaks tile.
float cirrusFlowAngle(vec2 uv, uint seed) {
  float regions = fbmGradient2(uv * 2.0, ivec2(2), noiseSeed(seed, 70u), 3, 0.5);
  float bends = fbmGradient2(uv * 6.0, ivec2(6), noiseSeed(seed, 71u), 2, 0.5);
  float wander = CIRRUS_FLOW_REGION_GAIN * regions + CIRRUS_FLOW_BEND_GAIN * bends;
  return CIRRUS_FLOW_MAX_WANDER * tanh(wander / CIRRUS_FLOW_MAX_WANDER);
}

// The path a texel's streaks are summed along, in tile units: it leaves uv in direction
// `theta` (radians from +u) and turns at `kappa` rad per tile (the flow's turn over the
// wisp), plus a hook of `hookTurn` rad in all, `hookRate` rad per tile at the start, fading as
// exp(-3 s / len). Texels nearby take nearly the same arc, so their streaks stay parallel; no
// flow lookup per step.
struct CirrusPath {
  float theta;     // the direction at the start
  float len;       // the wisp's length, tiles: 0.12 to 0.3
  float kappa;     // the flow's turn, rad per tile
  float hookTurn;  // the hook's whole turn, rad (signed; 0 outside the hooked regions)
  float hookRate;  // the hook's turn at the start, rad per tile
};

CirrusPath cirrusPath(vec2 uv, uint seed) {
  CirrusPath path;
  float lengthField = fbmGradient2(uv * 4.0, ivec2(4), noiseSeed(seed, 73u), 2, 0.5);
  path.len = mix(0.12, 0.3, clamp(0.5 + 2.0 * lengthField, 0.0, 1.0));
  // The flow's direction here, turning at the rate the flow turns over the first half of the
  // wisp, so it follows the streamline as an arc. The arc's end stays within the flow's own
  // bound: the path turns linearly from one direction in the band to another, so every
  // direction it takes lies in the band too.
  path.theta = cirrusFlowAngle(uv, seed);
  vec2 dir = vec2(cos(path.theta), sin(path.theta));
  float kappa = (cirrusFlowAngle(uv + 0.5 * path.len * dir, seed) - path.theta) / (0.5 * path.len);
  float end = clamp(path.theta + kappa * path.len, -CIRRUS_FLOW_MAX_WANDER, CIRRUS_FLOW_MAX_WANDER);
  path.kappa = (end - path.theta) / path.len;
  // Hooks (cirrus uncinus): in some regions the path turns by up to CIRRUS_HOOK_MAX_TURN more,
  // most of it within its first third, all one way within a region. Seen from the spot, its
  // streak curls near the head and trails straight. With the wander the path turns at most
  // CIRRUS_FLOW_MAX_WANDER + CIRRUS_HOOK_MAX_TURN < pi / 2 from +u: even a hook advances
  // downwind, so no streak closes on itself.
  float hookField = fbmGradient2(uv * 3.0, ivec2(3), noiseSeed(seed, 72u), 2, 0.5);
  path.hookTurn = CIRRUS_HOOK_MAX_TURN * sign(hookField) *
                  clamp((abs(hookField) - 0.2) / 0.2, 0.0, 1.0);
  // The integral of hookRate exp(-3 s / len) over the path is hookRate len (1 - e^-3) / 3.
  path.hookRate = path.hookTurn * 3.0 / ((1.0 - exp(-3.0)) * path.len);
  return path;
}

// The path's direction (radians from +u) at the fraction s in [0, 1] of its length, as the
// bake's steps take it (the hook's share is the integral of its exponential rate).
float cirrusPathAngle(CirrusPath path, float s) {
  return path.theta + path.kappa * path.len * s +
         path.hookTurn * (1.0 - exp(-3.0 * s)) / (1.0 - exp(-3.0));
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

// Quantiles of the cirrus field x (cirrusField) at 0, 5, ..., 100 %
// (CIRRUS_QUANTILES, high_cloud_bake_shared.h): cirrusRank() interpolates them, so the rank is
// about uniform and cover c clouds about a fraction c of the sky, as rankOf() does for fbm.
const float kCirrusQuantiles[CIRRUS_QUANTILE_COUNT] =
    float[CIRRUS_QUANTILE_COUNT](CIRRUS_QUANTILES);

float cirrusRank(float x) {
  if (x <= kCirrusQuantiles[0]) return 0.0;
  const int last = CIRRUS_QUANTILE_COUNT - 1;
  for (int k = 1; k <= last; ++k)
    if (x < kCirrusQuantiles[k])
      return (float(k - 1) + (x - kCirrusQuantiles[k - 1]) /
                                 (kCirrusQuantiles[k] - kCirrusQuantiles[k - 1])) /
             float(last);
  return 0.9999;
}

// A texel's cirrus before the rank: the field x the rank is taken of and the optical depth
// factor `shape`. Lengths are in tiles (30 km in the default scene): wisps 0.12 to 0.3 long
// from spots 1/32 across, fibres up to 0.06 long from spots 4 texels across (at most 256 a
// tile).
struct CirrusField {
  float x;
  float shape;
};

CirrusField cirrusField(vec2 uv, uint seed, float n) {
  CirrusPath path = cirrusPath(uv, seed);
  float len = path.len;
  vec2 dir = vec2(cos(path.theta), sin(path.theta));

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
    float turn = (path.kappa + path.hookRate * exp(-3.0 * s)) * h;
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
    float turn = (path.kappa + path.hookRate * exp(-3.0 * s * lf / len)) * h;
    d = normalize(d + turn * vec2(-d.y, d.x));
    p += d * h;
  }
  fibre /= weights;

  // Wisps and fibres in units of their 95th percentiles (0.15 and 0.05); the patch noise's
  // spread along a path is about 0.1 around 0.5. The rank follows all three, so cover first
  // fills the strongest wisps in the densest patches and their edges fray into fibres; the
  // optical depth follows wisp and fibre, so a wisp is brighter in its core and striated.
  float wn = wisp / 0.15, fn = min(fibre / 0.05, 2.0);
  CirrusField field;
  field.x = wn + 0.5 * fn + 0.35 * (patches - 0.5) / 0.1;
  field.shape = 1.8 * clamp(0.35 + 0.5 * wn, 0.0, 1.0) * (0.6 + 0.2 * fn);
  return field;
}

// Returns (rank, shape); ramp width HIGH_CLOUD_RAMP_CIRRUS.
vec2 cirrusRankShape(vec2 uv, uint seed, float n) {
  CirrusField field = cirrusField(uv, seed, n);
  return vec2(cirrusRank(field.x), field.shape);
}

#endif
