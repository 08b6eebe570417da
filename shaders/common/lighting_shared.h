// LightingState: the one description of the lights that every pass reads (DESIGN "One
// lighting API"). Computed once per frame on the CPU by engine/lighting/lighting_state.h.
// Units: radiance 1 = 10^4 cd/m^2; illuminance 1 = pi * 10^4 lux, so a white Lambertian
// surface under illuminance E has radiance E. Every value is physical: the night lift is an
// exposure the display path applies (output.exposure); see docs/lighting.md.
#ifndef SKY_LIGHTING_SHARED_H
#define SKY_LIGHTING_SHARED_H
#include "shared_prelude.h"

SKY_SHARED_BEGIN

struct DirectionalLight {
  vec4 direction;    // xyz: unit direction to the body (east-north-up); w: angular radius (rad)
  vec4 illuminance;  // rgb: illuminance at the ground, normal incidence, after the atmosphere
                     // and the horizon; w: fraction of the disc above the horizon
};

// The Kozlov colours at one elevation (engine/scene PaletteKey), scene-linear.
struct Palette {
  vec4 sky;            // rgb: Csky; w: glow size s
  vec4 fog;            // rgb: Cfog; w: haze top hmax (fraction of the dome height)
  vec4 glow;           // rgb: Csun (glow around the light); w: glow exponent n
  vec4 cloudLit;       // rgb: C1 (Kozlov 3.3)
  vec4 cloudDark;      // rgb: C2
  vec4 ambientTop;     // rgb
  vec4 ambientBottom;  // rgb
};

struct LightingState {
  DirectionalLight sun;   // the key light by day
  DirectionalLight moon;  // the key light by night; a weak second term by day
  Palette palette;        // at the sun's apparent elevation
  Palette moonPalette;    // at the moon's elevation, scaled to moonlight (the moonlit sky)
  vec4 sunDisc;           // rgb: disc radiance (scene-linear) at the disc centre
  vec4 moonLimb;          // xyz: unit tangent toward the moon's bright limb (east-north-up);
                          // w: phase angle (rad), 0 = full
  vec4 moonDisc;          // rgb: disc radiance per unit of Lommel-Seeliger shading (sunlit
                          // part); w: illuminated fraction
  vec4 moonEarthshine;    // rgb: radiance of the earthlit dark part; w: mean shading over
                          // the disc (so rgb * w + earthshine is the disc's mean radiance)
  vec4 night;             // x: day factor (1 day .. 0 night); y: unused (the night lift is
                          // the display's exposure, LightingState::nightLiftEv);
                          // z: star irradiance per V=0 star above the atmosphere (the star
                          // pass applies the extinction); w: unused
  vec4 equatorialToEnu[3];  // columns of the J2000 equatorial -> east-north-up rotation
  vec4 sunSpace;            // rgb: sun illuminance above the atmosphere (for models that apply
                            // their own transmittance, e.g. the physical sky); w: unused
  vec4 moonSpace;           // rgb: the same for the moon; w: unused
};

SKY_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(sky::shared::DirectionalLight) == 32, "std140 layout of DirectionalLight");
static_assert(sizeof(sky::shared::Palette) == 7 * 16, "std140 layout of Palette");
static_assert(sizeof(sky::shared::LightingState) == 2 * 32 + 2 * 7 * 16 + 5 * 16 + 3 * 16 + 2 * 16,
              "std140 layout of LightingState");
#endif
#endif
