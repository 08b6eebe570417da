// Geocentric Moon after Meeus, Astronomical Algorithms 2nd ed. (1998), chapter 47.
#include <cmath>
#include <cstdlib>
#include <iterator>

#include "engine/lighting/ephemeris.h"
#include "engine/lighting/moon_terms.h"

namespace sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kRadToDeg = 180.0 / kPi;

// Row counts of Tables 47.A and 47.B.
static_assert(std::size(meeus::kMoonLongitudeDistance) == 60);
static_assert(std::size(meeus::kMoonLatitude) == 60);

// [0, 360); a tiny negative input would otherwise round up to exactly 360.
double wrap360(double deg) {
  double w = std::fmod(deg, 360.0);
  if (w < 0.0) w += 360.0;
  return w >= 360.0 ? 0.0 : w;
}

// c0 + c1 T + c2 T² + c3 T³ + c4 T⁴, in degrees, reduced to [0, 360).
double quartic(double t, double c0, double c1, double c2, double c3, double c4) {
  return wrap360((((c4 * t + c3) * t + c2) * t + c1) * t + c0);
}

}  // namespace

GeocentricMoon moonGeocentric(double jde) {
  const double t = julianCenturies(jde);
  // Meeus (47.1)-(47.5): mean longitude, mean elongation, Sun's mean anomaly, Moon's mean
  // anomaly, argument of latitude (degrees).
  const double lp =
      quartic(t, 218.3164477, 481267.88123421, -0.0015786, 1.0 / 538841.0, -1.0 / 65194000.0);
  const double d =
      quartic(t, 297.8501921, 445267.1114034, -0.0018819, 1.0 / 545868.0, -1.0 / 113065000.0);
  const double m = quartic(t, 357.5291092, 35999.0502909, -0.0001536, 1.0 / 24490000.0, 0.0);
  const double mp =
      quartic(t, 134.9633964, 477198.8675055, 0.0087414, 1.0 / 69699.0, -1.0 / 14712000.0);
  const double f =
      quartic(t, 93.2720950, 483202.0175233, -0.0036539, -1.0 / 3526000.0, 1.0 / 863310000.0);
  // Venus (A1), Jupiter (A2) and the flattening of the Earth (A3), p. 338.
  const double a1 = wrap360(119.75 + 131.849 * t) * kDegToRad;
  const double a2 = wrap360(53.09 + 479264.290 * t) * kDegToRad;
  const double a3 = wrap360(313.45 + 481266.484 * t) * kDegToRad;
  // Meeus (47.6): the decreasing eccentricity of the Earth's orbit scales terms in M by E^|m|.
  const double e = 1.0 - t * (0.002516 + 0.0000074 * t);
  const double eFactor[3] = {1.0, e, e * e};

  const double dr = d * kDegToRad;
  const double mr = m * kDegToRad;
  const double mpr = mp * kDegToRad;
  const double fr = f * kDegToRad;
  const double lpr = lp * kDegToRad;

  double sigmaL = 0.0;
  double sigmaR = 0.0;
  for (const meeus::MoonLongitudeDistanceTerm& term : meeus::kMoonLongitudeDistance) {
    const double arg = term.d * dr + term.m * mr + term.mPrime * mpr + term.f * fr;
    const double scale = eFactor[std::abs(term.m)];
    sigmaL += term.sigmaL * scale * std::sin(arg);
    sigmaR += term.sigmaR * scale * std::cos(arg);
  }
  double sigmaB = 0.0;
  for (const meeus::MoonLatitudeTerm& term : meeus::kMoonLatitude) {
    const double arg = term.d * dr + term.m * mr + term.mPrime * mpr + term.f * fr;
    sigmaB += term.sigmaB * eFactor[std::abs(term.m)] * std::sin(arg);
  }
  // Additive terms, p. 342.
  sigmaL += 3958.0 * std::sin(a1) + 1962.0 * std::sin(lpr - fr) + 318.0 * std::sin(a2);
  sigmaB += -2235.0 * std::sin(lpr) + 382.0 * std::sin(a3) + 175.0 * std::sin(a1 - fr) +
            175.0 * std::sin(a1 + fr) + 127.0 * std::sin(lpr - mpr) - 115.0 * std::sin(lpr + mpr);

  GeocentricMoon moon{};
  moon.longitudeDeg = wrap360(lp + sigmaL / 1e6);  // λ, mean equinox of date
  moon.latitudeDeg = sigmaB / 1e6;                 // β
  moon.distanceKm = 385000.56 + sigmaR / 1000.0;   // Δ

  // Apparent place (p. 343): nutation in longitude, then the true obliquity.
  const Nutation n = nutation(jde);
  moon.apparentLongitudeDeg = wrap360(moon.longitudeDeg + n.longitudeDeg);
  const double lambda = moon.apparentLongitudeDeg * kDegToRad;
  const double beta = moon.latitudeDeg * kDegToRad;
  const double eps = n.trueObliquityDeg * kDegToRad;
  // Meeus (13.3), (13.4).
  const double alpha = std::atan2(std::sin(lambda) * std::cos(eps) - std::tan(beta) * std::sin(eps),
                                  std::cos(lambda));
  const double delta =
      std::asin(std::sin(beta) * std::cos(eps) + std::cos(beta) * std::sin(eps) * std::sin(lambda));
  moon.rightAscensionDeg = wrap360(alpha * kRadToDeg);
  moon.declinationDeg = delta * kRadToDeg;
  return moon;
}

}  // namespace sky
