#pragma once
// A spectral, brute-force reference for the physical sky (issue 30): the atmosphere of
// sky.model physical integrated wavelength by wavelength in double precision on the CPU, then
// converted to linear Rec. 709 (sRGB primaries, D65) through the CIE 1931 colour-matching
// functions, in the renderer's units. Nothing here shares code with the shaders, and no part of
// it uses Hillaire's Psi_ms for the first two orders:
// - order 1: sunlight scattered once along the view ray (Rayleigh and Cornette-Shanks phase
//   functions, the planet's shadow);
// - order 2: at points along the view ray, the once-scattered light (and the sunlit ground)
//   arriving from every direction of the sphere, each direction marched to the ground or the
//   top, weighted by the phase functions toward the camera;
// - orders 3 and up: isotropic, as a geometric series on the exact mean of the once-scattered
//   light at the point: sigma_s Lbar_1 f / (1 - f), f Hillaire's transfer factor (9) evaluated
//   directly. That is Hillaire's approximation moved one order up.
// Every sum is over "bands": wavelengths (spectralSky) or the renderer's three channels
// (channelSky), so the same integrator measures both and the difference between them is the
// three-channel rendering alone. docs/atmosphere.md ("A spectral reference") has the results.
#include <functional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/scene/scene.h"

namespace sky::test {

// The atmosphere as spectra. Defaults: Hillaire 2020's Earth (Bruneton & Neyret's Rayleigh,
// 300 DU of ozone in the 25 +- 15 km tent), aerosols as atmosphere.aerosols: turbidity makes them.
struct SpectralAtmosphere {
  double groundRadiusKm = 6360.0;
  double thicknessKm = 100.0;
  // Rayleigh scattering at the ground, beta(l) = rayleighAt550 (550 nm / l)^4: Bruneton &
  // Neyret's 1.24062e-6 m^-1 um^4 / l^4, from which Hillaire's 5.802, 13.558, 33.1 /Mm are its
  // values at 680, 550 and 440 nm. A pure l^-4: no dispersion of the refractive index and a
  // constant King factor (real air goes as about l^-4.08, Bodhaine et al. 1999).
  double rayleighAt550PerKm = 1.24062e-3 / (0.55 * 0.55 * 0.55 * 0.55);
  double rayleighScaleHeightKm = 8.0;
  // Aerosols: extinction at the ground at 550 nm, Angstrom's law (l / 550 nm)^-angstrom,
  // scattering the albedo's share of it; Cornette-Shanks phase with g, the same at every l.
  double mieExtinctionAt550PerKm = 0.1 / 1.2;
  double mieSingleScatteringAlbedo = 3.996 / 4.4;
  double mieAngstrom = 1.3;
  double mieScaleHeightKm = 1.2;
  double mieG = 0.6;
  // Ozone: its column in Dobson units (2.687e16 molecules/cm^2) spread over the tent, with the
  // 293 K cross-section of spectral_tables.h.
  double ozoneColumnDu = 300.0;
  double ozoneCenterKm = 25.0;
  double ozoneHalfWidthKm = 15.0;
  double groundAlbedo = 0.3;  // grey Lambertian
};

// The renderer's atmosphere (settings as physicalAtmosphere() resolves them) as spectra: the
// planet, the scale heights, the aerosols (mie_extinction at 550 nm, the Angstrom exponent,
// g, the albedo), the ozone tent's shape and the ground (grey, its Rec. 709 luminance). The
// Rayleigh strength and the ozone column are SpectralAtmosphere's: per-channel coefficients
// only sample those spectra.
SpectralAtmosphere spectralAtmosphere(const AtmosphereSettings& s);

// One band's optical properties, 1/km at density 1 (the ground for Rayleigh and Mie, the
// tent's peak for ozone), and what it adds to the result: rgb += toRgb * K, K the band's
// radiance per unit irradiance above the atmosphere in 1/sr.
struct SkyBand {
  double rayleigh = 0.0;
  double mieScattering = 0.0;
  double mieExtinction = 0.0;
  double ozone = 0.0;
  double groundAlbedo = 0.0;
  glm::dvec3 toRgb{0.0};
};

struct SkyMedium {
  double groundRadiusKm = 0.0, topRadiusKm = 0.0;
  double rayleighHeightKm = 0.0, mieHeightKm = 0.0, mieG = 0.0;
  double ozoneCenterKm = 0.0, ozoneHalfWidthKm = 0.0;
  std::vector<SkyBand> bands;
};

// Wavelengths 380..780 nm every stepNm (a multiple of 5). Each wavelength stands for the hat
// function around it (linear interpolation between samples), so toRgb is the integral of the
// colour-matching functions (to linear Rec. 709) times the solar spectrum over its hat. Scaled
// so that the sun above the atmosphere has luminance 1 and radiance is in the renderer's units
// (pi times 1/sr, docs/lighting.md): the result is renderer radiance per unit illuminance.
SkyMedium spectralSky(const SpectralAtmosphere& a, int stepNm);

// The renderer's three channels with the coefficients atmosphereParams() gives the GPU (the
// Mie coefficients scaled per channel by the Angstrom law), lit by `sunIlluminance` per channel.
SkyMedium channelSky(const AtmosphereSettings& s, glm::dvec3 sunIlluminance);

// The sun above the atmosphere in linear Rec. 709 with luminance 1 (from the E-490 spectrum).
glm::dvec3 solarColor();

// What the renderer's channels stand for: the averages of a spectrum over each channel's
// colour-matching function (CIE 1931 to linear Rec. 709) times the solar spectrum, the weights
// under which an optically thin atmosphere's three-channel sky equals its spectral sky. Negative
// averages (ozone in blue, where the blue function is negative) come back as 0.
glm::dvec3 channelAverage(const std::function<double(double wavelengthNm)>& spectrum);
// The same averages for the atmosphere's own spectra: Rayleigh (1/Mm at the ground), ozone
// (1/Mm at the tent's peak) and the aerosols' Angstrom factor (l / 550 nm)^-angstrom.
glm::dvec3 channelRayleighPerMm(const SpectralAtmosphere& a);
glm::dvec3 channelOzonePerMm(const SpectralAtmosphere& a);
glm::dvec3 channelAngstromFactor(double angstrom);

// Integration resolution. Checked against finer runs in spectral_sky_test.cpp and in
// docs/atmosphere.md.
struct BruteForceQuality {
  int viewSteps = 96;          // along the view ray (order 1, and where orders 2+ are applied)
  int scatterPoints = 12;      // segments along the view ray between sphere integrations
  int sphereBands = 8;         // Gauss-Legendre nodes in cos(zenith), above and below the horizon
  int sphereAzimuths = 16;     // over the whole circle
  int sphereSteps = 24;        // along each direction of the sphere
  int transferAltitudes = 48;  // altitudes of the table of f (orders 3+)
  int columnRadii = 96;        // the sun's optical-depth table: radii
  int columnAngles = 256;      //   and directions
  int columnSteps = 128;       //   steps along each of its rays
};

// Radiance in renderer units per unit illuminance above the atmosphere, linear Rec. 709, split
// by scattering order.
struct SkyRadiance {
  glm::dvec3 single{0.0};
  glm::dvec3 second{0.0};
  glm::dvec3 higher{0.0};
  // Orders 2+ as if the second order too were isotropic, sigma_s Lbar_1 / (1 - f): Hillaire's
  // Psi_ms with the true phase functions at the first scattering (a diagnostic).
  glm::dvec3 isotropic{0.0};
  // The same plus the second order's dependence on the view through the first Legendre moments
  // of the once-scattered light: its dipole for the aerosols (Rayleigh's phase has none) and
  // its quadrupole for both, 3 p_1 / (4 pi) int (dir.V) L_1 + 5 p_2 / (4 pi) int P_2(dir.V) L_1
  // (the LUTs' model since issue 30; a diagnostic).
  glm::dvec3 moments{0.0};
  glm::dvec3 total() const { return single + second + higher; }
};

class BruteForceSky {
public:
  // Builds the sun's optical-depth table and the table of f (a fraction of a second at the
  // default quality).
  BruteForceSky(SkyMedium medium, BruteForceQuality q = {});

