#version 460
// The low and mid cloud layers (Lu et al. 2023; Tang et al. 2019 as the alternative model):
// each view ray is intersected with the spherical shells of the layers (Lu (27)), marched with
// steps that grow with distance, and at each sample the weather map gives the cover CMc and
// the cloud type, the baked noise the density (Lu (3)-(18) or Tang), and a short march toward
// each light its attenuation (Lu (21)-(24)). Writes premultiplied radiance with opacity
// (1 - transmittance), the transmittance-weighted distance and the number of samples taken.
//
// The march in named steps: cloudViewRay (the pixel's ray), cloudMarchRay (the shells'
// intervals), cloudSeek (through clear air to the next cloud sample), cloudLightSample (the
// light at a cloud sample), cloudAccumulate (the sample's share of the pixel) and
// cloudTakeOpaqueRest (a ray stopped by the cutoff). main() averages clouds.samples such
// marches per pixel.
#include "common/volumetric_clouds_shared.h"
#include "common/view.glsl"
#include "common/geo.glsl"
#define LIGHTING_BINDING VOLUMETRIC_CLOUDS_BINDING_LIGHTING
#include "common/lighting.glsl"
#include "common/cloud_density.glsl"
#include "common/cloud_field.glsl"
#include "common/cloud_lighting.glsl"
#include "common/cloud_shells.glsl"
#include "common/cloud_ambient_shared.h"

// The variant's two switches of this shader (the rest: cloud_field.glsl). clouds.quality
// reference: small fixed steps, no early exit, no empty-space skipping, no light reused along
// the ray (its finer light march comes in the uniforms). clouds.light volume: the light beyond
// the first CLOUD_LIGHT_VOLUME_NEAR short steps comes from the cloud light volume
// (passes/cloud_light_volume) instead of this march.
#ifndef CLOUD_REFERENCE
#define CLOUD_REFERENCE 0
#endif
#ifndef CLOUD_LIGHT_VOLUME
#define CLOUD_LIGHT_VOLUME 0
#endif

// A light sample's footprint is at most this share of the outline's cell, where noiseKeep
// keeps all of it (cloud_field.glsl).
#define CLOUD_LIGHT_OUTLINE_RESOLVED 0.125

layout(local_size_x = VOLUMETRIC_CLOUDS_GROUP_X, local_size_y = VOLUMETRIC_CLOUDS_GROUP_Y) in;

layout(binding = VOLUMETRIC_CLOUDS_BINDING_CLOUDS, rgba32f) uniform writeonly image2D cloudImage;
layout(binding = VOLUMETRIC_CLOUDS_BINDING_DEPTH, rg32f) uniform writeonly image2D depthImage;
layout(binding = VOLUMETRIC_CLOUDS_BINDING_STEPS, rgba16f) uniform writeonly image2D stepImage;
// The sky's and the ground's light around the clouds (passes/cloud_ambient).
layout(binding = VOLUMETRIC_CLOUDS_BINDING_AMBIENT, rgba32f) uniform readonly image2D ambientImage;

// --- The light march ------------------------------------------------------------------------

#include "common/cloud_light_march.glsl"

// A light sample stands for a whole light step, tens to thousands of metres: it sees the
// cloud filtered to a quarter of that (or to the view sample's footprint, the larger), so
// the shadow of detail finer than the step does not alias into streaks across the cloud, but
// never so coarse that the clouds' outlines (the shape's R, a quarter of its repeat) blur
// into their mean. Beer-Lambert of a mean density is a uniform dusk where the gaps between
// real clouds let the sun through: the long step used to take the mean over its 4.8 km and
// left every cloud under a low sun grey (docs/clouds.md).
float lightFootprint(CloudLightPath path, float lengthM) {
  float outline = 0.25 / params.shapeRepeatsPerM;
  return max(path.footprintM, min(0.25 * lengthM, CLOUD_LIGHT_OUTLINE_RESOLVED * outline));
}

// The far part of the march resolves no detail whatever the footprint and does not read it
// (the reference reads everything everywhere).
float cloudDensityForLight(CloudLightPath path, vec3 p, float lengthM, int part) {
  CloudSample s;
  int noise = part == CLOUD_LIGHT_PART_MEAN ? CLOUD_NOISE_NONE
              : CLOUD_REFERENCE != 0 || part == CLOUD_LIGHT_PART_NEAR ? CLOUD_NOISE_ALL
                                                                      : CLOUD_NOISE_SHAPE;
  cloudSampleAtLla(p, latLonAltitudeOn(params.geo, path.line, p), lightFootprint(path, lengthM),
                   false, noise, s);
  return s.density;
}

// VOLUMETRIC_CLOUDS_HOST_DEPTH: a host's depth image (skylayers::Sky::record), at the view's
// pixels; each march stops at the host's geometry, so the clouds hold only what lies in front
// of it (the composite then lays all of them over the host's pixel).
#ifndef VOLUMETRIC_CLOUDS_HOST_DEPTH
#define VOLUMETRIC_CLOUDS_HOST_DEPTH 0
#endif
#if VOLUMETRIC_CLOUDS_HOST_DEPTH
#include "common/host_depth.glsl"
layout(binding = VOLUMETRIC_CLOUDS_BINDING_HOST_DEPTH) uniform sampler2D hostDepth;
layout(std140, binding = VOLUMETRIC_CLOUDS_BINDING_HOST_DEPTH_PARAMS) uniform HostDepthBlock {
  HostDepth hostDepthBlock[1];
};
#define hostDepthParams hostDepthBlock[SKY_PARAMS_INDEX]
#endif
#if CLOUD_LIGHT_VOLUME
#include "common/cloud_light_volume.glsl"
layout(binding = CLOUD_LIGHT_VOLUME_BINDING_IMAGE) uniform sampler3D lightVolume;
#endif

