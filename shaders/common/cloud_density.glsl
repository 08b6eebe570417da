// Cloud density for the volumetric low and mid clouds: Lu et al. 2023 (3)-(18) function by
// function, the cloud types through the weather map's type channel, and Tang et al. 2019's
// Simplex-Worley density (which follows Schneider 2015). Every function has a C++ twin of the
// same name in engine/clouds/cloud_math.h; tests/clouds compares the two on a grid of inputs.
// docs/cloud-model.md explains the choices.
//
// Inputs are the raw texture samples: `shape` is the shape texture's RGBA (Lu Table 1: R
// low-frequency Perlin-Worley, GBA Worley of rising frequency; Tang: R Simplex, GBA Worley),
// `detail` the detail texture's RGB (Worley of rising frequency), all in [0, 1]. `ph` is the
// height fraction inside the cloud (cloudHeightFraction), `cmc` the weather map's cover.
#ifndef SKY_CLOUD_DENSITY_GLSL
#define SKY_CLOUD_DENSITY_GLSL

// Lu (3): remap v from [lo, ho] to [ln, hn] (no clamping; lo != ho).
float luRemap(float v, float lo, float ho, float ln, float hn) {
  return ln + (v - lo) * (hn - ln) / (ho - lo);
}

// Lu (4): clamp to [0, 1].
float luSat(float v) {
  return clamp(v, 0.0, 1.0);
}

// Lu (16): linear interpolation, extrapolating outside t in [0, 1].
float luLerp(float v0, float v1, float t) {
  return (1.0 - t) * v0 + t * v1;
}

// Lu (5): rounds the cloud toward its base (0 at ph = 0, 1 from ph = 0.07).
float luGSb(float ph) {
  return luSat(luRemap(ph, 0.0, 0.07, 0.0, 1.0));
}

// Lu (6): rounds the cloud toward its top, which lies at ph = CMc. At CMc = 0 the remap's
// range is empty; its limit for ph > 0 is 0 (no cloud), which is returned for every ph.
float luGSt(float ph, float cmc) {
  if (cmc <= 0.0) return 0.0;
  return luSat(luRemap(ph, cmc * 0.2, cmc, 1.0, 0.0));
}

// Lu (7): the shape-altering height function.
float luGS(float ph, float cmc) {
  return luGSb(ph) * luGSt(ph, cmc);
}

// Lu (8): density grows with height, and more steeply below ph = 0.15 (wispy bases).
float luGDb(float ph) {
  return ph * luSat(luRemap(ph, 0.0, 0.15, 0.0, 1.0));
}

// Lu (9): soft fade over the top tenth.
float luGDt(float ph) {
  return luSat(luRemap(ph, 0.9, 1.0, 1.0, 0.0));
}

// Lu (10): the density-altering height function; CMc * 2 makes cover above 0.5 denser.
float luGD(float ph, float cmc) {
  return luGDb(ph) * luGDt(ph) * cmc * 2.0;
}

// Lu (11): the three-octave fbm with the paper's weights 0.625, 0.25, 0.125 (sum 1).
float luFbm(float n1, float n2, float n3) {
  return 0.625 * n1 + 0.25 * n2 + 0.125 * n3;
}

// Lu (12): the low-frequency Perlin-Worley (R) remapped by the Worley fbm of G, B, A. With all
// channels in [0, 1] the result lies in [0, 1] and the denominator 2 - fbm in [1, 2].
float luNStex(vec4 shape) {
  return luRemap(shape.r, luFbm(shape.g, shape.b, shape.a) - 1.0, 1.0, 0.0, 1.0);
}

// Lu (17): the shape noise shaped by GS and remapped by the coverage threshold. The paper's
// threshold is 1 - CMc; the calibrated coverage passes a threshold from the coverage LUT
// (engine/clouds/coverage_calibration.h). Thresholds at or above 1 leave no cloud (the remap
// would divide by zero or flip sign); thresholds below 0 are allowed (dense cover).
float luNSfinal(float nstex, float gs, float threshold) {
  if (threshold >= 1.0) return 0.0;
  return luSat(luRemap(nstex * gs, threshold, 1.0, 0.0, 1.0));
}

// Lu (13): the shape-only density, (17) times GD.
float luNS(float nstex, float gs, float threshold, float gd) {
  return luNSfinal(nstex, gs, threshold) * gd;
}

// Lu (14): the detail texture's Worley octaves through the fbm of (11).
float luNDfbm(vec3 detail) {
  return luFbm(detail.r, detail.g, detail.b);
}

// Lu (15): the erosion strength: at most 0.35, weaker under dense cover; wispy (fbm) at the
// base turning billowy (1 - fbm) above ph = 0.2.
float luNDmod(float ndfbm, float cmc, float ph) {
  return 0.35 * exp(-cmc * 0.75) * luLerp(ndfbm, 1.0 - ndfbm, luSat(ph * 5.0));
}

