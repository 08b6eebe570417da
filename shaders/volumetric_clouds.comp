#version 460
// The low and mid cloud layers (Lu et al. 2023; Tang et al. 2019 as the alternative model):
// each view ray is intersected with the spherical shells of the layers (Lu (27)), marched with
// steps that grow with distance, and at each sample the weather map gives the cover CMc and
// the cloud type, the baked noise the density (Lu (3)-(18) or Tang), and a short march toward
// the key light its attenuation (Lu (21)-(24)). Writes premultiplied radiance with opacity
// (1 - transmittance), the transmittance-weighted distance and the number of samples taken.
#include "common/volumetric_clouds_shared.h"
#include "common/view.glsl"
#include "common/geo.glsl"
#define LIGHTING_BINDING VOLUMETRIC_CLOUDS_BINDING_LIGHTING
#include "common/lighting.glsl"
#include "common/cloud_density.glsl"
#include "common/cloud_field.glsl"
#include "common/cloud_lighting.glsl"

// A light sample's footprint is at most this share of the outline's cell, where noiseKeep
// keeps all of it (cloud_field.glsl).
#define CLOUD_LIGHT_OUTLINE_RESOLVED 0.125
// The light steps that may read the detail noise and the shape noise (CloudParams): all of
// them when the file stands alone.
#ifndef CLOUD_LIGHT_DETAIL_STEPS
#define CLOUD_LIGHT_DETAIL_STEPS 17
#endif
#ifndef CLOUD_LIGHT_NOISE_STEPS
#define CLOUD_LIGHT_NOISE_STEPS 17
#endif
// Samples per short light step (CloudParams.lightSplit, clouds.light_split).
#ifndef CLOUD_LIGHT_SPLIT
#define CLOUD_LIGHT_SPLIT 1
#endif
// clouds.quality reference (CloudParams.reference): small fixed steps, no early exit, no
// empty-space skipping, no light reused along the ray, and a uniform light march.
#ifndef CLOUD_REFERENCE
#define CLOUD_REFERENCE 0
#endif
// The reference's light march: the standard one (lightMarchDensity) with each short step
// split this many ways and the long one into twice as many, so it is the same quadrature
// refined and reaches as far (Lu (22)'s clamp sees the same path).
#define CLOUD_REFERENCE_LIGHT_SPLIT 4
// 1: the light beyond the first CLOUD_LIGHT_VOLUME_NEAR short steps comes from the cloud
// light volume (passes/cloud_light_volume) instead of this march (clouds.light volume).
#ifndef CLOUD_LIGHT_VOLUME
#define CLOUD_LIGHT_VOLUME 0
#endif

layout(local_size_x = VOLUMETRIC_CLOUDS_GROUP_X, local_size_y = VOLUMETRIC_CLOUDS_GROUP_Y) in;

layout(binding = VOLUMETRIC_CLOUDS_BINDING_CLOUDS, rgba32f) uniform writeonly image2D cloudImage;
layout(binding = VOLUMETRIC_CLOUDS_BINDING_DEPTH, rg32f) uniform writeonly image2D depthImage;
layout(binding = VOLUMETRIC_CLOUDS_BINDING_STEPS, rgba16f) uniform writeonly image2D stepImage;

// Counts density evaluations inside the light march for the step heat map.
int gLightSamples = 0;
// The footprint of the view sample whose light is being marched.
float gFootprintM = 0.0;
// Where the light samples of this view sample sit inside their steps (lightMarchDensity's
// offset): a new value for every view sample, so the texel grid of the noise does not show
// through the shadows as a regular pattern.
float gLightOffset = 0.5;
// The light of the view ray's current cloud (CLOUD_LIGHT_REUSE_T): the optical depth toward
// the sun (x) and the moon (y) that its last light march found, and the layer it was marched
// in (each layer has its own light). A cloud's first sample always marches.
struct CloudLight {
  vec2 tau;
  int layer;
};

// The latitude and longitude along the light march being run (latLonLine through the view
// sample and the long step's sample, lightLongStepDistance).
LatLonLine gLightLine;

