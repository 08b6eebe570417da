// Lighting maths for the volumetric clouds: Beer-Lambert with Lu's clamp (Lu (21)(22)), the
// Henyey-Greenstein phase (Lu (23), Tang (3)) and a dual-lobe mix (Tang's stated next step),
// Tang's slab ambient with the exponential integral (Tang (6)(7)), multiple-scattering octaves
// (Wrenninge 2013), the energy-conserving step integral (Hillaire 2016) and the light-march
// schedule. Every function has a C++ twin of the same name in engine/clouds/cloud_math.h,
// compared in tests/clouds. See docs/cloud-model.md.
#ifndef SKY_CLOUD_LIGHTING_GLSL
#define SKY_CLOUD_LIGHTING_GLSL

#define CLOUD_PI 3.14159265358979
#define CLOUD_EULER_GAMMA 0.5772156649015329

// Lu (21): transmittance for extinction b over the accumulated density ds (density x metres).
float beerLambert(float b, float ds) {
  return exp(-b * ds);
}

// Lu (22): Beer-Lambert with the attenuation clamped; dsClamp is Lu's ac times the densest
// accumulated density the light march can see (the caller's choice), so no point goes darker
// than exp(-b * dsClamp).
float beerClamped(float b, float ds, float dsClamp) {
  return max(beerLambert(b, ds), beerLambert(b, dsClamp));
}

// Lu (23) / Tang (3): Henyey-Greenstein, normalised to 1 over the sphere. cosTheta is
// dot(view ray direction, direction to the light): 1 when looking into the light, where the
// forward peak of g > 0 lies.
float henyeyGreenstein(float cosTheta, float g) {
  float denom = 1.0 + g * g - 2.0 * g * cosTheta;
  return (1.0 - g * g) / (4.0 * CLOUD_PI * denom * sqrt(denom));
}

// Tang's stated next step (a phase with stronger back-scattering than HG): a normalised mix of
// a forward lobe and a back lobe (gBack < 0), backWeight the back lobe's share.
float dualLobeHG(float cosTheta, float gForward, float gBack, float backWeight) {
  return mix(henyeyGreenstein(cosTheta, gForward), henyeyGreenstein(cosTheta, gBack), backWeight);
}

// The exponential integral Ei(x) for x < 0, where Ei(x) = -E1(-x). For |x| < 1.5 the power
// series E1(z) = -gamma - ln z - sum_k (-z)^k / (k k!) (16 terms); above, the continued fraction
// E1(z) = e^-z / (z + 1 - 1/(z + 3 - 4/(z + 5 - ...))) evaluated from a fixed depth of 15
// (Abramowitz & Stegun 5.1.11, 5.1.22). Both are good to 1e-7 relative in exact arithmetic
// over [-60, -1e-4]; float rounding brings it to a few 1e-6.
float expIntegralEi(float x) {
  float z = -x;
  if (z < 1.5) {
    float term = 1.0, sum = 0.0;
    for (int k = 1; k <= 16; ++k) {
      term *= -z / float(k);
      sum += term / float(k);
    }
    return CLOUD_EULER_GAMMA + log(z) + sum;
  }
  float t = z + 31.0;
  for (int k = 15; k >= 1; --k) t = z + float(2 * k - 1) - float(k * k) / t;
  return -exp(-z) / t;
}

// Tang (6)(7): the share of isotropic ambient light that reaches a point at optical depth
// -a = sigmaT * H inside an infinite homogeneous slab, max(0, exp(a) - a Ei(a)) (this is the
// exponential integral E2(sigmaT H)). 1 at the slab's face (the limit a -> 0, where a Ei(a) -> 0),
// decreasing with depth.
float slabAmbient(float a) {
  if (a >= 0.0) return 1.0;
  return max(0.0, exp(a) - a * expIntegralEi(a));
}