// Lu (18): the shape eroded by the detail (NDmod <= 0.35, so the remap is well defined), times GD.
float luDensity(float nsfinal, float ndmod, float gd) {
  return luSat(luRemap(nsfinal, ndmod, 1.0, 0.0, 1.0)) * gd;
}

// Lu (12)-(18) composed: the density at a sample, 0 outside the cloud (ph outside [0, 1]).
float luCloudDensity(vec4 shape, vec3 detail, float ph, float cmc, float threshold) {
  if (ph < 0.0 || ph > 1.0) return 0.0;
  float nstex = luNStex(shape);                               // Lu (12)
  float nsfinal = luNSfinal(nstex, luGS(ph, cmc), threshold);  // Lu (17), (7)
  float ndmod = luNDmod(luNDfbm(detail), cmc, ph);             // Lu (14), (15)
  return luDensity(nsfinal, ndmod, luGD(ph, cmc));             // Lu (18), (10)
}

// --- Cloud types ---------------------------------------------------------------------------
// The map's type channel t picks how much of the layer a cloud fills: 0 stratiform, 0.5
// cellular, 1 convective, linear in between. [bottom, top] as fractions of the layer, chosen
// from typical thicknesses (WMO International Cloud Atlas; default layers: low 500-2500 m,
// i.e. 2 km, mid 3000-6500 m, i.e. 3.5 km):
//   low  t = 0   stratus        [0, 0.25]: 500 m; St is a few hundred metres thick
//        t = 0.5 stratocumulus  [0, 0.45]: 900 m; Sc sheets are 200 m to 1 km thick
//        t = 1   cumulus        [0, 1]:    2 km; Cu mediocris/congestus tops 1-3 km above base
//   mid  t = 0   altostratus    [0.1, 0.45]: 1.2 km; As is 1 km to a few km thick
//        t = 0.5 altocumulus    [0.15, 0.4]: 0.9 km; Ac layers are thin (a few hundred m to 1 km)
//        t = 1   convective mid [0.1, 0.75]: 2.3 km; Ac castellanus towers
// The mid keys start above the layer base so that a mid cloud never touches a low one in the
// default layers; the low keys start at the base (condensation level) as low clouds do.
vec2 cloudTypeRange(int layer, float t) {
  vec2 k0 = layer == 0 ? vec2(0.0, 0.25) : vec2(0.1, 0.45);
  vec2 k1 = layer == 0 ? vec2(0.0, 0.45) : vec2(0.15, 0.4);
  vec2 k2 = layer == 0 ? vec2(0.0, 1.0) : vec2(0.1, 0.75);
  float s = clamp(t, 0.0, 1.0) * 2.0;
  // Between two valid ranges (bottom < top) the interpolated range stays valid.
  return s < 1.0 ? mix(k0, k1, s) : mix(k1, k2, s - 1.0);
}

// How much of the noise's fine structure a cloud of type t keeps: 0 for stratiform cloud
// (stratus, altostratus), 1 from cellular on, smooth between. Our choice, not Lu's or Tang's
// (their density reads the type only through the height range): the shape's G, B, A octaves,
// the detail and the boundary sharpening fade with it, so a stratiform layer is a smooth sheet
// shaped by the shape's low octave alone instead of the cells an altocumulus shows.
float cloudTypeTexture(float t) {
  return smoothstep(0.0, 0.5, t);
}

// How much a low cloud of type t runs in rolls along the wind instead of round cells: 1 for
// stratocumulus (t = 0.5), fading to 0 by t = 0.2 and t = 0.8, and 0 in the mid layer
// (altocumulus keeps its small round cells). Our choice, after the boundary-layer rolls that
// line stratocumulus up in streets along the mean wind (Atkinson & Zhang 1996, "Mesoscale
// shallow convection in the atmosphere", Rev. Geophys. 34); neither paper has them. The
// caller stretches the shape noise along the wind by this share (cloud_field.glsl).
float cloudRollWeight(int layer, float t) {
  if (layer != 0) return 0.0;
  return 1.0 - smoothstep(0.2, 0.3, abs(t - 0.5));
}

// --- Cumulus (issue 46) -------------------------------------------------------------------
// Fair-weather cumulus differ from the cellular types in three ways this section gives them:
// their sizes range over a decade (cumulusOutline), their bases are flat and dense
// (cumulusGD), their tops billow (cumulusNDmod). Our choices; docs/cloud-model.md, "Cumulus
// shapes", has the measurements.

