#pragma once
// The C++ twins of shaders/common/cloud_density.glsl, cloud_lighting.glsl and
// cloud_light_march.glsl: same names, same float maths, so the CPU (coverage calibration,
// tests) and the GPU agree. tests/clouds compares every function with its GLSL twin; the
// comments on the GLSL side say what each equation is. All functions are pure.
#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "shaders/common/cloud_light_march_shared.h"

namespace sky::clouds {

// --- Density, cloud_density.glsl: Lu (3)-(18), cloud types, Tang ---
// Defined here (inline) so that the coverage calibration's inner loop inlines them.
// luCloudDensity: Lu (12)-(18) composed, 0 outside ph in [0, 1]; threshold 1 - cmc ('paper') or
// the LUT's. cloudTypeRange: [bottom, top] layer fractions of a cloud of type t (0 stratiform,
// 0.5 cellular, 1 convective) in layer 0 (low) or 1 (mid). cloudHeightFraction: Lu's ph inside
// that range (< 0 or > 1 outside the cloud). tang*: Tang's density and its parts.
// cloudCumulusWeight, cumulusOutline, cumulusShape, cumulusGD, cumulusNDmod,
// cumulusCloudDensity: cumulus (issue 46), the shape before Lu (12), Lu (10) and (15) for it.
inline float luRemap(float v, float lo, float ho, float ln, float hn) {
  return ln + (v - lo) * (hn - ln) / (ho - lo);  // Lu (3)
}

inline float luSat(float v) {
  return std::clamp(v, 0.0f, 1.0f);  // Lu (4)
}

inline float luLerp(float v0, float v1, float t) {
  return (1.0f - t) * v0 + t * v1;  // Lu (16)
}

inline float luGSb(float ph) {
  return luSat(luRemap(ph, 0.0f, 0.07f, 0.0f, 1.0f));  // Lu (5)
}

inline float luGSt(float ph, float cmc) {
  if (cmc <= 0.0f) return 0.0f;                            // the limit of an empty remap range
  return luSat(luRemap(ph, cmc * 0.2f, cmc, 1.0f, 0.0f));  // Lu (6)
}

inline float luGS(float ph, float cmc) {
  return luGSb(ph) * luGSt(ph, cmc);  // Lu (7)
}

inline float luGDb(float ph) {
  return ph * luSat(luRemap(ph, 0.0f, 0.15f, 0.0f, 1.0f));  // Lu (8)
}

inline float luGDt(float ph) {
  return luSat(luRemap(ph, 0.9f, 1.0f, 1.0f, 0.0f));  // Lu (9)
}

inline float luGD(float ph, float cmc) {
  return luGDb(ph) * luGDt(ph) * cmc * 2.0f;  // Lu (10)
}

inline float luFbm(float n1, float n2, float n3) {
  return 0.625f * n1 + 0.25f * n2 + 0.125f * n3;  // Lu (11)
}

inline float luNStex(glm::vec4 shape) {
  return luRemap(shape.r, luFbm(shape.g, shape.b, shape.a) - 1.0f, 1.0f, 0.0f, 1.0f);  // Lu (12)
}

inline float luNSfinal(float nstex, float gs, float threshold) {
  if (threshold >= 1.0f) return 0.0f;
  return luSat(luRemap(nstex * gs, threshold, 1.0f, 0.0f, 1.0f));  // Lu (17)
}

inline float luNS(float nstex, float gs, float threshold, float gd) {
  return luNSfinal(nstex, gs, threshold) * gd;  // Lu (13)
}

inline float luNDfbm(glm::vec3 detail) {
  return luFbm(detail.r, detail.g, detail.b);  // Lu (14)
}

inline float luNDmod(float ndfbm, float cmc, float ph) {
  return 0.35f * std::exp(-cmc * 0.75f) * luLerp(ndfbm, 1.0f - ndfbm, luSat(ph * 5.0f));  // Lu (15)
}

inline float luDensity(float nsfinal, float ndmod, float gd) {
  return luSat(luRemap(nsfinal, ndmod, 1.0f, 0.0f, 1.0f)) * gd;  // Lu (18)
}

inline float luCloudDensity(glm::vec4 shape, glm::vec3 detail, float ph, float cmc,
                            float threshold) {
  if (ph < 0.0f || ph > 1.0f) return 0.0f;
  const float nstex = luNStex(shape);                                // Lu (12)
  const float nsfinal = luNSfinal(nstex, luGS(ph, cmc), threshold);  // Lu (17), (7)
  const float ndmod = luNDmod(luNDfbm(detail), cmc, ph);             // Lu (14), (15)
  return luDensity(nsfinal, ndmod, luGD(ph, cmc));                   // Lu (18), (10)
}

inline glm::vec2 cloudTypeRange(int layer, float t) {
  const glm::vec2 k0 = layer == 0 ? glm::vec2(0.0f, 0.25f) : glm::vec2(0.1f, 0.45f);
  const glm::vec2 k1 = layer == 0 ? glm::vec2(0.0f, 0.45f) : glm::vec2(0.15f, 0.4f);
  const glm::vec2 k2 = layer == 0 ? glm::vec2(0.0f, 1.0f) : glm::vec2(0.1f, 0.75f);
  const float s = std::clamp(t, 0.0f, 1.0f) * 2.0f;
  return s < 1.0f ? glm::mix(k0, k1, s) : glm::mix(k1, k2, s - 1.0f);
}

inline float cloudTypeTexture(float t) {
  const float x = std::clamp(t / 0.5f, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);  // GLSL smoothstep(0, 0.5, t)
}

inline float cloudRollWeight(int layer, float t) {
  if (layer != 0) return 0.0f;
  const float x = std::clamp((std::abs(t - 0.5f) - 0.2f) / 0.1f, 0.0f, 1.0f);
  return 1.0f - x * x * (3.0f - 2.0f * x);  // GLSL 1 - smoothstep(0.2, 0.3, |t - 0.5|)
}

inline float cloudCumulusWeight(float t) {
  const float x = std::clamp((t - 0.5f) / 0.5f, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);  // GLSL smoothstep(0.5, 1, t)
}

inline float cumulusOutline(float blobFine, float blobMid, float blobCoarse, float sizeField) {
  const float s = luSat(2.0f * sizeField + 0.5f);
  const float fine = blobFine - 0.3f * s;
  const float mid = blobMid - 0.6f * std::abs(s - 0.5f);
  const float coarse = blobCoarse - 0.6f * (1.0f - s);
  return luSat(std::max(fine, std::max(mid, coarse)));
}

inline glm::vec4 cumulusShape(glm::vec4 shape, glm::vec4 shapeHalf, glm::vec4 shapeQuarter,
                              float meanR, float w) {
  const float outline =
      cumulusOutline(shape.g, shapeHalf.g, shapeQuarter.g, shapeQuarter.r - meanR);
  return {glm::mix(shape.r, outline, w), shape.g, shape.b, shape.a};
}

inline float cumulusGD(float ph, float cmc, float w) {
  if (w <= 0.0f) return luGD(ph, cmc);
  const float adiabatic = std::pow(std::max(ph, 0.0f), 2.0f / 3.0f);
  return glm::mix(luGDb(ph), adiabatic, w) * luGDt(ph) * cmc * 2.0f;
}

inline float cumulusNDmod(float ndfbm, float cmc, float ph, float w) {
  if (w <= 0.0f) return luNDmod(ndfbm, cmc, ph);
  const float wispy = 0.35f * std::exp(-cmc * 0.75f);
  const float billowy = glm::mix(wispy, 0.35f, w);
  return luLerp(wispy * ndfbm, billowy * (1.0f - ndfbm), luSat(ph * 5.0f));
}

inline float cumulusCloudDensity(glm::vec4 shape, glm::vec3 detail, float ph, float cmc,
                                 float threshold, float w) {
  if (w <= 0.0f) return luCloudDensity(shape, detail, ph, cmc, threshold);
  if (ph < 0.0f || ph > 1.0f) return 0.0f;
  const float nsfinal = luNSfinal(luNStex(shape), luGS(ph, cmc), threshold);  // Lu (17)
  const float ndmod = cumulusNDmod(luNDfbm(detail), cmc, ph, w);             // Lu (15)
  return luDensity(nsfinal, ndmod, cumulusGD(ph, cmc, w));                   // Lu (18)
}

inline float cloudHeightFraction(float layerFraction, glm::vec2 range) {
  return (layerFraction - range.x) / (range.y - range.x);
}

inline float tangTypeGradient(float ph, float type) {
  const float s = std::clamp(type, 0.0f, 1.0f) * 2.0f;
  const glm::vec2 k = s < 1.0f ? glm::mix(glm::vec2(0.1f, 0.75f), glm::vec2(0.2f, 0.55f), s)
                               : glm::mix(glm::vec2(0.2f, 0.55f), glm::vec2(0.1f, 0.5f), s - 1.0f);
  return luSat(luRemap(ph, 0.0f, k.x, 0.0f, 1.0f)) * luSat(luRemap(ph, k.y, 1.0f, 1.0f, 0.0f));
}

inline float tangBaseShape(glm::vec4 shape, float ph, float type) {
  return luNStex(shape) * tangTypeGradient(ph, type);
}

inline float tangErosion(float ndfbm, float ph) {
  return luLerp(ndfbm, 1.0f - ndfbm, luSat(ph * 10.0f)) * 0.2f;
}

inline float tangDensity(float base, float erosion, float cover, float threshold) {
  if (threshold >= 1.0f) return 0.0f;
  const float covered = luSat(luRemap(base, threshold, 1.0f, 0.0f, 1.0f));
  return luSat(luRemap(covered, erosion, 1.0f, 0.0f, 1.0f)) * cover;
}

inline float tangCloudDensity(glm::vec4 shape, glm::vec3 detail, float ph, float cover, float type,
                              float threshold) {
  if (ph < 0.0f || ph > 1.0f) return 0.0f;
  return tangDensity(tangBaseShape(shape, ph, type), tangErosion(luNDfbm(detail), ph), cover,
                     threshold);
}

// --- Lighting, cloud_lighting.glsl ---
float beerLambert(float b, float ds);                 // Lu (21)
float beerClamped(float b, float ds, float dsClamp);  // Lu (22)
float henyeyGreenstein(float cosTheta, float g);      // Lu (23), Tang (3)
float dualLobeHG(float cosTheta, float gForward, float gBack, float backWeight);
float expIntegralEi(float x);  // x < 0; Tang (7)
float slabAmbient(float a);    // Tang (6)(7), a = -sigmaT H
glm::vec3 cloudAmbient(glm::vec3 top, glm::vec3 bottom, float sigmaT, float hTopM, float hBottomM);
// Wrenninge 2013 octaves of Lu (22) * (23); phaseKind 0 HG, 1 dual lobe.
float cloudInScatter(float tauToLight, float tauClamp, float cosTheta, float g, float gBack,
                     float backWeight, int phaseKind, int octaves);
float diffuseTransmittance(float tau, float g);                   // two-stream, conservative slab
float cloudDiffuseInScatter(float tau, float g, float strength);  // the diffusion term
float cloudDiffusionLeak(float type);      // faster fall-off through finite convective cells
float cloudEdgeDensity(float d, float k);  // sharp boundaries
float cloudFarExtinction(float meanSigma, float fraction, float chordM);  // Markov mixture
glm::vec3 cloudAmbientDiffuse(glm::vec3 above, glm::vec3 below, glm::vec3 face, glm::vec3 back,
                              float sigmaT, float hTopM, float hBottomM, float tauView, float g,
                              float strength);  // Tang (6)(7) + diffusion between four faces
glm::vec3 cloudPhaseSkyLight(glm::vec3 excess, float tauTotal, float transmittance);  // tau T
glm::vec3 integrateStep(glm::vec3 S, float sigmaT, float dt);  // Hillaire 2016
glm::vec3 integrateStepRiemann(glm::vec3 S, float dt);

// --- Light march schedule, cloud_lighting.glsl and cloud_light_march.glsl ---
float lightStepStart(int i, int n, float distance);
float lightStepLength(int i, int n, float distance);
float lightLongStepDistance(float distance);
float lightLongStepLength(float distance);
float lightMarchReach(float distance);  // the march's whole length

// cloud_light_march.glsl's CloudLightPath, the parts the schedule needs.
struct LightPath {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, 1.0f};  // unit, toward the light
  float offset = 0.5f;                    // where each sample sits inside its step
  float distance = 1200.0f;               // the short steps' total length (m)
  int steps = 5;                          // short steps
  int split = 1;                          // samples per short step
  int nearSteps = 5;                      // the first nearSteps are CLOUD_LIGHT_PART_NEAR (0)
  float longEnd = 6000.0f;                // the long step runs over [distance, longEnd]
  int longParts = 3;                      // in this many equal parts
  float farEnd = 6000.0f;                 // the far step runs over [longEnd, farEnd]
  int farParts = 0;                       // in this many equal parts (part 2: the mean)
};

