#version 460
// Transmittance LUT (Hillaire 2020, section 5.1): transmittance from each (radius, cos zenith)
// of the Bruneton parametrisation to the top of the atmosphere, by a raymarch of the optical
// depth. Persistent; remade only when the atmosphere changes.
#include "common/params_block.glsl"
#include "common/atmosphere.glsl"

layout(local_size_x = ATMOSPHERE_GROUP_X, local_size_y = ATMOSPHERE_GROUP_Y) in;

layout(std140, binding = ATMOSPHERE_BINDING_PARAMS) uniform Params {
  AtmosphereParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = ATMOSPHERE_TRANSMITTANCE_BINDING_OUT, rgba32f) uniform writeonly image2D lutImage;

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(texel, uvec2(ATMOSPHERE_TRANSMITTANCE_WIDTH, ATMOSPHERE_TRANSMITTANCE_HEIGHT))))
    return;
  AtmosphereParams p = params;
  vec2 unit = vec2(atmosphereTexelToUnit(float(texel.x), float(ATMOSPHERE_TRANSMITTANCE_WIDTH)),
                   atmosphereTexelToUnit(float(texel.y), float(ATMOSPHERE_TRANSMITTANCE_HEIGHT)));
  float r, mu;
  atmosphereTransmittanceParams(p, unit, r, mu);
  float tMax = atmosphereDistanceToTop(p, r, mu);
  // Rays in this LUT never meet the ground: up-going ones start in their densest air.
  int warp = mu >= 0.0 ? 1 : 0;
  vec3 opticalDepth = vec3(0.0);
  const int n = ATMOSPHERE_TRANSMITTANCE_STEPS;
  for (int i = 0; i < n; ++i) {
    float t0 = atmosphereMarchT(float(i) / n, tMax, warp);
    float t1 = atmosphereMarchT(float(i + 1) / n, tMax, warp);
    float t = 0.5 * (t0 + t1);
    // Radius at distance t: r_t^2 = r^2 + 2 r mu t + t^2.
    float rt = sqrt(max(r * r + 2.0 * r * mu * t + t * t, 0.0));
    opticalDepth += atmosphereMedium(p, rt - p.radii.x).extinction * (t1 - t0);
  }
  imageStore(lutImage, ivec2(texel), vec4(exp(-opticalDepth), 1.0));
}