// A light sample stands for a whole light step, tens to thousands of metres: it sees the
// cloud filtered to a quarter of that (or to the view sample's footprint, the larger), so
// the shadow of detail finer than the step does not alias into streaks across the cloud.
// The steps from CLOUD_LIGHT_DETAIL_STEPS (CLOUD_LIGHT_NOISE_STEPS) on resolve no detail (no
// noise) whatever the footprint, and do not read it.
// What a light sample standing for `lengthM` of the march sees: the view sample's footprint,
// or a quarter of its step, but never so coarse that the clouds' outlines (the shape's R, a
// quarter of its repeat) blur into their mean. Beer-Lambert of a mean density is a uniform
// dusk where the gaps between real clouds let the sun through: the long step used to take
// the mean over its 4.8 km and left every cloud under a low sun grey (docs/clouds.md).
float lightFootprint(float lengthM) {
  float outline = 0.25 / params.shapeRepeatsPerM;
  return max(gFootprintM, min(0.25 * lengthM, CLOUD_LIGHT_OUTLINE_RESOLVED * outline));
}

float cloudDensityForLight(vec3 p, float lengthM, int step) {
  ++gLightSamples;
  CloudSample s;
  int noise = CLOUD_REFERENCE != 0 || step < CLOUD_LIGHT_DETAIL_STEPS ? CLOUD_NOISE_ALL
              : step < CLOUD_LIGHT_NOISE_STEPS ? CLOUD_NOISE_SHAPE
                                               : CLOUD_NOISE_NONE;
  cloudSampleAtLla(p, latLonAltitudeOn(gLightLine, p), lightFootprint(lengthM), false, noise, s);
  return s.density;
}
#include "common/cloud_light_march.glsl"

// The phase function's mean cosine, the asymmetry the diffusion term sees.
float meanCosine() {
  return CLOUD_DUAL_LOBE != 0 ? mix(params.g, params.gBack, params.backWeight) : params.g;
}

// The sun's (i = 0) or the moon's (1) illuminance at a layer, and whether the march lights
// with it at all (not when too dim to matter next to the other, or below the horizon).
vec3 keyLightAt(int i, int layer) {
  return i == 0 ? (layer == 0 ? params.sunAtLow.rgb : params.sunAtMid.rgb)
                : (layer == 0 ? params.moonAtLow.rgb : params.moonAtMid.rgb);
}
bool keyLightMarched(int i, int layer) {
  vec3 E = keyLightAt(i, layer);
  return (i == 0 ? params.sunMarched : params.moonMarched) != 0.0 && max(E.r, max(E.g, E.b)) > 0.0;
}

#if CLOUD_LIGHT_VOLUME
#include "common/cloud_light_volume.glsl"
layout(binding = CLOUD_LIGHT_VOLUME_BINDING_IMAGE) uniform sampler3D lightVolume;
#endif

// Lu (24): the optical depth from the cloud sample s at p toward the sun (x) and the moon (y).
vec2 marchKeyLights(vec3 p, CloudSample s) {
  vec2 tau = vec2(0.0);
  for (int i = 0; i < 2; ++i) {
    if (!keyLightMarched(i, s.layer)) continue;
    vec3 L = i == 0 ? params.sunDirection.xyz : params.moonDirection.xyz;
    gLightLine = latLonLine(p, s.latLon, L, lightLongStepDistance(params.lightDistanceM));
#if CLOUD_LIGHT_VOLUME
    // The cloud's own fine structure near the sample marched here, the rest from the volume
    // at the point where this part ends (it holds the light's path from there on).
    tau[i] = params.extinction *
             lightMarchDensityNear(p, L, params.lightDistanceM, CLOUD_LIGHT_STEPS,
                                   CLOUD_LIGHT_VOLUME_NEAR, CLOUD_LIGHT_SPLIT, gLightOffset);
    vec3 far = p + L * params.lightVolume.startM;
    tau[i] += textureLod(lightVolume, cloudLightVolumeCoord(params.lightVolume, params.geo, far),
                         0.0)[i];
#else
    // A short step's one sample is a random draw of its optical depth, and a noisy optical
    // depth brightens on average (the mean of exp(-tau) exceeds exp(-mean tau)): split steps
    // bring the shadowed parts of the clouds down to the reference's (clouds.light_split).
    tau[i] = params.extinction *
             (CLOUD_REFERENCE != 0
                  ? lightMarchDensityRefined(p, L, params.lightDistanceM, CLOUD_LIGHT_STEPS,
                                             CLOUD_REFERENCE_LIGHT_SPLIT, gLightOffset)
              : CLOUD_LIGHT_SPLIT > 1
                  ? lightMarchDensityRefined(p, L, params.lightDistanceM, CLOUD_LIGHT_STEPS,
                                             CLOUD_LIGHT_SPLIT, gLightOffset)
                  : lightMarchDensity(p, L, params.lightDistanceM, CLOUD_LIGHT_STEPS,
                                      gLightOffset));
#endif
  }
  return tau;
}