// The sun's (i = 0) or the moon's (1) light through the air in a layer, at its base (k = 0),
// middle (1) or top (2). Read member by member: a struct copied out of the uniform block
// into a local is a store between two struct types in SPIR-V, which validation rejects.
vec3 keyLightLevel(int i, int layer, int k) {
  if (i == 0) {
    if (layer == 0)
      return k == 0 ? params.sunAtLow.base.rgb
                    : (k == 1 ? params.sunAtLow.middle.rgb : params.sunAtLow.top.rgb);
    return k == 0 ? params.sunAtMid.base.rgb
                  : (k == 1 ? params.sunAtMid.middle.rgb : params.sunAtMid.top.rgb);
  }
  if (layer == 0)
    return k == 0 ? params.moonAtLow.base.rgb
                  : (k == 1 ? params.moonAtLow.middle.rgb : params.moonAtLow.top.rgb);
  return k == 0 ? params.moonAtMid.base.rgb
                : (k == 1 ? params.moonAtMid.middle.rgb : params.moonAtMid.top.rgb);
}
// Its illuminance at altitude `altitudeM` of the layer: log E quadratic through the base, the
// middle and the top (the air's optical depth above a point falls off exponentially with its
// altitude, so log E is smooth in it), 0 where the light is gone at the middle.
vec3 keyLightAt(int i, int layer, float altitudeM) {
  float base = layer == 0 ? params.lowBaseM : params.midBaseM;
  float top = layer == 0 ? params.lowTopM : params.midTopM;
  float f = clamp((altitudeM - base) / max(top - base, 1.0), 0.0, 1.0);
  vec3 middle = keyLightLevel(i, layer, 1);
  vec3 b = log(max(keyLightLevel(i, layer, 0), vec3(1e-30))), m = log(max(middle, vec3(1e-30)));
  vec3 t = log(max(keyLightLevel(i, layer, 2), vec3(1e-30)));
  vec3 E = exp(b * (2.0 * (f - 0.5) * (f - 1.0)) - m * (4.0 * f * (f - 1.0)) +
               t * (2.0 * f * (f - 0.5)));
  return mix(vec3(0.0), E, greaterThan(middle, vec3(0.0)));
}
// Whether the march lights with it at all (not when too dim to matter next to the other, or
// below the horizon).
bool keyLightMarched(int i, int layer) {
  vec3 E = keyLightLevel(i, layer, 1);
  return (i == 0 ? params.sunMarched : params.moonMarched) != 0.0 && max(E.r, max(E.g, E.b)) > 0.0;
}
vec3 keyLightDirection(int i) {
  return i == 0 ? params.sunDirection.xyz : params.moonDirection.xyz;
}

// The short steps for a sample `footprintM` wide: the doubling schedule over the same
// distance with its first step no shorter than half the footprint. A sample resolves no
// shadow much finer than itself, and a distant one is hundreds of metres wide where the first
// steps are tens of metres. A first step as long as the footprint saved 6-35 % of a still but
// brightened a 64 x 36 render by 8 % (its samples no longer saw the cloud right next to them);
// half of it saves up to 12 % and brightens by 1.4 % (docs/clouds.md, Lighting). At least
// one step; the light volume keeps the full schedule (its near part ends where its volume
// starts).
int cloudLightStepsFor(float footprintM, float distanceM) {
  int steps = int(params.lightSteps);
  if (CLOUD_REFERENCE != 0 || CLOUD_LIGHT_VOLUME != 0 || footprintM <= 0.0) return steps;
  return clamp(int(floor(log2(1.0 + 2.0 * distanceM / footprintM))), 1, steps);
}

// The light path from a cloud sample at p (latitude and longitude latLon, altitude h) toward
// L. Its long step ends where the path leaves the shells, if that comes before the clouds it
// resolves end (CLOUD_LIGHT_RESOLVED_REACH; the reference's reach): past there is no cloud,
// and the parts left are spent where the cloud is. A low sun's path runs through the layer
// for kilometres and takes the most parts, a high sun's few.
// `longShare` marches of one pixel share the long step: each reads it in parts that many
// times longer (CloudRay.longShare).
CloudLightPath cloudLightPath(vec3 p, vec2 latLon, float h, vec3 L, float footprintM,
                              float offset, int longShare) {
  float distance = params.lightDistanceM;
  float exitM = cloudShellExit(params.geo.origin.w, h, dot(L, geoUp(params.geo, p)),
                               params.shellBaseM, params.shellTopM);
  float resolved = CLOUD_REFERENCE != 0 ? lightMarchReach(distance)
                                         : CLOUD_LIGHT_RESOLVED_REACH * distance;
  float longEnd = clamp(exitM, distance, resolved);
  float farEnd = clamp(exitM, longEnd, max(CLOUD_LIGHT_FAR_REACH_M, longEnd));
  return CloudLightPath(p, L, latLonLine(params.geo, p, latLon, L, lightLongStepDistance(distance)),
                        footprintM, offset, distance, cloudLightStepsFor(footprintM, distance),
                        int(params.lightSplit), int(params.lightNearSteps), longEnd,
                        cloudLightLongParts(distance, longEnd,
                                            float(longShare) * params.lightLongPartM),
                        farEnd, cloudLightFarParts(longEnd, farEnd));
}

// What the light marches of one view sample found: the optical depth toward the sun (x, z)
// and the moon (y, w), through the sample's own cloud (xy) and beyond it (zw;
// CloudLightDepth), and how many density samples it took.
struct CloudKeyLights {
  vec4 tau;
  vec2 behind;  // the optical depth away from the sun (x) and the moon (y): cloudDepthBehind
  int samples;
};

