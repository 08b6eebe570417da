// The physically based atmosphere on the GPU (Hillaire 2020): the medium, the phase
// functions, ray geometry on the spherical planet, the LUT parametrisations and the functions
// every pass uses to sample the LUTs that passes/atmosphere_luts makes. docs/atmosphere.md
// describes what each LUT holds.
//
// Units: lengths in km, radii from the planet centre; directions unit vectors in the camera's
// east-north-up frame (z up, the camera on the z axis of the planet). The LUTs made per frame
// (sky-view, aerial perspective) hold radiance in the renderer's units, their illuminance
// already applied; transmittance is a plain ratio.
#ifndef SKY_ATMOSPHERE_GLSL
#define SKY_ATMOSPHERE_GLSL
#include "atmosphere_shared.h"

const float ATMOSPHERE_PI = 3.14159265358979;
// Radiance per unit illuminance in physical units (1/sr) times this is radiance per unit
// illuminance in the renderer's units, whose illuminance unit is pi times its radiance unit
// (docs/lighting.md: a white Lambertian surface under illuminance E has radiance E).
const float ATMOSPHERE_RENDERER_SCALE = ATMOSPHERE_PI;

// ---- Ray geometry: a ray leaving radius r with cosine of zenith angle mu ----

// r^2 mu^2 - (r^2 - Rg^2): the ray meets the ground where this is >= 0 and mu < 0. Written
// with (r - Rg)(r + Rg) so that it keeps its precision a few metres above the ground.
float atmosphereGroundDiscriminant(AtmosphereParams p, float r, float mu) {
  float Rg = p.radii.x;
  return r * r * mu * mu - (r - Rg) * (r + Rg);
}

bool atmosphereRayHitsGround(AtmosphereParams p, float r, float mu) {
  return mu < 0.0 && atmosphereGroundDiscriminant(p, r, mu) >= 0.0;
}

// Distance to the ground along a ray that hits it: the near root of t^2 + 2 r mu t + r^2 - Rg^2,
// as (product of the roots) / (far root) to avoid cancellation.
float atmosphereDistanceToGround(AtmosphereParams p, float r, float mu) {
  float Rg = p.radii.x;
  float far = -r * mu + sqrt(max(atmosphereGroundDiscriminant(p, r, mu), 0.0));
  return max((r - Rg) * (r + Rg), 0.0) / max(far, 1e-9);
}

// Distance to the top of the atmosphere from inside it (r <= top radius).
float atmosphereDistanceToTop(AtmosphereParams p, float r, float mu) {
  float Rt = p.radii.y;
  float c = (Rt - r) * (Rt + r);
  float root = sqrt(max(r * r * mu * mu + c, 0.0));
  // Upward, -r mu + root cancels; the same root as c / (r mu + root) does not.
  return mu > 0.0 ? max(c, 0.0) / max(r * mu + root, 1e-9) : max(-r * mu + root, 0.0);
}

// Where a ray from radius r ends: the ground if it hits it, else the top of the atmosphere.
float atmosphereRayLength(AtmosphereParams p, float r, float mu) {
  return atmosphereRayHitsGround(p, r, mu) ? atmosphereDistanceToGround(p, r, mu)
                                           : atmosphereDistanceToTop(p, r, mu);
}

// ---- The medium (Hillaire 2020, section 4 and Table 1) ----

struct AtmosphereMedium {
  vec3 rayleigh;    // Rayleigh scattering, 1/km
  vec3 mie;         // Mie scattering, 1/km
  vec3 scattering;  // both
  vec3 extinction;  // scattering + Mie absorption + ozone absorption
};

AtmosphereMedium atmosphereMedium(AtmosphereParams p, float altitude) {
  float h = max(altitude, 0.0);
  float rayleighDensity = exp(-h / p.rayleighScattering.w);
  float mieDensity = exp(-h / p.mieScattering.w);
  // Ozone: a tent around its centre altitude.
  float ozoneDensity = max(0.0, 1.0 - abs(h - p.ozoneProfile.x) / p.ozoneProfile.y);
  AtmosphereMedium m;
  m.rayleigh = p.rayleighScattering.rgb * rayleighDensity;
  m.mie = p.mieScattering.rgb * mieDensity;
  m.scattering = m.rayleigh + m.mie;
  m.extinction = m.rayleigh + p.mieExtinction.rgb * mieDensity + p.ozoneAbsorption.rgb * ozoneDensity;
  return m;
}

