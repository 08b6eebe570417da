#include "engine/lighting/time_scales.h"

#include <cmath>

namespace sky {
namespace {

// Horner evaluation of c[0] + c[1] t + c[2] t² + ...
template <int N>
double polynomial(double t, const double (&c)[N]) {
  double sum = 0.0;
  for (int i = N - 1; i >= 0; --i) sum = sum * t + c[i];
  return sum;
}

double longTermParabola(double year) {
  const double u = (year - 1820.0) / 100.0;
  return -20.0 + 32.0 * u * u;
}

}  // namespace

double julianDate(int year, int month, int day, int hour, int minute, double second) {
  // Meeus (7.1) with the Gregorian correction B = 2 - A + A/4.
  int y = year;
  int m = month;
  if (m <= 2) {
    y -= 1;
    m += 12;
  }
  const int a = static_cast<int>(std::floor(y / 100.0));
  const int b = 2 - a + static_cast<int>(std::floor(a / 4.0));
  const double dayFraction = (hour + (minute + second / 60.0) / 60.0) / 24.0;
  return std::floor(365.25 * (y + 4716)) + std::floor(30.6001 * (m + 1)) + day + dayFraction + b -
         1524.5;
}

double decimalYear(double jd) {
  return 2000.0 + (jd - kJulianDateJ2000) / 365.25;
}

double deltaTSeconds(double y) {
  // Espenak & Meeus (2006), one branch per interval; each polynomial's variable as published.
  if (y < -500.0) return longTermParabola(y);
  if (y < 500.0) {
    static constexpr double c[] = {10583.6,    -1014.41,    33.78311,    -5.952053,
                                   -0.1798452, 0.022174192, 0.0090316521};
    return polynomial(y / 100.0, c);
  }
  if (y < 1600.0) {
    static constexpr double c[] = {1574.2,     -556.01,      71.23472,    0.319781,
                                   -0.8503463, -0.005050998, 0.0083572073};
    return polynomial((y - 1000.0) / 100.0, c);
  }
  if (y < 1700.0) {
    static constexpr double c[] = {120.0, -0.9808, -0.01532, 1.0 / 7129.0};
    return polynomial(y - 1600.0, c);
  }
  if (y < 1800.0) {
    static constexpr double c[] = {8.83, 0.1603, -0.0059285, 0.00013336, -1.0 / 1174000.0};
    return polynomial(y - 1700.0, c);
  }
  if (y < 1860.0) {
    static constexpr double c[] = {13.72,       -0.332447,    0.0068612,     0.0041116,
                                   -0.00037436, 0.0000121272, -0.0000001699, 0.000000000875};
    return polynomial(y - 1800.0, c);
  }
  if (y < 1900.0) {
    static constexpr double c[] = {7.62,       0.5737,        -0.251754,
                                   0.01680668, -0.0004473624, 1.0 / 233174.0};
    return polynomial(y - 1860.0, c);
  }
  if (y < 1920.0) {
    static constexpr double c[] = {-2.79, 1.494119, -0.0598939, 0.0061966, -0.000197};
    return polynomial(y - 1900.0, c);
  }
  if (y < 1941.0) {
    static constexpr double c[] = {21.20, 0.84493, -0.076100, 0.0020936};
    return polynomial(y - 1920.0, c);
  }
  if (y < 1961.0) {
    static constexpr double c[] = {29.07, 0.407, -1.0 / 233.0, 1.0 / 2547.0};
    return polynomial(y - 1950.0, c);
  }
  if (y < 1986.0) {
    static constexpr double c[] = {45.45, 1.067, -1.0 / 260.0, -1.0 / 718.0};
    return polynomial(y - 1975.0, c);
  }
  if (y < 2005.0) {
    static constexpr double c[] = {63.86, 0.3345, -0.060374, 0.0017275, 0.000651814, 0.00002373599};
    return polynomial(y - 2000.0, c);
  }
  if (y < 2050.0) {
    static constexpr double c[] = {62.92, 0.32217, 0.005589};
    return polynomial(y - 2000.0, c);
  }
  // The last term joins this piece to the 2005-2050 one at 2050 and to the parabola at 2150.
  if (y < 2150.0) return longTermParabola(y) - 0.5628 * (2150.0 - y);
  return longTermParabola(y);
}

double greenwichMeanSiderealTimeDeg(double jdUt) {
  const double t = julianCenturies(jdUt);
  // Meeus (12.4).
  const double theta = 280.46061837 + 360.98564736629 * (jdUt - kJulianDateJ2000) +
                       t * t * (0.000387933 - t / 38710000.0);
  double wrapped = std::fmod(theta, 360.0);
  if (wrapped < 0.0) wrapped += 360.0;
  return wrapped >= 360.0 ? 0.0 : wrapped;
}

}  // namespace sky