// The sun's and the moon's light that a cloud sample of `layer` and `type` scatters toward
// the eye (direction d) per unit of extinction, given the optical depth toward each: Lu (24)
// with the clamp (22), the phase (23) and the multiple-scattering octaves, plus the diffusion
// term. Scattering equals extinction: cloud droplets barely absorb.
vec3 cloudKeyLightScattering(vec3 d, int layer, float type, vec2 tau) {
  vec3 S = vec3(0.0);
  // Lu (22): the attenuation is at most that of ac times the densest path toward the light.
  float tauClamp =
      params.extinction * params.attenuationClamp * lightMarchReach(params.lightDistanceM);
  for (int i = 0; i < 2; ++i) {
    if (!keyLightMarched(i, layer)) continue;
    vec3 E = keyLightAt(i, layer);
    vec3 L = i == 0 ? params.sunDirection.xyz : params.moonDirection.xyz;
    // The phase function is per steradian; in the renderer's units (illuminance 1 = pi x
    // radiance 1, lighting_shared.h) radiance = pi * E * phase.
    S += VIEW_PI * E *
         cloudInScatter(tau[i], tauClamp, dot(d, L), params.g, params.gBack, params.backWeight,
                        CLOUD_DUAL_LOBE, CLOUD_OCTAVES);
    S += E * cloudDiffuseInScatter(tau[i] * cloudDiffusionLeak(type), meanCosine(),
                                   params.multipleScattering);
  }
  return S;
}

// The sky above and the ground below scattered toward the eye per unit of extinction (Tang's
// slab ambient with diffusion); tauView: the optical depth along the view ray from where it
// entered this cloud.
vec3 cloudAmbientScattering(vec3 d, CloudSample s, float tauView) {
  float sigmaT = params.extinction * s.density;
  float viewDown = clamp(0.5 - 0.5 * d.z, 0.0, 1.0);
  return cloudAmbientDiffuse(params.ambientTop.rgb, params.ambientBottom.rgb, sigmaT, s.hTop,
                             s.hBottom, tauView, viewDown, meanCosine(), params.multipleScattering);
}

// White noise in [0, 1) from a hash of the pixel, the frame and a sample number (PCG3D,
// Jarzynski & Olano 2020): the march's jitters, so banding turns into grain with no pattern
// the eye can lock onto, and successive frames of a time-lapse average it out. An ordered
// pattern (interleaved gradient noise) showed as a 2-pixel checkerboard in shadows and at
// edges.
float pixelHash(uvec2 pixel, uint frame, uint n) {
  uvec3 v = uvec3(pixel, frame + n * 0x9E3779B9u) * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return float(v.x >> 8u) * (1.0 / 16777216.0);
}

// The shape-only clearance (CloudSample.clearance, noise units below the coverage threshold)
// at which the march may stride 4x through clear air; with less clearance it strides less.
// 0.3 spares the fringes the strides skipped at the default shape scale (docs/clouds.md).
#define CLOUD_STRIDE_CLEARANCE 0.3

// The view ray's steps inside a cloud are at most this many optical depths deep (and no
// shorter than CLOUD_STEP_MIN_M metres); half that in the reference.
#define CLOUD_STEP_MAX_TAU (CLOUD_REFERENCE != 0 ? 0.25 : 0.5)
#define CLOUD_STEP_MIN_M 2.0
#define CLOUD_NO_DEPTH_LIMIT 1e30

// Once the view ray's transmittance is below this, what is left of the pixel (at most this
// share) is lit with the light march of the sample before, a few metres back in the same
// cloud, instead of a new march: deep inside an opaque cloud half the samples lie past this
// point, and the light march is most of a sample's cost.
#define CLOUD_LIGHT_REUSE_T 0.1