// Phase functions of the cosine c between the light's and the view's direction of travel
// (c = dot(V, L) for V from the eye and L toward the light), per steradian.
float atmosphereRayleighPhase(float c) {
  return 3.0 / (16.0 * ATMOSPHERE_PI) * (1.0 + c * c);
}

// Cornette-Shanks (1992), the Mie phase function of Hillaire 2020.
float atmosphereCornetteShanksPhase(float g, float c) {
  float g2 = g * g;
  float denom = (2.0 + g2) * pow(max(1.0 + g2 - 2.0 * g * c, 1e-6), 1.5);
  return 3.0 / (8.0 * ATMOSPHERE_PI) * (1.0 - g2) * (1.0 + c * c) / denom;
}

// One step of a raymarch through a medium taken as constant over the step (Hillaire 2015,
// "energy-conserving" integration): the in-scattered radiance source S integrated against the
// step's own transmittance, (S - S T) / extinction.
vec3 atmosphereIntegrateStep(vec3 S, vec3 extinction, vec3 stepTransmittance, float dt) {
  vec3 safe = max(extinction, vec3(1e-9));
  return mix(S * dt, (S - S * stepTransmittance) / safe, greaterThan(extinction, vec3(1e-9)));
}

// Raymarch step positions: segment boundaries t(s) for s = i / n over [0, tMax]. Rays going
// up meet their densest air first (steps grow with s^2), rays that end on the ground meet it
// last (the mirror image), and the rest pass a lowest point somewhere along (uniform).
int atmosphereMarchWarp(AtmosphereParams p, float r, float mu) {
  return mu >= 0.0 ? 1 : (atmosphereRayHitsGround(p, r, mu) ? 2 : 0);
}

float atmosphereMarchT(float s, float tMax, int warp) {
  if (warp == 1) return tMax * s * s;
  if (warp == 2) return tMax * (1.0 - (1.0 - s) * (1.0 - s));
  return tMax * s;
}

// ---- LUT coordinates ----

// Unit coordinate x in [0, 1] <-> texture coordinate with x = 0 and x = 1 at the centres of
// the first and last texels, so the LUTs hold their domain's end points exactly.
float atmosphereUnitToUv(float x, float n) {
  return (0.5 + x * (n - 1.0)) / n;
}
float atmosphereTexelToUnit(float texel, float n) {
  return texel / (n - 1.0);
}

// Transmittance LUT (Bruneton & Neyret 2008, as Hillaire 2020): x from the distance to the
// top between its least (straight up) and largest (the horizon) value, y = rho / H with rho
// the distance to the horizon from r and H the same from the top of the atmosphere.
vec2 atmosphereTransmittanceUv(AtmosphereParams p, float r, float mu) {
  float Rg = p.radii.x, Rt = p.radii.y;
  float H = sqrt((Rt - Rg) * (Rt + Rg));
  float rho = sqrt(max((r - Rg) * (r + Rg), 0.0));
  float d = atmosphereDistanceToTop(p, r, mu);
  float dMin = Rt - r, dMax = rho + H;
  float xMu = clamp((d - dMin) / max(dMax - dMin, 1e-9), 0.0, 1.0);
  float xR = clamp(rho / H, 0.0, 1.0);
  return vec2(atmosphereUnitToUv(xMu, float(ATMOSPHERE_TRANSMITTANCE_WIDTH)),
              atmosphereUnitToUv(xR, float(ATMOSPHERE_TRANSMITTANCE_HEIGHT)));
}