// The cloud behind the sample at p, away from the light L, over CLOUD_BEHIND_M in
// CLOUD_BEHIND_PARTS equal parts each sampled once at `offset` of it with the shape alone, up
// to the first clear one (the sample's own cloud, as lightDepthAdd splits it): what sends the
// diffuse light back toward the lit face (diffuseBehindShare). A cloud that is still there
// at the last part goes on past the probe and counts as thick (CLOUD_BEHIND_THICK). 600 m is
// 20-60 optical depths of a cumulus' core, where the reflectance has reached 0.9 and more.
#define CLOUD_BEHIND_M 600.0
#define CLOUD_BEHIND_PARTS 2
#define CLOUD_BEHIND_THICK 1.0e6
float cloudDepthBehind(vec3 p, vec2 latLon, float h, vec3 L, float footprintM, float offset) {
  CloudLightPath back = cloudLightPath(p, latLon, h, -L, footprintM, offset, 1);
  float len = CLOUD_BEHIND_M / float(CLOUD_BEHIND_PARTS);
  float depth = 0.0;
  for (int j = 0; j < CLOUD_BEHIND_PARTS; ++j) {
    float density =
        cloudDensityForLight(back, p - L * ((float(j) + offset) * len), len, CLOUD_LIGHT_PART_FAR);
    if (density <= CLOUD_LIGHT_CLEAR_DENSITY) return depth;
    depth += density * len;
  }
  return CLOUD_BEHIND_THICK;
}

// Lu (24): the optical depth from the cloud sample s at p toward the sun and the moon.
CloudKeyLights marchKeyLights(vec3 p, float h, CloudSample s, float footprintM, float offset,
                              int longShare) {
  CloudKeyLights k = CloudKeyLights(vec4(0.0), vec2(0.0), 0);
  for (int i = 0; i < 2; ++i) {
    if (!keyLightMarched(i, s.layer)) continue;
    vec3 L = keyLightDirection(i);
    CloudLightPath path = cloudLightPath(p, s.latLon, h, L, footprintM, offset, longShare);
#if CLOUD_LIGHT_VOLUME
    // The cloud's own fine structure near the sample marched here, the rest from the volume
    // at the point where this part ends (it holds the light's path from there on as one sum:
    // beyond the sample's own cloud if this part left it, its own cloud's if not, as the full
    // march would count it until it finds clear air).
    CloudLightDepth d = lightMarchDepthNear(path, CLOUD_LIGHT_VOLUME_NEAR);
    k.samples += CLOUD_LIGHT_VOLUME_NEAR * path.split;
    vec3 far = p + L * params.lightVolume.startM;
    float rest = textureLod(lightVolume, cloudLightVolumeCoord(params.lightVolume, params.geo, far),
                            0.0)[i] / params.extinction;
    if (d.left) d.beyond += rest;
    else d.own += rest;
#else
    CloudLightDepth d = lightMarchDepth(path);
    k.samples += lightMarchSamples(path);
#endif
    k.tau[i] = params.extinction * d.own;
    k.tau[2 + i] = params.extinction * d.beyond;
    k.behind[i] = params.extinction * cloudDepthBehind(p, s.latLon, h, L, footprintM, offset);
    k.samples += CLOUD_BEHIND_PARTS;
  }
  return k;
}

// --- Lighting at a sample -------------------------------------------------------------------

// The phase function's mean cosine, the asymmetry the diffusion term sees.
float meanCosine() {
  return CLOUD_DUAL_LOBE != 0 ? mix(params.g, params.gBack, params.backWeight) : params.g;
}

// The sun's and the moon's light that a cloud sample of `layer` and `type` scatters toward
// the eye (direction d) per unit of extinction, given the optical depth toward each: Lu (24)
// with the clamp (22), the phase (23) and the multiple-scattering octaves, plus the diffusion
// term, of which the point keeps `diffuseShare` (diffuseBoundaryShare). Scattering equals
// extinction: cloud droplets barely absorb.
vec3 cloudKeyLightScattering(vec3 d, int layer, float altitudeM, float type, vec4 tau,
                             vec2 behind, float diffuseShare) {
  vec3 S = vec3(0.0);
  // Lu (22): the attenuation is at most that of ac times the densest path toward the light.
  float tauClamp =
      params.extinction * params.attenuationClamp * lightMarchReach(params.lightDistanceM);
  for (int i = 0; i < 2; ++i) {
    if (!keyLightMarched(i, layer)) continue;
    // The clouds beyond the sample's own shadow its light as a beam: what they scatter is
    // spread over the sky, of which the little that reaches this cloud is not counted (the
    // ambient is the clear sky's).
    vec3 E = keyLightAt(i, layer, altitudeM) * exp(-tau[2 + i]);
    // The phase function is per steradian; in the renderer's units (illuminance 1 = pi x
    // radiance 1, lighting_shared.h) radiance = pi * E * phase.
    S += VIEW_PI * E *
         cloudInScatter(tau[i], tauClamp, dot(d, keyLightDirection(i)), params.g, params.gBack,
                        params.backWeight, CLOUD_DUAL_LOBE, int(params.octaves));
    S += diffuseShare * diffuseBehindShare(tau[i], behind[i], meanCosine()) * E *
         cloudDiffuseInScatter(tau[i] * cloudDiffusionLeak(type), meanCosine(),
                               params.multipleScattering);
  }
  return S;
}

