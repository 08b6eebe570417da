// The light march of the volumetric clouds, generic over the density: the includer defines,
// after including this file (which declares it),
//   float cloudDensityForLight(CloudLightPath path, vec3 p, float lengthM, int part);
// (density at a world position, 0 outside the cloud, as seen by a sample standing for
// `lengthM` of the path: it may filter away detail finer than that; `part` is
// CLOUD_LIGHT_PART_NEAR for the short steps that may resolve the detail noise and
// CLOUD_LIGHT_PART_FAR for the others, a constant in each loop below so the includer can
// leave out the reads a far sample never needs, and CLOUD_LIGHT_PART_MEAN for the far step,
// which reads the clouds' statistical mean alone) before including this file.
// Its C++ twin, lightMarchDensity in engine/clouds/cloud_math.h, takes the density as a callable.
#ifndef SKY_CLOUD_LIGHT_MARCH_GLSL
#define SKY_CLOUD_LIGHT_MARCH_GLSL
#include "cloud_lighting.glsl"
#include "cloud_light_march_shared.h"
#include "geo.glsl"

// One light march: everything about the path from a cloud sample toward a light that the
// march and the includer's density need, passed along instead of kept in globals.
struct CloudLightPath {
  vec3 origin;       // the cloud sample (ENU, m)
  vec3 direction;    // unit, toward the light
  LatLonLine line;   // latitudes and longitudes along the path (geo.glsl)
  float footprintM;  // what the sample the light is marched for resolves (its pixel's width)
  float offset;      // [0, 1): where each sample sits inside its step (0.5: the midpoint)
  float distanceM;   // the short steps' total length (clouds.light_distance_m)
  int steps;         // short steps, each twice the one before (clouds.light_steps)
  int split;         // samples per short step (clouds.light_split)
  int nearSteps;     // the first nearSteps short steps are CLOUD_LIGHT_PART_NEAR
  float longEndM;    // the long step runs over [distanceM, longEndM]
  int longParts;     // in this many equal parts, each sampled once
  float farEndM;     // the far step runs over [longEndM, farEndM]
  int farParts;      // in this many equal parts, each reading the clouds' mean
};

#define CLOUD_LIGHT_PART_NEAR 0
#define CLOUD_LIGHT_PART_FAR 1
#define CLOUD_LIGHT_PART_MEAN 2

// Defined by the includer, after this file.
float cloudDensityForLight(CloudLightPath path, vec3 p, float lengthM, int part);

// The long step's parts: as many as it takes to keep each at most partM long (at most
// CLOUD_LIGHT_MAX_LONG_PARTS), none when the long step is empty. A long step whose parts are
// longer than the clouds sees a random draw of their optical depth, and a noisy optical depth
// brightens on average (the mean of exp(-tau) exceeds exp(-mean tau)): under a low sun, whose
// path runs through the layer for kilometres, four 1.2 km parts left sunset clouds 6-9 dB off
// the reference march (docs/clouds.md, "Light march").
int cloudLightLongParts(float distanceM, float longEndM, float partM) {
  float len = longEndM - distanceM;
  if (len <= 0.0) return 0;
  return clamp(int(ceil(len / partM)), 1, CLOUD_LIGHT_MAX_LONG_PARTS);
}

// The far step's parts (at most CLOUD_LIGHT_FAR_PART_M each), none when it is empty.
int cloudLightFarParts(float longEndM, float farEndM) {
  float len = farEndM - longEndM;
  if (len <= 0.0) return 0;
  return clamp(int(ceil(len / CLOUD_LIGHT_FAR_PART_M)), 1, CLOUD_LIGHT_MAX_FAR_PARTS);
}

// The optical depth (in density x metres) a light march gathers, split where the path first
// leaves cloud: `own` up to the first density sample at or below CLOUD_LIGHT_CLEAR_DENSITY,
// the sample's own cloud, through which its light diffuses (the octaves and the diffusion
// term of cloud_lighting.glsl), and `beyond`, the rest: the clouds between it and the light,
// which shadow it as a beam (volumetric_clouds.comp cloudKeyLightScattering).
struct CloudLightDepth {
  float own;
  float beyond;
  bool left;  // a sample has found clear air: everything after it is beyond
};

void lightDepthAdd(inout CloudLightDepth d, float density, float lengthM) {
  if (density <= CLOUD_LIGHT_CLEAR_DENSITY) d.left = true;
  if (d.left) d.beyond += density * lengthM;
  else d.own += density * lengthM;
}

