// Line by line as shaders/common/cloud_lighting.glsl (the GLSL side carries the full comments;
// the density twins are inline in the header); float everywhere, as on the GPU.
#include "engine/clouds/cloud_math.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace sky::clouds {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kEulerGamma = 0.5772156649015329f;
// Wrenninge 2013's octave factors (a, b, c in cloud_lighting.glsl).
constexpr float kOctaveAttenuation = 0.5f;
constexpr float kOctaveContribution = 0.5f;
constexpr float kOctaveEccentricity = 0.5f;

}  // namespace

float beerLambert(float b, float ds) {
  return std::exp(-b * ds);  // Lu (21)
}

float beerClamped(float b, float ds, float dsClamp) {
  return std::max(beerLambert(b, ds), beerLambert(b, dsClamp));  // Lu (22)
}

float henyeyGreenstein(float cosTheta, float g) {
  const float denom = 1.0f + g * g - 2.0f * g * cosTheta;
  return (1.0f - g * g) / (4.0f * kPi * denom * std::sqrt(denom));  // Lu (23)
}

float dualLobeHG(float cosTheta, float gForward, float gBack, float backWeight) {
  return glm::mix(henyeyGreenstein(cosTheta, gForward), henyeyGreenstein(cosTheta, gBack),
                  backWeight);
}

float expIntegralEi(float x) {
  const float z = -x;
  if (z < 1.5f) {  // A&S 5.1.11
    float term = 1.0f, sum = 0.0f;
    for (int k = 1; k <= 16; ++k) {
      term *= -z / float(k);
      sum += term / float(k);
    }
    return kEulerGamma + std::log(z) + sum;
  }
  float t = z + 31.0f;  // A&S 5.1.22, from depth 15 up
  for (int k = 15; k >= 1; --k) t = z + float(2 * k - 1) - float(k * k) / t;
  return -std::exp(-z) / t;
}

float slabAmbient(float a) {
  if (a >= 0.0f) return 1.0f;
  return std::max(0.0f, std::exp(a) - a * expIntegralEi(a));  // Tang (6)(7)
}

glm::vec3 cloudAmbient(glm::vec3 top, glm::vec3 bottom, float sigmaT, float hTopM, float hBottomM) {
  return top * slabAmbient(-sigmaT * hTopM) + bottom * slabAmbient(-sigmaT * hBottomM);
}

float cloudInScatter(float tauToLight, float tauClamp, float cosTheta, float g, float gBack,
                     float backWeight, int phaseKind, int octaves) {
  float sum = 0.0f;
  float a = 1.0f, b = 1.0f, c = 1.0f;
  for (int i = 0; i < octaves; ++i) {
    const float phase = phaseKind == 1 ? dualLobeHG(cosTheta, c * g, c * gBack, backWeight)
                                       : henyeyGreenstein(cosTheta, c * g);
    sum += b * beerClamped(1.0f, a * tauToLight, a * tauClamp) * phase;  // Lu (22) * (23)
    a *= kOctaveAttenuation;
    b *= kOctaveContribution;
    c *= kOctaveEccentricity;
  }
  return sum;
}

float diffuseTransmittance(float tau, float g) {
  return 1.0f / (1.0f + 0.75f * (1.0f - g) * std::max(tau, 0.0f));
}

float cloudDiffuseInScatter(float tau, float g, float strength) {
  return strength * diffuseTransmittance(tau, g);
}

float cloudDiffusionLeak(float type) {
  return 1.0f + 2.0f * std::clamp(2.0f * type - 1.0f, 0.0f, 1.0f);
}

glm::vec3 cloudAmbientDiffuse(glm::vec3 above, glm::vec3 below, glm::vec3 face, glm::vec3 back,
                              float sigmaT, float hTopM, float hBottomM, float tauView, float g,
                              float strength) {
  const float k = std::clamp(strength, 0.0f, 1.0f);
  const float wTop = diffuseTransmittance(sigmaT * hTopM, g);
  const float wBottom = diffuseTransmittance(sigmaT * hBottomM, g);
  const float wFace = diffuseTransmittance(tauView, g);
  const float wBack =
      diffuseTransmittance(std::max(sigmaT * (hTopM + hBottomM) - tauView, 0.0f), g);
  const glm::vec3 diffusion = (wTop * above + wBottom * below + wFace * face + wBack * back) /
                              (wTop + wBottom + wFace + wBack);
  const glm::vec3 tang = 0.5f * cloudAmbient(above, below, sigmaT, hTopM, hBottomM);
  return tang + (diffusion - tang) * k;
}

// The sky scattered once along the ray by the phase, less its mean: excess tau T.
glm::vec3 cloudPhaseSkyLight(glm::vec3 excess, float tauTotal, float transmittance) {
  return excess * (tauTotal * transmittance);
}

float cloudEdgeDensity(float d, float k) {
  if (d >= 1.0f) return d;
  return 1.0f - std::pow(1.0f - std::max(d, 0.0f), k);
}

float cloudFarExtinction(float meanSigma, float fraction, float chordM) {
  if (meanSigma <= 0.0f || fraction <= 0.0f) return 0.0f;
  const float a = std::min(fraction, 0.999f);
  const float q = a / (1.0f - a);
  const float tau = meanSigma / a * chordM;
  return 2.0f * tau * q /
         (tau + 1.0f + q + std::sqrt((tau - q) * (tau - q) + 2.0f * (tau + q) + 1.0f)) / chordM;
}

glm::vec3 integrateStep(glm::vec3 S, float sigmaT, float dt) {
  const float x = sigmaT * dt;
  if (x < 0.01f) return S * (dt * (1.0f - x * (0.5f - x * (1.0f / 6.0f - x * (1.0f / 24.0f)))));
  return (S - S * std::exp(-x)) / sigmaT;  // Hillaire 2016
}

glm::vec3 integrateStepRiemann(glm::vec3 S, float dt) {
  return S * dt;
}

float lightStepStart(int i, int n, float distance) {
  if (i >= n) return distance;
  return distance * (float(1 << i) - 1.0f) / (float(1 << n) - 1.0f);
}

float lightStepLength(int i, int n, float distance) {
  return lightStepStart(i + 1, n, distance) - lightStepStart(i, n, distance);
}

float lightLongStepDistance(float distance) {
  return 3.0f * distance;
}

float lightLongStepLength(float distance) {
  return 4.0f * distance;
}

float lightMarchReach(float distance) {
  return distance + lightLongStepLength(distance);
}

int lightLongParts(float distanceM, float longEndM, float partM) {
  const float len = longEndM - distanceM;
  if (len <= 0.0f) return 0;
  return std::clamp(static_cast<int>(std::ceil(len / partM)), 1, CLOUD_LIGHT_MAX_LONG_PARTS);
}

int lightFarParts(float longEndM, float farEndM) {
  const float len = farEndM - longEndM;
  if (len <= 0.0f) return 0;
  return std::clamp(static_cast<int>(std::ceil(len / float(CLOUD_LIGHT_FAR_PART_M))), 1,
                    CLOUD_LIGHT_MAX_FAR_PARTS);
}

}  // namespace sky::clouds