// The ambient light of a view ray (cloud_ambient_shared.h), the same at all its samples: the
// sky's and the ground's light on a surface facing up (the layer's top), down (its bottom),
// back along the ray (the face the ray entered by) and along it (the cloud's far side). From
// the sky that is actually there, so a face turned from a low sun takes the darker, bluer sky
// behind the camera, and the far side of a backlit cloud the bright sky around the sun.
struct CloudRayAmbient {
  vec3 above, below, face, back;
  vec3 phaseExcess;  // the sky scattered once along the ray less its mean (cloudPhaseSkyLight)
};
// Row `row0` + j of the table at unit vector n: bilinear in azimuth (wrapping) and elevation.
vec3 cloudAmbientTable(vec3 n, int row0) {
  float x = atan(n.y, n.x) * (float(CLOUD_AMBIENT_MAP_WIDTH) / (2.0 * VIEW_PI));
  float y = (asin(clamp(n.z, -1.0, 1.0)) / VIEW_PI + 0.5) * float(CLOUD_AMBIENT_MAP_HEIGHT - 1);
  float x0 = floor(x), y0 = min(floor(y), float(CLOUD_AMBIENT_MAP_HEIGHT - 2));
  vec2 f = vec2(x - x0, y - y0);
  int i0 = int(x0) & (CLOUD_AMBIENT_MAP_WIDTH - 1), i1 = (i0 + 1) & (CLOUD_AMBIENT_MAP_WIDTH - 1);
  int j0 = row0 + int(y0);
  vec3 a = mix(imageLoad(ambientImage, ivec2(i0, j0)).rgb, imageLoad(ambientImage, ivec2(i1, j0)).rgb, f.x);
  vec3 b = mix(imageLoad(ambientImage, ivec2(i0, j0 + 1)).rgb,
               imageLoad(ambientImage, ivec2(i1, j0 + 1)).rgb, f.x);
  return mix(a, b, f.y);
}
// The sky's and the ground's light on a surface of unit normal n.
vec3 cloudAmbientLight(vec3 n) { return cloudAmbientTable(n, 0); }
CloudRayAmbient cloudRayAmbient(vec3 d) {
  return CloudRayAmbient(cloudAmbientLight(vec3(0.0, 0.0, 1.0)),
                         cloudAmbientLight(vec3(0.0, 0.0, -1.0)), cloudAmbientLight(-d),
                         cloudAmbientLight(d), cloudAmbientTable(d, CLOUD_AMBIENT_PHASE_ROW));
}

// The sky's and the ground's light scattered toward the eye per unit of extinction (Tang's
// slab ambient with diffusion); tauView: the optical depth along the view ray from where it
// entered this cloud.
vec3 cloudAmbientScattering(CloudRayAmbient a, CloudSample s, float tauView) {
  float sigmaT = params.extinction * s.density;
  return cloudAmbientDiffuse(a.above, a.below, a.face, a.back, sigmaT, s.hTop, s.hBottom, tauView,
                             meanCosine(), params.multipleScattering);
}

// --- Random numbers -------------------------------------------------------------------------

// White noise in [0, 1) from a hash of the pixel, a seed and a sample number (PCG3D,
// Jarzynski & Olano 2020): the march's jitters, so banding turns into grain with no pattern
// the eye can lock onto, and successive frames of a time-lapse average it out. An ordered
// pattern (interleaved gradient noise) showed as a 2-pixel checkerboard in shadows and at
// edges.
float pixelHash(uvec2 pixel, uint seed, uint n) {
  uvec3 v = uvec3(pixel, seed + n * 0x9E3779B9u) * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return float(v.x >> 8u) * (1.0 / 16777216.0);
}

// --- The view ray ---------------------------------------------------------------------------

// One march of a pixel: its ray and its random numbers.
struct CloudRay {
  vec3 origin;     // ENU, m
  vec3 direction;  // unit
  uvec2 pixel;     // the view's pixel, for the hashes
  uint seed;       // the frame's jitter seed, different for each of the pixel's marches
  float jitter;    // [0, 1): how far into its first step the march starts
  float spreadPerM;  // what one sample of it resolves across, per metre of distance: a
                     // pixel's width, or a sub-pixel's where a pixel marches several rays
  CloudRayAmbient ambient;
  int longShare;     // how many of the pixel's marches share their light marches' long step
                     // (the horizon band's rays; cloudLightPath), 1: each reads all of it
  float maxT;        // where the march stops: a host's geometry (VOLUMETRIC_CLOUDS_HOST_DEPTH)
};

// Sub-pixel position `pixel` (in the view's pixels) of the ray: the camera's, or for a
// top-down frame straight down from above the clouds over that point of the region (row 0 the
// north edge, column 0 the west edge, equal lat/lon spacing).
CloudRay cloudViewRay(vec2 pixel, uvec2 id, uint seed, float jitter, float spreadPerM) {
  vec3 d = viewDirection(params.view, pixel);
  CloudRay ray =
      CloudRay(vec3(0.0), d, id, seed, jitter, spreadPerM, cloudRayAmbient(d), 1, 3.0e38);
  if (CLOUD_TOPDOWN != 0) {
    vec2 uv = pixel / vec2(params.view.size.xy);
    vec4 b = params.region.bounds;
    ray.origin = geoPosition(params.geo, mix(b.y, b.x, uv.y), mix(b.z, b.w, uv.x),
                             params.topDownStartM);
    ray.direction = -geoUp(params.geo, ray.origin);
    ray.ambient = cloudRayAmbient(vec3(0.0, 0.0, -1.0));
  }
  return ray;
}

// The intervals of the ray inside the marched shells (Lu (27)), before the ground.
int cloudRayIntervals(CloudRay ray, out vec2 iv[2]) {
  vec3 up = geoUp(params.geo, ray.origin);
  float h = CLOUD_TOPDOWN != 0 ? params.topDownStartM : params.geo.origin.z;
  return cloudShellIntervals(params.geo.origin.w, h, dot(ray.direction, up), params.shellBaseM,
                             params.shellTopM, iv);
}