// Tang (6)(7): the ambient light at a point hTopM below the layer top and hBottomM above its
// bottom: the top colour (sun and sky from above) through the slab above the point plus the
// bottom colour (ground reflection) through the slab below it.
vec3 cloudAmbient(vec3 top, vec3 bottom, float sigmaT, float hTopM, float hBottomM) {
  return top * slabAmbient(-sigmaT * hTopM) + bottom * slabAmbient(-sigmaT * hBottomM);
}

// Multiple scattering as octaves (Wrenninge 2013, "Oz: the great and volumetric"): octave i
// scatters with b^i of the energy, sees a^i of the optical depth toward the light and a phase
// whose asymmetry is c^i times smaller. a = b = c = 0.5 (Wrenninge's suggested values, which
// keep the sum of b^i below 2). Each octave keeps Lu (22)'s clamp; octave 0 is exactly
// Lu (22) * (23). tauToLight = b * ds toward the light, tauClamp = b * dsClamp.
// phaseKind 0: Henyey-Greenstein with g; 1: dualLobeHG(g, gBack, backWeight).
#define CLOUD_OCTAVE_ATTENUATION 0.5
#define CLOUD_OCTAVE_CONTRIBUTION 0.5
#define CLOUD_OCTAVE_ECCENTRICITY 0.5
float cloudInScatter(float tauToLight, float tauClamp, float cosTheta, float g, float gBack,
                     float backWeight, int phaseKind, int octaves) {
  float sum = 0.0;
  float a = 1.0, b = 1.0, c = 1.0;
  for (int i = 0; i < octaves; ++i) {
    float phase = phaseKind == 1 ? dualLobeHG(cosTheta, c * g, c * gBack, backWeight)
                                 : henyeyGreenstein(cosTheta, c * g);
    sum += b * beerClamped(1.0, a * tauToLight, a * tauClamp) * phase;  // Lu (22) * (23)
    a *= CLOUD_OCTAVE_ATTENUATION;
    b *= CLOUD_OCTAVE_CONTRIBUTION;
    c *= CLOUD_OCTAVE_ECCENTRICITY;
  }
  return sum;
}

// Multiple scattering in the diffusion limit. Light that has scattered many times inside a
// cloud of conservative scatterers (droplets barely absorb) is nearly isotropic, and the share
// of a beam's flux that reaches optical depth tau as such light falls off only as
// 1 / (1 + 3/4 (1 - g) tau): the two-stream (Eddington) diffuse transmittance of a
// non-absorbing slab (Bohren & Clothiaux 2006, "Fundamentals of Atmospheric Radiation" 6.3;
// Meador & Weaver 1980), g the phase function's mean cosine. The octaves above fall off as
// exp(-a^i tau) and leave a cumulus's shadowed base, 50 optical depths from the sunlit top,
// black; the path tracer (docs/cloud-model.md) puts a tenth of the top's light there.
float diffuseTransmittance(float tau, float g) {
  return 1.0 / (1.0 + 0.75 * (1.0 - g) * max(tau, 0.0));
}

