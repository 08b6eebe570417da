// Parameters, bindings and constants of the high-cloud texture passes in
// passes/high_cloud_textures (shaders/high_cloud_bake.comp, high_cloud_normals.comp,
// high_cloud_reduce.comp, high_cloud_cover_reduce.comp). The channels and the conventions
// are in docs/high-clouds.md.
//
// All textures are RGBA16F, row 0 = the north edge, column 0 = the west edge, and tile in
// both directions.
//   coefficients (N x N): R thin lit parts, G dense parts, B clear sky (transmittance), A sparse
//                         edges (Kozlov fig. 3), each in [0, 1]
//   normals      (N x N): xyz the unit tangent-space normal (x east, y north, z up), w = 0
//   coarse       (C x C): the coefficients box-filtered over (N / C)^2 texels
//   levels       ((N - 2C) x N/2): the coefficients' mip levels 1 .. L - 1 side by side
//                         (L = log2(N / C); level L is the coarse texture), level l box-filtered
//                         over 2^l x 2^l texels, N / 2^l on a side, at column N - 2N / 2^l
//                         (common/high_cloud_levels.glsl)
//   rank/shape   (N x N): R the texel's rank r, G its optical depth factor `shape`, BA = 0:
//                         tau(c) = shape * presence(r, c, w) at any cover c
//                         (common/high_cloud_coverage.glsl); procedural bakes only
//   cover coarse (C x C x HIGH_CLOUD_COVER_STEPS, 3D): layer k is the coarse texture the
//                         rank/shape texture gives at cover k / (STEPS - 1)
#ifndef SKY_HIGH_CLOUD_BAKE_SHARED_H
#define SKY_HIGH_CLOUD_BAKE_SHARED_H
#include "shared_prelude.h"

#define HIGH_CLOUD_GROUP_X 8
#define HIGH_CLOUD_GROUP_Y 8

#define HIGH_CLOUD_BAKE_BINDING_PARAMS 0
#define HIGH_CLOUD_BAKE_BINDING_COVER_MAP 1
#define HIGH_CLOUD_BAKE_BINDING_COEFFICIENTS 2
#define HIGH_CLOUD_BAKE_BINDING_RANK_SHAPE 3

#define HIGH_CLOUD_NORMALS_BINDING_COEFFICIENTS 0
#define HIGH_CLOUD_NORMALS_BINDING_NORMALS 1
#define HIGH_CLOUD_NORMALS_BINDING_LEVELS 2

#define HIGH_CLOUD_LEVELS_BINDING_COEFFICIENTS 0
#define HIGH_CLOUD_LEVELS_BINDING_LEVELS 1

#define HIGH_CLOUD_REDUCE_BINDING_COEFFICIENTS 0
#define HIGH_CLOUD_REDUCE_BINDING_COARSE 1

#define HIGH_CLOUD_COVER_REDUCE_BINDING_RANK_SHAPE 0
#define HIGH_CLOUD_COVER_REDUCE_BINDING_COARSE 1

// HighCloudBakeParams.size.w
#define HIGH_CLOUD_STYLE_CIRRUS 0u
#define HIGH_CLOUD_STYLE_CIRROSTRATUS 1u
#define HIGH_CLOUD_STYLE_CIRROCUMULUS 2u

// The soft width w of each style's cover ramp: cloud appears where the rank exceeds
// 1 - c (1 + w) and reaches its full optical depth w later (high_cloud_coverage.glsl).
#define HIGH_CLOUD_RAMP_CIRRUS 0.2
#define HIGH_CLOUD_RAMP_CIRROSTRATUS 0.5
#define HIGH_CLOUD_RAMP_CIRROCUMULUS 0.25

// The covers the per-cover coarse texture and the far-field table hold: k / (STEPS - 1) for
// k = 0 .. STEPS - 1, so cover 0 (clear) and 1 (the full-cover mean) are exact and a cover in
// between interpolates linearly over steps of 1/16.
#define HIGH_CLOUD_COVER_STEPS 17u

// The cover the coefficient texture is baked at when the cover comes per pixel from the
// weather map (regional cover): the draw then reads the rank/shape texture, and the
// coefficients only shape the normals, which at full cover exist wherever cloud can be.
#define HIGH_CLOUD_REGIONAL_REFERENCE_COVER 1.0

// Optical depth tau at which a texel turns from thin (R) to dense (G): the dense share of the
// opacity is smoothstep(LO, HI, tau).
#define HIGH_CLOUD_TAU_DENSE_LO 0.7
#define HIGH_CLOUD_TAU_DENSE_HI 2.5

