// Kozlov et al. 3.1: the clear-sky colour of a dome point seen in direction V.
#ifndef SKY_KOZLOV_SKY_GLSL
#define SKY_KOZLOV_SKY_GLSL

// V: view direction (unit, z up). S: light direction (unit). glowSize: s. hazeTop: hmax as
// a fraction of the dome height. Below the horizon the dome height is 0, so it shows Cfog.
vec3 kozlovClearSky(vec3 V, vec3 S, vec3 cSky, vec3 cFog, vec3 cSun, float glowSize, float hazeTop) {
  float cosVS = max(dot(V, S), 0.0);
  float l = glowSize * cosVS * cosVS;          // Kozlov 3.1: l = s * max(V·S, 0)^2
  float z = max(V.z, 0.0);                     // height of the point on a unit dome
  float h = min(z / hazeTop, 1.0);             // Kozlov 3.1: h = min(z / hmax, 1)
  return (cSky * h + cFog * (1.0 - h)) * (1.0 - l) + cSun * l;  // Kozlov 3.1: C
}

#endif