// How much of a cloud of type t is shaped as cumulus: 0 up to cellular cloud (t = 0.5), 1 for
// convective cloud (t = 1), smooth between. Stratocumulus rolls and altocumulus keep R's regular
// cells, because real ones are regular: their cells are all about as wide as the layer's depth
// makes them (open and closed cells, rolls), where the sizes of fair-weather cumulus range over a
// decade (Sengupta, Welch, Navar, Berendes & Chen 1990, J. Appl. Meteor. 29: the number per unit
// of diameter falls as D^-1.4..-2.3 below about 1 km, more steeply above).
float cloudCumulusWeight(float t) {
  return smoothstep(0.5, 1.0, t);
}

// The outline of a field of cumulus whose sizes range over a decade, from three lookups of the
// shape noise: the Worley fbm of its G channel at three scales (cells at the default 5 km
// repeat), `blobFine` at G's own frequency (625 m cells), `blobMid` at half of it (1.25 km),
// `blobCoarse` at a quarter (2.5 km), and `sizeField`, R at a quarter of its frequency less R's
// mean (Perlin-Worley, 5 km cells). The size field s = SAT(2 sizeField + 0.5) says which
// population a place holds, 0 small clouds to 1 large ones: the mid and coarse populations are
// lowered by 0.6 per unit of s away from their own places (0.5 and 1), the fine one by only 0.3
// away from 0, so small clouds also dot the clusters of large ones; the outline is the highest
// of the three. So clusters of large clouds, clear sky and small clouds between, as real fields
// group under the mesoscale circulation. Measured on top-down frames 40 km square at 40 %
// cover (CumulusShapeTest.SizesSpreadAsMeasuredFieldsDo): the number per unit of diameter falls
// as D^-1.8..-2.1 below 1 km and D^-3.0..-3.3 above, inside Sengupta's ranges; with the fine
// population lowered by 0.6 too it fell as D^-1.1..-1.5 below 1 km, too few small clouds. Inverted Worley cells are round, so each
// population's clouds stay apart at 40 % cover, where the thresholded Perlin-Worley of R is a
// network that joins them across the map (and R with a lower octave added, which raises and
// lowers the cover by regions, joins them more). In [0, 1].
float cumulusOutline(float blobFine, float blobMid, float blobCoarse, float sizeField) {
  float s = luSat(2.0 * sizeField + 0.5);
  float fine = blobFine - 0.3 * s;
  float mid = blobMid - 0.6 * abs(s - 0.5);
  float coarse = blobCoarse - 0.6 * (1.0 - s);
  return luSat(max(fine, max(mid, coarse)));
}

// The shape sample of a cloud whose cumulus weight (cloudCumulusWeight) is `w`: R mixed toward
// cumulusOutline of `shape` (the lookup at the point), `shapeHalf` and `shapeQuarter` (at a half
// and a quarter of the frequency); G, B, A as they are. `meanR`: R's mean over the texture. The
// caller passes the result to Lu (12) as the shape.
vec4 cumulusShape(vec4 shape, vec4 shapeHalf, vec4 shapeQuarter, float meanR, float w) {
  float outline = cumulusOutline(shape.g, shapeHalf.g, shapeQuarter.g, shapeQuarter.r - meanR);
  return vec4(mix(shape.r, outline, w), shape.gba);
}

// Lu (10) with a flat, dense base for cumulus: GDb (8) grows as ph^2 over the lowest 15 %, so the
// lowest 150-200 m of a 1.5 km cumulus hold almost nothing and the base seen from below is the
// soft, bulging surface where the optical depth reaches 1 (higher in the middle than at the
// edges). A cumulus' liquid water grows linearly with height above the condensation level
// (the adiabatic cloud), its droplets grow in number-conserving ascent, and so the extinction
// grows as height^(2/3) (the adiabatic model of Brenguier, Pawlowska, Schuller, Preusker, Fischer
// & Fouquart 2000, J. Atmos. Sci. 57): ph^(2/3) replaces GDb by `w`. At ph = 0.5 it is 26 %
// denser than GDb, at ph = 0.05 8 times, and the base reads as a surface.
float cumulusGD(float ph, float cmc, float w) {
  if (w <= 0.0) return luGD(ph, cmc);
  float adiabatic = pow(max(ph, 0.0), 2.0 / 3.0);
  return mix(luGDb(ph), adiabatic, w) * luGDt(ph) * cmc * 2.0;
}