// Up to two intervals along the ray (origin o, unit d) where the point lies between the
// spheres of radius rIn and rOut around c, before the ray meets the ground sphere rGround.
// Returns the count; intervals in iv[0..count-1] as (enter, exit).
int shellIntervals(vec3 o, vec3 d, vec3 c, float rIn, float rOut, float rGround, out vec2 iv[2]) {
  vec3 q = o - c;
  float b = dot(q, d);
  float qq = dot(q, q);
  iv[0] = vec2(0.0);
  iv[1] = vec2(0.0);
  // Outer sphere: the ray is inside it over [t0, t1].
  float discOut = b * b - (qq - rOut * rOut);
  if (discOut <= 0.0) return 0;
  float sOut = sqrt(discOut);
  float t0 = max(-b - sOut, 0.0), t1 = -b + sOut;
  if (t1 <= 0.0) return 0;
  // The ground ends the ray.
  float discGround = b * b - (qq - rGround * rGround);
  if (discGround > 0.0) {
    float tg = -b - sqrt(discGround);
    // A ray heading down from on (or, in float, just above) the ground meets it at once.
    if (tg > 0.0 || b < 0.0) t1 = min(t1, max(tg, 0.0));
  }
  // Inner sphere: cut [a0, a1] out of [t0, t1].
  float discIn = b * b - (qq - rIn * rIn);
  if (discIn <= 0.0) {
    iv[0] = vec2(t0, t1);
    return t1 > t0 ? 1 : 0;
  }
  float sIn = sqrt(discIn);
  float a0 = -b - sIn, a1 = -b + sIn;
  int n = 0;
  if (a0 > t0) iv[n++] = vec2(t0, min(a0, t1));
  if (a1 < t1 && a1 > t0) iv[n++] = vec2(max(a1, t0), t1);
  if (a1 <= t0 || a0 >= t1) {  // the inner sphere lies outside [t0, t1]
    n = 0;
    iv[n++] = vec2(t0, t1);
  }
  return n;
}

// What one view ray through the clouds gives: premultiplied radiance, the transmittance left,
// the transmittance-weighted distance (depthSum / (1 - transmittance) is the depth), the
// samples taken, and where the ray first reaches the shells (-1 if it never does). `id` is the
// pixel whose hash jitters the ray.
struct CloudRay {
  vec3 radiance;
  float transmittance;
  float depthSum;
  int samples;
  float shellEntry;
};

