// The physical sky against its spectral brute-force reference (issue 30; docs/atmosphere.md,
// "A spectral reference"), and checks of the reference itself: its colour conversion, its
// sun table, and that the renderer's channel coefficients are the channel averages of its
// spectra.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "atmosphere_reference.h"
#include "atmosphere_test_util.h"
#include "engine/lighting/light_model.h"
#include "engine/render/renderer.h"
#include "spectral_sky_compare.h"
#include "spectral_sky_reference.h"

namespace sky::test {
namespace {

TEST(SpectralSky, SunHasLuminanceOneAndBandsSplitItExactly) {
  // The sun above the atmosphere in Rec. 709 with luminance 1, warmer than D65 (the E-490
  // spectrum is a ~5800 K sun); every wavelength grid's hats add up to it, so a white
  // Lambertian under unit illuminance (radiance 1/pi per unit irradiance at every wavelength)
  // has radiance equal to the sun's colour, luminance 1, in renderer units.
  const glm::dvec3 sun = solarColor();
  // 1 up to the four digits of the XYZ <-> Rec. 709 matrices.
  EXPECT_NEAR(luminance709(sun), 1.0, 1e-4);
  EXPECT_GT(sun.r, sun.g);
  EXPECT_GT(sun.g, sun.b);
  for (int step : {5, 10, 20, 25, 40}) {
    const SkyMedium m = spectralSky(SpectralAtmosphere{}, step);
    glm::dvec3 white(0.0);
    for (const SkyBand& b : m.bands) white += b.toRgb / kPi;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(white[c], sun[c], 1e-9) << "step " << step;
  }
}

TEST(SpectralSky, CornetteShanksMomentsMatchQuadrature) {
  for (double g : {0.0, 0.6, 0.8}) {
    glm::dvec2 q(0.0);
    for (const auto& [x, w] : gaussLegendre(96)) {
      const double g2 = g * g;
      const double phase = 3.0 / (8.0 * kPi) * (1.0 - g2) * (1.0 + x * x) /
                           ((2.0 + g2) * std::pow(1.0 + g2 - 2.0 * g * x, 1.5));
      q += 2.0 * kPi * w * phase * glm::dvec2(x, 0.5 * (3.0 * x * x - 1.0));
    }
    const glm::dvec2 closed = cornetteShanksMoments(g);
    EXPECT_NEAR(closed.x, q.x, 1e-6) << "g " << g;
    EXPECT_NEAR(closed.y, q.y, 1e-6) << "g " << g;
  }
}

TEST(SpectralSky, SunTableMatchesDirectQuadrature) {
  // The sun's optical depths come from a table in (r, mu); against 4096-step quadrature
  // within 0.5 % of the optical depth (those under 0.1 count as 0.1) per band, from the
  // ground to the top and from straight up to below the horizontal. Measured: 0.14 % up to
  // 5 km, 0.45 % for a ray grazing the ground from 20 km up (optical depth 10).
  BruteForceQuality q;
  const BruteForceSky sky(spectralSky(spectralAtmosphere(physicalAtmosphere(Scene{})), 20), q);
  const double Rg = sky.medium().groundRadiusKm;
  double worst = 0.0;
  for (double h : {0.01, 0.2, 1.0, 5.0, 20.0, 60.0}) {
    const double r = Rg + h;
    const double muH = -std::sqrt(1.0 - (Rg / r) * (Rg / r));
    for (double mu : {1.0, 0.5, 0.2, 0.05, 0.0, 0.5 * muH, 0.99 * muH}) {
      const std::vector<double> table = sky.sunTransmittance(r, mu);
      const std::vector<double> direct = sky.sunTransmittanceDirect(r, mu, 4096);
      for (size_t b = 0; b < table.size(); ++b) {
        const double tauT = -std::log(table[b]), tauD = -std::log(direct[b]);
        worst = std::max(worst, std::abs(tauT - tauD) / std::max(tauD, 0.1));
      }
    }
  }
  std::cout << "sun table: worst optical-depth error " << worst << "\n";
  EXPECT_LT(worst, 5e-3);
}

}  // namespace
}  // namespace sky::test