// A top-down pixel averages CLOUD_TOPDOWN_SUBPIXELS x CLOUD_TOPDOWN_SUBPIXELS rays, the ones a
// render that many times the size would march there (hashed as that render's pixels). Its
// ground is kilometres wide, many clouds across (160 x 120 over the default 800 km map: 5 km,
// the clouds' cells 1.2 km), so one ray at its centre either hits a cloud or misses: a pixel
// showed 0 or 1 where the map says 0.35, and an 8 x 8 block of them strayed from the map's
// cover by 0.044 on average (Dice 0.968). Four rays show the share of the ground under cloud
// closely enough for the blocks to be within 0.02 (docs/clouds.md, "Coverage fidelity").
#define CLOUD_TOPDOWN_SUBPIXELS 2

// --- The march ------------------------------------------------------------------------------

// What the march has gathered along a view ray.
struct CloudMarch {
  vec3 radiance;        // premultiplied
  float transmittance;
  float depthSum;       // transmittance-weighted distance (m)
  int samples;          // density samples along the view ray
  int lightSamples;     // density samples in its light marches
  vec3 lastScattering;  // in-scattered light per unit of weight at the last sample
  float lastT;          // and where it was
  vec4 tau;             // the light (optical depth toward the sun, the moon; own, beyond) of the ray's
  vec2 behind;          // and away from them (CloudKeyLights.behind)
  int lightLayer;       // current cloud, and the layer it was marched in (-1: none yet)
  float lightT;         // where along the ray it was marched
  bool lightFar;        // for a sample of the far field
};

// Where the march stands inside one interval of the shells.
struct CloudSeek {
  float t;           // where the next step starts
  float stretch;     // how many normal steps long the next clear step may be (1-4)
  float tauView;     // optical depth since the ray entered the current cloud (0: not in one)
  float depthLimit;  // the longest step the density of the sample before allows
};

// A step whose sample found cloud.
struct CloudStep {
  float t;          // where it starts
  float dt;         // its length
  vec3 p;           // its sample, at its middle
  float altitudeM;  // of p
  float footprint;  // what the sample resolves (m)
  CloudSample s;
};

// The shape-only clearance (CloudSample.clearance, noise units below the coverage threshold)
// at which the march may stride 4x through clear air; with less clearance it strides less.
// 0.3 spares the fringes the strides skipped at the default shape scale (docs/clouds.md).
#define CLOUD_STRIDE_CLEARANCE 0.3

// The view ray's steps inside a cloud are at most this many optical depths deep (and no
// shorter than CLOUD_STEP_MIN_M metres); half that in the reference.
#define CLOUD_STEP_MAX_TAU (CLOUD_REFERENCE != 0 ? 0.25 : 0.5)
#define CLOUD_STEP_MIN_M 2.0
// The shortest view step as a multiple of the ray's spread at its distance (cloudBaseStep).
#define CLOUD_STEP_PER_SPREAD 2.0
#define CLOUD_NO_DEPTH_LIMIT 1e30

// Once the view ray's transmittance is below this, what is left of the pixel (at most this
// share) is lit with the light march of the sample before, a few metres back in the same
// cloud, instead of a new march: deep inside an opaque cloud half the samples lie past this
// point, and the light march is most of a sample's cost.
#define CLOUD_LIGHT_REUSE_T 0.1
// Far-field samples within this share of the outline's cell of the last one marched take its
// light (cloudLightSample).
#define CLOUD_FAR_LIGHT_REUSE 4.0

// The band just above the horizon, where the clouds are a few pixels across: a pixel whose
// ray reaches the shells where its width is at least CLOUD_BAND_FROM of the outline's cell
// marches CLOUD_BAND_RAYS_NEAR rays, from 1.5 times that CLOUD_BAND_RAYS, up to
// CLOUD_BAND_TO, where the outline fades into the far field even for those. One ray hit or
// missed each small cloud at random, a speckle 20 % RMS off a 4x supersampled render
// (docs/clouds.md, "The horizon"); nearer the clouds are many pixels across, farther the far
// field is smooth. The clouds there are flattened in the view: a cloud's depth along the
// ray shows as a sliver of its height, the sine of a few degrees of it, so the rays are
// stratified in the vertical, one in each of `count` equal slices of the pixel's height, at
// golden-ratio places across it. Six such rays are as close to the supersampled render as
// nine at R2 places were (4.4 % RMS; four of them 6.2 %, four at R2 places 7.7 %). Each of
// the six resolves CLOUD_BAND_RESOLVE of the pixel's width, as the nine did (the footprint of
// a render three times the size), the four their share as any marches do: at the sixth of its
// area a ray covers, the sheet of moonlit altocumulus blurred into a cloudy mean at every
// sample of the band and its light marches doubled.
#define CLOUD_BAND_FROM 0.04
#define CLOUD_BAND_TO 0.3
#define CLOUD_BAND_RAYS_NEAR 4
#define CLOUD_BAND_RAYS 6
#define CLOUD_BAND_RESOLVE (1.0 / 3.0)
// Only rays that rise by less than this sine (4 degrees): the band as a viewer on or under
// the clouds sees it. Grazing rays cross many clouds a pixel: with nine rays the band cost
// 1.4-1.5x the still of a view with a horizon, with six sharing the long step 1.0-1.08x (the
// moonlit sheet about 1.25x; benchmarks/README.md); taking every grazing ray, or those that
// fall too (the layer below a camera at 4 km), cost up to 2.5x.
#define CLOUD_BAND_SINE 0.07

