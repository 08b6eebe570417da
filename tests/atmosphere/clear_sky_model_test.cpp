// The physical sky against independent clear-sky models (issue 15, "One atmosphere"), for
// the sun at 10, 30 and 60 degrees and Preetham turbidity 2 and 3 (aerosol optical depth at
// 550 nm 0.10 and 0.20: beta = 0.04608 T - 0.04586, tau = beta 0.55^-1.3), over the sky from
// the zenith to 10 degrees above the horizon and more than 10 degrees from the sun:
// - the luminance relative to the zenith against the CIE standard clear sky, type 12 of the
//   CIE Standard General Sky (CIE S 011/E:2003, ISO 15469:2004), fitted to measured sky
//   scans. The goal: a median deviation of at most 5 %, a 90th percentile of 15 %.
//   Since issue 30 the sky follows its spectral reference within 1-3 % (spectral_sky_test),
//   and that reference itself is 16 % off CIE 12 at the 90th percentile (3.7 % median): the
//   percentile is held at 17 %, what this atmosphere allows (docs/atmosphere.md).
// - the chromaticity (CIE x, y) against Preetham, Shirley & Smits 1999, "A Practical
//   Analytic Model for Daylight" (the CIE skies have no colour): within 10 %.
// - Preetham's luminance is printed and held where it is: its gradation swings from a
//   horizon 6 times the zenith at T 2 to 2 times at T 3, which no physical atmosphere does
//   between these two aerosol loads (docs/atmosphere.md).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere_test_util.h"
#include "engine/render/renderer.h"

