// Parameters and bindings of passes/atmosphere_composite (shaders/atmosphere_composite.comp).
// The physical variant (ATMOSPHERE_COMPOSITE_PHYSICAL 1) also binds the atmosphere's
// parameters, its transmittance LUT and its aerial-perspective volume.
//
// The pass draws the image in bands of whole rows of workgroups, one dispatch each, with
// the variant the band needs (AtmosphereCompositeBand): lavapipe runs every side of a branch
// for every pixel, so the ground below the horizon and the air in front of the volumetric
// clouds cost all pixels of a dispatch that holds them, whether or not a pixel needs them.
#ifndef SKY_ATMOSPHERE_COMPOSITE_SHARED_H
#define SKY_ATMOSPHERE_COMPOSITE_SHARED_H
#include "shared_prelude.h"
#include "cloud_shadow_shared.h"
#include "host_depth_shared.h"
#include "view_shared.h"

#define ATMOSPHERE_COMPOSITE_GROUP_X 8
#define ATMOSPHERE_COMPOSITE_GROUP_Y 8
#define ATMOSPHERE_COMPOSITE_BINDING_PARAMS 0
#define ATMOSPHERE_COMPOSITE_BINDING_BEAUTY 1
#define ATMOSPHERE_COMPOSITE_BINDING_SKY 2  // read: from passes/sky_high_clouds
#define ATMOSPHERE_COMPOSITE_BINDING_LIGHTING 3
#define ATMOSPHERE_COMPOSITE_BINDING_STARS 4
#define ATMOSPHERE_COMPOSITE_BINDING_HIGH_CLOUDS 5  // read: from passes/sky_high_clouds
#define ATMOSPHERE_COMPOSITE_BINDING_CLOUDS 6       // read: from passes/volumetric_clouds
#define ATMOSPHERE_COMPOSITE_BINDING_CLOUD_DEPTH 7  // read: from passes/volumetric_clouds
#define ATMOSPHERE_COMPOSITE_BINDING_CLOUD_SHADOW 8 // sampled: from passes/cloud_shadow
// sky.model physical only:
#define ATMOSPHERE_COMPOSITE_BINDING_ATMOSPHERE 9
#define ATMOSPHERE_COMPOSITE_BINDING_TRANSMITTANCE 10
#define ATMOSPHERE_COMPOSITE_BINDING_AERIAL_PERSPECTIVE 11
// Drawing into a host's images (ATMOSPHERE_COMPOSITE_HOST 1, skylayers::Sky::record):
#define ATMOSPHERE_COMPOSITE_BINDING_HOST_COLOUR 12  // read and written: the host's colour
#define ATMOSPHERE_COMPOSITE_BINDING_HOST_DEPTH 13   // sampled: the host's depth (optional)
// The perception layers (ATMOSPHERE_COMPOSITE_PERCEPTION 1, docs/outputs.md):
#define ATMOSPHERE_COMPOSITE_BINDING_CLOUD_HIT 14   // read: from passes/cloud_perception
#define ATMOSPHERE_COMPOSITE_BINDING_PERCEPTION 15  // out: r label, g cloud type, b the air's
                                                    // transmittance, a the ground's cloud shadow

// Kasten & Czeplak (1980): under full overcast the ground receives a quarter of the clear
// sky's global irradiance (light::overcastGlobalShare(1)), all of it diffuse light the clouds
// pass on: the ground's diffuse light under its cover share.
#define CLOUD_DIFFUSE_TRANSMISSION 0.25

SKY_SHARED_BEGIN

struct AtmosphereCompositeParams {
  ViewState view;
  CloudShadowMap shadow;  // valid 0: no shadow map is bound, the ground is unshadowed

  uint clouds;          // 1 when the volumetric clouds are bound
  uint aboveHighClouds; // 1 when the camera is above the high-cloud layer (they then lie in
                        // front of the volumetric clouds)
  uint observer;        // 1: the lit ground below the horizon and the aerial perspective;
                        // 0: neither (a top-down render, whose rays the cloud pass places)
  float highCloudsAltitudeM;  // the high-cloud layer's altitude (m above sea level): where
                              // the perception layers' air ends for a high-cloud pixel

  float planetRadiusM;  // the sphere the ground lies on (the sky model's planet)
  float cameraRadiusM;  // the camera's distance from its centre
  float overcast;       // the local weather's overcast share 0..1 (LightingState overcast)
  float airLight;       // scales the light the air scatters toward the camera: below the
                        // clouds an overcast shades the air too (1 above them or in the clear)

  vec4 groundAlbedo;  // rgb: ground.albedo; w: unused
  vec4 sunAtGround;   // rgb: the sun's illuminance at the ground, normal incidence (kozlov; the
                      // physical variant takes it from its transmittance LUT); w: unused
  vec4 moonAtGround;  // rgb: the moon's
  // The haze of sky.model kozlov (light::hazeMedium): extinction at sea level (1/m) and the
  // scale height (m) of the air molecules and of the aerosols.
  vec4 hazeRayleigh;  // rgb: 1/m; w: scale height (m)
  vec4 hazeAerosol;   // rgb: 1/m; w: scale height (m)
  HostDepth host;     // ATMOSPHERE_COMPOSITE_HOST only
};

// Push constants: the band of rows one dispatch draws.
struct AtmosphereCompositeBand {
  uvec4 rows;  // x: the band's first row; y: its row count; zw: unused
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::AtmosphereCompositeBand) == 16,
              "layout of AtmosphereCompositeBand");
static_assert(sizeof(sky::shared::AtmosphereCompositeParams) == 64 + 48 + 2 * 16 + 5 * 16 + 16,
              "std140 layout of AtmosphereCompositeParams");
#endif
#endif
