// The cloud density field of passes/volumetric_clouds at a point: which layer it lies in, the
// weather map's cover and type there, and the density from the baked noise (Lu (3)-(18) or
// Tang). Shared by the raymarch and the density-slice debug view, which bind the same
// parameters and textures at the same slots (declared here). The functions read `params`
// directly: passing the 2 KB struct by value copies it (coverage table included) into every
// call on some compilers (lavapipe's LLVM spilled it, a thousand times slower).
#ifndef SKY_CLOUD_FIELD_GLSL
#define SKY_CLOUD_FIELD_GLSL
#include "params_block.glsl"
#include "volumetric_clouds_shared.h"
#include "geo.glsl"
#include "cloud_density.glsl"
#include "cloud_lighting.glsl"

// The shader variant: the scene's discrete choices as compile-time constants, one pipeline per
// combination, generated from one C++ CloudVariant (passes/volumetric_clouds,
// cloudVariantDefines) whose fields are enums: CLOUD_TOPDOWN (the frame), CLOUD_TANG (the
// model), CLOUD_DUAL_LOBE (the phase), CLOUD_ENERGY_CONSERVING (the step integral),
// CLOUD_CALIBRATED (the coverage), CLOUD_ROLLS (whether the map has stratocumulus rolls),
// CLOUD_CUMULUS (whether it has cumulus, whose sizes spread: cloudCumulusWeight) and, in
// volumetric_clouds.comp, CLOUD_REFERENCE and CLOUD_LIGHT_VOLUME. The compiler then drops
// the unused model and lookups, which on lavapipe (running both sides of every branch) no
// test at run time can. Nothing continuous is among them: a slider never compiles a pipeline.
// Standing alone (the shader tests compile every file on its own) the file takes the default
// scene's choices, with the rolls' and the cumulus sizes' lookups compiled in.
#ifndef CLOUD_TOPDOWN
#define CLOUD_TOPDOWN 0
#endif
#ifndef CLOUD_DUAL_LOBE
#define CLOUD_DUAL_LOBE 1
#endif
#ifndef CLOUD_ENERGY_CONSERVING
#define CLOUD_ENERGY_CONSERVING 1
#endif
#ifndef CLOUD_CALIBRATED
#define CLOUD_CALIBRATED 1
#endif
#ifndef CLOUD_TANG
#define CLOUD_TANG 0
#endif
#ifndef CLOUD_ROLLS
#define CLOUD_ROLLS 1
#endif
#ifndef CLOUD_CUMULUS
#define CLOUD_CUMULUS 1
#endif

// cloudSampleAtLla's `noise`: which noise textures a sample may read at all. Fewer only where
// they would be faded out whatever the footprint; a constant argument lets the compiler drop
// the lookups (lavapipe runs both sides of a branch that depends on a run-time value).
#define CLOUD_NOISE_NONE 0   // the far field's mean alone
#define CLOUD_NOISE_SHAPE 1  // the shape noise, not the detail or the curl
#define CLOUD_NOISE_ALL 2

layout(std140, binding = VOLUMETRIC_CLOUDS_BINDING_PARAMS) uniform CloudParamsBlock {
  CloudParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = VOLUMETRIC_CLOUDS_BINDING_SHAPE) uniform sampler3D shapeNoise;
layout(binding = VOLUMETRIC_CLOUDS_BINDING_DETAIL) uniform sampler3D detailNoise;
layout(binding = VOLUMETRIC_CLOUDS_BINDING_CURL) uniform sampler2D curlNoise;
layout(binding = VOLUMETRIC_CLOUDS_BINDING_WEATHER) uniform sampler2D weatherMap;
layout(binding = VOLUMETRIC_CLOUDS_BINDING_WEATHER_COARSE) uniform sampler2D weatherCoarse;

struct CloudSample {
  float density;  // at the point, weather density scale included (0 outside clouds)
  int layer;      // 0 low, 1 mid, -1 neither
  float ph;       // height fraction inside the cloud's vertical range (Lu's ph)
  float hTop;     // distance up to the top of the cloud's range (m)
  float hBottom;  // distance down to its bottom (m)
  float type;     // the weather map's cloud type (0 stratiform, 0.5 cellular, 1 convective)
  // How far below the coverage threshold the shape alone leaves this point (noise units,
  // >= 0): 0 in or near a cloud and wherever the outline is not resolved. The detail only
  // erodes, so a point with a large clearance lies well outside any cloud and the march may
  // stride there (CLOUD_STRIDE_CLEARANCE in volumetric_clouds.comp).
  float clearance;
  // Inside a layer with cover but above or below the cloud type's vertical range (Lu's ph
  // outside [0, 1]): how far (m of altitude) the range is. The clearance says nothing there,
  // and a stride that ignored this skipped the thin base of a sheet of altocumulus along
  // whole rows of the view. 0 inside the range and where there is no cover.
  float rangeGapM;
  // How much of the clouds' outline the sample resolves (noiseKeep of the shape's R): 1 near,
  // 0 in the far field, where the density is the clouds' effective mean.
  float outline;
  vec2 latLon;    // the point's latitude and longitude (degrees)
};

