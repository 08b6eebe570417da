#version 460
// Aerial-perspective LUT (Hillaire 2020, section 5.4): a froxel volume over the camera's
// screen holding, per view ray and distance slice, the light in-scattered between the camera
// and the slice (sun and moon, their illuminance applied) and the mean transmittance. One
// invocation marches one view ray through all the slices, storing as it passes each, so each
// slice continues the integral of the one before. Made every frame.
#include "common/params_block.glsl"
#include "common/atmosphere.glsl"
#include "common/view.glsl"

layout(local_size_x = ATMOSPHERE_GROUP_X, local_size_y = ATMOSPHERE_GROUP_Y) in;

layout(std140, binding = ATMOSPHERE_BINDING_PARAMS) uniform Params {
  AtmosphereParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = ATMOSPHERE_AP_BINDING_TRANSMITTANCE) uniform sampler2D transmittanceLut;
layout(binding = ATMOSPHERE_AP_BINDING_MULTISCATTERING) uniform sampler2D multiScatteringLut;
layout(binding = ATMOSPHERE_AP_BINDING_OUT, rgba32f) uniform writeonly image3D apImage;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(id, uvec2(ATMOSPHERE_AP_SIZE)))) return;
  AtmosphereParams p = params;
  vec2 uv = (vec2(id) + 0.5) / float(ATMOSPHERE_AP_SIZE);
  // The view ray through screen position uv, whatever the view's projection.
  vec3 V = viewDirection(p.view, uv * vec2(p.view.size.xy));
  float r0 = p.radii.z, Rg = p.radii.x;
  vec3 origin = vec3(0.0, 0.0, r0);
  // Past the top of the atmosphere nothing more is added. Past the ground the march goes on
  // through air as dense as at the ground (the medium clamps the altitude) in the planet's
  // shadow: no object lies there, but froxels next to a ray that ends on the ground then
  // interpolate smoothly with it, rather than with a value frozen at its ground distance.
  float tEnd = atmosphereRayHitsGround(p, r0, V.z) ? 1e30 : atmosphereDistanceToTop(p, r0, V.z);
  vec3 Ls = p.sunDirection.xyz, Lm = p.moonDirection.xyz;
  vec3 Es = ATMOSPHERE_RENDERER_SCALE * p.sunIlluminance.rgb;
  vec3 Em = ATMOSPHERE_RENDERER_SCALE * p.moonIlluminance.rgb;

  vec3 radiance = vec3(0.0), T = vec3(1.0);
  float tPrev = 0.0;
  const int slices = ATMOSPHERE_AP_SLICES;
  for (int k = 0; k < slices; ++k) {
    float tSlice = atmosphereApSliceDistance(p, (float(k) + 0.5) / float(slices));
    float tNext = min(tSlice, tEnd);
    if (tNext > tPrev) {
      float dt = (tNext - tPrev) / float(ATMOSPHERE_AP_STEPS_PER_SLICE);
      for (int j = 0; j < ATMOSPHERE_AP_STEPS_PER_SLICE; ++j) {
        vec3 pos = origin + (tPrev + (float(j) + 0.5) * dt) * V;
        float r = length(pos);
        AtmosphereMedium m = atmosphereMedium(p, r - Rg);
        vec3 stepT = exp(-m.extinction * dt);
        vec3 S = atmosphereInScattering(p, transmittanceLut, multiScatteringLut, m, pos, r, V, Ls) * Es +
                 atmosphereInScattering(p, transmittanceLut, multiScatteringLut, m, pos, r, V, Lm) * Em;
        radiance += T * atmosphereIntegrateStep(S, m.extinction, stepT, dt);
        T *= stepT;
      }
      tPrev = tNext;
    }
    imageStore(apImage, ivec3(id, k), vec4(radiance, dot(T, vec3(1.0 / 3.0))));
  }
}
