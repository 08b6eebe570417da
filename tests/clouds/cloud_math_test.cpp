// engine/clouds/cloud_math.h against values worked out by hand from the papers' formulas, and
// the properties the renderer relies on: phase functions normalised, Ei accurate, the ambient's
// limits, the octave sum's first term, the step integral's limits, the light schedule, and the
// density falling as the threshold rises (what the coverage calibration's search assumes).
// The GPU side equals these twins (cloud_kernel_test.cpp), so the checks hold there too.
#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "engine/clouds/cloud_math.h"

namespace sky::test {
namespace {
using namespace sky::clouds;

constexpr double kPi = 3.14159265358979323846;

TEST(CloudMath, LuHeightFunctionsAtHandComputedPoints) {
  // Lu (5): halfway up the 0..0.07 ramp.
  EXPECT_FLOAT_EQ(luGSb(0.035f), 0.5f);
  EXPECT_FLOAT_EQ(luGSb(0.5f), 1.0f);
  EXPECT_FLOAT_EQ(luGSb(-0.1f), 0.0f);
  // Lu (6) with CMc = 0.5: the ramp runs from 1 at ph = 0.1 down to 0 at ph = 0.5.
  EXPECT_FLOAT_EQ(luGSt(0.3f, 0.5f), 0.5f);
  EXPECT_FLOAT_EQ(luGSt(0.05f, 0.5f), 1.0f);
  EXPECT_FLOAT_EQ(luGSt(0.6f, 0.5f), 0.0f);
  EXPECT_FLOAT_EQ(luGSt(0.0f, 0.0f), 0.0f);  // CMc = 0: no cloud, not a division by zero
  // Lu (7) = (5) * (6).
  EXPECT_FLOAT_EQ(luGS(0.035f, 0.5f), 0.5f);
  // Lu (8): ph times the 0..0.15 ramp.
  EXPECT_FLOAT_EQ(luGDb(0.075f), 0.0375f);
  EXPECT_FLOAT_EQ(luGDb(0.6f), 0.6f);
  // Lu (9): halfway down the 0.9..1 ramp.
  EXPECT_NEAR(luGDt(0.95f), 0.5f, 1e-6f);
  // Lu (10): 0.5 * 1 * CMc * 2.
  EXPECT_FLOAT_EQ(luGD(0.5f, 0.5f), 0.5f);
  EXPECT_FLOAT_EQ(luGD(0.5f, 1.0f), 1.0f);
}

TEST(CloudMath, LuNoiseFunctionsAtHandComputedPoints) {
  // Lu (3): 0.25 of the way through [0, 2] lands 0.25 of the way through [10, 30].
  EXPECT_FLOAT_EQ(luRemap(0.5f, 0.0f, 2.0f, 10.0f, 30.0f), 15.0f);
  // Lu (4), (16).
  EXPECT_FLOAT_EQ(luSat(-0.5f), 0.0f);
  EXPECT_FLOAT_EQ(luSat(1.5f), 1.0f);
  EXPECT_FLOAT_EQ(luLerp(2.0f, 4.0f, 0.25f), 2.5f);
  EXPECT_FLOAT_EQ(luLerp(2.0f, 4.0f, 1.5f), 5.0f);  // extrapolates, as Lu says
  // Lu (11): the weights sum to 1.
  EXPECT_FLOAT_EQ(luFbm(1.0f, 1.0f, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(luFbm(0.8f, 0.4f, 0.0f), 0.6f);
  // Lu (12): fbm(G, B, A) = 0.4, so R = 0.5 is remapped from [-0.6, 1]: 1.1 / 1.6.
  EXPECT_FLOAT_EQ(luNStex({0.5f, 0.4f, 0.4f, 0.4f}), 0.6875f);
  EXPECT_FLOAT_EQ(luNStex({1.0f, 0.0f, 0.0f, 0.0f}), 1.0f);
  EXPECT_FLOAT_EQ(luNStex({0.0f, 1.0f, 1.0f, 1.0f}), 0.0f);
  // Lu (17) with the paper's threshold 1 - CMc, CMc = 0.5: NStex * GS = 0.8 -> 0.3 / 0.5.
  EXPECT_FLOAT_EQ(luNSfinal(1.0f, 0.8f, 0.5f), 0.6f);
  EXPECT_FLOAT_EQ(luNSfinal(1.0f, 0.8f, 1.0f), 0.0f);  // threshold 1: no cloud
  // Lu (13) = (17) * GD.
  EXPECT_FLOAT_EQ(luNS(1.0f, 0.8f, 0.5f, 0.5f), 0.3f);
  // Lu (15): at ph = 0 the fbm itself, at ph >= 0.2 its complement, times 0.35 exp(-0.75 CMc).
  EXPECT_FLOAT_EQ(luNDmod(0.3f, 0.0f, 0.0f), 0.105f);
  EXPECT_FLOAT_EQ(luNDmod(0.3f, 0.0f, 1.0f), 0.245f);
  EXPECT_NEAR(luNDmod(0.3f, 1.0f, 1.0f), 0.245 * std::exp(-0.75), 1e-7);
  // Lu (18): (0.6 - 0.2) / 0.8 * GD 0.5.
  EXPECT_FLOAT_EQ(luDensity(0.6f, 0.2f, 0.5f), 0.25f);
}

TEST(CloudMath, LuCloudDensityComposesTheEquations) {
  const glm::vec4 shape(0.7f, 0.5f, 0.4f, 0.3f);
  const glm::vec3 detail(0.2f, 0.6f, 0.5f);
  const float ph = 0.3f, cmc = 0.6f, threshold = 1.0f - cmc;
  const float nsfinal = luNSfinal(luNStex(shape), luGS(ph, cmc), threshold);
  const float expected = luDensity(nsfinal, luNDmod(luNDfbm(detail), cmc, ph), luGD(ph, cmc));
  EXPECT_GT(expected, 0.0f);
  EXPECT_FLOAT_EQ(luCloudDensity(shape, detail, ph, cmc, threshold), expected);
  // Outside the cloud and above every possible shape value: nothing.
  EXPECT_EQ(luCloudDensity(shape, detail, -0.01f, cmc, -0.5f), 0.0f);
  EXPECT_EQ(luCloudDensity(shape, detail, 1.01f, cmc, -0.5f), 0.0f);
  EXPECT_EQ(luCloudDensity(shape, detail, ph, cmc, 1.0f), 0.0f);
  EXPECT_EQ(luCloudDensity(shape, detail, ph, 0.0f, -0.5f), 0.0f);  // CMc = 0: GD = 0
}

TEST(CloudMath, DensityFallsAsTheThresholdRises) {
  // The calibration's bisection needs opacity monotone in the threshold; every remap the
  // threshold enters must therefore be non-increasing in it. Checked on a grid of everything.
  for (float r : {0.1f, 0.5f, 0.9f})
    for (float g : {0.0f, 0.5f, 1.0f})
      for (float d : {0.1f, 0.5f, 0.9f})
        for (float ph : {0.05f, 0.3f, 0.7f, 0.95f})
          for (float cmc : {0.05f, 0.4f, 1.0f})
            for (float type : {0.0f, 0.5f, 1.0f}) {
              const glm::vec4 shape(r, g, 1.0f - g, 0.5f);
              const glm::vec3 detail(d, 1.0f - d, 0.5f);
              float lastLu = 2.0f, lastTang = 2.0f;
              for (float t = -1.0f; t <= 1.0f; t += 0.05f) {
                const float lu = luCloudDensity(shape, detail, ph, cmc, t);
                const float tang = tangCloudDensity(shape, detail, ph, cmc, type, t);
                ASSERT_LE(lu, lastLu) << "threshold " << t;
                ASSERT_LE(tang, lastTang) << "threshold " << t;
                lastLu = lu;
                lastTang = tang;
              }
            }
}

TEST(CloudMath, CloudTypeRanges) {
  // The keys: stratus, stratocumulus, cumulus; altostratus, altocumulus, convective mid.
  const glm::vec2 low[3] = {{0.0f, 0.25f}, {0.0f, 0.45f}, {0.0f, 1.0f}};
  const glm::vec2 mid[3] = {{0.1f, 0.45f}, {0.15f, 0.4f}, {0.1f, 0.75f}};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(cloudTypeRange(0, 0.5f * float(k)), low[k]) << "low key " << k;
    EXPECT_EQ(cloudTypeRange(1, 0.5f * float(k)), mid[k]) << "mid key " << k;
  }
  EXPECT_EQ(cloudTypeRange(0, -1.0f), low[0]);
  EXPECT_EQ(cloudTypeRange(1, 2.0f), mid[2]);
  // Halfway between keys, halfway between their ranges; always a non-empty range in [0, 1].
  EXPECT_NEAR(cloudTypeRange(0, 0.75f).y, 0.725f, 1e-6f);
  for (int layer = 0; layer < 2; ++layer)
    for (float t = 0.0f; t <= 1.0f; t += 0.01f) {
      const glm::vec2 r = cloudTypeRange(layer, t);
      EXPECT_GE(r.x, 0.0f);
      EXPECT_LE(r.y, 1.0f);
      EXPECT_GT(r.y - r.x, 0.2f) << "layer " << layer << " type " << t;
    }
  // ph: 0 at the cloud's bottom, 1 at its top, outside beyond.
  const glm::vec2 r(0.1f, 0.5f);
  EXPECT_FLOAT_EQ(cloudHeightFraction(0.1f, r), 0.0f);
  EXPECT_FLOAT_EQ(cloudHeightFraction(0.3f, r), 0.5f);
  EXPECT_FLOAT_EQ(cloudHeightFraction(0.5f, r), 1.0f);
  EXPECT_LT(cloudHeightFraction(0.05f, r), 0.0f);
  EXPECT_GT(cloudHeightFraction(0.6f, r), 1.0f);
}

TEST(CloudMath, TangDensity) {
  const glm::vec4 shape(0.9f, 0.8f, 0.7f, 0.6f);
  const glm::vec3 detail(0.3f, 0.4f, 0.5f);
  // Zero outside the cloud, at threshold 1, and at zero cover; never above the cover.
  EXPECT_EQ(tangCloudDensity(shape, detail, -0.01f, 0.5f, 1.0f, 0.0f), 0.0f);
  EXPECT_EQ(tangCloudDensity(shape, detail, 1.01f, 0.5f, 1.0f, 0.0f), 0.0f);
  EXPECT_EQ(tangCloudDensity(shape, detail, 0.3f, 0.5f, 1.0f, 1.0f), 0.0f);
  EXPECT_EQ(tangCloudDensity(shape, detail, 0.3f, 0.0f, 1.0f, 0.0f), 0.0f);
  for (float cover : {0.2f, 0.6f, 1.0f})
    for (float ph = 0.0f; ph <= 1.0f; ph += 0.05f) {
      const float d = tangCloudDensity(shape, detail, ph, cover, 0.5f, -0.5f);
      EXPECT_GE(d, 0.0f);
      EXPECT_LE(d, cover);
    }
  // The type gradient: 0 at the cloud's bottom and top, 1 in between, for every type.
  for (float type : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
    EXPECT_EQ(tangTypeGradient(0.0f, type), 0.0f);
    EXPECT_EQ(tangTypeGradient(1.0f, type), 0.0f);
    EXPECT_EQ(tangTypeGradient(0.3f, type), 1.0f);
  }
  // By hand: base 1 (shape R = 1) at ph = 0.3, threshold 0.5 -> 1; erosion of fbm 0.2 above
  // ph = 0.1 is 0.2 * 0.8 = 0.16 -> (1 - 0.16) / 0.84 = 1; times cover 0.4.
  EXPECT_FLOAT_EQ(
      tangCloudDensity({1.0f, 0.5f, 0.5f, 0.5f}, glm::vec3(0.2f), 0.3f, 0.4f, 1.0f, 0.5f), 0.4f);
  EXPECT_FLOAT_EQ(tangErosion(0.2f, 0.0f), 0.04f);
  EXPECT_FLOAT_EQ(tangErosion(0.2f, 0.5f), 0.16f);
}

TEST(CloudMath, BeerLambertAndLuClamp) {
  EXPECT_FLOAT_EQ(beerLambert(0.04f, 25.0f), float(std::exp(-1.0)));  // Lu (21)
  // Lu (22): the clamp only lifts what lies past dsClamp.
  EXPECT_FLOAT_EQ(beerClamped(0.04f, 10.0f, 50.0f), beerLambert(0.04f, 10.0f));
  EXPECT_FLOAT_EQ(beerClamped(0.04f, 100.0f, 50.0f), beerLambert(0.04f, 50.0f));
}

// 2 pi * integral of p(mu) over mu in [-1, 1]: 200,000 midpoints, summed in double (HG's peak at
// |g| = 0.9 is about 0.006 wide in mu, 600 points).
template <class Phase>
double sphereIntegral(Phase p) {
  const int n = 200000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double mu = -1.0 + 2.0 * (i + 0.5) / n;
    sum += p(float(mu));
  }
  return 2.0 * kPi * sum * 2.0 / n;
}

TEST(CloudMath, PhaseFunctionsIntegrateToOneOverTheSphere) {
  // Lu (23) / Tang (3) with either sign of g (|g| = 0.9 peaks at 95/4pi: 2e5 points resolve it).
  for (float g : {-0.9f, -0.5f, -0.1f, 0.0f, 0.3f, 0.6f, 0.9f})
    EXPECT_NEAR(sphereIntegral([g](float mu) { return henyeyGreenstein(mu, g); }), 1.0, 1e-4)
        << "g " << g;
  EXPECT_NEAR(sphereIntegral([](float mu) { return dualLobeHG(mu, 0.6f, -0.3f, 0.2f); }), 1.0,
              1e-4);
  EXPECT_NEAR(sphereIntegral([](float mu) { return dualLobeHG(mu, 0.9f, -0.9f, 0.7f); }), 1.0,
              1e-4);
  // Isotropic at g = 0; forward peak for g > 0.
  EXPECT_NEAR(henyeyGreenstein(0.3f, 0.0f), 1.0 / (4.0 * kPi), 1e-8);
  EXPECT_GT(henyeyGreenstein(1.0f, 0.6f), henyeyGreenstein(-1.0f, 0.6f));
  // HG(1) = (1 + g) / (4 pi (1 - g)^2).
  EXPECT_NEAR(henyeyGreenstein(1.0f, 0.5f), 1.5 / (4.0 * kPi * 0.25), 1e-6);
  // The back lobe lifts back-scattering: what Tang wanted from a better phase function.
  EXPECT_GT(dualLobeHG(-1.0f, 0.6f, -0.3f, 0.2f), henyeyGreenstein(-1.0f, 0.6f));
}

TEST(CloudMath, ExponentialIntegralIsAccurateOverItsRange) {
  // 1e-4 relative over [-60, -1e-4] against libstdc++'s double std::expint (Ei).
  double worst = 0;
  for (double lx = std::log(1e-4); lx <= std::log(60.0); lx += 0.01) {
    const double x = -std::exp(lx);
    const double want = std::expint(x);
    const double got = expIntegralEi(float(x));
    // float(x) differs from x by 6e-8 relative; Ei' = e^x / x moves Ei by about as much.
    worst = std::max(worst, std::abs(got / std::expint(double(float(x))) - 1.0));
    EXPECT_NEAR(got, want, 1e-4 * std::abs(want)) << "Ei(" << x << ")";
  }
  std::cout << "Ei worst relative error " << worst << "\n";
  EXPECT_NEAR(expIntegralEi(-1.0f), -0.219383934, 1e-6);
  EXPECT_NEAR(expIntegralEi(-0.1f), -1.822923958, 1e-5);
  EXPECT_NEAR(expIntegralEi(-5.0f), -0.001148296, 1e-9);
}

TEST(CloudMath, SlabAmbientLimits) {
  // Tang (6)(7): 1 at the face of the slab, E2(1) one optical depth in, falling with depth.
  EXPECT_EQ(slabAmbient(0.0f), 1.0f);
  EXPECT_NEAR(slabAmbient(-1e-7f), 1.0f, 1e-5f);
  EXPECT_NEAR(slabAmbient(-1.0f), 0.148495507, 1e-6);
  float last = 1.0f;
  // Down to optical depth 60 (e^-60: float's exp underflows not far beyond).
  for (float h = 1.0f; h <= 1500.0f; h *= 1.1f) {
    const float s = slabAmbient(-0.04f * h);
    EXPECT_LT(s, last) << "H " << h;
    EXPECT_GE(s, 0.0f);
    last = s;
  }
  // cloudAmbient: the top colour through the slab above, the bottom one through the slab below.
  const glm::vec3 amb = cloudAmbient({1, 2, 3}, {4, 5, 6}, 0.02f, 50.0f, 0.0f);
  EXPECT_NEAR(amb.x, slabAmbient(-1.0f) + 4.0f, 1e-6f);
  EXPECT_NEAR(amb.z, 3.0f * slabAmbient(-1.0f) + 6.0f, 1e-6f);
}

// cloudAmbientDiffuse in the diffusion limit (strength 1): a conservative cloud lit alike from
// every side is as bright as that light, however deep the point; lit from above alone it is
// the brighter the nearer the top. The ambient before issue 30 (each source halved and
// attenuated on its own way in) gave half the light at the face and a few per cent deep in.
TEST(CloudMath, AmbientDiffusionIsTheMeanOfTheFacesLight) {
  const glm::vec3 sky(0.2f, 0.3f, 0.5f), dark(0.0f);
  for (float sigma : {0.01f, 0.05f, 0.1f})
    for (float h : {10.0f, 300.0f, 1000.0f})
      for (float tauView : {0.0f, 5.0f, 50.0f}) {
        const glm::vec3 a =
            cloudAmbientDiffuse(sky, sky, sky, sky, sigma, h, 2.0f * h, tauView, 0.42f, 1.0f);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], sky[c], 1e-5f) << sigma << " " << h;
      }
  const float g = 0.42f, sigma = 0.05f;
  const glm::vec3 nearTop =
      cloudAmbientDiffuse(sky, dark, dark, dark, sigma, 20.0f, 980.0f, 40.0f, g, 1.0f);
  const glm::vec3 nearBase =
      cloudAmbientDiffuse(sky, dark, dark, dark, sigma, 980.0f, 20.0f, 40.0f, g, 1.0f);
  EXPECT_GT(nearTop.b, 2.0f * nearBase.b);
  EXPECT_LT(nearTop.b, sky.b);
  // Strength 0 is Tang's: half the light above through the slab, half the light below.
  const glm::vec3 tang =
      cloudAmbientDiffuse(sky, dark, sky, sky, sigma, 20.0f, 980.0f, 0.0f, g, 0.0f);
  EXPECT_NEAR(tang.b, 0.5f * sky.b * slabAmbient(-sigma * 20.0f), 1e-6f);
}

