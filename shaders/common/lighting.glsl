// The shared lighting model on the GPU side: LightingState (lighting_shared.h) and the
// Kozlov clear sky lit by the sun and the moon. A pass that reads the state defines
// LIGHTING_BINDING before including this file. (The cloud passes add the phase functions and
// the ambient terms here, with their kernel tests.)
#ifndef SKY_LIGHTING_GLSL
#define SKY_LIGHTING_GLSL
#include "params_block.glsl"
#include "lighting_shared.h"
#include "kozlov_sky.glsl"

#ifdef LIGHTING_BINDING
layout(std140, binding = LIGHTING_BINDING) uniform LightingBlock {
  LightingState lightingBlock[1];
};
#define lighting lightingBlock[SKY_PARAMS_INDEX]
#endif

// LIGHTING_MOON 0 leaves the moon's light out: a pass compiles that variant for frames with
// the sun above the horizon (moonLightNegligible in engine/lighting/lighting_state.h), where
// moonlight is a few millionths of the sunlit sky and changes no pixel.
#ifndef LIGHTING_MOON
#define LIGHTING_MOON 1
#endif

// The clear sky in direction V: the daylit Kozlov sky around the sun plus the moonlit copy
// around the moon (LightingState.moonPalette is already dimmed to moonlight).
vec3 clearSky(LightingState L, vec3 V) {
  Palette d = L.palette;
  Palette m = L.moonPalette;
  vec3 sky = kozlovClearSky(V, L.sun.direction.xyz, d.sky.rgb, d.fog.rgb, d.glow.rgb, d.sky.w,
                            d.glow.w, d.fog.w);
#if LIGHTING_MOON
  sky += kozlovClearSky(V, L.moon.direction.xyz, m.sky.rgb, m.fog.rgb, m.glow.rgb, m.sky.w,
                        m.glow.w, m.fog.w);
#endif
  return sky;
}

#endif