// The diffuse field near the cloud's free boundaries. In the two-stream solution for a
// conservative slab (Bohren & Clothiaux 2006, 6.3; Meador & Weaver 1980) the diffuse radiance
// at a face where no diffuse light comes in is about half its value inside (only the outgoing
// stream is there), and it recovers over about
// 1 / (3/4 (1 - g)) optical depths, the scale of diffuseTransmittance. So a point tauBottom
// above the cloud's base and tauTop below its top keeps this share of the diffusion term.
// The path tracer draws a cumulus seen from the side with a sun 3 degrees behind the camera
// bright in its middle and dark at the base (docs/cloud-model.md, "The diffuse field at the
// boundaries"): the term without this lit the whole face evenly and the base twice too
// bright (30.8 % off Cycles, 24 % with).
// What leaves through a boundary is not thinned, and it is not isotropic: the same solution's
// radiance going out through a face is I0 (1 + 3/2 mu), mu the cosine from the face's normal,
// I0 the face's isotropic part (half the interior's), so an eye looking straight into the
// base from below sees 1.25 times the interior's diffuse light and one looking along it half.
// `viewUp` is the view ray's cosine with the local up; each boundary's share goes to
// CLOUD_EMERGENT_PEAK with the square of the cosine of the eye looking into it. A deck seen
// from below was 34 % off Cycles without the term, 28.1 % with it going to 1, 24.0 % going to
// 1.25; with the cosine itself instead of its square 26.7 % (too bright looking obliquely
// into the base), and the cumulus scenes moved by 0.3 points at most (docs/cloud-model.md).
#define CLOUD_EMERGENT_PEAK 1.25
float diffuseBoundaryShare(float tauBottom, float tauTop, float g, float viewUp) {
  float c = 0.75 * (1.0 - g);
  float bottom = (1.0 + c * max(tauBottom, 0.0)) / (2.0 + c * max(tauBottom, 0.0));
  float top = (1.0 + c * max(tauTop, 0.0)) / (2.0 + c * max(tauTop, 0.0));
  float up = max(viewUp, 0.0), down = max(-viewUp, 0.0);
  return mix(bottom, CLOUD_EMERGENT_PEAK, up * up) * mix(top, CLOUD_EMERGENT_PEAK, down * down);
}

// The diffuse light scattered toward the eye per unit of extinction and of illuminance, at
// optical depth tau toward the light: `strength` (clouds.multiple_scattering, calibrated
// against the path tracer, docs/cloud-model.md) times the diffuse transmittance. In the
// renderer's units (illuminance 1 = pi x radiance 1) it is added to pi x the octaves.
float cloudDiffuseInScatter(float tau, float g, float strength) {
  return strength * diffuseTransmittance(tau, g);
}

// The cloud behind a sample, away from the light, is what sends its diffuse light back toward
// the lit face. The terms above take every cloud for a thick slab, whose lit face reflects all
// of the diffuse light that does not pass through; a small cumulus, a few optical depths
// across, lets most of it through and its lit face is dim. In the two-stream solution for a
// conservative slab of total optical depth T (Bohren & Clothiaux 2006, 6.3) the diffuse field
// at the lit face is the reflectance R(T) = cT / (1 + cT), c = 3/4 (1 - g), of what a thick
// one has, and at the far face the transmittance, which diffuseTransmittance already gives;
// between the two it is linear in optical depth. So the diffusion term keeps this share: R(T)
// at the lit face, rising linearly to 1 at the far face, T = tau + tauBehind, tau the optical
// depth toward the light through the sample's own cloud and tauBehind away from it (a large
// tauBehind, the cloud going on past where it was probed: 1). Issue 46, against Cycles on the
// path-traced field with a 3 degree sun behind the camera: 2.8 % too bright and 19.6 % off per
// pixel without it, 0.3 % and 18.5 % with it (docs/cloud-model.md, "The sky that other
// clouds hide").
float diffuseBehindShare(float tau, float tauBehind, float g) {
  float c = 0.75 * (1.0 - g);
  float total = max(tau, 0.0) + max(tauBehind, 0.0);
  if (total <= 0.0) return 1.0;
  float reflectance = c * total / (1.0 + c * total);
  return mix(reflectance, 1.0, clamp(max(tau, 0.0) / total, 0.0, 1.0));
}

// The slab keeps the diffuse light it does not let through; a cumulus cell, about as wide as
// it is tall, loses it through its sides as well, so light toward its far side falls off
// faster. cloudDiffuseInScatter's depth is scaled by this: 1 for stratiform and cellular
// cloud (type up to 0.5), rising to 3 for convective cells (type 1). Calibrated against the
// path tracer: the deck's base and the cumulus's lit/shadowed ratio (docs/cloud-model.md).
float cloudDiffusionLeak(float type) {
  return 1.0 + 2.0 * clamp(2.0 * type - 1.0, 0.0, 1.0);
}