  // The sky from a camera `altitudeKm` above the ground along unit V (east-north-up, z up) lit
  // by a light in direction L: the air only, to the top or the ground (the ground itself is
  // not in it, as in the sky-view LUT). Thread-safe.
  SkyRadiance radiance(double altitudeKm, glm::dvec3 V, glm::dvec3 L) const;

  // radiance() for many directions on `threads` threads.
  std::vector<SkyRadiance> radiance(double altitudeKm, const std::vector<glm::dvec3>& V,
                                    glm::dvec3 L, int threads) const;

  const SkyMedium& medium() const { return mM; }

  // Transmittance per band from radius r along cos(zenith) mu to the top, from the table (0
  // in the planet's shadow), and the same by direct quadrature with `steps` steps (tests).
  std::vector<double> sunTransmittance(double r, double mu) const;
  std::vector<double> sunTransmittanceDirect(double r, double mu, int steps) const;

private:
  struct Columns {
    double rayleigh = 0.0, mie = 0.0, ozone = 0.0;  // km of unit density
  };
  Columns sunColumns(double r, double mu) const;
  Columns columnsDirect(double r, double mu, int steps) const;
  double transferFactor(size_t band, double r) const;

  SkyMedium mM;
  BruteForceQuality mQ;
  std::vector<Columns> mColumns;  // columnRadii x columnAngles
  std::vector<double> mTransfer;  // transferAltitudes x bands
};

// Rec. 709 luminance and CIE xy chromaticity of a linear Rec. 709 colour.
double luminance709(glm::dvec3 rgb);
glm::dvec2 chromaticity709(glm::dvec3 rgb);

}  // namespace sky::test
