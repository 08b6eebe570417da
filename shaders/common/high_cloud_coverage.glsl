// How much high cloud a texel carries at a cover c, shared by the bake
// (high_cloud_bake.comp: the coefficient texture at the scene's cover), the per-cover coarse
// texture (high_cloud_cover_reduce.comp) and the draw with a cover per pixel from the weather
// map (sky_high_clouds.comp, regional cover). A procedural texel is a rank r (about uniform
// over the tile) and a cover-independent optical depth factor `shape`; at cover c its optical
// depth is tau = shape * presence(r, c, w), turned into Kozlov's four channels. See
// docs/high-clouds.md.
#ifndef SKY_HIGH_CLOUD_COVERAGE_GLSL
#define SKY_HIGH_CLOUD_COVERAGE_GLSL
#include "high_cloud_bake_shared.h"

// How much cloud a point of rank r carries at local cover c: 0 below the threshold 1 - c(1+w),
// rising over the soft width w. c = 0 gives 0 everywhere (r < 1), c = 1 gives 1 everywhere
// (r >= 0), and it never decreases with c, so the mean opacity grows with cover. About a
// fraction c of the tile lies past the middle of the ramp.
float highCloudPresence(float r, float c, float w) {
  float t = 1.0 - c * (1.0 + w);
  return smoothstep(t, t + w, r);
}

// The ramp width w of a style (HIGH_CLOUD_STYLE_*).
float highCloudRampWidth(uint style) {
  if (style == HIGH_CLOUD_STYLE_CIRROSTRATUS) return HIGH_CLOUD_RAMP_CIRROSTRATUS;
  if (style == HIGH_CLOUD_STYLE_CIRROCUMULUS) return HIGH_CLOUD_RAMP_CIRROCUMULUS;
  return HIGH_CLOUD_RAMP_CIRRUS;
}

// The four Kozlov channels from the optical depth (docs/high-clouds.md):
// B = exp(-tau) (Beer-Lambert transmittance, the clear sky seen through the layer),
// alpha = 1 - B split into thin (R) and dense (G) by the dense share
// smoothstep(TAU_DENSE_LO, TAU_DENSE_HI, tau), so R + G + B = 1, and
// A = 27/4 alpha (1 - alpha)^2, the sparse edges: largest (1) where alpha = 1/3, zero in the
// clear and in opaque cores.
vec4 coefficientsFromTau(float tau) {
  float b = exp(-tau);
  float alpha = 1.0 - b;
  float dense = smoothstep(HIGH_CLOUD_TAU_DENSE_LO, HIGH_CLOUD_TAU_DENSE_HI, tau);
  float edges = 6.75 * alpha * (1.0 - alpha) * (1.0 - alpha);
  return clamp(vec4(alpha * (1.0 - dense), alpha * dense, b, edges), 0.0, 1.0);
}

// The coefficients of a texel with rank/shape `rankShape` (x rank, y shape) at cover c.
vec4 highCloudCoefficients(vec2 rankShape, float c, float w) {
  return coefficientsFromTau(rankShape.y * highCloudPresence(rankShape.x, c, w));
}

#endif