// Tang (6)(7)'s ambient with the diffusion limit. Tang's slab share slabAmbient is the light
// that reaches a point without scattering, E2(tau), gone ten optical depths in. But droplets
// barely absorb: sky light that scatters on is not lost, it diffuses until it leaves through
// some boundary, and the mean radiance inside a conservative scatterer lit from all sides is
// the average of what comes in at its boundaries, each weighted by how near it is in
// diffusion terms (the linear profile of the two-stream solution between two faces, Bohren &
// Clothiaux 2006, 6.3; a cloud in a uniform sky is as bright as the sky, however deep). Four
// boundaries, each with the sky's and the ground's light on a surface facing out of it: the
// layer's top (above) and bottom (below), hTopM and hBottomM away; the face the view ray came
// in through (face), tauView away; and the cloud's far side along the ray (back), taken as far
// as the cloud is thick here less what the ray has crossed (a cumulus cell is about as wide
// as it is tall). The faces stand in for a cumulus's sides: a face turned from a low sun sees
// the darker, bluer sky behind the camera, the far side of a backlit cloud the bright sky
// around the sun. Each weighs its diffuse transmittance from the point. The path tracer
// (docs/cloud-model.md) puts 97 % of a backlit core's light on the sky, and the core at 2.2
// times what halving and attenuating each source gave (the model before issue 30).
// `strength` (clamped to [0, 1]) blends from Tang's (0: half of the light above and below,
// isotropic in-scattering of a hemisphere) to this (1). Returns radiance per unit of
// extinction.
vec3 cloudAmbientDiffuse(vec3 above, vec3 below, vec3 face, vec3 back, float sigmaT, float hTopM,
                         float hBottomM, float tauView, float g, float strength) {
  float k = clamp(strength, 0.0, 1.0);
  float wTop = diffuseTransmittance(sigmaT * hTopM, g);
  float wBottom = diffuseTransmittance(sigmaT * hBottomM, g);
  float wFace = diffuseTransmittance(tauView, g);
  float wBack = diffuseTransmittance(max(sigmaT * (hTopM + hBottomM) - tauView, 0.0), g);
  vec3 diffusion = (wTop * above + wBottom * below + wFace * face + wBack * back) /
                   (wTop + wBottom + wFace + wBack);
  vec3 tang = 0.5 * cloudAmbient(above, below, sigmaT, hTopM, hBottomM);  // Tang (6)(7)
  return mix(tang, diffusion, k);
}

// The sky scattered once by the phase function, for what the diffusion mean above leaves out.
// That mean treats the sky's light as isotropic inside the cloud, which holds where it is
// opaque and the light is diffuse. A thin part (a backlit cloud's silver rim) scatters the sky
// once, mostly forward: before a low sun, from the bright aureole behind it (Cycles lights such
// rims with 4x the sky light the diffusion mean gave; docs/cloud-model.md). `excess` is the
// sky scattered once toward the eye by a ray along the view less its mean radiance,
// P(d) - Lmean (cloud_ambient_shared.h). Light arriving straight along the ray and scattered
// once toward the eye is, through any density along it, the integral of
// sigma(x) T(0, x) T(x, end) dx = tau T (T(0, x) T(x, end) is the whole ray's T): at most 1/e
// of the excess, at tau = 1, and nothing in opaque cloud. The light from behind the camera
// (T(0, x)^2) is taken the same way, which is exact in the thin limit.
vec3 cloudPhaseSkyLight(vec3 excess, float tauTotal, float transmittance) {
  return excess * (tauTotal * transmittance);
}

// Sharp cloud boundaries: real cumulus reach an optical depth of one within tens of metres of
// their edge, but the noise rises over hundreds. 1 - (1 - d)^k rises k times faster at the
// boundary (slope k at d = 0) and keeps 1 at 1, so cores keep their relief. Densities at or
// above 1 (Lu (10)'s GD reaches 2) pass unchanged, and k = 1 is the identity.
float cloudEdgeDensity(float d, float k) {
  if (d >= 1.0) return d;
  return 1.0 - pow(1.0 - max(d, 0.0), k);
}

