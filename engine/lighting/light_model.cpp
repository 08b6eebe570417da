#include "engine/lighting/light_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>

#include "engine/lighting/spectral_tables.h"
#include "shaders/common/geo_shared.h"

namespace sky::light {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
// The geographic Earth (engine/weather/geo.h): the sphere whose horizon a point above the
// ground sees below.
constexpr double kEarthRadiusM = GEO_EARTH_RADIUS_M;

// Ozone, 300 Dobson units = 8.07e18 molecules/cm^2, times the channel's cross-section.
constexpr double kOzoneColumnPerCm2 = 8.07e18;

}  // namespace

double airMass(double apparentElevationDeg) {
  double h = std::max(apparentElevationDeg, -1.0);
  // Kasten & Young (1989): m = 1 / (sin h + 0.50572 (h + 6.07995)^-1.6364).
  return 1.0 / (std::sin(h * kDeg) + 0.50572 * std::pow(h + 6.07995, -1.6364));
}

HazeMedium hazeMedium(double turbidity) {
  HazeMedium h;
  for (int c = 0; c < 3; ++c) {
    // A column of optical depth tau with scale height H has tau / H at its base.
    h.rayleighPerM[c] = kChannelRayleighDepth[c] / h.rayleighHeightM;
    h.aerosolPerM[c] = turbidity *
                       std::pow(kChannelAerosolWavelengthsNm[c] / 550.0, -kAerosolAngstrom) /
                       h.aerosolHeightM;
  }
  return h;
}

double rayleighDepth(double lambdaNm) {
  const double l2 = (lambdaNm * 1e-3) * (lambdaNm * 1e-3);  // micrometres squared
  return 0.008569 / (l2 * l2) * (1.0 + 0.0113 / l2 + 0.00013 / (l2 * l2));
}

namespace {

// One slant path of a light's beam: `airMass` air masses from `altitudeM` up (negative: the
// part of a longer path that another one counts twice).
struct SlantPath {
  double airMass;
  double altitudeM;
};

// The broadband transmittance of the beam along the sum of `paths`, per channel: each
// channel's share of the sunlight (spectral_tables.h) that the air lets through, every 5 nm.
glm::dvec3 broadbandTransmittance(std::initializer_list<SlantPath> paths, double turbidity) {
  const HazeMedium haze = hazeMedium(turbidity);
  // Optical depth per unit of its 550 nm or per-wavelength column: the standard atmosphere's
  // Rayleigh column (pressure scale height 8.434 km), the aerosols' (mostly below 1.2 km) and
  // the ozone's (above 15 km, the same for every path that starts below it).
  double rayleighColumns = 0.0, aerosolColumns = 0.0, ozoneColumns = 0.0;
  for (const SlantPath& p : paths) {
    const double h = std::max(p.altitudeM, 0.0);
    rayleighColumns += p.airMass * std::exp(-p.altitudeM / haze.rayleighHeightM);
    aerosolColumns += p.airMass * turbidity * std::exp(-h / haze.aerosolHeightM);
    ozoneColumns += p.airMass;
  }
  glm::dvec3 through(0.0), all(0.0);
  for (int i = 0; i < spectral::kCount; ++i) {
    const double nm = spectral::wavelengthNm(i);
    const double tau = rayleighDepth(nm) * rayleighColumns +
                       kOzoneColumnPerCm2 * spectral::kOzoneCrossSection[i] * 1e-21 * ozoneColumns +
                       std::pow(nm / 550.0, -kAerosolAngstrom) * aerosolColumns;
    const glm::dvec3 sun =
        spectral::tableWeight(i) * spectral::kSolarIrradiance[i] * spectral::rgbMatching(i);
    through += sun * std::exp(-tau);  // Beer-Lambert along the path
    all += sun;
  }
  // Blue's matching function dips below zero in the red: where only red light is left the
  // blue channel's sum can go slightly negative, and no air adds light.
  return glm::max(through / all, glm::dvec3(0.0));
}

}  // namespace

glm::dvec3 atmosphereTransmittance(double apparentElevationDeg, double altitudeM,
                                   double turbidity) {
  return broadbandTransmittance({{airMass(apparentElevationDeg), altitudeM}}, turbidity);
}

double discAboveHorizon(double elevationDeg, double radiusDeg) {
  if (radiusDeg <= 0.0) return elevationDeg >= 0.0 ? 1.0 : 0.0;
  double x = std::clamp(elevationDeg / radiusDeg, -1.0, 1.0);
  // Area of the circular segment above a chord at height -x (unit disc), over pi.
  return (std::acos(-x) + x * std::sqrt(1.0 - x * x)) / kPi;
}

double moonIlluminanceLux(double phaseAngleDeg, double distanceKm) {
  double a = std::fabs(phaseAngleDeg);
  double footCandles = std::pow(10.0, -0.4 * (3.84 + 0.026 * a + 4e-9 * a * a * a * a));
  double d = 384400.0 / distanceKm;
  return footCandles * 10.7639 * d * d;
}

double earthshineRatio(double moonIlluminatedFraction) {
  return 2.4e-4 * std::clamp(1.0 - moonIlluminatedFraction, 0.0, 1.0);
}

