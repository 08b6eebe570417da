// Kozlov et al. 3.1: the clear-sky colour of a dome point seen in direction V.
#ifndef SKY_KOZLOV_SKY_GLSL
#define SKY_KOZLOV_SKY_GLSL

// How much of the sky colour is not haze at dome height z (0 at the horizon, 1 at hmax and
// above). Kozlov 3.1 ramps h = min(z / hmax, 1) linearly; its kink at hmax showed as a dark
// saturated arc above a pale band (a Mach band), so the ramp eases out: h = 1 - (1 - t)^2
// with t = min(z / hmax, 1), the same hmax and no kink (docs/lighting.md).
float kozlovHaze(float z, float hazeTop) {
  float t = min(max(z, 0.0) / hazeTop, 1.0);
  return 1.0 - (1.0 - t) * (1.0 - t);
}

// V: view direction (unit, z up). S: light direction (unit). glowSize: s. glowExponent: n.
// hazeTop: hmax as a fraction of the dome height. Below the horizon the dome height is 0, so
// it shows Cfog.
vec3 kozlovClearSky(vec3 V, vec3 S, vec3 cSky, vec3 cFog, vec3 cSun, float glowSize,
                    float glowExponent, float hazeTop) {
  float cosVS = max(dot(V, S), 0.0);
  // Kozlov 3.1: l = s max(V·S, 0)^2. The exponent is a setting (sky.glow_exponent): the
  // paper's square spreads the glow over half the sky, which mixed the sun's warm light into
  // the blue far from it (a mauve sky at sunset); 8 keeps it to the aureole.
  float l = glowSize * pow(cosVS, glowExponent);
  float h = kozlovHaze(V.z, hazeTop);
  return (cSky * h + cFog * (1.0 - h)) * (1.0 - l) + cSun * l;  // Kozlov 3.1: C
}

#endif
