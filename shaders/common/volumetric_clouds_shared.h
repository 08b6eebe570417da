// Parameters and bindings of passes/volumetric_clouds (shaders/volumetric_clouds.comp): the
// low and mid cloud layers raymarched through the weather map and the baked noise.
#ifndef SKY_VOLUMETRIC_CLOUDS_SHARED_H
#define SKY_VOLUMETRIC_CLOUDS_SHARED_H
#include "shared_prelude.h"
#include "geo_shared.h"
#include "view_shared.h"
#include "cloud_light_volume_shared.h"
#include "host_depth_shared.h"

#define VOLUMETRIC_CLOUDS_GROUP_X 8
#define VOLUMETRIC_CLOUDS_GROUP_Y 8
#define VOLUMETRIC_CLOUDS_BINDING_PARAMS 0
#define VOLUMETRIC_CLOUDS_BINDING_LIGHTING 1
#define VOLUMETRIC_CLOUDS_BINDING_CLOUDS 2  // out: rgb premultiplied radiance, a opacity
#define VOLUMETRIC_CLOUDS_BINDING_DEPTH 3   // out: r transmittance-weighted distance (m),
                                            // g where the ray reaches the shells (-1: never)
#define VOLUMETRIC_CLOUDS_BINDING_STEPS 4   // out: r density samples taken, g light samples
#define VOLUMETRIC_CLOUDS_BINDING_SHAPE 5
#define VOLUMETRIC_CLOUDS_BINDING_DETAIL 6
#define VOLUMETRIC_CLOUDS_BINDING_CURL 7
#define VOLUMETRIC_CLOUDS_BINDING_WEATHER 8
#define VOLUMETRIC_CLOUDS_BINDING_WEATHER_COARSE 9
// 10: the light volume (cloud_light_volume_shared.h).
#define VOLUMETRIC_CLOUDS_BINDING_AMBIENT 11  // the CloudAmbient buffer (cloud_ambient_shared.h)
#define VOLUMETRIC_CLOUDS_BINDING_HOST_DEPTH 12  // VOLUMETRIC_CLOUDS_HOST_DEPTH: a host's depth
#define VOLUMETRIC_CLOUDS_BINDING_HOST_DEPTH_PARAMS 13  // and how it maps to distance

// Density slice (the debug output "cloud_density_slice"): same params, its own image.
#define CLOUD_SLICE_BINDING_IMAGE 2

// Calibrated coverage: thresholds for cover i / (CLOUD_COVERAGE_LUT_SIZE - 1), for each layer
// (low, mid) and each type key (0 stratiform, 0.5 cellular, 1 convective).
#define CLOUD_COVERAGE_LUT_SIZE 64
#define CLOUD_COVERAGE_TYPE_KEYS 3
#define CLOUD_COVERAGE_LUT_VEC4S (2 * CLOUD_COVERAGE_TYPE_KEYS * CLOUD_COVERAGE_LUT_SIZE / 4)
// With calibrated coverage, the far field's mean density and share in cloud
// (engine/clouds/coverage_calibration.h farMeanDensity), a pair (2 floats) for cover
// i / (CLOUD_FAR_MEAN_COVERS - 1) at height fraction (j + 0.5) / CLOUD_FAR_MEAN_HEIGHTS, for
// each layer and type key: [layer][type][cover][height].
#define CLOUD_FAR_MEAN_COVERS 16
#define CLOUD_FAR_MEAN_HEIGHTS 8
#define CLOUD_FAR_MEAN_VEC4S \
  (2 * CLOUD_COVERAGE_TYPE_KEYS * CLOUD_FAR_MEAN_COVERS * CLOUD_FAR_MEAN_HEIGHTS * 2 / 4)

// The far field (cloudSampleAtLla in cloud_field.glsl, where a sample resolves none of the
// clouds' outline): with the paper's coverage, the mean density per unit of cover and height
// profile, about the share of a cloud's core density its volume averages to (docs/clouds.md,
// the horizon; calibrated coverage reads the measured farMeanLut instead), and the
// chord through a cloud, as a share of the outline's cell, whose optical depth sets the far
// field's clumping.
#define CLOUD_FAR_DENSITY 0.5
#ifndef CLOUD_FAR_CHORD
#define CLOUD_FAR_CHORD 0.1
#endif
// With calibrated coverage, the far field's clouds are as long, along a path, as this share
// of the outline's cell (875 m with the default 5 km shape repeat) in the Markov mixture
// (cloudFarExtinction). Measured, not assumed: the resolved clouds' light along paths at 1-12
// degrees through broken cumulus and a stratocumulus deck
// (CloudFieldCpu.TheFarFieldLetsALowSunThroughAsTheResolvedCloudsDo) is matched within 0.06
// by 0.7; 0.1 let through 0.07 against 0.25 at 1 degree, 1.0 let through 0.37.
#define CLOUD_FAR_MARKOV_CHORD 0.7
// The same for cumulus (cloudCumulusWeight 1; cloudFarChord mixes by the weight): their sizes
// spread over a decade (cumulusOutline), most of them far smaller than the cell. Measured the
// same way: at 1 degree from cloud 0.248 against the resolved 0.261, every path within 0.025;
// 0.7 let through 0.342.
#define CLOUD_FAR_MARKOV_CHORD_CUMULUS 0.45

// Cumulus sizes (cumulusOutline, cloud_density.glsl): the shape noise is also read at a half and
// a quarter of its frequency, so those lookups repeat every this many shape repeats.
#define CLOUD_CUMULUS_REPEAT_SHAPES 4

SKY_SHARED_BEGIN