TEST(CloudMath, ThePhaseSkyLightIsOnceScatteredAndGoneInOpaqueCloud) {
  // excess tau T: the light arriving along the ray, scattered once (any density along it).
  const glm::vec3 excess(0.3f, 0.2f, -0.1f);
  EXPECT_EQ(cloudPhaseSkyLight(excess, 0.0f, 1.0f), glm::vec3(0.0f)) << "no cloud";
  // A homogeneous cloud of optical depth tau: largest, 1/e of the excess, at tau = 1.
  auto atDepth = [&](float tau) { return cloudPhaseSkyLight(excess, tau, std::exp(-tau)).r; };
  EXPECT_NEAR(atDepth(1.0f), 0.3f / std::exp(1.0f), 1e-6f);
  EXPECT_LT(atDepth(0.5f), atDepth(1.0f));
  EXPECT_LT(atDepth(2.0f), atDepth(1.0f));
  EXPECT_LT(atDepth(20.0f), 1e-6f) << "opaque cloud: the diffusion mean alone";
  EXPECT_LT(cloudPhaseSkyLight(excess, 1.0f, std::exp(-1.0f)).b, 0.0f)
      << "a sky darker behind the cloud than its mean takes light away";
}

TEST(CloudMath, InScatterOctaves) {
  for (float tau : {0.0f, 0.5f, 3.0f, 20.0f})
    for (float cosTheta : {-1.0f, 0.0f, 0.7f, 1.0f}) {
      // One octave is exactly Lu (22) * (23), for either phase.
      EXPECT_EQ(cloudInScatter(tau, 4.0f, cosTheta, 0.6f, -0.3f, 0.2f, 0, 1),
                beerClamped(1.0f, tau, 4.0f) * henyeyGreenstein(cosTheta, 0.6f));
      EXPECT_EQ(cloudInScatter(tau, 4.0f, cosTheta, 0.6f, -0.3f, 0.2f, 1, 1),
                beerClamped(1.0f, tau, 4.0f) * dualLobeHG(cosTheta, 0.6f, -0.3f, 0.2f));
    }
  // Isotropic and unshadowed: the octaves sum b^i = 2 (1 - 0.5^n).
  EXPECT_NEAR(cloudInScatter(0.0f, 0.0f, 0.3f, 0.0f, 0.0f, 0.0f, 0, 3), 1.75 / (4.0 * kPi), 1e-7);
  // Octave i sees half the optical depth of octave i - 1 (Wrenninge).
  const float two = cloudInScatter(4.0f, 100.0f, 0.3f, 0.0f, 0.0f, 0.0f, 0, 2);
  EXPECT_NEAR(two, (std::exp(-4.0) + 0.5 * std::exp(-2.0)) / (4.0 * kPi), 1e-7);
  EXPECT_EQ(cloudInScatter(1.0f, 1.0f, 0.3f, 0.5f, 0.0f, 0.0f, 0, 0), 0.0f);
}

