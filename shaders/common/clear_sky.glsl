// The frame's clear sky in direction V, without discs, stars or clouds, for either sky model:
// Kozlov 3.1 from the palette (clearSky, lighting.glsl), or with SKY_PHYSICAL_SKY Hillaire
// 2020's sky-view LUTs, which already carry each light's illuminance. Shared by the pass that
// draws the sky (sky_high_clouds.comp) and the one that gathers the clouds' ambient light from
// it (cloud_ambient.comp), so the clouds are lit by the sky the viewer sees. The includer
// includes lighting.glsl and, with SKY_PHYSICAL_SKY, atmosphere.glsl, and declares
// `atmosphere`, `skyViewSunLut` and (with LIGHTING_MOON) `skyViewMoonLut`.
#ifndef SKY_CLEAR_SKY_GLSL
#define SKY_CLEAR_SKY_GLSL
#include "lighting.glsl"

vec3 frameSkyRadiance(LightingState L, vec3 V) {
#if SKY_PHYSICAL_SKY
  vec3 sky = skyViewRadiance(atmosphere, skyViewSunLut, V, L.sun.direction.xyz);
#if LIGHTING_MOON
  sky += skyViewRadiance(atmosphere, skyViewMoonLut, V, L.moon.direction.xyz);
#endif
  return sky;
#else
  return clearSky(L, V);  // Kozlov 3.1 around the sun and the moon
#endif
}

#endif
