// The volumetric clouds' ambient light, gathered from the frame's own sky (passes/cloud_ambient,
// shaders/cloud_ambient.comp) and read by the raymarch (volumetric_clouds.comp): the sky's light
// on a surface of any orientation, and the ground below. docs/clouds.md, "Lighting".
#ifndef SKY_CLOUD_AMBIENT_SHARED_H
#define SKY_CLOUD_AMBIENT_SHARED_H
#include "shared_prelude.h"

// One workgroup; each invocation evaluates the sky in CLOUD_AMBIENT_DIRECTIONS_PER_INVOCATION
// directions of a stratified grid over the upper hemisphere (32 rings equal in solid angle x
// 32 azimuths: the Kozlov glow around a low sun, a few degrees wide, spans several of them).
#define CLOUD_AMBIENT_GROUP 256
#define CLOUD_AMBIENT_RINGS 32
#define CLOUD_AMBIENT_AZIMUTHS 32
#define CLOUD_AMBIENT_DIRECTIONS_PER_INVOCATION \
  (CLOUD_AMBIENT_RINGS * CLOUD_AMBIENT_AZIMUTHS / CLOUD_AMBIENT_GROUP)

#define CLOUD_AMBIENT_BINDING_PARAMS 0
#define CLOUD_AMBIENT_BINDING_LIGHTING 1
#define CLOUD_AMBIENT_BINDING_OUT 2  // the CloudAmbient image
#define CLOUD_AMBIENT_BINDING_ATMOSPHERE 3
#define CLOUD_AMBIENT_BINDING_TRANSMITTANCE 4
#define CLOUD_AMBIENT_BINDING_SKY_VIEW_SUN 5
#define CLOUD_AMBIENT_BINDING_SKY_VIEW_MOON 6

SKY_SHARED_BEGIN

struct CloudAmbientParams {
  vec4 groundAlbedo;  // rgb: ground.albedo (linear reflectance)
  // rgb: the optical depth of the air straight down from the clouds' base to the ground;
  // along a slant path below the horizon it is this over the sine of the depression, and the
  // ground takes on the horizon sky's colour by 1 - its transmittance.
  vec4 airDepth;
  float groundLight;  // the share of the ground's clear-sky light that comes through the
                      // cloud cover around the camera (light::overcastGlobalShare)
  // The clouds' phase function (clouds.g, clouds.phase), for the table of the sky scattered
  // once toward each direction: dualLobeHG(g, gBack, backWeight); Henyey-Greenstein with g
  // where backWeight is 0.
  float phaseG;
  float phaseGBack;
  float phaseBackWeight;
  // How much of the sky other clouds hide from a cloud (cloud_ambient.comp, skyHidden): a
  // direction at elevation e keeps its own radiance by exp(-skyOcclusion / sin e), and takes
  // the sky's mean for the rest. CLOUD_AMBIENT_OCCLUSION_PER_COVER times the cover around the
  // camera.
  float skyOcclusion;
  float pad0, pad1, pad2;
};

SKY_SHARED_END

// The light around the clouds as the mean radiance a surface of unit normal n (east, north, up)
// receives: its irradiance over pi, in renderer units its illuminance. An image of
// CLOUD_AMBIENT_MAP_WIDTH x CLOUD_AMBIENT_IMAGE_HEIGHT RGBA32F texels (the debug image
// "cloud_ambient"): row j < CLOUD_AMBIENT_MAP_HEIGHT, column i holds the light for the normal
// at elevation -90 + 180 j / (HEIGHT - 1) degrees and azimuth 360 i / WIDTH degrees from east
// toward north, the cosine-weighted sum over the sky's sampled radiance above the horizon and
// below it the ground's through the air (brightest toward the horizon, the haze); the next
// row's first texel the ground's own radiance (for the debug image). Spherical harmonics of first order
// rang below zero on the side turned from a low sun's bright aureole, the very side a backlit
// cloud shows the camera; a table of the cosine-weighted sums does not.
// In a field of clouds a cloud does not see the clear sky: near the horizon the sky lies behind
// kilometres of the layer, whose other clouds hide it. What they hide is mostly the sky's
// direction: its bright glow around a low sun, which, seen as the light on the cloud's face
// toward that sun, lit every cloud of a field as if it stood alone. Each upper direction at
// elevation e keeps its radiance by exp(-k / sin e), the chance that a path through the
// layer's share above a cloud, 1 / sin e times as long as the way up, meets no other cloud,
// and takes the sky's mean radiance for the rest (other clouds lit by that sky, scattered
// around in azimuth); k = CLOUD_AMBIENT_OCCLUSION_PER_COVER x the cover around the camera.
// Fitted against Cycles on the path-traced field (docs/cloud-model.md, "A path-traced
// field", "The sky that other clouds hide"): a 40 % cumulus field (cover 0.24 around the
// camera) with a 3 degree sun behind the camera went from 12 % to 0.3 % brighter than Cycles
// (on the cumulus shapes' smaller clouds from 27 % to 15 %, and the near clouds in the shadow
// of others, the darkest tenth, from 1.66 to 1.37 times Cycles' light). Held fixed over the
// frames, k = 0.5 and 1 gave the field the same within a point and the deck (cover 0.56) 14.6 %
// and 16.6 % too bright, k = 2 there 18 %; 4 x the cover, the deck 18.3 % and the field and
// the sunset's lit hue (SunsetLookTest) the same.
// The sky's mean as the rest: each ring's own mean (which keeps zenith and horizon apart)
// left the field 20 % too bright. The ground below the horizon is left as it is: a cloud's
// base sees it past the layer, and hiding it behind the sky's mean lit the deck 32 % too
// bright.
#define CLOUD_AMBIENT_OCCLUSION_PER_COVER 2.0
#define CLOUD_AMBIENT_MAP_WIDTH 16
#define CLOUD_AMBIENT_MAP_HEIGHT 9
#define CLOUD_AMBIENT_GROUND_ROW CLOUD_AMBIENT_MAP_HEIGHT
// Below the ground's row, CLOUD_AMBIENT_MAP_HEIGHT rows more on the same grid, now of view
// directions d: the sky and the ground scattered once toward the eye by a ray along d, less
// what an isotropic phase would scatter, P(d) - Lmean with P(d) = the integral over the sphere
// of L(s) phase(s . d) ds and Lmean the sphere's mean radiance (cloudPhaseSkyLight). Positive
// toward a low sun's aureole, negative away from it.
#define CLOUD_AMBIENT_PHASE_ROW (CLOUD_AMBIENT_GROUND_ROW + 1)
#define CLOUD_AMBIENT_IMAGE_HEIGHT (CLOUD_AMBIENT_PHASE_ROW + CLOUD_AMBIENT_MAP_HEIGHT)

#ifdef __cplusplus
static_assert(sizeof(sky::shared::CloudAmbientParams) == 64, "std140 layout of CloudAmbientParams");
#endif
#endif
