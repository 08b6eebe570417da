// The light march of the volumetric clouds, generic over the density: the includer defines
//   float cloudDensityForLight(vec3 p, float lengthM, int step);
// (density at a world position, 0 outside the cloud, as seen by a sample standing for
// `lengthM` of the march: it may filter away detail finer than that; `step` is the sample's
// place in the march, 0 .. n - 1 for the short steps and n for the long one, a constant once
// the march is unrolled, so the includer can leave out what a step never resolves) before
// including this file.
// Its C++ twin, lightMarchDensity in engine/clouds/cloud_math.h, takes the density as a callable.
#ifndef SKY_CLOUD_LIGHT_MARCH_GLSL
#define SKY_CLOUD_LIGHT_MARCH_GLSL
#include "cloud_lighting.glsl"
#include "cloud_light_march_shared.h"

// Defined by the includer (declared here so this file stands on its own).
float cloudDensityForLight(vec3 p, float lengthM, int step);

// Lu (24)'s ds: the density accumulated from p toward the light L (unit) in density x metres,
// by the midpoint rule over the n short steps covering [0, distance] (lightStepLength) and the
// one long step over [distance, 5 distance] (lightLongStepDistance) in CLOUD_LIGHT_LONG_SAMPLES
// parts. Exact for densities linear along the ray; a density edge costs at most the length of
// the step it falls in.
// `offset` in [0, 1) places each sample inside its step (0.5: the midpoint); a caller that
// varies it from sample to sample turns the pattern of a fixed placement into fine noise.
float lightMarchDensity(vec3 p, vec3 L, float distance, int n, float offset) {
  float ds = 0.0;
  for (int i = 0; i < n; ++i) {
    float start = lightStepStart(i, n, distance);
    float len = lightStepLength(i, n, distance);
    ds += cloudDensityForLight(p + L * (start + offset * len), len, i) * len;
  }
  // The long step in CLOUD_LIGHT_LONG_SAMPLES equal parts (1: its middle alone, as Schneider's
  // one far sample), each standing for its part.
  float part = lightLongStepLength(distance) / float(CLOUD_LIGHT_LONG_SAMPLES);
  for (int j = 0; j < CLOUD_LIGHT_LONG_SAMPLES; ++j) {
    float at = CLOUD_LIGHT_LONG_SAMPLES == 1 ? lightLongStepDistance(distance)
                                             : distance + (float(j) + offset) * part;
    ds += cloudDensityForLight(p + L * at, part, n) * part;
  }
  return ds;
}

// The first `k` of the n short steps of lightMarchDensity alone, [0, lightStepStart(k)]:
// the part near the point, where the cloud's fine structure shadows itself, that a caller
// reading the rest from the light volume (cloud_light_volume.glsl) marches itself. Each step
// split `split` ways as in lightMarchDensityRefined (1: one sample a step); a sub-step may
// resolve noise its whole step cannot, so a split march tells the includer step 0.
float lightMarchDensityNear(vec3 p, vec3 L, float distance, int n, int k, int split,
                            float offset) {
  float ds = 0.0;
  for (int i = 0; i < k; ++i) {
    float start = lightStepStart(i, n, distance);
    float len = lightStepLength(i, n, distance) / float(split);
    for (int j = 0; j < split; ++j)
      ds += cloudDensityForLight(p + L * (start + (float(j) + offset) * len), len,
                                 split > 1 ? 0 : i) *
            len;
  }
  return ds;
}

// lightMarchDensity refined: each short step split `split` ways and the long one twice as
// many, every sample standing for its sub-step. The reference march takes it at every view
// sample; the light volume once per texel.
float lightMarchDensityRefined(vec3 p, vec3 L, float distance, int n, int split, float offset) {
  float ds = lightMarchDensityNear(p, L, distance, n, n, split, offset);
  int parts = 2 * split;
  float len = lightLongStepLength(distance) / float(parts);
  for (int j = 0; j < parts; ++j)
    ds += cloudDensityForLight(p + L * (distance + (float(j) + offset) * len), len, 0) * len;
  return ds;
}

#endif