// The normal step at distance t along `ray`: Lu's step that grows with distance; in the far
// field, where a sample resolves none of the clouds' outline (its spread at least half the
// outline's cell), never shorter than the spread: the field is smooth there, a step finer
// than a sample is wide gains nothing, and at the horizon, where a pixel is hundreds of
// metres wide, such steps spent most of the frame. Nearer, Lu's step stays: steps of a
// pixel's width at 20 km left the moonlit and high views 3-6 dB off the reference. The
// reference keeps Lu's (halved) step everywhere.
float cloudBaseStep(CloudRay ray, float t) {
  float lu = params.stepM + params.stepGrowth * t;
  float spread = ray.spreadPerM * t;
  bool far = spread * 4.0 * params.shapeRepeatsPerM >= 0.5;
  return CLOUD_REFERENCE == 0 && far ? max(lu, CLOUD_STEP_PER_SPREAD * spread) : lu;
}

// How many normal steps the clear step after this sample may stride: as far as the clearance
// says no cloud is near. A stretched step samples its middle alone and skips what lies
// between: striding up to 4x right beside the clouds missed their thin fringes in the same
// way along whole rows of the view, whose rays cross the gap below a cloud in nearly the same
// steps (horizontal striations). Above or below the cloud type's vertical range the clearance
// says nothing; there the next step, at its longest (1.5x its mean), must end before the ray
// reaches the range: striding into the thin base of a sheet of altocumulus lost its fringes
// along whole rows (7 dB by moonlight, docs/clouds.md "Strides").
float cloudStrideCap(CloudRay ray, CloudStep st) {
  if (CLOUD_REFERENCE != 0 || st.s.density > 0.0) return 1.0;
  if (st.s.rangeGapM > 0.0) {
    float climb = abs(dot(ray.direction, geoUp(params.geo, st.p)));
    float reachM = st.s.rangeGapM / max(climb, 1e-3) - 0.5 * st.dt;
    return clamp(reachM / (1.5 * cloudBaseStep(ray, st.t)), 1.0, 4.0);
  }
  return clamp(1.0 + 3.0 * st.s.clearance / CLOUD_STRIDE_CLEARANCE, 1.0, 4.0);
}

// Steps through clear air from seek.t until a sample finds cloud before `end`: true with the
// step in `st`, false when the interval (or the ray's samples) ended in clear air. This loop
// holds all that a clear sample costs, and the lighting runs once per cloud sample outside
// it: lavapipe runs both sides of a branch for a whole group of invocations but leaves a loop
// once none is left in it, so with the lighting inside every clear step of every group in
// which any ray was in a cloud paid for a light march, most of a sample's cost.
bool cloudSeek(CloudRay ray, float end, inout CloudSeek seek, inout CloudMarch m,
               out CloudStep st) {
  while (seek.t < end && m.samples < int(params.maxSteps)) {
    float stepLen = cloudBaseStep(ray, seek.t) * seek.stretch;
    // A stretched step's length is random (mean unchanged): what strides still skip turns
    // into fine grain instead of lines where the strides of neighbouring rays line up.
    if (seek.stretch > 1.0) stepLen *= 0.5 + pixelHash(ray.pixel, ray.seed, uint(m.samples) + 1u);
    st.t = seek.t;
    st.dt = min(min(stepLen, seek.depthLimit), end - seek.t);
    st.p = ray.origin + ray.direction * (seek.t + 0.5 * st.dt);
    // What one sample resolves: a pixel's width at this distance, or a quarter of the step
    // along the ray, the larger (top-down: full detail, the cover is measured there).
    st.footprint = CLOUD_TOPDOWN != 0
                       ? 0.0
                       : max((seek.t + 0.5 * st.dt) * ray.spreadPerM, 0.25 * st.dt);
    vec3 lla = latLonAltitude(params.geo, st.p);
    st.altitudeM = lla.z;
    // The reference takes no coarse map.
    if (!cloudSampleAtLla(st.p, lla, st.footprint, CLOUD_REFERENCE == 0, CLOUD_NOISE_ALL, st.s)) {
      // Outside the region, between the layers or far from any cover: nothing to sample;
      // stride on (the coarse map is dilated by a whole block, kilometres, so a double step
      // cannot jump a cloud). The next cloud is entered afresh. The reference takes single
      // steps.
      seek.tauView = 0.0;
      seek.depthLimit = CLOUD_NO_DEPTH_LIMIT;
      seek.t += CLOUD_REFERENCE != 0 ? st.dt : 2.0 * st.dt;
    } else {
      ++m.samples;
      // A step deeper than CLOUD_STEP_MAX_TAU optical depths would take the density and light
      // of its middle, tens of metres inside, for the whole step, though what the eye sees of
      // an opaque cloud lies within an optical depth or two of its face. So each step is no
      // longer than that depth at the density of the sample before it; where the density
      // rises within a step the next one is shorter.
      float limit = st.s.density > 0.0 ? max(CLOUD_STEP_MAX_TAU / (params.extinction * st.s.density),
                                             CLOUD_STEP_MIN_M)
                                       : CLOUD_NO_DEPTH_LIMIT;
      bool deepFirst = seek.tauView <= 0.0 && st.dt > 1.01 * limit;
      if (st.s.density > 0.0 && (seek.stretch > 1.0 || deepFirst)) {
        // A cloud begins somewhere inside this step, a stretched one or one too deep for it:
        // march it again from its start at the normal step no deeper than that, so cloud
        // edges take neither the stretched step's coarse spacing nor a deep first sample.
        seek.stretch = 1.0;
        seek.depthLimit = limit;
      } else {
        seek.depthLimit = limit;
        seek.stretch = min(seek.stretch * 1.5, cloudStrideCap(ray, st));
        if (st.s.density > 0.0) return true;
        seek.tauView = 0.0;  // out of this cloud: the next one is entered afresh
        seek.t += st.dt;
      }
    }
  }
  return false;
}