float coverageLutEntry(int index) {
  return params.coverageLut[index >> 2][index & 3];
}

// The remap threshold for `cover`: the paper's 1 - CMc (Lu (13)(17)), or the calibrated one
// from the table built from the baked noise (passes/volumetric_clouds), bilinear in cover and
// type so a map whose type varies stays continuous.
float coverageThreshold(int layer, float type, float cover) {
  if (CLOUD_CALIBRATED == 0) return 1.0 - cover;
  float x = clamp(cover, 0.0, 1.0) * float(CLOUD_COVERAGE_LUT_SIZE - 1);
  float y = clamp(type, 0.0, 1.0) * float(CLOUD_COVERAGE_TYPE_KEYS - 1);
  int x0 = min(int(x), CLOUD_COVERAGE_LUT_SIZE - 2);
  int y0 = min(int(y), CLOUD_COVERAGE_TYPE_KEYS - 2);
  float fx = x - float(x0), fy = y - float(y0);
  int base = layer * CLOUD_COVERAGE_TYPE_KEYS * CLOUD_COVERAGE_LUT_SIZE;
  int r0 = base + y0 * CLOUD_COVERAGE_LUT_SIZE + x0;
  int r1 = r0 + CLOUD_COVERAGE_LUT_SIZE;
  float a = mix(coverageLutEntry(r0), coverageLutEntry(r0 + 1), fx);
  float b = mix(coverageLutEntry(r1), coverageLutEntry(r1 + 1), fx);
  return mix(a, b, fy);
}

// The far field's mean density and share in cloud (CloudParams.farMeanLut) of a layer at
// `cover` and height fraction ph of a type's range: linear in height between the slices'
// middles (held beyond the outer ones), in cover and in type. engine/render/cloud_field.cpp
// has the CPU twin.
vec2 farMeanEntry(int index) {
  vec4 pair = params.farMeanLut[index >> 1];
  return (index & 1) == 0 ? pair.xy : pair.zw;
}
vec2 farMeanDensity(int layer, float type, float cover, float ph) {
  float x = clamp(cover, 0.0, 1.0) * float(CLOUD_FAR_MEAN_COVERS - 1);
  float y = clamp(type, 0.0, 1.0) * float(CLOUD_COVERAGE_TYPE_KEYS - 1);
  float z = clamp(ph * float(CLOUD_FAR_MEAN_HEIGHTS) - 0.5, 0.0, float(CLOUD_FAR_MEAN_HEIGHTS - 1));
  int x0 = min(int(x), CLOUD_FAR_MEAN_COVERS - 2);
  int y0 = min(int(y), CLOUD_COVERAGE_TYPE_KEYS - 2);
  int z0 = min(int(z), CLOUD_FAR_MEAN_HEIGHTS - 2);
  float fx = x - float(x0), fy = y - float(y0), fz = z - float(z0);
  vec2 v[2];
  for (int t = 0; t < 2; ++t) {
    int row = ((layer * CLOUD_COVERAGE_TYPE_KEYS + y0 + t) * CLOUD_FAR_MEAN_COVERS + x0) *
              CLOUD_FAR_MEAN_HEIGHTS + z0;
    int next = row + CLOUD_FAR_MEAN_HEIGHTS;  // the next cover entry
    v[t] = mix(mix(farMeanEntry(row), farMeanEntry(row + 1), fz),
               mix(farMeanEntry(next), farMeanEntry(next + 1), fz), fx);
  }
  return mix(v[0], v[1], fy);
}

// Point p of the frame in ECEF axes relative to the camera (m). Added to a texture's origin
// (shapeOrigin, detailOrigin) it gives the point's Earth-fixed noise position, so the noise
// stays with the ground (and the wind) when the camera moves.
vec3 ecefOffset(vec3 p) {
  return p.x * params.geo.east.xyz + p.y * params.geo.north.xyz + p.z * params.geo.up.xyz;
}

