// Parameters and bindings of passes/volumetric_clouds (shaders/volumetric_clouds.comp): the
// low and mid cloud layers raymarched through the weather map and the baked noise.
#ifndef SKY_VOLUMETRIC_CLOUDS_SHARED_H
#define SKY_VOLUMETRIC_CLOUDS_SHARED_H
#include "shared_prelude.h"
#include "geo_shared.h"
#include "view_shared.h"

#define VOLUMETRIC_CLOUDS_GROUP_X 8
#define VOLUMETRIC_CLOUDS_GROUP_Y 8
#define VOLUMETRIC_CLOUDS_BINDING_PARAMS 0
#define VOLUMETRIC_CLOUDS_BINDING_LIGHTING 1
#define VOLUMETRIC_CLOUDS_BINDING_CLOUDS 2  // out: rgb premultiplied radiance, a opacity
#define VOLUMETRIC_CLOUDS_BINDING_DEPTH 3   // out: r transmittance-weighted distance (m)
#define VOLUMETRIC_CLOUDS_BINDING_STEPS 4   // out: r density samples taken, g light samples
#define VOLUMETRIC_CLOUDS_BINDING_SHAPE 5
#define VOLUMETRIC_CLOUDS_BINDING_DETAIL 6
#define VOLUMETRIC_CLOUDS_BINDING_CURL 7
#define VOLUMETRIC_CLOUDS_BINDING_WEATHER 8
#define VOLUMETRIC_CLOUDS_BINDING_WEATHER_COARSE 9

// Density slice (the debug output "cloud_density_slice"): same params, its own image.
#define CLOUD_SLICE_BINDING_IMAGE 2

// CloudParams.frame.x: how rays start.
#define CLOUD_FRAME_OBSERVER 0u  // from the camera along the view's rays
#define CLOUD_FRAME_TOPDOWN 1u   // straight down from above the clouds over each pixel's lat/lon

// Calibrated coverage: thresholds for cover i / (CLOUD_COVERAGE_LUT_SIZE - 1), for each layer
// (low, mid) and each type key (0 stratiform, 0.5 cellular, 1 convective).
#define CLOUD_COVERAGE_LUT_SIZE 64
#define CLOUD_COVERAGE_TYPE_KEYS 3
#define CLOUD_COVERAGE_LUT_VEC4S (2 * CLOUD_COVERAGE_TYPE_KEYS * CLOUD_COVERAGE_LUT_SIZE / 4)

SKY_SHARED_BEGIN

struct CloudParams {
  ViewState view;
  GeoFrame geo;         // the camera's frame (top-down: the region's centre, above the clouds)
  GeoRegion region;     // the weather map's bounds
  // frame.xzw and options pick the shader variant (compile-time constants, cloud_field.glsl);
  // the shader reads only frame.y.
  uvec4 frame;          // x: CLOUD_FRAME_*; y: max view steps; z: light steps; w: octaves
  uvec4 options;        // x: phase (0 hg, 1 dual lobe); y: energy-conserving steps (1) or not;
                        // z: calibrated coverage (1) or paper (0); w: model (0 lu2023, 1 tang2019)
  vec4 layers;          // low base, low top, mid base, mid top (m above sea level)
  vec4 shell;           // x, y: march between these altitudes (the layers with cover);
                        // z: top-down rays start at this altitude; w: 1 if any cover, else 0
  // The camera in each noise texture's Earth-fixed frame (ECEF axes, m, wind drift taken
  // off), reduced by whole repeats of that texture so floats keep their precision.
  vec4 shapeOrigin;     // xyz: for the shape noise (repeat 1 / noiseScale.x)
  vec4 detailOrigin;    // xyz: for the detail noise (repeat 1 / noiseScale.y)
  vec4 curlOrigin;      // xy: east and north on the ground plane at the camera, for the curl
                        // noise (repeat 1 / noiseScale.w)
  vec4 noiseScale;      // x: shape repeats per metre; y: detail repeats per metre;
                        // z: curl strength (tang2019, detail repeats); w: curl repeats per metre
  vec4 march;           // x: step at the camera (m); y: growth per metre; z: transmittance
                        // cutoff; w: jitter (0..1, 1 = a whole step)
  vec4 light;           // x: distance of the short light steps (m); y: attenuation clamp ac;
                        // z: weather texels across (u); w: texels down (v)
  vec4 medium;          // x: extinction (1/m at density 1); y: g; z: g back; w: back weight
  vec4 keyDirection;    // xyz: unit direction to the brighter light at the clouds (ENU);
                        // w: 1 sun, 0 moon (for reports and tests)
  vec4 lightDirection[2];  // [0] sun, [1] moon: xyz unit direction (ENU); w: 1 when marched
  vec4 lightAtLow[2];      // rgb: each light's illuminance at the low layer
  vec4 lightAtMid[2];      // rgb: at the mid layer
  vec4 ambientTop;      // rgb: sky light from above (radiance)
  vec4 ambientBottom;   // rgb: ground light from below (radiance)
  vec4 slice;           // density slice: x: length (m); y: top altitude (m); zw: unused
  vec4 coverageLut[CLOUD_COVERAGE_LUT_VEC4S];
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::CloudParams) ==
                  64 + 64 + 16 + 2 * 16 + 19 * 16 + CLOUD_COVERAGE_LUT_VEC4S * 16,
              "std140 layout of CloudParams");
#endif
#endif