CloudRay marchCloudRay(uvec2 id, vec3 o, vec3 d) {
  vec3 radiance = vec3(0.0);
  float transmittance = 1.0;
  float depthSum = 0.0;
  int samples = 0;
  // Where the ray first reaches the shells, -1 if it never does (the ground comes first): the
  // temporal pass's upsampling compares rays by it (cloud_temporal.comp).
  float shellEntry = -1.0;
  vec3 lastScattering = vec3(0.0);  // in-scattered light per unit of weight, last sample
  float lastT = 0.0;
  if (params.anyCover > 0.0) {
    float R = params.geo.origin.w;
    vec2 iv[2];
    int n = shellIntervals(o, d, geoCentre(params.geo), R + params.shellBaseM, R + params.shellTopM,
                           R, iv);
    if (n > 0) shellEntry = iv[0].x;
    float jitter = pixelHash(id, params.frameIndex, 0u) * params.jitter;
    int maxSteps = int(params.maxSteps);
    CloudLight light = CloudLight(vec2(0.0), -1);
    for (int k = 0; k < n && samples < maxSteps; ++k) {
      float t = iv[k].x;
      float stepLen = params.stepM + params.stepGrowth * t;
      t += jitter * stepLen;
      // Through clear air the step stretches (up to 4x) and shrinks back at the first cloud.
      float stretch = 1.0;
      float tauView = 0.0;
      // The longest step the density of the sample before allows (CLOUD_STEP_MAX_TAU).
      float depthLimit = CLOUD_NO_DEPTH_LIMIT;
      while (t < iv[k].y && samples < maxSteps && transmittance > params.transmittanceCutoff) {
        // Step through clear air until a sample finds cloud: this inner loop holds all that a
        // clear sample costs and the lighting below runs once per sample in a cloud. lavapipe
        // runs both sides of a branch for a whole group of invocations but leaves a loop once
        // none is left in it; with the lighting inside this loop every clear step of every
        // group in which any ray was in a cloud paid for a light march, most of a sample's
        // cost. The steps are the same either way.
        float dt;
        vec3 p;
        float footprint;
        CloudSample s;
        bool inCloud = false;
        do {
          stepLen = (params.stepM + params.stepGrowth * t) * stretch;  // Lu: grows with distance
          // A stretched step's length is random (mean unchanged): what strides still skip turns
          // into fine grain instead of lines where the strides of neighbouring rays line up.
          if (stretch > 1.0) stepLen *= 0.5 + pixelHash(id, params.frameIndex, uint(samples) + 1u);
          dt = min(min(stepLen, depthLimit), iv[k].y - t);
          p = o + d * (t + 0.5 * dt);
          // What one sample resolves: a pixel's width at this distance, or a quarter of the step
          // along the ray, the larger (top-down: full detail, the cover is measured there).
          footprint =
              CLOUD_TOPDOWN != 0 ? 0.0 : max((t + 0.5 * dt) * params.view.forward.w, 0.25 * dt);
          bool anyCloud = CLOUD_REFERENCE != 0
                              ? cloudSampleAtLla(p, latLonAltitude(params.geo, p), footprint, false,
                                                 CLOUD_NOISE_ALL, s)
                              : cloudSampleAt(p, footprint, s);
          if (!anyCloud) {
            // Outside the region or far from any cover: nothing to sample; stride on (the coarse
            // map is dilated by a whole block, kilometres, so a double step cannot jump a cloud).
            // The reference takes no coarse map and no double steps.
            tauView = 0.0;  // out of the layers or the map: the next cloud is entered afresh
            depthLimit = CLOUD_NO_DEPTH_LIMIT;
            t += CLOUD_REFERENCE != 0 ? dt : 2.0 * dt;
            continue;
          }
          ++samples;
          // A step deeper than CLOUD_STEP_MAX_TAU optical depths would take the density and
          // light of its middle, tens of metres inside, for the whole step, though what the eye
          // sees of an opaque cloud lies within an optical depth or two of its face. So each
          // step is no longer than that depth at the density of the sample before it; where the
          // density rises within a step the next one is shorter.
          float limit =
              s.density > 0.0
                  ? max(CLOUD_STEP_MAX_TAU / (params.extinction * s.density), CLOUD_STEP_MIN_M)
                  : CLOUD_NO_DEPTH_LIMIT;
          if (s.density > 0.0 && (stretch > 1.0 || (tauView <= 0.0 && dt > 1.01 * limit))) {
            // A cloud begins somewhere inside this step, a stretched one or one too deep for it:
            // march it again from its start at the normal step no deeper than that, so cloud
            // edges take neither the stretched step's coarse spacing nor a deep first sample.
            stretch = 1.0;
            depthLimit = limit;
            continue;
          }
          depthLimit = limit;
          // Stride only as far as the clearance says no cloud is near: a stretched step samples
          // its middle alone and skips what lies between. Striding up to 4x right beside the
          // clouds missed their thin fringes in the same way along whole rows of the view, whose
          // rays cross the gap below a cloud in nearly the same steps: horizontal striations.
          float strideCap = s.density > 0.0 || CLOUD_REFERENCE != 0
                                ? 1.0
                                : clamp(1.0 + 3.0 * s.clearance / CLOUD_STRIDE_CLEARANCE, 1.0, 4.0);
          stretch = min(stretch * 1.5, strideCap);
          if (s.density > 0.0) {
            inCloud = true;
            break;
          }
          tauView = 0.0;  // out of this cloud: the next one is entered afresh
          t += dt;
        } while (t < iv[k].y && samples < maxSteps);
        if (!inCloud) break;  // this interval ended in clear air
        // A sample in a cloud: Lu (19)(20) over its step, lit by the sky and the key lights.
        float sigmaT = params.extinction * s.density;
        float stepT = exp(-sigmaT * dt);  // Lu (19)(20) over one step
        // The step's integral of the in-scattered light S is weight x (S per unit of
        // extinction): integrateStep is linear in S.
        float weight = transmittance * (CLOUD_ENERGY_CONSERVING != 0
                                            ? integrateStep(vec3(sigmaT), sigmaT, dt).x
                                            : sigmaT * dt);
        vec3 scattering = cloudAmbientScattering(d, s, tauView + 0.5 * sigmaT * dt);
        // In the tail of this cloud the light march of the sample before serves.
        bool tail = CLOUD_REFERENCE == 0 && tauView > 0.0 && s.layer == light.layer &&
                    transmittance < CLOUD_LIGHT_REUSE_T;
        if (!tail) {
          gFootprintM = footprint;
          gLightOffset = fract(jitter + 0.6180339887 * float(samples));  // golden-ratio sequence
          light = CloudLight(marchKeyLights(p, s), s.layer);
        }
        scattering += cloudKeyLightScattering(d, s.layer, s.type, light.tau);
        radiance += weight * scattering;
        lastScattering = scattering;
        lastT = t + 0.5 * dt;
        depthSum += transmittance * (1.0 - stepT) * (t + 0.5 * dt);
        transmittance *= stepT;
        tauView += sigmaT * dt;
        t += dt;
      }
    }
  }
  // A ray stopped by the cutoff is taken as opaque: the rest of its transmittance goes to the
  // light of its last sample, as if that sample's step ran on to infinite depth (Lu (19)(20):
  // the step's weight tends to the transmittance left). Left out, 5 % of the sky showed through
  // every opaque cloud and the light of its far side was missing (docs/clouds.md, "Cutoff").
  if (CLOUD_REFERENCE == 0 && transmittance <= params.transmittanceCutoff && transmittance > 0.0) {
    radiance += transmittance * lastScattering;
    depthSum += transmittance * lastT;
    transmittance = 0.0;
  }
  return CloudRay(radiance, transmittance, depthSum, samples, shellEntry);
}