// Level of detail by footprint: how much of a noise channel whose cells are `cellM` wide a
// sample `footprintM` wide (a pixel's width at its distance) can resolve. 1 (keep) up to an
// eighth of a cell, 0 (replace by the channel's mean) from half a cell, two samples a cell,
// where the channel would alias into speckle (docs/clouds.md, the horizon).
float noiseKeep(float footprintM, float cellM) {
  return 1.0 - smoothstep(0.125, 0.5, footprintM / cellM);
}

// CLOUD_FAR_DENSITY, CLOUD_FAR_CHORD and CLOUD_FAR_MARKOV_CHORD, the far field's mean and
// clumping, are in volumetric_clouds_shared.h: the CPU twin (engine/render/cloud_field.cpp)
// reads them too.

// The outline's cell for a cloud of cumulus weight w: R's, a quarter of the shape repeat
// `shapeCellM`, for cellular cloud; a sixth for cumulus, whose smallest clouds
// (cumulusOutline's fine population, G's cells) are an eighth. A pixel wider than that sees
// the clouds' mean (the far field). At R's cell the small clouds of a field at the horizon
// were hit or missed at random from pixel to pixel: 4.9 times the variance between
// neighbours of a supersampled render (CloudLookTest.TheHorizonBandIsNoNoisierThanA
// SupersampledRender, 3.5 allowed); a sixth gives 3.0, a fifth 4.0. At G's own eighth, 1.6,
// but the mean then stood for clouds a still resolves: the sunset still backlit by a 3 degree
// sun fell from 45.6 to 34.7 dB against the reference march (38.8 at a sixth;
// CloudStills.ComeWithin35DbOfTheReference).
float cloudOutlineCell(float shapeCellM, float w) {
  return shapeCellM / mix(4.0, 6.0, w);
}

// The far field's cloud chord (cloudFarExtinction), in outline cells, for a cloud of cumulus
// weight w: CLOUD_FAR_MARKOV_CHORD for cellular cloud, CLOUD_FAR_MARKOV_CHORD_CUMULUS for
// cumulus, whose many small clouds (cumulusOutline) are shorter along a path.
float cloudFarChord(float w) {
  return mix(CLOUD_FAR_MARKOV_CHORD, CLOUD_FAR_MARKOV_CHORD_CUMULUS, w);
}

