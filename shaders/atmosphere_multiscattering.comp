#version 460
// Multiple-scattering LUT (Hillaire 2020, section 5.2, (5)-(11), extended): for each altitude
// and cos(light zenith), the once-scattered light L_1 reaching a point from every direction of
// the sphere (with the true phase functions, and the lit ground), its mean L_2nd and the
// transfer factor f_ms, whose product with the geometric series F_ms = 1 / (1 - f_ms) is Psi_ms
// and the second order's dependence on the direction it is scattered into, through L_1's
// dipole and quadrupole (atmosphere_shared.h, docs/atmosphere.md). One workgroup per texel, one invocation per direction of the sphere.
// Persistent; remade only when the atmosphere changes.
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

// Per direction: L_1, the transfer path of (9), and L_1 times the direction's moments in the
// light's frame (x toward the light's azimuth, z up): z, x, z^2 - 1/3, x^2 - 1/3, x z.
#define SUMS 7
shared vec3 sharedSums[SUMS][DIRECTIONS];

void main() {
  AtmosphereParams p = params;
  uvec2 texel = gl_WorkGroupID.xy;
  uint index = gl_LocalInvocationIndex;
  float n = float(ATMOSPHERE_MULTISCATTERING_SIZE);
  float muS = atmosphereTexelToUnit(float(texel.x), n) * 2.0 - 1.0;
  // Keep the point a little inside the atmosphere (as the camera), so that rays from it are
  // well defined at both ends of the altitude range.
  float Rg = p.radii.x, Rt = p.radii.y;
  float y = atmosphereTexelToUnit(float(texel.y), n);
  float r = clamp(Rg + y * y * (Rt - Rg), Rg + 0.01, Rt - 0.01);
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
  // The first scattering with the true phase functions (Hillaire's isotropic one made the
  // sky 5-14 % too bright away from a high sun and too dark toward a low one, measured against
  // the spectral reference): the light reaching the texel from V was scattered by the angle
  // between V and the light's direction.
  float cosLight = dot(V, L);
  float phaseR = atmosphereRayleighPhase(cosLight);
  float phaseM = atmosphereCornetteShanksPhase(p.mieExtinction.w, cosLight);
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
    // Hillaire (7) with the phase functions in place of the isotropic one.
    radiance += T * atmosphereIntegrateStep((m.rayleigh * phaseR + m.mie * phaseM) * sun,
                                            m.extinction, stepT, dt);
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
  vec3 sums[SUMS] = vec3[SUMS](radiance, transfer, radiance * V.z, radiance * V.x,
                               radiance * (V.z * V.z - 1.0 / 3.0),
                               radiance * (V.x * V.x - 1.0 / 3.0), radiance * (V.x * V.z));
  for (int k = 0; k < SUMS; ++k) sharedSums[k][index] = sums[k];
  barrier();
  for (uint stride = DIRECTIONS / 2; stride > 0; stride /= 2) {
    if (index < stride) {
      for (int k = 0; k < SUMS; ++k) sharedSums[k][index] += sharedSums[k][index + stride];
    }
    barrier();
  }
  // Integrals over the sphere are 4 pi times the means over the equal-area directions (the
  // mirrored half circle has the same means; its odd moments in y vanish).
  if (index < ATMOSPHERE_MS_TEXELS) {
    vec3 mean[SUMS];
    for (int k = 0; k < SUMS; ++k) mean[k] = sharedSums[k][0] / float(DIRECTIONS);
    // Hillaire (6), (8), (10), (11): Psi_ms = L_2nd F_ms, F_ms = 1 / (1 - f_ms).
    vec3 psi = mean[0] / max(vec3(1.0) - mean[1], vec3(1e-6));
    // The phase function's P_1 term, 3 / (4 pi) int (w.V) L_1 dw = d.V with d = 3 mean(w L_1),
    // and its P_2 term, 5 / (4 pi) int P_2(w.V) L_1 dw = V^T q V, q = 15/2 mean((w w^T - I/3) L_1).
    vec3 du = 3.0 * mean[2], dl = 3.0 * mean[3];
    vec3 quu = 7.5 * mean[4], qll = 7.5 * mean[5], qul = 7.5 * mean[6];
    float v[4 * ATMOSPHERE_MS_TEXELS] =
        float[](psi.r, psi.g, psi.b, du.r, du.g, du.b, dl.r, dl.g, dl.b, quu.r, quu.g, quu.b,
                qll.r, qll.g, qll.b, qul.r, qul.g, qul.b, 0.0, 0.0);
    uint k = 4u * index;
    imageStore(lutImage, ivec2(texel.x + index * ATMOSPHERE_MULTISCATTERING_SIZE, texel.y),
               vec4(v[k], v[k + 1u], v[k + 2u], v[k + 3u]));
  }
}