// The height field the normals come from is the opacity 1 - B times this relief, in units of
// the tile's width: 0.015 of a 50 km tile is 750 m of cloud-top relief, the order of a cirrus
// layer's thickness.
#define HIGH_CLOUD_NORMAL_RELIEF 0.015
// Procedural cirrus's relief (its normals also come from a mip level, high_cloud_textures.cpp):
// a third, 150 m of a 30 km tile. Thin ice wisps are translucent, lit by scattering more than
// by the slope of a surface; at the full relief a low sun gave each wisp a bright and a grey
// flank, darker than the sky beside the sun.
#define HIGH_CLOUD_CIRRUS_NORMAL_RELIEF 0.005

// Procedural cirrus's flow (common/cirrus.glsl): its direction is +u (laid downwind by the
// draw) plus a wander, the slow and the fast fbm times these gains (radians per unit of fbm),
// softly clamped to at most CIRRUS_FLOW_MAX_WANDER from +u. A hook turns a wisp's head by at
// most CIRRUS_HOOK_MAX_TURN more. The two sum to less than pi / 2, so every path a streak is
// drawn along advances downwind and none can curl around a point.
#define CIRRUS_FLOW_REGION_GAIN 0.6
#define CIRRUS_FLOW_BEND_GAIN 0.5
#define CIRRUS_FLOW_MAX_WANDER 0.4
#define CIRRUS_HOOK_MAX_TURN 1.0

// Quantiles of procedural cirrus's field x (cirrusField) at 0, 5, ..., 100 %, measured over
// the tile at N = 512 and averaged over seeds 1, 3, 7 and 42 by
// CirrusKernelTest.QuantileTableMatchesTheField, which fails when the field's statistics
// move away from them.
#define CIRRUS_QUANTILE_COUNT 21
#define CIRRUS_QUANTILES                                                                       \
  -0.8660, -0.3781, -0.2215, -0.1023, 0.0009, 0.0904, 0.1695, 0.2438, 0.3143, 0.3844, 0.4562, \
      0.5285, 0.6047, 0.6860, 0.7714, 0.8680, 0.9774, 1.1070, 1.2785, 1.5346, 3.7337

// The coarse texture is N / 16 texels on a side, and never smaller than 4.
#define HIGH_CLOUD_COARSE_DIVISOR 16u
#define HIGH_CLOUD_COARSE_MIN 4u

SKY_SHARED_BEGIN

// Uniform of high_cloud_bake.comp; one dispatch fills the band of rows [y0, y0 + rows).
struct HighCloudBakeParams {
  uvec4 size;   // x: N; y: first row of the band; z: rows in the band; w: HIGH_CLOUD_STYLE_*
  vec4 cover;   // x: cover 0..1; y: 1 when the cover map multiplies it, else 0; zw: unused
  uvec4 seed;   // x: the scene's seed; yzw: unused
};

// Push constants of high_cloud_normals.comp.
struct HighCloudNormalsParams {
  uvec4 size;   // x: N; y: the mip level the height field is read from (0: the coefficients
                // themselves, l > 0: level l of the levels texture); z: C; w: unused
  vec4 relief;  // x: the relief (HIGH_CLOUD_NORMAL_RELIEF, or _CIRRUS_) * N, the height of
                // opacity 1 in texels
};

// Push constants of high_cloud_levels.comp.
struct HighCloudLevelsParams {
  uvec4 size;  // x: N; y: C, the coarse size; zw: unused
};

// Push constants of high_cloud_reduce.comp.
struct HighCloudReduceParams {
  uvec4 size;  // x: N; y: C, the coarse size; z: N / C, the box width; w: unused
};

// Push constants of high_cloud_cover_reduce.comp.
struct HighCloudCoverReduceParams {
  uvec4 size;  // x: N; y: C, the coarse size; z: N / C, the box width; w: HIGH_CLOUD_COVER_STEPS
  vec4 ramp;   // x: the style's ramp width w; yzw: unused
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::HighCloudBakeParams) == 48,
              "std140 layout of HighCloudBakeParams");
static_assert(sizeof(sky::shared::HighCloudNormalsParams) == 32,
              "layout of HighCloudNormalsParams");
static_assert(sizeof(sky::shared::HighCloudReduceParams) == 16, "layout of HighCloudReduceParams");
static_assert(sizeof(sky::shared::HighCloudLevelsParams) == 16, "layout of HighCloudLevelsParams");
static_assert(sizeof(sky::shared::HighCloudCoverReduceParams) == 32,
              "layout of HighCloudCoverReduceParams");
#endif
#endif