double twilightIlluminanceLux(double sunElevationDeg) {
  // (elevation, log10 lux), clear sky, sun and sky together.
  static constexpr std::array<std::array<double, 2>, 16> kTable = {{
      {-90.0, -3.30},
      {-18.0, -3.22},
      {-16.0, -3.05},
      {-14.0, -2.75},
      {-12.0, -2.10},
      {-10.0, -1.40},
      {-8.0, -0.50},
      {-6.0, 0.53},
      {-4.0, 1.45},
      {-2.0, 2.30},
      {0.0, 2.88},
      {5.0, 3.90},
      {10.0, 4.30},
      {30.0, 4.78},
      {60.0, 5.00},
      {90.0, 5.05},
  }};
  double h = std::clamp(sunElevationDeg, -90.0, 90.0);
  for (size_t i = 1; i < kTable.size(); ++i) {
    if (h <= kTable[i][0]) {
      double t = (h - kTable[i - 1][0]) / (kTable[i][0] - kTable[i - 1][0]);
      return std::pow(10.0, kTable[i - 1][1] + t * (kTable[i][1] - kTable[i - 1][1]));
    }
  }
  return std::pow(10.0, kTable.back()[1]);
}

double nightLiftEv(double sunElevationDeg, double adaptation) {
  if (sunElevationDeg >= 0.0) return 0.0;
  return adaptation *
         std::log2(twilightIlluminanceLux(0.0) / twilightIlluminanceLux(sunElevationDeg));
}

double sceneNightLiftEv(double sunElevationDeg, double skyLuminance, double moonlitSkyLuminance,
                        double adaptation) {
  // Every stop the twilight has lost: the most an eye can make up, 0 while the sun is up.
  const double twilightStops = nightLiftEv(sunElevationDeg, 1.0);
  // Anchored where a night ends up: the brightest moonlit sky gets the full night lift the
  // sun's lift gives every night, a darker sky `adaptation` of each stop it is darker more.
  // Through the twilight the cap is the tighter bound, so the exposure follows the fading sky
  // all the way down to moonlight and makes up only part of the loss below it, roughly as an
  // eye adapts almost fully in cone and mesopic light and only partly where the rods alone see.
  const double night = skyLuminance > 0.0 && moonlitSkyLuminance > 0.0
                           ? nightLiftEv(-90.0, adaptation) +
                                 adaptation * std::log2(moonlitSkyLuminance / skyLuminance)
                           : twilightStops;
  return std::max(nightLiftEv(sunElevationDeg, adaptation), std::min(night, twilightStops));
}

double lowSunLiftEv(double sunElevationDeg) {
  constexpr double kDaylightDeg = 10.0;
  const double h = std::clamp(sunElevationDeg, 0.0, kDaylightDeg);
  return kLowSunAdaptation *
         std::log2(twilightIlluminanceLux(kDaylightDeg) / twilightIlluminanceLux(h));
}

double autoExposureEv(double sunElevationDeg, double nightLift) {
  return std::max(lowSunLiftEv(sunElevationDeg), nightLift);
}

double paletteExposureEv(double sunElevationDeg) {
  return nightLiftEv(sunElevationDeg, kPaletteNightAdaptation);
}

double dayFactor(double sunElevationDeg) {
  double full = std::log2(twilightIlluminanceLux(0.0) / twilightIlluminanceLux(-90.0));
  return std::clamp(1.0 - nightLiftEv(sunElevationDeg, 1.0) / full, 0.0, 1.0);
}

glm::dvec3 moonColor() {
  // A B-V excess of 0.27 mag over the sun, spread over the channels by wavelength (redder
  // light loses less): about -0.12, 0, +0.15 mag in R, G, B.
  glm::dvec3 c{std::pow(10.0, 0.4 * 0.12), 1.0, std::pow(10.0, -0.4 * 0.15)};
  return c / luminance(c);
}

glm::dvec3 solarColor() {
  static const glm::dvec3 kColor = [] {
    glm::dvec3 c(0.0);
    for (int i = 0; i < spectral::kCount; ++i)
      c += spectral::rgbMatching(i) * spectral::kSolarIrradiance[i] * spectral::tableWeight(i);
    return c / luminance(c);
  }();
  return kColor;
}

double overcastGlobalShare(double n) {
  return 1.0 - 0.75 * std::pow(std::clamp(n, 0.0, 1.0), 3.4);
}

double luminance(const glm::dvec3& rgb) {
  return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
}

LayerIlluminance illuminanceAcrossLayer(const glm::vec3& aboveAtmosphere, double elevationDeg,
                                        double radiusDeg, double baseM, double topM,
                                        double turbidity) {
  const auto at = [&](double altitudeM) {
    return illuminanceAtAltitude(aboveAtmosphere, elevationDeg, radiusDeg, altitudeM, turbidity);
  };
  return {at(baseM), at(0.5 * (baseM + topM)), at(topM)};
}

glm::vec3 illuminanceAtAltitude(const glm::vec3& aboveAtmosphere, double elevationDeg,
                                double radiusDeg, double altitudeM, double turbidity) {
  const double h = std::max(altitudeM, 0.0);
  const double dipDeg = std::acos(kEarthRadiusM / (kEarthRadiusM + h)) / kDeg;
  const double visible = discAboveHorizon(elevationDeg + dipDeg, radiusDeg);
  if (visible <= 0.0) return glm::vec3(0.0f);
  glm::dvec3 t;
  if (elevationDeg >= 0.0) {
    t = atmosphereTransmittance(elevationDeg, h, turbidity);
  } else {
    // Below the point's horizontal the ray dips to a tangent height ht before climbing out:
    // roughly a horizontal path out from ht, plus the descent from h to ht (the horizontal
    // path from ht less the one from h). Equal to the path from h at elevation 0.
    const double c = std::cos(std::min(-elevationDeg, dipDeg) * kDeg);
    const double ht = (kEarthRadiusM + h) * c - kEarthRadiusM;
    const double horizontal = airMass(0.0);
    t = broadbandTransmittance({{2.0 * horizontal, ht}, {-horizontal, h}}, turbidity);
  }
  return glm::vec3(glm::dvec3(aboveAtmosphere) * t * visible);
}

}  // namespace sky::light
