// Observer-dependent part of the ephemeris: topocentric parallax, horizontal coordinates,
// refraction, the Moon's phase and limb angles, and the star-field rotation.
#include "engine/lighting/ephemeris.h"

#include <cmath>
#include <sstream>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "engine/core/error.h"

namespace sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kRadToDeg = 180.0 / kPi;
constexpr double kEarthEquatorialRadiusKm = 6378.14;  // Meeus ch. 11 and SPA (IAU 1976)
constexpr double kEarthAxisRatio = 0.99664719;        // b/a, Meeus ch. 11
constexpr double kAuKm = 149597870.7;

// [0, 360); a tiny negative input would otherwise round up to exactly 360.
double wrap360(double deg) {
  double w = std::fmod(deg, 360.0);
  if (w < 0.0) w += 360.0;
  return w >= 360.0 ? 0.0 : w;
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void requireRange(const char* what, double v, double lo, double hi) {
  if (!std::isfinite(v)) inputError(std::string("ephemeris: ") + what + " is not a finite number");
  if (v < lo || v > hi)
    inputError(std::string("ephemeris: ") + what + " " + number(v) + " is out of range [" +
               number(lo) + ", " + number(hi) + "]");
}

void validate(double jdUtc, const Observer& o, const std::optional<double>& deltaT) {
  if (!std::isfinite(jdUtc)) inputError("ephemeris: julian date is not a finite number");
  requireRange("latitude", o.latitudeDeg, -90.0, 90.0);
  requireRange("longitude", o.longitudeDeg, -180.0, 180.0);
  if (!std::isfinite(o.heightM)) inputError("ephemeris: height is not a finite number");
  if (!std::isfinite(o.pressureHpa)) inputError("ephemeris: pressure is not a finite number");
  if (o.pressureHpa < 0.0)
    inputError("ephemeris: pressure " + number(o.pressureHpa) + " hPa is negative");
  requireRange("temperature", o.temperatureC, -100.0, 100.0);
  if (deltaT && !std::isfinite(*deltaT)) inputError("ephemeris: delta T is not a finite number");
}

// glm matrices are column-major; this takes rows as they are written on paper.
glm::dmat3 fromRows(double a00, double a01, double a02, double a10, double a11, double a12,
                    double a20, double a21, double a22) {
  return glm::dmat3(a00, a10, a20, a01, a11, a21, a02, a12, a22);
}

// Coordinate-frame rotations by angle a (radians) about x, y, z (IERS R1, R2, R3).
glm::dmat3 rotX(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return fromRows(1, 0, 0, 0, c, s, 0, -s, c);
}
glm::dmat3 rotY(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return fromRows(c, 0, -s, 0, 1, 0, s, 0, c);
}
glm::dmat3 rotZ(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return fromRows(c, s, 0, -s, c, 0, 0, 0, 1);
}

// Observer's position relative to the geocentre: ρ sin φ' and ρ cos φ' in Earth equatorial
// radii, Meeus ch. 11 (SPA 3.12.2-3.12.4).
struct ObserverGeocentric {
  double rhoSinPhi;
  double rhoCosPhi;
};

ObserverGeocentric observerGeocentric(const Observer& o) {
  const double phi = o.latitudeDeg * kDegToRad;
  const double u = std::atan(kEarthAxisRatio * std::tan(phi));
  const double h = o.heightM / (kEarthEquatorialRadiusKm * 1000.0);
  return {kEarthAxisRatio * std::sin(u) + h * std::sin(phi), std::cos(u) + h * std::cos(phi)};
}

struct Topocentric {
  double rightAscensionDeg;
  double declinationDeg;
  double hourAngleDeg;
  double distanceOverGeocentric;  // topocentric distance / geocentric distance
};

// Rigorous parallax in right ascension and declination, Meeus (40.2), (40.3) = SPA (3.12.5),
// (3.12.6), for a body at geocentric (α, δ), hour angle H and equatorial horizontal parallax
// π (sin π = a / distance).
Topocentric topocentric(double alphaDeg, double deltaDeg, double hourAngleDeg, double sinParallax,
                        const ObserverGeocentric& obs) {
  const double h = hourAngleDeg * kDegToRad;
  const double delta = deltaDeg * kDegToRad;
  const double denominator = std::cos(delta) - obs.rhoCosPhi * sinParallax * std::cos(h);
  const double deltaAlpha = std::atan2(-obs.rhoCosPhi * sinParallax * std::sin(h), denominator);
  const double deltaPrime = std::atan2(
      (std::sin(delta) - obs.rhoSinPhi * sinParallax) * std::cos(deltaAlpha), denominator);
  // Distance ratio from the observer-to-body vector in units of the geocentric distance: the
  // body at (cos δ cos H, -cos δ sin H, sin δ) in the frame of the local meridian, the observer
  // at (ρ cos φ', 0, ρ sin φ') sin π.
  const double x = std::cos(delta) * std::cos(h) - obs.rhoCosPhi * sinParallax;
  const double y = -std::cos(delta) * std::sin(h);
  const double z = std::sin(delta) - obs.rhoSinPhi * sinParallax;
  return {wrap360(alphaDeg + deltaAlpha * kRadToDeg), deltaPrime * kRadToDeg,
          hourAngleDeg - deltaAlpha * kRadToDeg, std::sqrt(x * x + y * y + z * z)};
}

// Horizontal coordinates from topocentric hour angle and declination, SPA (3.14.1), (3.15.1)
// (= Meeus (13.5), (13.6) with azimuth from north), then refraction.
SkyPosition horizontal(const Topocentric& t, const Observer& o) {
  const double phi = o.latitudeDeg * kDegToRad;
  const double h = t.hourAngleDeg * kDegToRad;
  const double delta = t.declinationDeg * kDegToRad;
  const double sinE =
      std::sin(phi) * std::sin(delta) + std::cos(phi) * std::cos(delta) * std::cos(h);
  const double e0 = std::asin(std::fmax(-1.0, std::fmin(1.0, sinE))) * kRadToDeg;
  // Azimuth from north through east: atan2 of the east and north components (the form
  // atan2(sin H, cos H sin φ - tan δ cos φ) + 180 of SPA (3.15.1) without tan δ at the poles).
  const double east = -std::cos(delta) * std::sin(h);
  const double north =
      std::sin(delta) * std::cos(phi) - std::cos(delta) * std::sin(phi) * std::cos(h);
  SkyPosition p{};
  p.azimuthDeg = wrap360(std::atan2(east, north) * kRadToDeg);
  p.elevationGeometricDeg = e0;
  p.elevationDeg = e0 + refractionDeg(e0, o.pressureHpa, o.temperatureC);
  p.rightAscensionDeg = t.rightAscensionDeg;
  p.declinationDeg = t.declinationDeg;
  return p;
}

// SPA (3.14.8): Sæmundsson's refraction for apparent-from-true elevation, 1.02' cot(e + 10.3'/
// (e + 5.11)), at 1010 hPa and 10 °C, scaled for pressure and temperature. Degrees.
double saemundssonDeg(double e, double scale) {
  return scale * 1.02 / (60.0 * std::tan((e + 10.3 / (e + 5.11)) * kDegToRad));
}

double saemundssonSlope(double e, double scale) {
  const double x = (e + 10.3 / (e + 5.11)) * kDegToRad;
  const double dxde = 1.0 - 10.3 / ((e + 5.11) * (e + 5.11));
  const double s = std::sin(x);
  return -scale * 1.02 / 60.0 * kDegToRad * dxde / (s * s);
}

}  // namespace

