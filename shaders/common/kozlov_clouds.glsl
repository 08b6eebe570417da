// Kozlov et al. 3.2-3.4: the colour terms of a cloud layer drawn from a coefficient texture,
// for one directional light. The coefficient texture's channels weight them (see
// docs/high-clouds.md): R thin lit parts, G dense parts, B clear sky, A sparse edges.
#ifndef SKY_KOZLOV_CLOUDS_GLSL
#define SKY_KOZLOV_CLOUDS_GLSL
#include "lighting_shared.h"

// Kozlov 3.2: lit parts, C = Clight (N . S'), with N from the normal map and S' the light in
// the layer's tangent space. In our units a surface under illuminance E facing the light has
// radiance E, so Clight is the light's illuminance at the layer. The palette's ambient (sky
// light from above, ground light from below, mixed by the normal's tilt) keeps the parts
// that face away from the light from turning black.
vec3 kozlovLitParts(vec3 normalTs, vec3 lightTs, vec3 lightIlluminance, Palette p) {
  vec3 ambient = mix(p.ambientBottom.rgb, p.ambientTop.rgb, 0.5 + 0.5 * normalTs.z);
  return lightIlluminance * max(dot(normalTs, lightTs), 0.0) + ambient;
}

// Kozlov 3.3: dense parts, p(w) = 3/4 (1 + cos^2 w) between C1 (toward the light) and C2.
// The paper interpolates with p itself, which runs over [3/4, 3/2] and so leaves [0, 1]; we
// map that range onto [0, 1], t = (p - 3/4) / (3/4) = cos^2 w, on the light's side of the sky
// and hold C2 on the far side, where cos w < 0 (p is symmetric and cannot tell the two apart).
vec3 kozlovDenseParts(float cosW, Palette p) {
  float phase = 0.75 * (1.0 + cosW * cosW);                // Kozlov 3.3: p(w)
  float t = cosW > 0.0 ? (phase - 0.75) / 0.75 : 0.0;      // p mapped onto [0, 1]
  return mix(p.cloudDark.rgb, p.cloudLit.rgb, t);          // Kozlov 3.3: C1 (1-p) + C2 p
}

// Kozlov 3.4: sparse edges, C = Clight f(w, l), a glow around the light of angular width l.
// We take f as a normalised small-angle forward-scattering lobe, exp(-(w/l)^2) / (pi l^2)
// per steradian (its integral over the sphere is ~1), so the A channel reads as the edges'
// scattering optical depth and the glow keeps its energy when l changes.
vec3 kozlovSparseEdges(float cosW, float widthL, vec3 lightIlluminance) {
  float w = acos(clamp(cosW, -1.0, 1.0));
  float f = exp(-(w * w) / (widthL * widthL)) / (3.14159265 * widthL * widthL);  // f(w, l)
  return lightIlluminance * f;                                                    // Clight f
}

// Clight for the lit parts: a thin ice cloud seen from below is no white wall facing the
// light; it sends on about a quarter of the light it receives (diffuse transmittance of an
// optical depth near 1), so Clight = E / 4.
#define KOZLOV_THIN_TRANSMITTANCE 0.25
// The A channel (1 where edges are most typical) read as optical depth: sparse edges are at
// most about 0.3 deep, so their glow is a thin single-scattering lobe, not a second sun.
#define KOZLOV_EDGE_OPTICAL_DEPTH 0.3
// The asymmetry g of the ice crystals' phase function. Cirrus ice (columns, plates, bullet
// rosettes and their aggregates, tens to hundreds of micrometres) scatters visible light with
// g = 0.74 to 0.84 by shape (Macke, Mueller and Raschke 1996, "Single scattering properties of
// atmospheric ice crystals", J. Atmos. Sci. 53, 2813-2825); roughened crystals, the model of
// the operational MODIS ice retrievals, give about 0.75 (Yang et al. 2013, "Spectrally
// consistent scattering, absorption, and polarization properties of atmospheric ice crystals
// at wavelengths from 0.2 to 100 um", J. Atmos. Sci. 70, 330-347).
#define KOZLOV_ICE_PHASE_G 0.75

// The ice's phase function: Henyey-Greenstein, normalised to 1 over the sphere (per
// steradian), Lu (23). cosW = V . S, 1 looking into the light.
float kozlovIcePhase(float cosW) {
  const float g = KOZLOV_ICE_PHASE_G;
  float denom = 1.0 + g * g - 2.0 * g * cosW;
  return (1.0 - g * g) / (4.0 * 3.14159265 * denom * sqrt(denom));
}

// Forward scattering by the layer's ice, the term Kozlov's model lacks: 3.2 lights the thin
// parts by the slope of a surface, 3.3 blends two artist colours by a Rayleigh-shaped p(w)
// and 3.4 gives only the sparse edges a narrow glow, so near a low sun (N . S' near 0) the
// layer turned darker than the bright sky around the sun, where real cirrus glow. In the
// small-angle limit of a strongly forward-scattering layer the light it takes out of the
// beam, a share 1 - B (the B channel is the layer's transmittance), leaves spread over the
// phase function around the beam's direction, so it adds Clight p_ice(w) (1 - B) per unit of
// illuminance, Clight the full illuminance at the layer (the light is scattered, not passed on
// diffusely as in 3.2). Read like 3.4: a coefficient (the opacity) times the light times a
// normalised lobe. The lobe is 2.2 E per steradian looking into the light, 0.58 at 20 degrees and
// 0.018 at 90 (against up to a quarter in 3.2), so away from the light the layer's look stays
// Kozlov's.
vec3 kozlovIceScattering(float cosW, float opacity, vec3 lightIlluminance) {
  return lightIlluminance * kozlovIcePhase(cosW) * opacity;
}

// All four terms for one light, weighted by the coefficients (R thin, G dense, A edges, and
// the opacity 1 - B for the ice's forward scattering).
vec3 kozlovCloudTerms(vec4 coefficients, vec3 normalTs, vec3 lightTs, float cosW,
                      vec3 lightIlluminance, Palette p, float edgeWidth) {
  vec3 cLight = KOZLOV_THIN_TRANSMITTANCE * lightIlluminance;
  return coefficients.r * kozlovLitParts(normalTs, lightTs, cLight, p) +
         coefficients.g * kozlovDenseParts(cosW, p) +
         coefficients.a * KOZLOV_EDGE_OPTICAL_DEPTH *
             kozlovSparseEdges(cosW, edgeWidth, lightIlluminance) +
         kozlovIceScattering(cosW, 1.0 - coefficients.b, lightIlluminance);
}

#endif