// The inverse, from unit coordinates: the radius and direction a texel stands for.
void atmosphereTransmittanceParams(AtmosphereParams p, vec2 unit, out float r, out float mu) {
  float Rg = p.radii.x, Rt = p.radii.y;
  float H = sqrt((Rt - Rg) * (Rt + Rg));
  float rho = H * unit.y;
  r = sqrt(rho * rho + Rg * Rg);
  float dMin = Rt - r, dMax = rho + H;
  float d = dMin + unit.x * (dMax - dMin);
  // Law of cosines in the triangle centre - r - exit point: Rt^2 = r^2 + d^2 + 2 r d mu.
  mu = d <= 0.0 ? 1.0 : clamp((H * H - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
}

// The LUT as stored, for a ray known to reach the top.
vec3 atmosphereTransmittanceLut(AtmosphereParams p, sampler2D lut, float r, float mu) {
  return texture(lut, atmosphereTransmittanceUv(p, r, mu)).rgb;
}

// Transmittance from radius r along cos-zenith mu to the top of the atmosphere; 0 where the
// ground blocks the ray (the planet's shadow).
vec3 transmittanceToTop(AtmosphereParams p, sampler2D lut, float r, float mu) {
  if (atmosphereRayHitsGround(p, r, mu)) return vec3(0.0);
  return atmosphereTransmittanceLut(p, lut, r, mu);
}

// Transmittance between the camera (radius p.radii.z) and the point `distance` km away along
// unit V, as the ratio of two transmittances to the top (Bruneton & Neyret 2008); a ray that
// ends on the ground uses the reversed rays, which do reach the top. Distances beyond the
// ground or the top of the atmosphere count up to there.
vec3 transmittanceAlong(AtmosphereParams p, sampler2D lut, vec3 V, float distance) {
  float r = p.radii.z, mu = V.z;
  bool ground = atmosphereRayHitsGround(p, r, mu);
  float d = clamp(distance, 0.0, atmosphereRayLength(p, r, mu));
  float rd = sqrt(max(d * d + 2.0 * r * mu * d + r * r, 0.0));
  float mud = clamp((r * mu + d) / rd, -1.0, 1.0);
  vec3 num, den;
  if (ground) {
    num = atmosphereTransmittanceLut(p, lut, rd, -mud);
    den = atmosphereTransmittanceLut(p, lut, r, -mu);
  } else {
    num = atmosphereTransmittanceLut(p, lut, r, mu);
    den = atmosphereTransmittanceLut(p, lut, rd, mud);
  }
  return min(num / max(den, vec3(1e-30)), vec3(1.0));
}

// transmittanceAlong to three distances along the same V at once (columns 0..2 for d.x, d.y,
// d.z). The lookup at the camera's end of the ray is the same for all three, so this takes
// four LUT samples where three calls take six: the composite's aerial perspective needs the
// transmittance to a cloud, to the froxel volume's end and to the end of the ray per pixel.
mat3 transmittancesAlong(AtmosphereParams p, sampler2D lut, vec3 V, vec3 distance) {
  float r = p.radii.z, mu = V.z;
  bool ground = atmosphereRayHitsGround(p, r, mu);
  vec3 camera = atmosphereTransmittanceLut(p, lut, r, ground ? -mu : mu);
  float rayLength = atmosphereRayLength(p, r, mu);
  mat3 result;
  for (int i = 0; i < 3; ++i) {
    float d = clamp(distance[i], 0.0, rayLength);
    float rd = sqrt(max(d * d + 2.0 * r * mu * d + r * r, 0.0));
    float mud = clamp((r * mu + d) / rd, -1.0, 1.0);
    vec3 far = atmosphereTransmittanceLut(p, lut, rd, ground ? -mud : mud);
    vec3 num = ground ? far : camera, den = ground ? camera : far;
    result[i] = min(num / max(den, vec3(1e-30)), vec3(1.0));
  }
  return result;
}

// Multiple-scattering LUT (Hillaire 2020, section 5.2): x = cos(light zenith) over [-1, 1],
// y = sqrt(altitude / thickness) (texels dense near the ground, where the aerosols are); the
// blocks of atmosphere_shared.h side by side in x, each sampled within its texel centres so
// that none bleeds into the next.
vec2 atmosphereMultiScatteringUnit(AtmosphereParams p, float r, float muS) {
  float x = clamp(muS * 0.5 + 0.5, 0.0, 1.0);
  float y = sqrt(clamp((r - p.radii.x) / (p.radii.y - p.radii.x), 0.0, 1.0));
  return vec2(x, y);
}

vec4 atmosphereMultiScatteringTexel(sampler2D lut, vec2 unit, int block) {
  float n = float(ATMOSPHERE_MULTISCATTERING_SIZE);
  float u = (float(block) * n + 0.5 + unit.x * (n - 1.0)) / (n * float(ATMOSPHERE_MS_TEXELS));
  return texture(lut, vec2(u, atmosphereUnitToUv(unit.y, n)));
}

// The first two Legendre moments (p1, p2) of the Cornette-Shanks phase function, P = sum
// (2l + 1) p_l P_l(c) / (4 pi): it is 3 (1 + c^2) / (2 (2 + g^2)) times Henyey-Greenstein,
// whose moments are g^l, and c (1 + c^2), P_2(c) (1 + c^2) expand in Legendre polynomials.
vec2 atmosphereCornetteShanksMoments(float g) {
  float g2 = g * g, k = 3.0 / (2.0 * (2.0 + g2));
  return k * vec2((8.0 * g + 2.0 * g * g2) / 5.0,
                  2.0 / 15.0 + 32.0 / 21.0 * g2 + 12.0 / 35.0 * g2 * g2);
}
// Rayleigh's 3 (1 + c^2) / (16 pi) = (1 + P_2(c) / 2) / (4 pi): p1 = 0, p2 = 1/10.
const float ATMOSPHERE_RAYLEIGH_P2 = 0.1;

// Light scattered toward the eye at `pos` (|pos| = r) along V (from the eye) by orders 2 and
// up, per unit illuminance of a light in direction L, per km: sigma_s Psi_ms (Hillaire (11))
// plus the second order's dependence on V (atmosphere_shared.h).
vec3 atmosphereMultipleScattering(AtmosphereParams p, sampler2D lut, AtmosphereMedium m, vec3 pos,
                                  float r, vec3 V, vec3 L) {
  vec3 up = pos / r;
  float muS = dot(up, L);
  vec2 unit = atmosphereMultiScatteringUnit(p, r, muS);
  vec4 t0 = atmosphereMultiScatteringTexel(lut, unit, 0);
  vec4 t1 = atmosphereMultiScatteringTexel(lut, unit, 1);
  vec4 t2 = atmosphereMultiScatteringTexel(lut, unit, 2);
  vec4 t3 = atmosphereMultiScatteringTexel(lut, unit, 3);
  vec4 t4 = atmosphereMultiScatteringTexel(lut, unit, 4);
  vec3 psi = t0.rgb;
  vec3 du = vec3(t0.a, t1.rg), dl = vec3(t1.ba, t2.r);
  vec3 quu = t2.gba, qll = t3.rgb, qul = vec3(t3.a, t4.rg);
  // The horizontal toward the light; with the light overhead every horizontal is the same and
  // d_l, q_ul hold 0 and q_ll the across value.
  vec3 h = L - muS * up;
  float hLength = length(h);
  h = hLength > 1e-6 ? h / hLength : vec3(0.0);
  float vu = dot(V, up), vl = dot(V, h);
  float across = max(1.0 - vu * vu - vl * vl, 0.0);
  vec3 dipole = du * vu + dl * vl;
  // V^T q V with the across component q_ee = -q_uu - q_ll (q is traceless).
  vec3 quadrupole = quu * (vu * vu - across) + qll * (vl * vl - across) + 2.0 * qul * (vu * vl);
  vec2 mie = atmosphereCornetteShanksMoments(p.mieExtinction.w);
  vec3 s = m.scattering * psi + m.mie * mie.x * dipole +
           (m.rayleigh * ATMOSPHERE_RAYLEIGH_P2 + m.mie * mie.y) * quadrupole;
  // Two moments cannot make light negative where the second order is faint.
  return max(s, vec3(0.0));
}

// Light scattered toward the eye at `pos` (planet-centred, |pos| = r) along V per unit
// illuminance of a light in direction L above the atmosphere, per km: single scattering with
// the Rayleigh and Cornette-Shanks phase functions and the planet's shadow, plus multiple
// scattering (atmosphereMultipleScattering).
vec3 atmosphereInScattering(AtmosphereParams p, sampler2D transmittanceLut, sampler2D msLut,
                            AtmosphereMedium m, vec3 pos, float r, vec3 V, vec3 L) {
  float cosViewLight = dot(V, L);
  float muS = dot(pos, L) / r;
  vec3 sun = transmittanceToTop(p, transmittanceLut, r, muS);
  vec3 single = (m.rayleigh * atmosphereRayleighPhase(cosViewLight) +
                 m.mie * atmosphereCornetteShanksPhase(p.mieExtinction.w, cosViewLight)) * sun;
  return single + atmosphereMultipleScattering(p, msLut, m, pos, r, V, L);
}

// ---- Sky-view LUT (Hillaire 2020, section 5.3) ----
// x: the azimuth between view and light, x = sqrt((1 - cos) / 2) (0 toward the light);
// y: the zenith angle, split at the camera's geometric horizon (y = 0.5) with a square-root
// mapping on each side that puts texels near the horizon. Below the horizon it shows the lit
// ground. Made for one camera altitude (p.radii.z/w).

// Angle between the ray to the horizon and the nadir; the horizon's zenith angle is pi - it.
float atmosphereHorizonBeta(AtmosphereParams p) {
  float h = p.radii.w;
  float toHorizon = sqrt(max(h * (2.0 * p.radii.x + h), 0.0));
  return acos(clamp(toHorizon / p.radii.z, 0.0, 1.0));
}

vec2 atmosphereSkyViewUv(AtmosphereParams p, vec3 V, vec3 L) {
  float beta = atmosphereHorizonBeta(p);
  float zenithHorizon = ATMOSPHERE_PI - beta;
  float theta = acos(clamp(V.z, -1.0, 1.0));
  float y;
  if (theta < zenithHorizon) {
    y = 0.5 * (1.0 - sqrt(max(1.0 - theta / zenithHorizon, 0.0)));
  } else {
    y = 0.5 + 0.5 * sqrt(clamp((theta - zenithHorizon) / beta, 0.0, 1.0));
  }
  float lengths = length(V.xy) * length(L.xy);
  float cosPhi = lengths > 1e-12 ? clamp(dot(V.xy, L.xy) / lengths, -1.0, 1.0) : 1.0;
  float x = sqrt(max(0.5 - 0.5 * cosPhi, 0.0));
  return vec2(atmosphereUnitToUv(x, float(ATMOSPHERE_SKY_VIEW_WIDTH)),
              atmosphereUnitToUv(y, float(ATMOSPHERE_SKY_VIEW_HEIGHT)));
}

// The inverse, from unit coordinates: cos(view zenith) and cos(azimuth from the light).
void atmosphereSkyViewParams(AtmosphereParams p, vec2 unit, out float cosTheta, out float cosPhi) {
  float beta = atmosphereHorizonBeta(p);
  float zenithHorizon = ATMOSPHERE_PI - beta;
  float theta;
  if (unit.y < 0.5) {
    float c = 1.0 - 2.0 * unit.y;
    theta = zenithHorizon * (1.0 - c * c);
  } else {
    float c = 2.0 * unit.y - 1.0;
    theta = zenithHorizon + beta * c * c;
  }
  cosTheta = cos(theta);
  cosPhi = 1.0 - 2.0 * unit.x * unit.x;
}

// Sky radiance in direction V (unit, east-north-up) from a sky-view LUT made for the light
// direction L, at the camera altitude the LUT was made for: renderer units, the light's
// illuminance applied.
vec3 skyViewRadiance(AtmosphereParams p, sampler2D skyView, vec3 V, vec3 L) {
  return texture(skyView, atmosphereSkyViewUv(p, V, L)).rgb;
}

// ---- Aerial perspective (Hillaire 2020, section 5.4) ----
// A 32^3 froxel volume over the camera's screen: x, y the screen (uv, row 0 at the top), z the
// distance along the view ray with slices spread quadratically (distance = D z^2, D =
// p.aerialPerspective.x; Hillaire's sample code does the same), so near slices are thin.
// Texel k holds the light in-scattered between the camera and distance D ((k + 0.5) / n)^2.

float atmosphereApSliceDistance(AtmosphereParams p, float z) {
  return p.aerialPerspective.x * z * z;
}

// rgb: in-scattered radiance between the camera and `distance` km along the view ray through
// screen position uv (sun and moon, renderer units); a: mean transmittance over rgb. Nearer
// than the first slice it fades to nothing; beyond the last it holds the last slice's value.
vec4 aerialPerspective(AtmosphereParams p, sampler3D ap, vec2 uv, float distance) {
  float first = 0.5 / p.aerialPerspective.y;
  float z = sqrt(max(distance, 0.0) / p.aerialPerspective.x);
  vec4 s = texture(ap, vec3(uv, max(z, first)));
  return mix(vec4(0.0, 0.0, 0.0, 1.0), s, clamp(z / first, 0.0, 1.0));
}

#endif
