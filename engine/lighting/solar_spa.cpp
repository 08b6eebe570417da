// Geocentric Sun and nutation after the NREL Solar Position Algorithm (Reda & Andreas,
// NREL/TP-560-34302, revised 2008); equation numbers "SPA (3.x.y)" are the report's.
#include <cmath>
#include <iterator>

#include "engine/lighting/ephemeris.h"
#include "engine/lighting/spa_terms.h"

namespace sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kRadToDeg = 180.0 / kPi;

// Row counts of SPA Tables A4.2 and A4.3: a dropped or doubled row fails the build.
static_assert(std::size(spa::kL0) == 64 && std::size(spa::kL1) == 34 && std::size(spa::kL2) == 20 &&
              std::size(spa::kL3) == 7 && std::size(spa::kL4) == 3 && std::size(spa::kL5) == 1);
static_assert(std::size(spa::kB0) == 5 && std::size(spa::kB1) == 2);
static_assert(std::size(spa::kR0) == 40 && std::size(spa::kR1) == 10 && std::size(spa::kR2) == 6 &&
              std::size(spa::kR3) == 2 && std::size(spa::kR4) == 1);
static_assert(std::size(spa::kNutation) == 63);

// [0, 360); a tiny negative input would otherwise round up to exactly 360.
double wrap360(double deg) {
  double w = std::fmod(deg, 360.0);
  if (w < 0.0) w += 360.0;
  return w >= 360.0 ? 0.0 : w;
}

// SPA (3.2.1): sum of A cos(B + C tau) over one series.
template <std::size_t N>
double seriesSum(const spa::EarthTerm (&terms)[N], double tau) {
  double sum = 0.0;
  for (const spa::EarthTerm& t : terms) sum += t.a * std::cos(t.b + t.c * tau);
  return sum;
}

// SPA (3.2.7) / (3.2.8): (S0 + S1 tau + S2 tau² + ...) / 1e8, in radians or AU.
double polynomialInTau(const double* sums, int count, double tau) {
  double value = 0.0;
  for (int i = count - 1; i >= 0; --i) value = value * tau + sums[i];
  return value / 1e8;
}

struct HeliocentricEarth {
  double longitudeDeg;
  double latitudeDeg;
  double radiusAu;
};

HeliocentricEarth earthHeliocentric(double jme) {
  const double l[] = {seriesSum(spa::kL0, jme), seriesSum(spa::kL1, jme), seriesSum(spa::kL2, jme),
                      seriesSum(spa::kL3, jme), seriesSum(spa::kL4, jme), seriesSum(spa::kL5, jme)};
  const double b[] = {seriesSum(spa::kB0, jme), seriesSum(spa::kB1, jme)};
  const double r[] = {seriesSum(spa::kR0, jme), seriesSum(spa::kR1, jme), seriesSum(spa::kR2, jme),
                      seriesSum(spa::kR3, jme), seriesSum(spa::kR4, jme)};
  return {wrap360(polynomialInTau(l, 6, jme) * kRadToDeg),  // SPA (3.2.7)-(3.2.8)
          polynomialInTau(b, 2, jme) * kRadToDeg,           // SPA (3.2.9)
          polynomialInTau(r, 5, jme)};                      // SPA (3.2.10)
}

double cubic(double a, double b, double c, double d, double x) {
  return ((a * x + b) * x + c) * x + d;
}

}  // namespace

Nutation nutation(double jde) {
  const double jce = julianCenturies(jde);
  // SPA (3.4.1)-(3.4.5) = Meeus (22.x): mean elongation of the Moon from the Sun, mean anomaly
  // of the Sun, mean anomaly of the Moon, Moon's argument of latitude, longitude of the
  // ascending node of the Moon's mean orbit. Degrees.
  const double x[5] = {
      cubic(1.0 / 189474.0, -0.0019142, 445267.11148, 297.85036, jce),
      cubic(-1.0 / 300000.0, -0.0001603, 35999.05034, 357.52772, jce),
      cubic(1.0 / 56250.0, 0.0086972, 477198.867398, 134.96298, jce),
      cubic(1.0 / 327270.0, -0.0036825, 483202.017538, 93.27191, jce),
      cubic(1.0 / 450000.0, 0.0020708, -1934.136261, 125.04452, jce),
  };
  double psi = 0.0;
  double eps = 0.0;
  // Smallest terms first, so the sum loses the least to rounding.
  for (auto it = std::rbegin(spa::kNutation); it != std::rend(spa::kNutation); ++it) {
    double arg = 0.0;
    for (int j = 0; j < 5; ++j) arg += it->multiple[j] * x[j];
    arg *= kDegToRad;
    psi += (it->a + it->b * jce) * std::sin(arg);  // SPA (3.4.7)
    eps += (it->c + it->d * jce) * std::cos(arg);  // SPA (3.4.8)
  }
  Nutation n{};
  n.longitudeDeg = psi / 36000000.0;  // SPA (3.4.9): units of 0.0001" to degrees
  n.obliquityDeg = eps / 36000000.0;  // SPA (3.4.10)
  // SPA (3.5.1) = Meeus (22.3), Laskar's expression, U = JME / 10 = T / 100; arcseconds.
  const double u = jce / 100.0;
  static constexpr double kLaskar[] = {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67,
                                       -39.05,    7.12,     27.87, 5.79,    2.45};
  double epsilon0 = 0.0;
  for (int i = static_cast<int>(std::size(kLaskar)) - 1; i >= 0; --i)
    epsilon0 = epsilon0 * u + kLaskar[i];
  n.meanObliquityDeg = epsilon0 / 3600.0;
  n.trueObliquityDeg = n.meanObliquityDeg + n.obliquityDeg;  // SPA (3.5.2)
  return n;
}

GeocentricSun sunGeocentric(double jde) {
  const double jme = julianCenturies(jde) / 10.0;  // SPA (3.1.4): Julian ephemeris millennia
  const HeliocentricEarth earth = earthHeliocentric(jme);
  const double theta = wrap360(earth.longitudeDeg + 180.0);  // SPA (3.3.1)
  const double beta = -earth.latitudeDeg;                    // SPA (3.3.3)
  const Nutation n = nutation(jde);
  const double aberration = -20.4898 / (3600.0 * earth.radiusAu);      // SPA (3.6.1)
  const double lambda = wrap360(theta + n.longitudeDeg + aberration);  // SPA (3.7.1)

  const double lambdaRad = lambda * kDegToRad;
  const double betaRad = beta * kDegToRad;
  const double epsRad = n.trueObliquityDeg * kDegToRad;
  // SPA (3.8.1), (3.9.1) = Meeus (13.3), (13.4).
  const double alpha =
      std::atan2(std::sin(lambdaRad) * std::cos(epsRad) - std::tan(betaRad) * std::sin(epsRad),
                 std::cos(lambdaRad));
  const double delta = std::asin(std::sin(betaRad) * std::cos(epsRad) +
                                 std::cos(betaRad) * std::sin(epsRad) * std::sin(lambdaRad));
  return {lambda, beta, earth.radiusAu, wrap360(alpha * kRadToDeg), delta * kRadToDeg};
}

}  // namespace sky
