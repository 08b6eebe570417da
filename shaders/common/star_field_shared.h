// Parameters, bindings and buffer layouts of passes/star_field (shaders/star_clear.comp,
// shaders/star_field.comp) and of the reader side, shaders/common/star_field.glsl.
//
// The star buffer (persistent, std430): one vec4 per star, xyz the unit J2000 direction,
// w the flux relative to a V = 0 star, 10^(-0.4 V).
// The flux buffer (transient, std430): a uvec4 header (width, height, 0, 0) and then one
// uint per pixel, row-major, row 0 at the top like the images, holding the star flux that
// landed in the pixel in V = 0 units times STAR_FLUX_FIXED_ONE.
// Range: a pixel holds < 2^32 counts, i.e. the flux of < 2^32 / 2^16 = 65536 V = 0 stars.
// Each star is clamped to STAR_FLUX_MAX_PER_STAR (2^24 counts) first, so a pixel wraps only
// after 256 stars of the largest flux land in it; the whole catalogue sums to ~96 V = 0
// stars, so even every star in one pixel stays far inside the range.
#ifndef SKY_STAR_FIELD_SHARED_H
#define SKY_STAR_FIELD_SHARED_H
#include "shared_prelude.h"
#include "view_shared.h"

#define STAR_FIELD_GROUP_SIZE 64
#define STAR_FIELD_BINDING_PARAMS 0
#define STAR_FIELD_BINDING_STARS 1
#define STAR_FIELD_BINDING_FLUX 2

#define STAR_CLEAR_GROUP_X 8
#define STAR_CLEAR_GROUP_Y 8
#define STAR_CLEAR_BINDING_FLUX 0

// Fixed point of the flux buffer: counts per V = 0 star (2^16).
#define STAR_FLUX_FIXED_ONE 65536.0
// uints before the first pixel: the uvec4 (width, height, 0, 0) header.
#define STAR_FLUX_HEADER_UINTS 4
// Largest flux one star may add (V = -6, brighter than any star; Venus at its brightest is
// V = -4.9): 256 * 2^16 = 2^24 counts.
#define STAR_FLUX_MAX_PER_STAR 256.0
// Stars fade out over this many degrees below the (geometric) horizon instead of popping.
#define STAR_FIELD_HORIZON_FADE_DEG 0.5

SKY_SHARED_BEGIN

struct StarFieldParams {
  ViewState view;
  // The rotation from J2000 equatorial to the camera's east-north-up frame as three columns
  // (xyz; w unused): enu = mat3(c0, c1, c2) * j2000. Comes from the ephemeris every frame.
  vec4 j2000ToEnu0;
  vec4 j2000ToEnu1;
  vec4 j2000ToEnu2;
  vec4 extinction;  // x: k, V-band extinction in magnitudes per air mass; yzw: unused
  uvec4 counts;     // x: number of stars in the star buffer; yzw: unused
};

// Push constants of star_clear.comp.
struct StarClearParams {
  uvec4 size;  // x, y: image size in pixels
};

SKY_SHARED_END

#ifdef __cplusplus
#include <cstddef>
static_assert(sizeof(sky::shared::StarFieldParams) == 64 + 5 * 16,
              "std140 layout of StarFieldParams");
static_assert(offsetof(sky::shared::StarFieldParams, j2000ToEnu0) == 64,
              "std140 layout of StarFieldParams");
static_assert(offsetof(sky::shared::StarFieldParams, counts) == 128,
              "std140 layout of StarFieldParams");
static_assert(sizeof(sky::shared::StarClearParams) == 16, "layout of StarClearParams");
#endif
#endif
