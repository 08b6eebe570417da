// The shared lighting model on the GPU side: LightingState (lighting_shared.h), the phase
// functions, and the Kozlov clear sky lit by the sun and the moon. A pass that reads the
// state defines LIGHTING_BINDING before including this file.
#ifndef SKY_LIGHTING_GLSL
#define SKY_LIGHTING_GLSL
#include "lighting_shared.h"
#include "kozlov_sky.glsl"

#ifdef LIGHTING_BINDING
layout(std140, binding = LIGHTING_BINDING) uniform LightingBlock {
  LightingState lighting;
};
#endif

const float kPi = 3.14159265358979;

// Rayleigh phase function 3/4 (1 + cos^2), normalised to 4 pi (also Kozlov 3.3's p(w)).
float rayleighPhase(float cosTheta) {
  return 3.0 / (16.0 * kPi) * (1.0 + cosTheta * cosTheta);
}

// Henyey-Greenstein phase function (Tang (3)), normalised to 4 pi.
float henyeyGreenstein(float cosTheta, float g) {
  float d = 1.0 + g * g - 2.0 * g * cosTheta;
  return (1.0 - g * g) / (4.0 * kPi * d * sqrt(d));
}

// Two HG lobes, forward and backward, blended by `w` (weight of the forward lobe).
float dualHenyeyGreenstein(float cosTheta, float gForward, float gBackward, float w) {
  return mix(henyeyGreenstein(cosTheta, gBackward), henyeyGreenstein(cosTheta, gForward), w);
}

// The clear sky in direction V: the daylit Kozlov sky around the sun plus the moonlit copy
// around the moon (LightingState.moonPalette is already dimmed to moonlight).
vec3 clearSky(LightingState L, vec3 V) {
  Palette d = L.palette;
  Palette m = L.moonPalette;
  return kozlovClearSky(V, L.sun.direction.xyz, d.sky.rgb, d.fog.rgb, d.glow.rgb, d.sky.w, d.fog.w) +
         kozlovClearSky(V, L.moon.direction.xyz, m.sky.rgb, m.fog.rgb, m.glow.rgb, m.sky.w, m.fog.w);
}

#endif
