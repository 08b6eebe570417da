#version 460
// Sky-view LUTs (Hillaire 2020, section 5.3): the sky's radiance around the camera at its
// altitude, single and multiple scattering, in the latitude/longitude parametrisation of
// shaders/common/atmosphere.glsl, lit by the sun or by the moon (one dispatch each, the push
// constant saying which), the light's illuminance applied. Below the horizon: the light the air in front of the
// ground scatters toward the camera, without the ground itself, which the composite draws
// lit, shadowed by the clouds and dimmed by this same air (passes/atmosphere_composite).
// Made again only when what it depends on changes (passes/atmosphere_luts).
#include "common/params_block.glsl"
#include "common/atmosphere.glsl"

layout(local_size_x = ATMOSPHERE_GROUP_X, local_size_y = ATMOSPHERE_GROUP_Y) in;

layout(std140, binding = ATMOSPHERE_BINDING_PARAMS) uniform Params {
  AtmosphereParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = ATMOSPHERE_SKY_VIEW_BINDING_TRANSMITTANCE) uniform sampler2D transmittanceLut;
layout(binding = ATMOSPHERE_SKY_VIEW_BINDING_MULTISCATTERING) uniform sampler2D multiScatteringLut;
layout(push_constant) uniform Push {
  AtmosphereSkyViewLight which;
};
layout(binding = ATMOSPHERE_SKY_VIEW_BINDING_OUT, rgba32f) uniform writeonly image2D lutImage;

// Radiance reaching the camera along V per unit illuminance of the light L (1/sr).
vec3 skyRadiance(AtmosphereParams p, vec3 V, vec3 L) {
  float r0 = p.radii.z, mu = V.z, Rg = p.radii.x;
  vec3 origin = vec3(0.0, 0.0, r0);
  float tMax = atmosphereRayLength(p, r0, mu);
  int warp = atmosphereMarchWarp(p, r0, mu);
  vec3 radiance = vec3(0.0), T = vec3(1.0);
  const int steps = ATMOSPHERE_SKY_VIEW_STEPS;
  for (int i = 0; i < steps; ++i) {
    float t0 = atmosphereMarchT(float(i) / steps, tMax, warp);
    float t1 = atmosphereMarchT(float(i + 1) / steps, tMax, warp);
    float dt = t1 - t0;
    vec3 pos = origin + 0.5 * (t0 + t1) * V;
    float r = length(pos);
    AtmosphereMedium m = atmosphereMedium(p, r - Rg);
    vec3 stepT = exp(-m.extinction * dt);
    vec3 S = atmosphereInScattering(p, transmittanceLut, multiScatteringLut, m, pos, r, V, L);
    radiance += T * atmosphereIntegrateStep(S, m.extinction, stepT, dt);
    T *= stepT;
  }
  return radiance;
}

void main() {
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= ATMOSPHERE_SKY_VIEW_WIDTH || id.y >= ATMOSPHERE_SKY_VIEW_HEIGHT) return;
  AtmosphereParams p = params;
  bool moon = which.light.x == ATMOSPHERE_SKY_VIEW_LIGHT_MOON;
  vec3 light = moon ? p.moonDirection.xyz : p.sunDirection.xyz;
  vec3 illuminance = moon ? p.moonIlluminance.rgb : p.sunIlluminance.rgb;
  vec2 unit = vec2(atmosphereTexelToUnit(float(id.x), float(ATMOSPHERE_SKY_VIEW_WIDTH)),
                   atmosphereTexelToUnit(float(id.y), float(ATMOSPHERE_SKY_VIEW_HEIGHT)));
  float cosTheta, cosPhi;
  atmosphereSkyViewParams(p, unit, cosTheta, cosPhi);
  float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
  float sinPhi = sqrt(max(1.0 - cosPhi * cosPhi, 0.0));
  // In the LUT's own frame the light lies in the x-z plane; only its elevation matters.
  float muS = clamp(light.z, -1.0, 1.0);
  vec3 L = vec3(sqrt(max(1.0 - muS * muS, 0.0)), 0.0, muS);
  vec3 V = vec3(sinTheta * cosPhi, sinTheta * sinPhi, cosTheta);
  vec4 value = vec4(ATMOSPHERE_RENDERER_SCALE * skyRadiance(p, V, L) * illuminance, 1.0);
  imageStore(lutImage, ivec2(id.xy), value);
}