// The light at a cloud sample: the sky's and the ground's, and the sun's and the moon's
// through the cloud toward them (a new light march, or in the tail of an opaque cloud the one
// of the sample before). Returns the in-scattered light per unit of extinction.
vec3 cloudLightSample(CloudRay ray, CloudStep st, float tauView, inout CloudMarch m) {
  float sigmaT = params.extinction * st.s.density;
  vec3 scattering = cloudAmbientScattering(ray.ambient, st.s, tauView + 0.5 * sigmaT * st.dt);
  bool tail = CLOUD_REFERENCE == 0 && tauView > 0.0 && st.s.layer == m.lightLayer &&
              m.transmittance < CLOUD_LIGHT_REUSE_T;
  // The far field is smooth over a cloud cell: its light changes little from one sample to
  // the next, and a march at every one of its samples was most of the band at the horizon's
  // cost (a thousand light samples a pixel there).
  bool far = st.s.outline <= 0.0;
  bool smoothFar = CLOUD_REFERENCE == 0 && far && m.lightFar && st.s.layer == m.lightLayer &&
                st.t - m.lightT < CLOUD_FAR_LIGHT_REUSE * 0.25 / params.shapeRepeatsPerM;
  if (!tail && !smoothFar) {
    // Each view sample places its light samples differently inside their steps (a
    // golden-ratio sequence seeded by the ray's jitter), so the texel grid of the noise does
    // not show through the shadows as a regular pattern.
    float offset = fract(ray.jitter + 0.6180339887 * float(m.samples));
    CloudKeyLights k =
        marchKeyLights(st.p, st.altitudeM, st.s, st.footprint, offset, ray.longShare);
    m.tau = k.tau;
    m.behind = k.behind;
    m.lightLayer = st.s.layer;
    m.lightT = st.t;
    m.lightFar = far;
    m.lightSamples += k.samples;
  }
  // The depths to the base and the top at this point's density, as the ambient takes them.
  float share = diffuseBoundaryShare(sigmaT * st.s.hBottom, sigmaT * st.s.hTop, meanCosine(),
                                     dot(ray.direction, geoUp(params.geo, st.p)));
  return scattering + cloudKeyLightScattering(ray.direction, st.s.layer, st.altitudeM,
                                              st.s.type, m.tau, m.behind, share);
}

// A cloud sample's share of the pixel: Lu (19)(20) over its step. The step's integral of the
// in-scattered light S is weight x S: integrateStep is linear in S.
void cloudAccumulate(CloudStep st, vec3 scattering, inout CloudMarch m) {
  float sigmaT = params.extinction * st.s.density;
  float stepT = exp(-sigmaT * st.dt);  // Lu (19)(20) over one step
  float weight = m.transmittance * (CLOUD_ENERGY_CONSERVING != 0
                                        ? integrateStep(vec3(sigmaT), sigmaT, st.dt).x
                                        : sigmaT * st.dt);
  float tMid = st.t + 0.5 * st.dt;
  m.radiance += weight * scattering;
  m.lastScattering = scattering;
  m.lastT = tMid;
  m.depthSum += m.transmittance * (1.0 - stepT) * tMid;
  m.transmittance *= stepT;
}

// A ray stopped by the cutoff is taken as opaque: the rest of its transmittance goes to the
// light of its last sample, as if that sample's step ran on to infinite depth (Lu (19)(20):
// the step's weight tends to the transmittance left). Left out, 5 % of the sky showed through
// every opaque cloud and the light of its far side was missing (docs/clouds.md, "Cutoff").
void cloudTakeOpaqueRest(inout CloudMarch m) {
  if (CLOUD_REFERENCE == 0 && m.transmittance <= params.transmittanceCutoff &&
      m.transmittance > 0.0) {
    m.radiance += m.transmittance * m.lastScattering;
    m.depthSum += m.transmittance * m.lastT;
    m.transmittance = 0.0;
  }
}