namespace sky::test {
namespace {

struct Perez {
  double A, B, C, D, E;
  double operator()(double theta, double gamma) const {
    return (1.0 + A * std::exp(B / std::max(std::cos(theta), 0.01))) *
           (1.0 + C * std::exp(D * gamma) + E * std::cos(gamma) * std::cos(gamma));
  }
};

// Preetham's coefficients (their Table/Appendix A.2) and zenith chromaticity (A.3).
Perez perezY(double T) {
  return {0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771,
          -0.0670 * T + 0.3703};
}
Perez perezX(double T) {
  return {-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125, -0.0641 * T - 0.8989,
          -0.0033 * T + 0.0452};
}
Perez perezYc(double T) {
  return {-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102, -0.0441 * T - 1.6537,
          -0.0109 * T + 0.0529};
}
// CIE S 011 standard general sky: gradation phi(Z) = 1 + a exp(b / cos Z) times indicatrix
// f(chi) = 1 + c (exp(d chi) - exp(d pi / 2)) + e cos^2 chi, relative to the zenith.
struct CieSky {
  double a, b, c, d, e;
  double operator()(double Z, double chi) const {
    const double gradation = 1.0 + a * std::exp(b / std::max(std::cos(Z), 1e-3));
    const double indicatrix =
        1.0 + c * (std::exp(d * chi) - std::exp(d * kPi / 2.0)) + e * std::cos(chi) * std::cos(chi);
    return gradation * indicatrix;
  }
};
constexpr CieSky kCieClearSky{-1.0, -0.32, 10.0, -3.0, 0.45};  // type 12

double zenithChromaticity(const double m[3][4], double T, double thetaS) {
  const double t[3] = {T * T, T, 1.0};
  const double s[4] = {thetaS * thetaS * thetaS, thetaS * thetaS, thetaS, 1.0};
  double v = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) v += t[i] * m[i][j] * s[j];
  return v;
}
constexpr double kZenithX[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                   {-0.02903, 0.06377, -0.03202, 0.00394},
                                   {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                   {-0.04214, 0.08970, -0.04153, 0.00516},
                                   {0.15346, -0.26756, 0.06670, 0.26688}};

glm::dvec3 xyz(const glm::dvec3& rgb) {  // linear Rec.709 to CIE XYZ (D65)
  return {0.4124 * rgb.r + 0.3576 * rgb.g + 0.1805 * rgb.b,
          0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b,
          0.0193 * rgb.r + 0.1192 * rgb.g + 0.9505 * rgb.b};
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

TEST_F(AtmosphereTest, PhysicalSkyAgainstCieAndPreetham) {
  constexpr int kW = 72, kH = 36;
  std::vector<double> cieAll, preethamAll, chromaAll;
  for (double T : {2.0, 3.0}) {
    const double beta = 0.04608 * T - 0.04586;
    Scene scene;
    scene.sky.model = SkyModel::Physical;
    scene.lighting.turbidity = beta * std::pow(0.55, -1.3);
    for (double elevation : {10.0, 30.0, 60.0}) {
      AtmosphereLuts::Frame frame = sunFrame(180.0, elevation);
      frame.atmosphere = physicalAtmosphere(scene);
      const FrameResult result = run(frame, kW, kH);
      const ReadbackImage& probe = result.output("probe");
      const glm::dvec3 S = enuDirection(180.0, elevation);
      const double thetaS = (90.0 - elevation) * kPi / 180.0;
      const Perez pY = perezY(T), px = perezX(T), py = perezYc(T);
      const double xz = zenithChromaticity(kZenithX, T, thetaS);
      const double yz = zenithChromaticity(kZenithY, T, thetaS);
      auto rgbAt = [&](int col, int row) {
        const float* p =
            &probe.pixels[(static_cast<size_t>(row) * probe.width + col) * probe.channels];
        return glm::dvec3(p[0], p[1], p[2]);
      };
      glm::dvec3 zenith(0.0);
      for (int col = 0; col < kW; ++col) zenith += rgbAt(col, 0);
      const double ourZenithY = xyz(zenith / double(kW)).y;
      std::vector<double> cie, preetham, chroma;
      for (int row = 0; row < kH / 2; ++row) {
        const double el = 90.0 - 180.0 * (row + 0.5) / kH;
        if (el < 10.0) continue;
        for (int col = 0; col < kW; ++col) {
          const glm::dvec3 V = enuDirection(360.0 * (col + 0.5) / kW, el);
          const double gamma = std::acos(std::clamp(glm::dot(V, S), -1.0, 1.0));
          if (gamma < 10.0 * kPi / 180.0) continue;
          const double theta = (90.0 - el) * kPi / 180.0;
          const glm::dvec3 c = xyz(rgbAt(col, row));
          const double relative = c.y / ourZenithY;
          cie.push_back(
              std::abs(relative / (kCieClearSky(theta, gamma) / kCieClearSky(0.0, thetaS)) - 1.0));
          preetham.push_back(std::abs(relative / (pY(theta, gamma) / pY(0.0, thetaS)) - 1.0));
          const double sum = c.x + c.y + c.z;
          const double x = c.x / sum, y = c.y / sum;
          const double wantX = xz * px(theta, gamma) / px(0.0, thetaS);
          const double wantY = yz * py(theta, gamma) / py(0.0, thetaS);
          chroma.push_back(std::max(std::abs(x / wantX - 1.0), std::abs(y / wantY - 1.0)));
        }
      }
      std::cout << "T " << T << ", sun " << elevation << ": luminance against CIE 12 median "
                << quantile(cie, 0.5) << ", 90th " << quantile(cie, 0.9)
                << "; against Preetham median " << quantile(preetham, 0.5) << ", 90th "
                << quantile(preetham, 0.9) << "; chromaticity median " << quantile(chroma, 0.5)
                << ", 90th " << quantile(chroma, 0.9) << "\n";
      cieAll.insert(cieAll.end(), cie.begin(), cie.end());
      preethamAll.insert(preethamAll.end(), preetham.begin(), preetham.end());
      chromaAll.insert(chromaAll.end(), chroma.begin(), chroma.end());
    }
  }
  const double median = quantile(cieAll, 0.5), p90 = quantile(cieAll, 0.9);
  const double preethamMedian = quantile(preethamAll, 0.5);
  const double preethamP90 = quantile(preethamAll, 0.9);
  const double chromaMedian = quantile(chromaAll, 0.5), chromaP90 = quantile(chromaAll, 0.9);
  std::cout << "all: luminance against CIE 12 median " << median << ", 90th " << p90
            << "; against Preetham median " << preethamMedian << ", 90th " << preethamP90
            << "; chromaticity median " << chromaMedian << ", 90th " << chromaP90 << "\n";
  EXPECT_LE(median, 0.05);
  EXPECT_LE(p90, 0.17);
  EXPECT_LE(chromaMedian, 0.10);
  EXPECT_LE(chromaP90, 0.10);
  // Today's level with a little room (see the file's comment).
  EXPECT_LT(preethamMedian, 0.15);
  EXPECT_LT(preethamP90, 0.40);
}

}  // namespace
}  // namespace sky::test