double refractionDeg(double e, double pressureHpa, double temperatureC) {
  constexpr double kFormulaFloor = -1.0;  // below this SPA's formula is not used
  constexpr double kZeroBelow = -5.0;     // no refraction below this
  if (pressureHpa <= 0.0 || e <= kZeroBelow) return 0.0;
  const double scale = (pressureHpa / 1010.0) * (283.0 / (273.0 + temperatureC));
  if (e >= kFormulaFloor) return saemundssonDeg(e, scale);
  // Cubic Hermite from (kZeroBelow, 0, slope 0) to (kFormulaFloor, R, R'): continuous value and
  // slope at both ends, so a sunset time-lapse sees neither a jump nor a kink. (The formula
  // itself peaks near -1.9° and blows up at -5.11°; SPA cuts it to 0 at -0.8333°, a 0.6° step.)
  const double width = kFormulaFloor - kZeroBelow;
  const double s = (e - kZeroBelow) / width;
  const double value = saemundssonDeg(kFormulaFloor, scale);
  const double slope = saemundssonSlope(kFormulaFloor, scale) * width;
  return value * s * s * (3.0 - 2.0 * s) + slope * s * s * (s - 1.0);
}

glm::dmat3 precessionMatrix(double jde) {
  const double t = julianCenturies(jde);
  constexpr double kArcsec = kDegToRad / 3600.0;
  // Meeus (21.3) with the starting epoch J2000 (T = 0), arcseconds.
  const double zeta = ((0.017998 * t + 0.30188) * t + 2306.2181) * t * kArcsec;
  const double z = ((0.018203 * t + 1.09468) * t + 2306.2181) * t * kArcsec;
  const double theta = ((-0.041833 * t - 0.42665) * t + 2004.3109) * t * kArcsec;
  // Meeus (21.4) as rotations: P = R3(-z) R2(θ) R3(-ζ).
  return rotZ(-z) * rotY(theta) * rotZ(-zeta);
}

glm::dmat3 nutationMatrix(const Nutation& n) {
  const double eps0 = n.meanObliquityDeg * kDegToRad;
  const double eps = n.trueObliquityDeg * kDegToRad;
  // N = R1(-ε) R3(-Δψ) R1(ε0): to the mean ecliptic, shift the equinox by Δψ, back to the true
  // equator.
  return rotX(-eps) * rotZ(-n.longitudeDeg * kDegToRad) * rotX(eps0);
}