// Lu (15) with the billows of cumulus at full strength: Lu weakens the erosion by exp(-0.75 CMc)
// for dense cover, and the calibrated coverage (which gives the height functions CMc = 1)
// always takes it at its weakest, 0.165, which leaves a cumulus' top a smooth ball. For `w` the
// billowy (1 - NDfbm) part above ph = 0.2 takes the strength 0.35, Lu's at CMc = 0 and Schneider's
// (2015), so the inverted Worley cells of the detail stand out as rounded billows at three
// scales; the wispy base keeps Lu's.
float cumulusNDmod(float ndfbm, float cmc, float ph, float w) {
  if (w <= 0.0) return luNDmod(ndfbm, cmc, ph);
  float wispy = 0.35 * exp(-cmc * 0.75);
  float billowy = mix(wispy, 0.35, w);
  return luLerp(wispy * ndfbm, billowy * (1.0 - ndfbm), luSat(ph * 5.0));
}

// Lu (12)-(18) composed with the cumulus profile and billows of weight `w` (luCloudDensity
// for w = 0). `shape` is cumulusShape's.
float cumulusCloudDensity(vec4 shape, vec3 detail, float ph, float cmc, float threshold, float w) {
  if (w <= 0.0) return luCloudDensity(shape, detail, ph, cmc, threshold);
  if (ph < 0.0 || ph > 1.0) return 0.0;
  float nsfinal = luNSfinal(luNStex(shape), luGS(ph, cmc), threshold);  // Lu (17), (12), (7)
  float ndmod = cumulusNDmod(luNDfbm(detail), cmc, ph, w);               // Lu (14), (15)
  return luDensity(nsfinal, ndmod, cumulusGD(ph, cmc, w));               // Lu (18), (10)
}

// Lu's ph: the height fraction inside the cloud's [bottom, top] (layer fractions). Outside the
// cloud it is < 0 or > 1, and every density function returns 0 there.
float cloudHeightFraction(float layerFraction, vec2 range) {
  return (layerFraction - range.x) / (range.y - range.x);
}

// --- Tang et al. 2019 (after Schneider 2015) -----------------------------------------------
// Tang gives no density formula beyond "sample the noises and the cover"; they follow
// Schneider 2015 (GPU Pro 7, "Real-time volumetric cloudscapes"), which we write out here.

// The type's height gradient inside the cloud: a linear rise over [0, up] and a fall over
// [down, 1], with (up, down) per type, interpolated like cloudTypeRange. Our choice (Schneider
// gives curves per type over the whole layer; the layer part is already in cloudTypeRange):
// stratiform (0.1, 0.75) a flat slab with soft faces, cellular (0.2, 0.55) rounded above and
// below, convective (0.1, 0.5) a flat base and a dome that the threshold turns into towers.
float tangTypeGradient(float ph, float type) {
  float s = clamp(type, 0.0, 1.0) * 2.0;
  vec2 k = s < 1.0 ? mix(vec2(0.1, 0.75), vec2(0.2, 0.55), s)
                   : mix(vec2(0.2, 0.55), vec2(0.1, 0.5), s - 1.0);
  return luSat(luRemap(ph, 0.0, k.x, 0.0, 1.0)) * luSat(luRemap(ph, k.y, 1.0, 1.0, 0.0));
}

// Tang's base shape: the Simplex (R) remapped by the Worley fbm of G, B, A (Schneider's
// Perlin-Worley remap, the same formula as Lu (12), with Lu's fbm weights (11): Tang's fbm (1)
// leaves them open), times the type's height gradient.
float tangBaseShape(vec4 shape, float ph, float type) {
  return luNStex(shape) * tangTypeGradient(ph, type);
}

// Tang's erosion: the detail fbm (the caller has already perturbed the detail lookup with curl
// noise), wispy at the base turning billowy above ph = 0.1, with Schneider's strength 0.2.
float tangErosion(float ndfbm, float ph) {
  return luLerp(ndfbm, 1.0 - ndfbm, luSat(ph * 10.0)) * 0.2;
}

// Tang's density from its parts: the coverage remap with `threshold` (paper: 1 - cover; at or
// above 1 no cloud, as in luNSfinal), the erosion remap (erosion <= 0.2, so it is well
// defined), times the cover (Schneider: sparse cover gives thinner clouds). Our choice of order:
// Schneider scales by the cover before eroding, which erases every cloud once the cover drops
// below the erosion (about 0.1); scaling last, as Lu (18) applies GD, keeps thin cover visible.
float tangDensity(float base, float erosion, float cover, float threshold) {
  if (threshold >= 1.0) return 0.0;
  float covered = luSat(luRemap(base, threshold, 1.0, 0.0, 1.0));
  return luSat(luRemap(covered, erosion, 1.0, 0.0, 1.0)) * cover;
}

// Tang's density at a sample, 0 outside the cloud (ph outside [0, 1]).
float tangCloudDensity(vec4 shape, vec3 detail, float ph, float cover, float type, float threshold) {
  if (ph < 0.0 || ph > 1.0) return 0.0;
  return tangDensity(tangBaseShape(shape, ph, type), tangErosion(luNDfbm(detail), ph), cover,
                     threshold);
}

#endif
