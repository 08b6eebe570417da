#include "engine/lighting/sun_position.h"

#include <cmath>

namespace sky {
namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
double wrap360(double a) {
  a = std::fmod(a, 360.0);
  return a < 0 ? a + 360.0 : a;
}
}  // namespace

HorizontalPosition sunPosition(double jd, double latDeg, double lonDeg) {
  // Astronomical Almanac, "Low precision formulas for the Sun" (section C).
  const double n = jd - 2451545.0;
  const double L = wrap360(280.460 + 0.9856474 * n);         // mean longitude
  const double g = wrap360(357.528 + 0.9856003 * n) * kDeg;  // mean anomaly
  const double lambda =
      (L + 1.915 * std::sin(g) + 0.020 * std::sin(2 * g)) * kDeg;  // ecliptic longitude
  const double eps = (23.439 - 0.0000004 * n) * kDeg;              // obliquity of the ecliptic
  const double ra = std::atan2(std::cos(eps) * std::sin(lambda), std::cos(lambda));
  const double dec = std::asin(std::sin(eps) * std::sin(lambda));
  // Greenwich mean sidereal time (IAU 1982, linear term) -> local hour angle.
  const double gmst = wrap360(280.46061837 + 360.98564736629 * n);
  const double ha = (gmst + lonDeg) * kDeg - ra;
  const double lat = latDeg * kDeg;
  const double sinEl = std::sin(lat) * std::sin(dec) + std::cos(lat) * std::cos(dec) * std::cos(ha);
  const double el = std::asin(std::fmax(-1.0, std::fmin(1.0, sinEl)));
  const double az =
      std::atan2(-std::sin(ha) * std::cos(dec),
                 std::sin(dec) * std::cos(lat) - std::cos(dec) * std::sin(lat) * std::cos(ha));
  return {wrap360(az / kDeg), el / kDeg};
}

}  // namespace sky