// One march of the ray through the shells: steps through clear air to each cloud sample,
// lights it and adds its share, until the shells end, the ray's samples run out or the
// transmittance falls below the cutoff.
CloudMarch cloudMarchRay(CloudRay ray) {
  CloudMarch m = CloudMarch(vec3(0.0), 1.0, 0.0, 0, 0, vec3(0.0), 0.0, vec4(0.0), vec2(0.0), -1, 0.0, false);
  if (params.anyCover <= 0.0) return m;
  vec2 iv[2];
  float tauTotal = 0.0;
  int n = cloudRayIntervals(ray, iv);
#if VOLUMETRIC_CLOUDS_HOST_DEPTH
  // The host's geometry hides what lies behind it: the intervals end there.
  for (int k = 0; k < n; ++k) iv[k].y = min(iv[k].y, ray.maxT);
  if (n > 1 && iv[1].x >= iv[1].y) n = 1;
  if (n > 0 && iv[0].x >= iv[0].y) n = 0;
#endif
  for (int k = 0; k < n && m.samples < int(params.maxSteps); ++k) {
    CloudSeek seek = CloudSeek(iv[k].x + ray.jitter * cloudBaseStep(ray, iv[k].x), 1.0, 0.0,
                               CLOUD_NO_DEPTH_LIMIT);
    CloudStep st;
    while (m.transmittance > params.transmittanceCutoff && cloudSeek(ray, iv[k].y, seek, m, st)) {
      vec3 scattering = cloudLightSample(ray, st, seek.tauView, m);
      cloudAccumulate(st, scattering, m);
      tauTotal += params.extinction * st.s.density * st.dt;
      seek.tauView += params.extinction * st.s.density * st.dt;
      seek.t += st.dt;
    }
  }
  m.radiance += cloudPhaseSkyLight(ray.ambient.phaseExcess, tauTotal, m.transmittance);
  cloudTakeOpaqueRest(m);
  return m;
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
  // Where the pixel's centre ray first reaches the shells, -1 if it never does (the ground
  // comes first): the temporal pass's upsampling compares rays by it (cloud_temporal.comp).
  vec2 centreIv[2];
  CloudRay centre = cloudViewRay(vec2(id) + 0.5, id, params.frameIndex, 0.0, params.view.forward.w);
  bool meets = cloudRayIntervals(centre, centreIv) > 0;
  float shellEntry = meets ? centreIv[0].x : -1.0;
  // How wide the pixel is where its ray finds its clouds (for a camera inside the layers,
  // a quarter of the way through them), against the clouds' outline cell.
  float cloudsAt = meets ? max(centreIv[0].x, 0.25 * centreIv[0].y) : 0.0;
  float width = cloudsAt * params.view.forward.w * 4.0 * params.shapeRepeatsPerM;
  bool grazing = centre.direction.z >= 0.0 && centre.direction.z < CLOUD_BAND_SINE;
  int band = CLOUD_TOPDOWN != 0 || !grazing || width < CLOUD_BAND_FROM || width > CLOUD_BAND_TO ? 1
             : width < 1.5 * CLOUD_BAND_FROM ? CLOUD_BAND_RAYS_NEAR
                                             : CLOUD_BAND_RAYS;
  // The band's own rays, unless the still asked for at least as many marches (clouds.samples).
  bool bandRays = band > int(params.samplesPerPixel);

  // clouds.samples marches per pixel, averaged: the first at the pixel's centre with the
  // frame's jitter (one sample is the plain march), the others at low-discrepancy positions
  // inside the pixel (the R2 sequence, Roberts 2018, rotated per pixel) with their starts
  // stratified over the step, so a still converges and its cloud edges are antialiased.
  // Each resolves its share of the pixel (the footprint of a render sqrt(count) times the
  // size). The band at the horizon takes at least `band`, placed and resolving as above. A
  // top-down pixel marches the CLOUD_TOPDOWN_SUBPIXELS^2 rays of a render that many times the
  // size instead.
  int count = CLOUD_TOPDOWN != 0 ? CLOUD_TOPDOWN_SUBPIXELS * CLOUD_TOPDOWN_SUBPIXELS
                                 : max(int(params.samplesPerPixel), band);
  float spread = params.view.forward.w * (bandRays && band == CLOUD_BAND_RAYS
                                             ? CLOUD_BAND_RESOLVE
                                             : 1.0 / sqrt(float(count)));
  float jitter0 = pixelHash(id, params.frameIndex, 0u) * params.jitter;
  vec2 rotation = vec2(pixelHash(id, params.frameIndex, 0x51u), pixelHash(id, params.frameIndex, 0x52u));
  vec3 radiance = vec3(0.0);
  float alphaSum = 0.0, depthSum = 0.0;
  int samples = 0, lightSamples = 0;
  for (int i = 0; i < count; ++i) {
    CloudRay ray;
    if (CLOUD_TOPDOWN != 0) {
      uvec2 sub = id * uint(CLOUD_TOPDOWN_SUBPIXELS) +
                  uvec2(i % CLOUD_TOPDOWN_SUBPIXELS, i / CLOUD_TOPDOWN_SUBPIXELS);
      ray = cloudViewRay((vec2(sub) + 0.5) / float(CLOUD_TOPDOWN_SUBPIXELS), sub,
                         params.frameIndex, pixelHash(sub, params.frameIndex, 0u) * params.jitter,
                         spread);
    } else {
      vec2 inPixel = bandRays ? vec2(fract(rotation.x + float(i) * 0.6180339887),
                                     (float(i) + rotation.y) / float(count))
                     : i == 0 ? vec2(0.5)
                              : fract(rotation + float(i) * vec2(0.7548776662, 0.5698402910));
      float jitter = fract(jitter0 + float(i) / float(count));
      ray = cloudViewRay(vec2(id) + inPixel, id, params.frameIndex + uint(i) * 0x632BE5ABu, jitter,
                         spread);
    }
    // The band's rays resolve the small clouds across the pixel, each at its own place; the
    // light's long step, kilometres toward a low sun through cloud the pixel does not resolve
    // anyway, they share: each reads it in parts `count` times as long, at its own offset, so
    // the pixel reads it as often as one ray did, stratified over its rays. Each reading all
    // of it took 37-43 % of the band's light samples and 10-13 % of a still; shared, the band
    // is as far off a supersampled render as before (docs/clouds.md, "Away from noon").
    // A still that asked for as many marches (clouds.samples) keeps each one's whole long
    // step: it averages them to converge.
    if (bandRays) ray.longShare = count;
#if VOLUMETRIC_CLOUDS_HOST_DEPTH
    float host = hostDistance(hostDepthParams, texelFetch(hostDepth, ivec2(id), 0).r,
                              ray.direction, params.view.forward.xyz);
    if (host > 0.0) ray.maxT = host;
#endif
    CloudMarch m = cloudMarchRay(ray);
    radiance += m.radiance;
    alphaSum += 1.0 - m.transmittance;
    depthSum += m.depthSum;
    samples += m.samples;
    lightSamples += m.lightSamples;
  }
  float alpha = alphaSum / float(count);
  imageStore(cloudImage, ip, vec4(radiance / float(count), alpha));
  imageStore(depthImage, ip, vec4(alphaSum > 0.0 ? depthSum / alphaSum : 0.0, shellEntry, 0.0, 0.0));
  imageStore(stepImage, ip, vec4(float(samples), float(lightSamples), 0.0, 0.0));
}