// A light's illuminance (rgb, renderer units; w unused) through the air at a layer's base,
// middle and top altitude. A low sun's path to the base crosses more air than to the top: at
// 3 degrees the low layer's base (750 m) gets 30 % less sunlight than its middle, and redder
// light. The raymarch interpolates log E quadratically between the three (cloudLayerLight).
struct CloudLayerLight {
  vec4 base;
  vec4 middle;
  vec4 top;
};

// std140: scalars pack four to a 16-byte row, so they come in groups of four; a vec4 starts a
// row. Directions and colours are vec4s whose w is unused (a bare vec3 differs in C++).
struct CloudParams {
  ViewState view;
  GeoFrame geo;         // the camera's frame (top-down: the region's centre, above the clouds)
  GeoRegion region;     // the weather map's bounds

  uint frameIndex;           // the frame's jitter seed, so successive frames differ
  float jitter;              // start offset along the view ray, 0..1 of a step
  float transmittanceCutoff; // a ray stops below this transmittance
  float anyCover;            // 1 if the map has cover in either layer, else 0

  float lowBaseM, lowTopM, midBaseM, midTopM;  // the layers (m above sea level)

  float shellBaseM;     // the march runs between these altitudes (the layers with cover)
  float shellTopM;
  float topDownStartM;  // top-down rays start at this altitude
  float stepM;          // view-ray step at the camera (m)

  float stepGrowth;        // extra step length per metre of distance
  float lightDistanceM;    // length of the short light steps together (m)
  float attenuationClamp;  // Lu (22)'s ac
  float extinction;        // 1/m at density 1

  float g;           // Henyey-Greenstein asymmetry (the forward lobe)
  float gBack;       // the back lobe's asymmetry
  float backWeight;  // the back lobe's share
  float edgeSharpness;  // density gain at the cloud's boundary (cloudEdgeDensity)

  float shapeRepeatsPerM;   // shape noise repeats per metre
  float detailRepeatsPerM;  // detail noise repeats per metre
  float curlRepeatsPerM;    // curl noise repeats per metre
  float curlStrength;       // how far the curl bends the detail lookup (detail repeats)

  float sunMarched;   // 1 when the sun is marched toward (it gives a visible share), else 0
  float moonMarched;  // the same for the moon
  float sliceLengthM; // density slice: how far ahead it reaches (m)
  float sliceTopM;    // density slice: its top altitude (m)

  // Stratocumulus rolls (cloudRollWeight): the shape noise is looked up with a point's
  // coordinate along rollAxis shortened by this share, 1 - 1 / (how much longer than wide).
  float rollCompression;
  float multipleScattering;  // strength of the diffusion term (cloudDiffuseInScatter), 0: off
  uint maxSteps;             // density samples per view ray
  uint octaves;              // multiple-scattering octaves (Wrenninge)

  // The light march (cloud_light_march.glsl): short steps toward each light, samples per short
  // step, how many of the first short steps may resolve the detail noise (the others and the
  // long step do not read it: a light sample's footprint is at least a quarter of its step,
  // and noiseKeep resolves nothing from half a cell), and the longest part of the long step.
  uint lightSteps;
  uint lightSplit;
  uint lightNearSteps;
  float lightLongPartM;

  // Which pixels this dispatch marches (temporal reuse, passes/cloud_temporal): invocation
  // (x, y) marches pixel (x, y) * marchBlock + marchOffset of the view, and the pass's images
  // are the view's size divided by marchBlock (rounded up). 1 and (0, 0): every pixel.
  uint marchBlock;
  uint marchOffsetX;
  uint marchOffsetY;
  // Marches per pixel, averaged (clouds.samples): 1 is the plain march; more converge a still.
  uint samplesPerPixel;

  // The camera in each noise texture's Earth-fixed frame (ECEF axes, m, wind drift taken
  // off), reduced by whole repeats of that texture so floats keep their precision.
  vec4 shapeOrigin;   // xyz: for the shape noise (repeat 1 / shapeRepeatsPerM)
  vec4 detailOrigin;  // xyz: for the detail noise (repeat 1 / detailRepeatsPerM)
  vec4 curlOrigin;    // xy: east and north on the ground plane at the camera (curl noise)
  vec4 rollOrigin;    // xyz: shapeOrigin in the rolls' frame (shortened along rollAxis), reduced
                      // by whole repeats likewise
  vec4 rollAxis;      // xyz: unit ECEF direction the stratocumulus rolls run along (the wind's)
  vec4 cumulusOrigin;  // xyz: for the cumulus sizes' slower lookups (repeat
                      // CLOUD_CUMULUS_REPEAT_SHAPES / shapeRepeatsPerM), reduced likewise
  vec4 sunDirection;  // xyz: unit direction to the sun (ENU)
  vec4 moonDirection; // xyz: to the moon
  CloudLayerLight sunAtLow;   // the sun's illuminance through the air in the low layer
  CloudLayerLight sunAtMid;   // in the mid layer
  CloudLayerLight moonAtLow;  // the moon's, likewise
  CloudLayerLight moonAtMid;
  // The mean of each noise channel over its texture: what octaves finer than a pixel's
  // footprint average to, so distant clouds fade to it instead of aliasing (cloudSampleAt).
  vec4 shapeMean;     // rgba: of the shape texture
  vec4 detailMean;    // rgb: of the detail texture
  // Where the cloud light volume lies (clouds.light volume; passes/cloud_light_volume).
  CloudLightVolume lightVolume;
  vec4 coverageLut[CLOUD_COVERAGE_LUT_VEC4S];
  vec4 farMeanLut[CLOUD_FAR_MEAN_VEC4S];
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::CloudParams) ==
                  64 + 64 + 16 + 10 * 16 + 22 * 16 + 32 + CLOUD_COVERAGE_LUT_VEC4S * 16 +
                      CLOUD_FAR_MEAN_VEC4S * 16,
              "std140 layout of CloudParams");
#endif
#endif