// A field of clouds seen at a scale that resolves none of them (the far field): the mean
// extinction meanSigma, of which a share `fraction` of the space is cloud with chords chordM
// long, dims a beam not by the mean but at the decay rate of the transmittance through a
// binary Markov mixture of cloud and clear air (Levermore, Pomraning, Sanzo & Wong 1986,
// "Linear transport theory in a random medium"): the smaller root of its two-state equations,
// with tau = the chord's optical depth in cloud and q = fraction / (1 - fraction) the ratio of
// the chords in cloud to the gaps between them, in units of the chord,
//   sigma chord = 2 tau q / (tau + 1 + q + sqrt((tau - q)^2 + 2 (tau + q) + 1)).
// Sparse opaque clouds dim at the rate a beam meets them (about q / chord, not the mean); a
// closed deck (q large) at the mean itself; thin clouds (tau small) at the mean.
float cloudFarExtinction(float meanSigma, float fraction, float chordM) {
  if (meanSigma <= 0.0 || fraction <= 0.0) return 0.0;
  float a = min(fraction, 0.999);
  float q = a / (1.0 - a);
  float tau = meanSigma / a * chordM;
  return 2.0 * tau * q / (tau + 1.0 + q + sqrt((tau - q) * (tau - q) + 2.0 * (tau + q) + 1.0)) /
         chordM;
}

// Hillaire 2016 ("Physically based sky, atmosphere and cloud rendering in Frostbite"): the
// in-scattered light S integrated over a step of length dt with the step's own extinction,
// (S - S exp(-sigmaT dt)) / sigmaT. Summed over steps with the transmittance before each, a
// homogeneous medium gives the exact answer for any step length. For sigmaT dt < 0.01 the
// series dt (1 - x/2 + x^2/6 - x^3/24) replaces 1 - exp(-x), which float cannot resolve there;
// sigmaT -> 0 gives S dt.
vec3 integrateStep(vec3 S, float sigmaT, float dt) {
  float x = sigmaT * dt;
  if (x < 0.01) return S * (dt * (1.0 - x * (0.5 - x * (1.0 / 6.0 - x * (1.0 / 24.0)))));
  return (S - S * exp(-x)) / sigmaT;
}

// The plain Riemann sum of the same step, S dt, for comparison (biased for long steps).
vec3 integrateStepRiemann(vec3 S, float dt) {
  return S * dt;
}

// --- Light march schedule -------------------------------------------------------------------
// n short steps toward the light whose lengths double, so the first samples sit close to the
// point (self-shadowing detail) and the last ones reach far; together they cover exactly
// `distance`. Then one long step over [distance, 5 distance], sampled at its middle (3
// distance), for the shadow of distant cloud (Schneider 2015 takes one far sample the same way).

// Where short step i starts: distance (2^i - 1) / (2^n - 1); distance itself for i >= n.
float lightStepStart(int i, int n, float distance) {
  if (i >= n) return distance;
  return distance * (float(1 << i) - 1.0) / (float(1 << n) - 1.0);
}

// The length of short step i of n (n <= 30); the n lengths sum to `distance`.
float lightStepLength(int i, int n, float distance) {
  return lightStepStart(i + 1, n, distance) - lightStepStart(i, n, distance);
}

// Where the long step samples: 3 distance from the point.
float lightLongStepDistance(float distance) {
  return 3.0 * distance;
}

// The long step's length: it spans [distance, 5 distance].
float lightLongStepLength(float distance) {
  return 4.0 * distance;
}

// How far the whole march reaches (5 distance): the length of the densest path it can see,
// for Lu (22)'s clamp (dsClamp = ac * the largest density * this).
float lightMarchReach(float distance) {
  return distance + lightLongStepLength(distance);
}

#endif