namespace sky::test {
namespace {

TEST(SpectralSky, ChannelCoefficientsAreTheSpectrumsChannelAverages) {
  // The renderer's defaults and the lighting model's channel constants are the channel
  // averages of the spectral atmosphere (spectral_sky_reference.h: channelAverage), to the
  // digits they are written with.
  const SpectralAtmosphere a;
  const AtmosphereSettings s;
  const glm::dvec3 rayleigh = channelRayleighPerMm(a), ozone = channelOzonePerMm(a);
  const glm::dvec3 aerosol = channelAngstromFactor(light::kAerosolAngstrom);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(s.rayleighScattering[c], rayleigh[c], 1e-3 * rayleigh[c]) << "channel " << c;
    EXPECT_NEAR(s.ozoneAbsorption[c], ozone[c], 1e-3) << "channel " << c;
    EXPECT_NEAR(std::pow(light::kChannelAerosolWavelengthsNm[c] / 550.0, -light::kAerosolAngstrom),
                aerosol[c], 1e-4)
        << "channel " << c;
    // The cross-section: absorption at the tent's peak (1/km) times its half width over the
    // column (molecules per cm^2).
    EXPECT_NEAR(light::kChannelOzoneCrossSectionCm2[c] * 1e21,
                ozone[c] * 1e-3 * a.ozoneHalfWidthKm / (a.ozoneColumnDu * 2.687e16) * 1e21, 2e-3)
        << "channel " << c;
  }
  // Hansen & Travis' Rayleigh optical depth, averaged.
  const glm::dvec3 ht = channelAverage([](double nm) {
    const double l2 = nm * nm * 1e-6;
    return 0.008569 / (l2 * l2) * (1.0 + 0.0113 / l2 + 0.00013 / (l2 * l2));
  });
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(light::kChannelRayleighDepth[c], ht[c], 1e-5);
}

TEST(SpectralSky, ThinAtmosphereInChannelsIsItsSpectrum) {
  // Why the channel averages: an optically thin atmosphere (a thousandth of Earth's air, no
  // ozone, no aerosols) rendered in three channels with the averaged coefficients and lit by
  // the sun's colour equals its spectral rendering, to the first order in the optical depth.
  SpectralAtmosphere a;
  a.rayleighAt550PerKm *= 1e-3;
  a.mieExtinctionAt550PerKm = 0.0;
  a.ozoneColumnDu = 0.0;
  a.groundAlbedo = 0.0;
  AtmosphereSettings s;
  s.rayleighScattering = glm::vec3(channelRayleighPerMm(a));
  s.mieScattering = s.mieExtinction = 0.0;
  s.ozoneAbsorption = glm::vec3(0.0f);
  s.groundAlbedo = glm::vec3(0.0f);
  BruteForceQuality q;
  q.scatterPoints = 2;
  q.sphereBands = 2;
  q.sphereAzimuths = 4;
  const BruteForceSky spectral(spectralSky(a, 10), q);
  const BruteForceSky channels(channelSky(s, solarColor()), q);
  const glm::dvec3 L = glm::normalize(glm::dvec3(0.0, -1.0, 0.5));
  for (const glm::dvec3& V : {glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(1, 1, 0.2))}) {
    const glm::dvec3 want = spectral.radiance(0.2, V, L).total();
    const glm::dvec3 got = channels.radiance(0.2, V, L).total();
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c] / want[c], 1.0, 2e-3) << "channel " << c;
  }
}

}  // namespace
}  // namespace sky::test

namespace sky::test {
namespace {

TEST_F(AtmosphereTest, LutSkyMatchesTheSpectralReference) {
  // Goal 6 of issue 30: the LUT sky (the probe, through skyViewRadiance) within 5 % median
  // luminance of the spectral brute-force reference over the dome, the LUTs lit by the sun's
  // own colour. A 36 x 18 probe (10 degree cells; the half dome on one side of the sun, 162
  // directions) and the reference at its "test" resolution every 20 nm, which stays within
  // 0.4-2.0 % median luminance of the "default" one every 10 nm (docs/atmosphere.md, "A
  // spectral reference"). Per case, over the upper half dome weighted by solid angle: luminance
  // |Y / Y_ref - 1| median at most 5 % and 90th percentile 10 %; chromaticity (the larger
  // relative error of CIE x and y) median 3 %, 90th percentile 5 %; the zenith's R/G within
  // 8 %. Measured: luminance 0.5-3.0 % and 2.0-5.8 %, chromaticity 0.3-1.4 % and 0.8-2.1 %,
  // R/G 0.998-1.04 times the reference's. Before issue 30 the twelve cases of the docs gave
  // up to 9 %, 14 %, 5 %, 8 % and 1.28 times.
  const HalfDome dome{36, 18};
  const std::vector<glm::dvec3> directions = dome.directions();
  const BruteForceQuality q = referenceQuality("test");
  const int threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
  const glm::dvec3 sun = solarColor();
  for (const SkyCase& c : standardCases({5.0, 10.0, 30.0, 60.0})) {
    // Four of the twelve cases of docs/atmosphere.md, to keep to a few seconds: each
    // turbidity with a low and a high sun ("default" has T 2's aerosols, 0.1 against 0.1008).
    const bool t2 = c.name == "T 2", t3 = c.name == "T 3";
    if (!(t2 && (c.sunElevationDeg == 10.0 || c.sunElevationDeg == 60.0)) &&
        !(t3 && (c.sunElevationDeg == 5.0 || c.sunElevationDeg == 30.0)))
      continue;
    SCOPED_TRACE(c.name + ", sun " + std::to_string(c.sunElevationDeg));
    const AtmosphereLuts::Frame frame = caseFrame(c, sun);
    const FrameResult result =
        run(frame, static_cast<uint32_t>(dome.width), static_cast<uint32_t>(dome.height));
    const std::vector<glm::dvec3> lut = halfDomeOf(result.output("probe"), dome);
    const BruteForceSky reference(
        spectralSky(spectralAtmosphere(frame.atmosphere), kTestWavelengthStepNm), q);
    std::vector<glm::dvec3> ref;
    for (const SkyRadiance& s :
         reference.radiance(kCompareAltitudeKm, directions, caseSunDirection(c), threads))
      ref.push_back(s.total());
    const SkyStats s = compareSky(lut, ref, dome);
    std::cout << c.name << ", sun " << c.sunElevationDeg << ": luminance median "
              << s.luminanceMedian << ", 90th " << s.luminanceP90 << "; chromaticity median "
              << s.chromaMedian << ", 90th " << s.chromaP90 << "; zenith R/G "
              << s.zenithRg() / s.zenithRgRef() << " of the reference's\n";
    EXPECT_LE(s.luminanceMedian, 0.05);
    EXPECT_LE(s.luminanceP90, 0.10);
    EXPECT_LE(s.chromaMedian, 0.03);
    EXPECT_LE(s.chromaP90, 0.05);
    EXPECT_NEAR(s.zenithRg() / s.zenithRgRef(), 1.0, 0.08);
  }
}

}  // namespace
}  // namespace sky::test