Ephemeris computeEphemeris(double jdUtc, const Observer& observer,
                           std::optional<double> deltaTOverrideSeconds) {
  validate(jdUtc, observer, deltaTOverrideSeconds);
  Ephemeris out{};
  out.julianDateUtc = jdUtc;
  out.deltaTSeconds =
      deltaTOverrideSeconds ? *deltaTOverrideSeconds : deltaTSeconds(decimalYear(jdUtc));
  out.julianDateTt = jdUtc + out.deltaTSeconds / 86400.0;
  const double jde = out.julianDateTt;

  const Nutation n = nutation(jde);
  // Greenwich apparent sidereal time, SPA (3.8.2)-(3.8.3) = Meeus (12.4) plus the equation of
  // the equinoxes Δψ cos ε; local by adding the east longitude.
  const double gast = greenwichMeanSiderealTimeDeg(jdUtc) +
                      n.longitudeDeg * std::cos(n.trueObliquityDeg * kDegToRad);
  const double localSidereal = wrap360(gast + observer.longitudeDeg);
  const ObserverGeocentric obs = observerGeocentric(observer);

  // Sun.
  const GeocentricSun sun = sunGeocentric(jde);
  const double sunParallax = std::sin(8.794 / 3600.0 * kDegToRad) / sun.distanceAu;  // SPA 3.12.1
  const Topocentric sunTopo = topocentric(sun.rightAscensionDeg, sun.declinationDeg,
                                          localSidereal - sun.rightAscensionDeg, sunParallax, obs);
  out.sun.position = horizontal(sunTopo, observer);
  out.sun.distanceAu = sun.distanceAu;

  // Moon.
  const GeocentricMoon moon = moonGeocentric(jde);
  const double moonParallax = kEarthEquatorialRadiusKm / moon.distanceKm;  // sin π, Meeus p. 337
  const Topocentric moonTopo =
      topocentric(moon.rightAscensionDeg, moon.declinationDeg,
                  localSidereal - moon.rightAscensionDeg, moonParallax, obs);
  out.moon.position = horizontal(moonTopo, observer);
  out.moon.distanceKm = moon.distanceKm;
  out.moon.topocentricDistanceKm = moon.distanceKm * moonTopo.distanceOverGeocentric;

  // Phase, Meeus chapter 48, from the geocentric places of both bodies.
  const double a0 = sun.rightAscensionDeg * kDegToRad, d0 = sun.declinationDeg * kDegToRad;
  const double a = moon.rightAscensionDeg * kDegToRad, d = moon.declinationDeg * kDegToRad;
  const double cosPsi =
      std::sin(d0) * std::sin(d) + std::cos(d0) * std::cos(d) * std::cos(a0 - a);  // (48.2)
  const double psi = std::acos(std::fmax(-1.0, std::fmin(1.0, cosPsi)));
  const double sunKm = sun.distanceAu * kAuKm;
  const double i =
      std::atan2(sunKm * std::sin(psi), moon.distanceKm - sunKm * std::cos(psi));  // (48.3)
  out.moon.phaseAngleDeg = i * kRadToDeg;
  out.moon.illuminatedFraction = (1.0 + std::cos(i)) / 2.0;  // (48.1)
  const double chi = std::atan2(
      std::cos(d0) * std::sin(a0 - a),
      std::sin(d0) * std::cos(d) - std::cos(d0) * std::sin(d) * std::cos(a0 - a));  // (48.5)
  out.moon.brightLimbAngleDeg = wrap360(chi * kRadToDeg);

  // Parallactic angle for the observer's view of the disc, Meeus (14.1), topocentric H and δ.
  const double phi = observer.latitudeDeg * kDegToRad;
  const double hm = moonTopo.hourAngleDeg * kDegToRad, dm = moonTopo.declinationDeg * kDegToRad;
  // tan q = sin H / (tan φ cos δ - sin δ cos H), numerator and denominator multiplied by
  // cos φ >= 0 so that atan2 keeps the quadrant and the poles need no special case (q = 0).
  out.moon.parallacticAngleDeg =
      std::atan2(std::cos(phi) * std::sin(hm),
                 std::sin(phi) * std::cos(dm) - std::cos(phi) * std::sin(dm) * std::cos(hm)) *
      kRadToDeg;

  // Star field: J2000 mean equator -> true equator of date -> local meridian frame -> ENU.
  const glm::dmat3 earthRotation = rotZ(localSidereal * kDegToRad);
  const double sp = std::sin(phi), cp = std::cos(phi);
  // The meridian frame has x toward the equator on the upper meridian, y toward hour angle
  // -90° (due east) and z toward the pole; east, north and up follow from the latitude.
  const glm::dmat3 meridianToEnu = fromRows(0, 1, 0,     // east
                                            -sp, 0, cp,  // north
                                            cp, 0, sp);  // up
  out.equatorialJ2000ToEnu =
      meridianToEnu * earthRotation * nutationMatrix(n) * precessionMatrix(jde);
  return out;
}

}  // namespace sky