// A top-down pixel averages CLOUD_TOPDOWN_SUBPIXELS x CLOUD_TOPDOWN_SUBPIXELS rays, the ones a
// render that many times the size would march there (hashed as that render's pixels). Its
// ground is kilometres wide, many clouds across (160 x 120 over the default 800 km map: 5 km,
// the clouds' cells 1.2 km), so one ray at its centre either hits a cloud or misses: a pixel
// showed 0 or 1 where the map says 0.35, and an 8 x 8 block of them strayed from the map's
// cover by 0.044 on average (Dice 0.968). Four rays show the share of the ground under cloud
// closely enough for the blocks to be within 0.02 (docs/clouds.md, "Coverage fidelity").
#define CLOUD_TOPDOWN_SUBPIXELS 2

// The top-down ray through point `pixel` of the image (pixel units): it starts at that
// point's latitude and longitude (row 0 the north edge, column 0 the west edge, equal lat/lon
// spacing) above the highest layer and goes straight down.
void topDownRay(vec2 pixel, out vec3 o, out vec3 d) {
  vec2 uv = pixel / vec2(params.view.size.xy);
  vec4 b = params.region.bounds;
  float lat = mix(b.y, b.x, uv.y);
  float lon = mix(b.z, b.w, uv.x);
  o = geoPosition(params.geo, lat, lon, params.topDownStartM);
  d = -geoUp(params.geo, o);
}

void main() {
  // This invocation's texel of the pass's images, and the view's pixel it marches: every
  // pixel, or with temporal reuse one of each marchBlock x marchBlock square (a square cut
  // by the image's edge marches its nearest pixel).
  ivec2 ip = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(ip, imageSize(cloudImage)))) return;
  uvec2 id = min(gl_GlobalInvocationID.xy * params.marchBlock +
                     uvec2(params.marchOffsetX, params.marchOffsetY),
                 params.view.size.xy - 1u);
  vec2 pixel = vec2(id) + 0.5;

  // Rays in the frame's ENU coordinates: from the camera, or straight down (top-down).
  CloudRay ray;
  if (CLOUD_TOPDOWN != 0) {
    const int n = CLOUD_TOPDOWN_SUBPIXELS;
    ray = CloudRay(vec3(0.0), 0.0, 0.0, 0, -1.0);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        uvec2 sub = id * uint(n) + uvec2(i, j);
        vec3 o, d;
        topDownRay((vec2(sub) + 0.5) / float(n), o, d);
        CloudRay r = marchCloudRay(sub, o, d);
        ray.radiance += r.radiance;
        ray.transmittance += r.transmittance;
        ray.depthSum += r.depthSum;
        ray.samples += r.samples;
        ray.shellEntry = max(ray.shellEntry, r.shellEntry);
      }
    ray.radiance /= float(n * n);
    ray.transmittance /= float(n * n);
    ray.depthSum /= float(n * n);
  } else {
    ray = marchCloudRay(id, vec3(0.0), viewDirection(params.view, pixel));
  }
  float alpha = 1.0 - ray.transmittance;
  imageStore(cloudImage, ip, vec4(ray.radiance, alpha));
  float depth = alpha > 0.0 ? ray.depthSum / alpha : 0.0;
  imageStore(depthImage, ip, vec4(depth, ray.shellEntry, 0.0, 0.0));
  imageStore(stepImage, ip, vec4(float(ray.samples), float(gLightSamples), 0.0, 0.0));
}
