#version 460
// Multiple-scattering LUT (Hillaire 2020, section 5.2, (5)-(11)): for each altitude and
// cos(light zenith), the second-order radiance L_2nd reaching a point from all directions,
// with an isotropic phase function, and the transfer factor f_ms; their product with the
// geometric series F_ms = 1 / (1 - f_ms) is Psi_ms, per unit illuminance. One workgroup per
// texel, one invocation per direction of the sphere. Persistent; remade only when the
// atmosphere changes.
#include "common/params_block.glsl"
#include "common/atmosphere.glsl"

#define DIRECTIONS (ATMOSPHERE_MS_ZENITH_BANDS * ATMOSPHERE_MS_AZIMUTHS)
layout(local_size_x = DIRECTIONS) in;

layout(std140, binding = ATMOSPHERE_BINDING_PARAMS) uniform Params {
  AtmosphereParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = ATMOSPHERE_MULTISCATTERING_BINDING_TRANSMITTANCE) uniform sampler2D transmittanceLut;
layout(binding = ATMOSPHERE_MULTISCATTERING_BINDING_OUT, rgba32f) uniform writeonly image2D lutImage;

shared vec3 sharedL[DIRECTIONS];
shared vec3 sharedF[DIRECTIONS];

void main() {
  AtmosphereParams p = params;
  uvec2 texel = gl_WorkGroupID.xy;
  uint index = gl_LocalInvocationIndex;
  float n = float(ATMOSPHERE_MULTISCATTERING_SIZE);
  float muS = atmosphereTexelToUnit(float(texel.x), n) * 2.0 - 1.0;
  // Keep the point a little inside the atmosphere (as the camera), so that rays from it are
  // well defined at both ends of the altitude range.
  float Rg = p.radii.x, Rt = p.radii.y;
  float r = clamp(Rg + atmosphereTexelToUnit(float(texel.y), n) * (Rt - Rg), Rg + 0.01, Rt - 0.01);
  vec3 L = vec3(sqrt(max(1.0 - muS * muS, 0.0)), 0.0, muS);

  // Equal-area directions: bands of equal width in cos(zenith), azimuths over the half circle
  // on one side of the light's vertical plane (the other side is its mirror image).
  uint band = index / ATMOSPHERE_MS_AZIMUTHS, az = index % ATMOSPHERE_MS_AZIMUTHS;
  float cosTheta = 1.0 - 2.0 * (float(band) + 0.5) / float(ATMOSPHERE_MS_ZENITH_BANDS);
  float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
  float phi = ATMOSPHERE_PI * (float(az) + 0.5) / float(ATMOSPHERE_MS_AZIMUTHS);
  vec3 V = vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);

  vec3 origin = vec3(0.0, 0.0, r);
  bool ground = atmosphereRayHitsGround(p, r, cosTheta);
  float tMax = atmosphereRayLength(p, r, cosTheta);
  int warp = atmosphereMarchWarp(p, r, cosTheta);
  const float isotropic = 1.0 / (4.0 * ATMOSPHERE_PI);
  vec3 radiance = vec3(0.0), transfer = vec3(0.0), T = vec3(1.0);
  const int steps = ATMOSPHERE_MS_STEPS;
  for (int i = 0; i < steps; ++i) {
    float t0 = atmosphereMarchT(float(i) / steps, tMax, warp);
    float t1 = atmosphereMarchT(float(i + 1) / steps, tMax, warp);
    float dt = t1 - t0;
    vec3 pos = origin + 0.5 * (t0 + t1) * V;
    float rt = length(pos);
    AtmosphereMedium m = atmosphereMedium(p, rt - Rg);
    vec3 stepT = exp(-m.extinction * dt);
    vec3 sun = transmittanceToTop(p, transmittanceLut, rt, dot(pos, L) / rt);
    // Hillaire (7): second-order light with the isotropic phase function.
    radiance += T * atmosphereIntegrateStep(m.scattering * sun * isotropic, m.extinction, stepT, dt);
    // Hillaire (9): the same path with unit light arriving from everywhere.
    transfer += T * atmosphereIntegrateStep(m.scattering, m.extinction, stepT, dt);
    T *= stepT;
  }
  if (ground) {
    // The Lambertian ground lit by the light through the atmosphere (Hillaire (7), last term).
    vec3 pos = origin + tMax * V;
    float rg = length(pos);
    float muG = dot(pos, L) / rg;
    radiance += T * p.groundAlbedo.rgb / ATMOSPHERE_PI * max(muG, 0.0) *
                atmosphereTransmittanceLut(p, transmittanceLut, Rg, max(muG, 0.0));
  }
  sharedL[index] = radiance;
  sharedF[index] = transfer;
  barrier();
  for (uint stride = DIRECTIONS / 2; stride > 0; stride /= 2) {
    if (index < stride) {
      sharedL[index] += sharedL[index + stride];
      sharedF[index] += sharedF[index + stride];
    }
    barrier();
  }
  if (index == 0) {
    // Hillaire (6) and (8): integrals over the sphere against the isotropic phase function,
    // i.e. the means over the equal-area directions.
    vec3 L2 = sharedL[0] / float(DIRECTIONS);
    vec3 fms = sharedF[0] / float(DIRECTIONS);
    // Hillaire (10), (11): Psi_ms = L_2nd F_ms, F_ms = 1 / (1 - f_ms).
    imageStore(lutImage, ivec2(texel), vec4(L2 / max(vec3(1.0) - fms, vec3(1e-6)), 1.0));
  }
}