// Short steps first .. last - 1, each split path.split ways, every sample standing for its
// sub-step, tagged `part`.
void lightMarchShortSteps(CloudLightPath path, int first, int last, int part,
                          inout CloudLightDepth d) {
  for (int i = first; i < last; ++i) {
    float start = lightStepStart(i, path.steps, path.distanceM);
    float len = lightStepLength(i, path.steps, path.distanceM) / float(path.split);
    for (int j = 0; j < path.split; ++j)
      lightDepthAdd(d,
                    cloudDensityForLight(
                        path, path.origin + path.direction * (start + (float(j) + path.offset) * len),
                        len, part),
                    len);
  }
}

// The path over [startM, endM] in `parts` equal parts, each sampled once at path.offset of it
// and tagged `part`: the long step and the far step.
void lightMarchParts(CloudLightPath path, float startM, float endM, int parts, int part,
                     inout CloudLightDepth d) {
  float len = (endM - startM) / float(max(parts, 1));
  for (int j = 0; j < parts; ++j) {
    vec3 p = path.origin + path.direction * (startM + (float(j) + path.offset) * len);
    lightDepthAdd(d, cloudDensityForLight(path, p, len, part), len);
  }
}

// The long step over [distanceM, longEndM] in longParts equal parts.
void lightMarchLongStep(CloudLightPath path, inout CloudLightDepth d) {
  lightMarchParts(path, path.distanceM, path.longEndM, path.longParts, CLOUD_LIGHT_PART_FAR, d);
}

// The far step over [longEndM, farEndM] in farParts equal parts: where a low light's path
// still runs through the layer after the long step. It reads the clouds' effective mean (the
// far field's clumped density, cloudSampleAtLla with CLOUD_NOISE_NONE): the chance that a
// path of tens of kilometres misses every cloud of a broken field, not which clouds it hits.
// Without it a 3 degree sun, whose path crosses a 1.5 km layer over some 25 km, lit a
// stratocumulus deck's underside as if the sky toward it were clear past 6 km: 58 % brighter
// than Cycles' (docs/cloud-model.md, "A path-traced field").
void lightMarchFarStep(CloudLightPath path, inout CloudLightDepth d) {
  lightMarchParts(path, path.longEndM, path.farEndM, path.farParts, CLOUD_LIGHT_PART_MEAN, d);
}

// Lu (24)'s ds: the density accumulated from path.origin toward the light in density x
// metres, by the midpoint rule (each sample at path.offset of its step) over the short steps
// covering [0, distanceM] (lightStepLength), the long step over [distanceM, longEndM] and
// the far step over [longEndM, farEndM], split into the sample's own cloud and what lies
// beyond. Exact for densities linear along the path; a density edge costs at most the length
// of the (sub-)step it falls in.
CloudLightDepth lightMarchDepth(CloudLightPath path) {
  CloudLightDepth d = CloudLightDepth(0.0, 0.0, false);
  int near = clamp(path.nearSteps, 0, path.steps);
  lightMarchShortSteps(path, 0, near, CLOUD_LIGHT_PART_NEAR, d);
  lightMarchShortSteps(path, near, path.steps, CLOUD_LIGHT_PART_FAR, d);
  lightMarchLongStep(path, d);
  lightMarchFarStep(path, d);
  return d;
}

// All of it, own and beyond (the light volume stores the sum).
float lightMarchDensity(CloudLightPath path) {
  CloudLightDepth d = lightMarchDepth(path);
  return d.own + d.beyond;
}

// The first `k` short steps alone, [0, lightStepStart(k)]: the part near the point, where the
// cloud's fine structure shadows itself, that a caller reading the rest from the light volume
// (cloud_light_volume.glsl) marches itself.
CloudLightDepth lightMarchDepthNear(CloudLightPath path, int k) {
  CloudLightDepth d = CloudLightDepth(0.0, 0.0, false);
  int near = clamp(path.nearSteps, 0, k);
  lightMarchShortSteps(path, 0, near, CLOUD_LIGHT_PART_NEAR, d);
  lightMarchShortSteps(path, near, k, CLOUD_LIGHT_PART_FAR, d);
  return d;
}

// How many density samples lightMarchDensity takes (the cost heat map counts them).
int lightMarchSamples(CloudLightPath path) {
  return path.steps * path.split + path.longParts + path.farParts;
}

#endif