// The long step's parts for parts at most partM long (cloudLightLongParts).
int lightLongParts(float distanceM, float longEndM, float partM);

// The far step's parts for parts at most CLOUD_LIGHT_FAR_PART_M long (cloudLightFarParts).
int lightFarParts(float longEndM, float farEndM);

// cloud_light_march.glsl's CloudLightDepth: the march's density x metres through the sample's
// own cloud (up to the first sample at or below CLOUD_LIGHT_CLEAR_DENSITY) and beyond it.
struct LightDepth {
  float own = 0.0f, beyond = 0.0f;
  bool left = false;
  void add(float density, float lengthM) {
    if (density <= CLOUD_LIGHT_CLEAR_DENSITY) left = true;
    (left ? beyond : own) += density * lengthM;
  }
};

// Lu (24)'s ds toward the light, split (lightMarchDepth): `density(glm::vec3 p, float
// lengthM, int part)` plays cloudDensityForLight (part 0 near, 1 far, 2 the far step's mean).
template <class DensityFn>
LightDepth lightMarchDepth(const LightPath& path, DensityFn&& density) {
  LightDepth d;
  const auto shortSteps = [&](int first, int last, int part) {
    for (int i = first; i < last; ++i) {
      const float start = lightStepStart(i, path.steps, path.distance);
      const float len =
          lightStepLength(i, path.steps, path.distance) / static_cast<float>(path.split);
      for (int j = 0; j < path.split; ++j)
        d.add(density(path.origin +
                          path.direction * (start + (static_cast<float>(j) + path.offset) * len),
                      len, part),
              len);
    }
  };
  const int near = std::clamp(path.nearSteps, 0, path.steps);
  shortSteps(0, near, 0);
  shortSteps(near, path.steps, 1);
  const float len =
      (path.longEnd - path.distance) / static_cast<float>(std::max(path.longParts, 1));
  for (int j = 0; j < path.longParts; ++j)
    d.add(density(path.origin + path.direction *
                                    (path.distance + (static_cast<float>(j) + path.offset) * len),
                  len, 1),
          len);
  const float farLen =
      (path.farEnd - path.longEnd) / static_cast<float>(std::max(path.farParts, 1));
  for (int j = 0; j < path.farParts; ++j)
    d.add(density(path.origin + path.direction *
                                    (path.longEnd + (static_cast<float>(j) + path.offset) * farLen),
                  farLen, 2),
          farLen);
  return d;
}

// lightMarchDensity: all of it, own and beyond.
template <class DensityFn>
float lightMarchDensity(const LightPath& path, DensityFn&& density) {
  const LightDepth d = lightMarchDepth(path, std::forward<DensityFn>(density));
  return d.own + d.beyond;
}

}  // namespace sky::clouds