TEST(CloudMath, IntegrateStepLimits) {
  const glm::vec3 S(1.0f, 2.0f, 3.0f);
  // sigmaT -> 0: S dt; both sides of the series switch agree.
  EXPECT_EQ(integrateStep(S, 0.0f, 10.0f), S * 10.0f);
  const glm::vec3 below = integrateStep(S, 0.00999f, 1.0f),
                  above = integrateStep(S, 0.01001f, 1.0f);
  EXPECT_NEAR(below.y, above.y, 1e-4f);
  EXPECT_NEAR(below.y, 2.0 * (1.0 - std::exp(-0.00999)) / 0.00999, 1e-6);
  // A long step saturates at S / sigmaT, where Riemann keeps growing.
  EXPECT_NEAR(integrateStep(S, 0.1f, 1000.0f).x, 10.0f, 1e-5f);
  EXPECT_EQ(integrateStepRiemann(S, 1000.0f).x, 1000.0f);
}

TEST(CloudMath, LightStepSchedule) {
  for (int n = 1; n <= 10; ++n) {
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      sum += lightStepLength(i, n, 1200.0f);
      EXPECT_FLOAT_EQ(lightStepStart(i, n, 1200.0f), float(sum - lightStepLength(i, n, 1200.0f)));
      if (i > 0) {  // lengths double
        EXPECT_NEAR(lightStepLength(i, n, 1200.0f), 2.0f * lightStepLength(i - 1, n, 1200.0f),
                    1e-3f);
      }
    }
    EXPECT_NEAR(sum, 1200.0, 1e-3) << n << " steps";
    EXPECT_EQ(lightStepStart(n, n, 1200.0f), 1200.0f);
  }
  EXPECT_EQ(lightStepLength(0, 1, 500.0f), 500.0f);
  EXPECT_FLOAT_EQ(lightStepLength(0, 5, 1240.0f), 40.0f);  // 1240 / 31
  // The long step: [d, 5d], sampled at 3d.
  EXPECT_EQ(lightLongStepDistance(1200.0f), 3600.0f);
  EXPECT_EQ(lightLongStepLength(1200.0f), 4800.0f);
  EXPECT_EQ(lightMarchReach(1200.0f), 6000.0f);
}

}  // namespace
}  // namespace sky::test
