// A still's clouds, their march's grain filtered out (passes/cloud_denoise,
// shaders/cloud_denoise.comp): clouds.denoise, in frames with no temporal reuse.
#ifndef SKY_CLOUD_DENOISE_SHARED_H
#define SKY_CLOUD_DENOISE_SHARED_H
#include "shared_prelude.h"
#include "view_shared.h"

#define CLOUD_DENOISE_GROUP_X 8
#define CLOUD_DENOISE_GROUP_Y 8
#define CLOUD_DENOISE_BINDING_PARAMS 0
#define CLOUD_DENOISE_BINDING_CLOUDS 1      // rgba32f: premultiplied radiance, opacity
#define CLOUD_DENOISE_BINDING_DEPTH 2       // rg32f: depth (m), where the ray reaches the shells
#define CLOUD_DENOISE_BINDING_OUT_CLOUDS 3  // out: rgba32f
#define CLOUD_DENOISE_BINDING_OUT_DEPTH 4   // out: rg32f

// Two neighbours that both hold cloud (opacity above this) mix only as far as their depths
// agree; where either holds less, the pair is an edge, and mixes by distance alone, so an
// edge's grain is smoothed too.
#define CLOUD_DENOISE_CLOUDY 0.05
// Two neighbours mix only where the finest detail cell (detailCellM) is more than this many
// pixels wide at the farther of the two (fully from twice as many): a pixel as wide as the
// cloud's texture holds real texture, which the filter would take, and the march's grain is a
// small share of it. Ungated, the filter took a 96 x 54 frame (a pixel 1.1 degrees wide) from
// 38 dB against the reference march to 28 (measured on the cumulus of branch cumulus2); gated,
// it leaves main's at 43.0 dB as it was. From 1.5
// the lit faces of the peer's noon view at 640 x 360 keep 0.96 of the reference's
// high-frequency energy (2: 1.05; 1: 0.82, and the 96 x 54 frame lost 2 dB).
#define CLOUD_DENOISE_FINE_PIXELS 1.5
// How far the depths of two cloudy neighbours may differ, relative to the nearer: depthSpread,
// plus up to 1 where a pixel is far narrower than the finest detail cell (detailCellM), this
// many pixels to a cell or more: there the cloud has no texture a pixel wide, and all of a
// pixel's difference from its neighbours is the march's grain (its depth is grainy too).
#define CLOUD_DENOISE_NEAR_PIXELS 32.0

SKY_SHARED_BEGIN

struct CloudDenoiseParams {
  ViewState view;
  float depthSpread;  // relative depth difference at which two cloudy pixels mix by 1/e
  float detailCellM;  // the finest cell of the detail noise (m)
  float pad0, pad1;
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::CloudDenoiseParams) == 64 + 16,
              "std140 layout of CloudDenoiseParams");
#endif
#endif
