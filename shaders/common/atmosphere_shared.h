// The physically based atmosphere (Hillaire 2020): the parameters every atmosphere shader
// reads, the LUT sizes and the binding numbers of passes/atmosphere_luts. See docs/atmosphere.md.
// Units on the GPU: lengths in km (positions from the planet centre), coefficients in 1/km,
// directions in the camera's east-north-up frame (z up); illuminance and radiance in the
// renderer's units (docs/lighting.md).
#ifndef SKY_ATMOSPHERE_SHARED_H
#define SKY_ATMOSPHERE_SHARED_H
#include "shared_prelude.h"
#include "view_shared.h"

// LUT sizes (Hillaire 2020, section 4).
#define ATMOSPHERE_TRANSMITTANCE_WIDTH 256
#define ATMOSPHERE_TRANSMITTANCE_HEIGHT 64
#define ATMOSPHERE_MULTISCATTERING_SIZE 32
// The multiple-scattering LUT holds, per texel of altitude and light elevation, 18 values per
// unit illuminance (1/sr), each rgb: Psi_ms, the isotropic part of orders 2 and up (Hillaire
// (10), (11)); and the second order's dependence on the direction V it is scattered into, in
// the frame of the point (u up, l the horizontal toward the light): the once-scattered
// light's dipole d_u, d_l (for the aerosols' phase function) and traceless quadrupole q_uu,
// q_ll, q_ul (for both), so that the light scattered toward the eye is sigma_s Psi +
// sigma_M p1 d.V + (sigma_R p2_R + sigma_M p2_M) V^T q V (docs/atmosphere.md). In that order
// they fill ATMOSPHERE_MS_TEXELS RGBA texels side by side: the LUT is that many blocks of
// SIZE x SIZE texels wide (five 2D samples cost lavapipe less than six of a 3D texture).
#define ATMOSPHERE_MS_TEXELS 5
#define ATMOSPHERE_SKY_VIEW_WIDTH 192
#define ATMOSPHERE_SKY_VIEW_HEIGHT 108
#define ATMOSPHERE_AP_SIZE 32    // froxels across and down the screen
#define ATMOSPHERE_AP_SLICES 32  // depth slices
#define ATMOSPHERE_AP_DEPTH_KM 32.0  // distance of the far end of the froxel volume

// Integration: steps along each ray, and the sphere of directions of the multiple-scattering
// LUT (one invocation per direction: cos(zenith) bands x azimuths over half a circle, the
// other half being the mirror image about the plane that holds the light).
#define ATMOSPHERE_TRANSMITTANCE_STEPS 64
#define ATMOSPHERE_MS_STEPS 20
#define ATMOSPHERE_MS_ZENITH_BANDS 16
#define ATMOSPHERE_MS_AZIMUTHS 8
#define ATMOSPHERE_SKY_VIEW_STEPS 30
#define ATMOSPHERE_AP_STEPS_PER_SLICE 2

#define ATMOSPHERE_GROUP_X 8
#define ATMOSPHERE_GROUP_Y 8

// Bindings. Every pass takes AtmosphereParams at binding 0.
#define ATMOSPHERE_BINDING_PARAMS 0
#define ATMOSPHERE_TRANSMITTANCE_BINDING_OUT 1
#define ATMOSPHERE_MULTISCATTERING_BINDING_TRANSMITTANCE 1
#define ATMOSPHERE_MULTISCATTERING_BINDING_OUT 2
#define ATMOSPHERE_SKY_VIEW_BINDING_TRANSMITTANCE 1
#define ATMOSPHERE_SKY_VIEW_BINDING_MULTISCATTERING 2
#define ATMOSPHERE_SKY_VIEW_BINDING_OUT 3
#define ATMOSPHERE_AP_BINDING_TRANSMITTANCE 1
#define ATMOSPHERE_AP_BINDING_MULTISCATTERING 2
#define ATMOSPHERE_AP_BINDING_OUT 3
#define ATMOSPHERE_SKY_PROBE_BINDING_SUN 1
#define ATMOSPHERE_SKY_PROBE_BINDING_MOON 2
#define ATMOSPHERE_SKY_PROBE_BINDING_OUT 3

SKY_SHARED_BEGIN

struct AtmosphereParams {
  vec4 radii;               // x: ground radius, y: top radius, z: camera radius (clamped into
                            // the atmosphere), w: camera altitude (the same, as ground offset)
  vec4 rayleighScattering;  // rgb: at the ground, 1/km (= extinction); w: scale height, km
  vec4 mieScattering;       // rgb: at the ground, 1/km; w: scale height, km
  vec4 mieExtinction;       // rgb: at the ground, 1/km; w: Cornette-Shanks anisotropy g
  vec4 ozoneAbsorption;     // rgb: at the tent's peak, 1/km; w: unused
  vec4 ozoneProfile;        // x: tent centre altitude, km; y: tent half width, km
  vec4 groundAlbedo;        // rgb: Lambertian albedo; w: unused
  vec4 sunDirection;        // xyz: unit, east-north-up; w: unused
  vec4 sunIlluminance;      // rgb: above the atmosphere, renderer units; w: unused
  vec4 moonDirection;       // xyz: unit, east-north-up; w: unused
  vec4 moonIlluminance;     // rgb: above the atmosphere, renderer units; w: unused
  vec4 aerialPerspective;   // x: depth of the froxel volume's far end, km; y: slice count
  ViewState view;           // the camera whose screen the aerial-perspective froxels cover
};

// Push constants of atmosphere_sky_view.comp: which light's LUT a dispatch makes. The sun's
// and the moon's are separate passes, so a frame remakes only the one whose light moved and
// culls the moon's when nothing reads it (daylight: LIGHTING_MOON 0 everywhere).
#define ATMOSPHERE_SKY_VIEW_LIGHT_SUN 0u
#define ATMOSPHERE_SKY_VIEW_LIGHT_MOON 1u
struct AtmosphereSkyViewLight {
  uvec4 light;  // x: ATMOSPHERE_SKY_VIEW_LIGHT_SUN or _MOON; yzw: unused
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::AtmosphereParams) == 12 * 16 + 64,
              "std140 layout of AtmosphereParams");
static_assert(sizeof(sky::shared::AtmosphereSkyViewLight) == 16,
              "layout of AtmosphereSkyViewLight");
#endif
#endif