// The cloud at point p, whose latitude, longitude (degrees) and altitude are lla, seen by a
// sample `footprintM` wide (0: full detail). Returns false where no cloud can be (outside
// both layers, outside the weather region, or, with `coarseCheck`, where the coarse map has
// no cover nearby): the caller may step faster there. `s.density` is 0 then. A caller that
// only wants the density skips the coarse check: the weather map's cover is 0 there too.
// `noise` (CLOUD_NOISE_*): the textures it may read.
bool cloudSampleAtLla(vec3 p, vec3 lla, float footprintM, bool coarseCheck, int noise,
                      out CloudSample s) {
  s.density = 0.0;
  s.layer = -1;
  s.ph = 0.0;
  s.hTop = 0.0;
  s.hBottom = 0.0;
  s.type = 0.0;
  s.clearance = 1.0;  // no cloud can be here
  s.rangeGapM = 0.0;
  s.outline = 1.0;
  s.latLon = lla.xy;
  float h = lla.z;
  int layer = (h >= params.lowBaseM && h <= params.lowTopM)   ? 0
              : (h >= params.midBaseM && h <= params.midTopM) ? 1
                                                              : -1;
  if (layer < 0) return false;
  vec2 uv;
  if (!regionUv(params.region, lla.x, lla.y, uv)) return false;  // Lu: only inside the region
  // The coarse map holds the largest cover around each block, dilated by a block, so a
  // bilinear value of 0 means no cover anywhere near.
  if (coarseCheck) {
    vec2 coarse = textureLod(weatherCoarse, uv, 0.0).rg;
    if ((layer == 0 ? coarse.r : coarse.g) <= 0.0) return false;
  }
  s.layer = layer;
  vec4 w = textureLod(weatherMap, uv, 0.0);
  float cover = layer == 0 ? w.r : w.g;
  float type = w.b;
  s.type = type;
  float base = layer == 0 ? params.lowBaseM : params.midBaseM;
  float top = layer == 0 ? params.lowTopM : params.midTopM;
  float f = (h - base) / (top - base);
  vec2 range = cloudTypeRange(layer, type);
  s.ph = cloudHeightFraction(f, range);
  s.hTop = max(range.y - f, 0.0) * (top - base);
  s.hBottom = max(f - range.x, 0.0) * (top - base);
  if (cover > 0.0) s.rangeGapM = max(max(range.x - f, f - range.y), 0.0) * (top - base);
  if (cover <= 0.0 || s.ph < 0.0 || s.ph > 1.0) return true;
  s.clearance = 0.0;

  // Far away a sample spans whole clouds (the shape's R has 4 cells a repeat), and the field
  // there is drawn as a smooth medium instead of the speckle of clouds hit and missed at
  // random. Where the outline is not resolved at all no noise is read (the far light step,
  // most samples near the horizon). A field of separate opaque clouds dims a ray by the
  // clouds it meets, not by their density spread out: the mean alone was an opaque haze of
  // 60 m mean free path, under which the light from a low sun crossed a hundred optical
  // depths (docs/clouds.md, "The horizon"). With calibrated coverage the density is the
  // measured mean per height seen through a Markov mixture (cloudFarExtinction). The paper's
  // coverage takes the cover times the height profile times CLOUD_FAR_DENSITY, times the
  // clumping factor (1 - e^-tau) / tau of a cloud's optical depth tau across a chord of
  // CLOUD_FAR_CHORD of its cell.
  const bool tang = CLOUD_TANG != 0;
  // Lu's height profile (6)(10) and erosion (15) read CMc too: a cell at 30 % cover gets
  // clouds only 30 % of the layer tall and a third as dense, which no threshold can make look
  // 30 % covered. Calibrated coverage therefore evaluates them as for full cover (the shape of
  // a well-developed cloud) and leaves the cover to the calibrated threshold alone; the paper's
  // mode keeps CMc everywhere. engine/clouds/coverage_calibration.h calibrates the same way.
  float profileCover = CLOUD_CALIBRATED != 0 ? 1.0 : cover;
  float shapeCellM = 1.0 / params.shapeRepeatsPerM;
  // How much of the cloud is shaped as cumulus (cloudCumulusWeight): its outline, profile and
  // billows. 0 where the map has none (the variant without the lookups).
  float cumulus = CLOUD_CUMULUS != 0 ? cloudCumulusWeight(type) : 0.0;
  // The outline is resolved down to R's cells (a quarter of the repeat), a cumulus' down to a
  // sixth of it, where the far field takes over (cloudOutlineCell).
  float keepOutline = noiseKeep(footprintM, cloudOutlineCell(shapeCellM, cumulus));
  float profile = tang ? tangTypeGradient(s.ph, type) : cumulusGD(s.ph, profileCover, cumulus);
  s.outline = keepOutline;
  float farDensity;
  if (CLOUD_CALIBRATED != 0) {
    // Calibrated coverage knows the clouds' mean and their share of the space at each height
    // (farMeanLut), and dims by the Markov mixture of the two (cloudFarExtinction).
    vec2 far = farMeanDensity(layer, type, cover, s.ph);
    float sigma = params.extinction * w.a;
    farDensity = sigma > 0.0 ? cloudFarExtinction(sigma * far.x, far.y,
                                                  cloudFarChord(cumulus) * shapeCellM / 4.0) / sigma
                             : 0.0;
  } else {
    float cellTau = params.extinction * profile * w.a * CLOUD_FAR_DENSITY * CLOUD_FAR_CHORD *
                    shapeCellM / 4.0;
    float clump = cellTau > 1e-4 ? (1.0 - exp(-cellTau)) / cellTau : 1.0;
    farDensity = cover * profile * CLOUD_FAR_DENSITY * clump;
  }
  s.density = farDensity * w.a;
  if (keepOutline <= 0.0 || noise == CLOUD_NOISE_NONE) return true;

  vec3 offset = ecefOffset(p);
  // Stratocumulus runs in rolls along the wind (cloudRollWeight): the shape noise stretched
  // along params.rollAxis. Between cells and rolls the two lookups are blended.
  float roll = CLOUD_ROLLS != 0 ? cloudRollWeight(layer, type) : 0.0;
  vec4 shape = vec4(0.0);
  if (roll < 1.0)
    shape =
        textureLod(shapeNoise, (params.shapeOrigin.xyz + offset) * params.shapeRepeatsPerM, 0.0);
  if (roll > 0.0) {
    vec3 rolled = params.rollOrigin.xyz + offset -
                  params.rollCompression * dot(offset, params.rollAxis.xyz) * params.rollAxis.xyz;
    shape = mix(shape, textureLod(shapeNoise, rolled * params.shapeRepeatsPerM, 0.0), roll);
  }
  // Cumulus take their outline from the shape noise at three scales (cumulusOutline), so their
  // sizes range over a decade; the other types keep R's cells. The slower lookups have their
  // own origin, reduced by whole repeats of theirs (CLOUD_CUMULUS_REPEAT_SHAPES shape repeats).
  // Read from the texture as it is, before the level of detail below: R is the outline, which
  // stays resolved until the far field takes over (keepOutline).
  if (cumulus > 0.0) {
    vec3 quarter = (params.cumulusOrigin.xyz + offset) *
                   (params.shapeRepeatsPerM / float(CLOUD_CUMULUS_REPEAT_SHAPES));
    shape = cumulusShape(shape, textureLod(shapeNoise, 2.0 * quarter, 0.0),
                         textureLod(shapeNoise, quarter, 0.0), params.shapeMean.r, cumulus);
  }
  // Shape channels G, B, A are Worley fbm at 8, 16 and 32 cells a repeat (docs/cloud-noise.md);
  // R (4 cells) stays: it is the cloud's outline, and a metre-wide pixel at 100 km still
  // resolves it.
  // A stratiform type keeps less of the fine structure at any footprint (cloudTypeTexture).
  float typeKeep = cloudTypeTexture(type);
  vec3 keepShape = typeKeep * vec3(noiseKeep(footprintM, shapeCellM / 8.0),
                                   noiseKeep(footprintM, shapeCellM / 16.0),
                                   noiseKeep(footprintM, shapeCellM / 32.0));
  shape.gba = mix(params.shapeMean.gba, shape.gba, keepShape);
  vec3 dq = (params.detailOrigin.xyz + offset) * params.detailRepeatsPerM;
  // Detail R, G, B: Worley fbm at 2, 4, 8 cells (lu2023) or 4, 8, 16 (tang2019).
  float detailCellM = 1.0 / params.detailRepeatsPerM / (CLOUD_TANG != 0 ? 4.0 : 2.0);
  vec3 keepDetail = typeKeep * vec3(noiseKeep(footprintM, detailCellM),
                                    noiseKeep(footprintM, detailCellM / 2.0),
                                    noiseKeep(footprintM, detailCellM / 4.0));
  float threshold = coverageThreshold(layer, type, cover);
  // The detail noise only erodes (Lu (18), Tang's erosion): where the shape alone leaves no
  // cloud there is none, and the costly detail lookup is skipped.
  float nstex = luNStex(shape);  // Lu (12)
  float gs = luGS(s.ph, profileCover);  // Lu (7)
  float baseShape = tang ? tangBaseShape(shape, s.ph, type) : nstex * gs;
  float shapeOnly = tang ? tangDensity(baseShape, 0.0, cover, threshold)
                         : luNSfinal(nstex, gs, threshold);  // Lu (17)
  // Only where the outline is fully resolved does the shape bound the cloud.
  if (keepOutline >= 1.0) s.clearance = max(threshold - baseShape, 0.0);
  s.density = mix(farDensity, 0.0, keepOutline) * w.a;
  if (shapeOnly <= 0.0) return true;
  // Detail finer than the sample resolves is its mean: when none of it is resolved (light
  // samples of the longer steps), nothing is read.
  bool anyDetail = keepDetail.x > 0.0 && noise == CLOUD_NOISE_ALL;
  vec3 detail = params.detailMean.rgb;
  if (anyDetail) {
    // Curl noise bends the detail lookup, more toward the bottom, so the erosion swirls into
    // wisps there instead of repeating the detail texture's cells (Tang; Schneider 2015). Lu
    // has no curl term; ours takes Tang's. The bend leaves the detail's distribution as it
    // is, so the coverage calibration, which reads the detail unbent, still holds.
    vec2 ground = params.curlOrigin.xy + p.xy;  // east, north on the camera's ground plane
    vec3 curl = textureLod(curlNoise, ground * params.curlRepeatsPerM, 0.0).xyz * 2.0 - 1.0;
    dq += curl * params.curlStrength * (1.0 - s.ph);
    detail = mix(detail, textureLod(detailNoise, dq, 0.0).rgb, keepDetail);
  }
  float density = tang ? tangCloudDensity(shape, detail, s.ph, cover, type, threshold)
                       : cumulusCloudDensity(shape, detail, s.ph, profileCover, threshold, cumulus);
  // The boundary can be no sharper than the sample resolves: the gain falls to 1 as the
  // shape's medium octave (G) fades (and, with it, for stratiform cloud).
  float sharpness = mix(1.0, params.edgeSharpness, keepShape.x);
  s.density = mix(farDensity, cloudEdgeDensity(density, sharpness), keepOutline) * w.a;
  return true;
}

// cloudSampleAtLla at p with its exact latitude, longitude and altitude.
bool cloudSampleAt(vec3 p, float footprintM, out CloudSample s) {
  return cloudSampleAtLla(p, latLonAltitude(params.geo, p), footprintM, true, CLOUD_NOISE_ALL, s);
}

#endif
