#pragma once
// Sun and Moon ephemeris for an observer on the Earth: apparent topocentric horizontal
// positions with atmospheric refraction, distances, the Moon's phase and the orientation of its
// lit limb, and the rotation that places J2000 star directions in the observer's sky.
//
// Sun: the NREL Solar Position Algorithm (Reda & Andreas, NREL/TP-560-34302, 2008), truncated
// VSOP87 with IAU 1980 nutation, aberration and topocentric parallax, ±0.0003° (1950-2100).
// Moon: Meeus, Astronomical Algorithms 2nd ed. (1998), chapter 47 (full tables 47.A/47.B),
// nutation chapter 22, parallax chapter 40, phase and bright limb chapter 48, parallactic angle
// chapter 14; about 10" in longitude and 4" in latitude.
// Angles are degrees; azimuth runs from north through east in [0, 360).
#include <optional>

#include <glm/mat3x3.hpp>

#include "engine/lighting/time_scales.h"

namespace sky {

struct Observer {
  double latitudeDeg = 0.0;     // geodetic, [-90, 90], north positive
  double longitudeDeg = 0.0;    // [-180, 180], east positive
  double heightM = 0.0;         // above the reference ellipsoid
  double pressureHpa = 1010.0;  // local air pressure for refraction; 0 turns refraction off
  double temperatureC = 10.0;   // local air temperature for refraction, [-100, 100]
};

struct SkyPosition {
  double azimuthDeg;             // topocentric, from north through east, [0, 360)
  double elevationDeg;           // topocentric, apparent: with refraction
  double elevationGeometricDeg;  // topocentric, without refraction
  double rightAscensionDeg;      // topocentric apparent (true equator and equinox of date)
  double declinationDeg;         // topocentric apparent
};

struct SunEphemeris {
  SkyPosition position;
  double distanceAu;  // Earth centre to Sun centre
};

struct MoonEphemeris {
  SkyPosition position;
  double distanceKm;             // Earth centre to Moon centre, Meeus Δ
  double topocentricDistanceKm;  // observer to Moon centre
  double illuminatedFraction;    // k in [0, 1], Meeus (48.1)
  double phaseAngleDeg;          // i in [0, 180]: 0 full, 180 new, Meeus (48.3)
  // Position angle of the midpoint of the lit limb, from the disc's north point (toward the
  // celestial pole) through east, [0, 360), Meeus (48.5). Near 270 waxing, near 90 waning.
  double brightLimbAngleDeg;
  // Parallactic angle q of the Moon for this observer, Meeus (14.1), in (-180, 180]: the
  // position angle of the zenith seen from the disc's centre (from its north point through
  // east), negative east of the meridian and positive west of it. brightLimbAngleDeg -
  // parallacticAngleDeg is the lit limb's angle from the top of the disc (toward the zenith),
  // counter-clockwise as the observer sees it.
  double parallacticAngleDeg;
};

struct Ephemeris {
  double julianDateUtc;
  double julianDateTt;  // julianDateUtc + ΔT
  double deltaTSeconds;
  SunEphemeris sun;
  MoonEphemeris moon;
  // Turns a unit vector in the mean equator and equinox of J2000 (x toward RA 0h Dec 0, z
  // toward the north celestial pole) into the observer's east-north-up frame: precession
  // (IAU 1976), nutation (IAU 1980), Greenwich apparent sidereal time and the geodetic latitude.
  // No aberration, parallax or refraction: meant for the star field.
  glm::dmat3 equatorialJ2000ToEnu;
};

// Everything for one instant (Julian date in UTC, taken as UT1) and place. ΔT comes from
// deltaTSeconds(decimalYear(jd)) unless deltaTOverrideSeconds is given (e.g. a published ΔT).
// Throws sky::Error (BadInput) for out-of-range or non-finite inputs.
Ephemeris computeEphemeris(double julianDateUtc, const Observer& observer,
                           std::optional<double> deltaTOverrideSeconds = std::nullopt);

// Atmospheric refraction in degrees to add to a geometric (airless) elevation. Above -1° this
// is SPA's formula (Sæmundsson's, scaled by pressure/1010 and 283/(273 + temperature));
// between -1° and -5° it fades to zero along a cubic that matches the formula's value and slope
// at -1°, and it is zero below -5°: continuous and smooth in elevation, where SPA jumps at
// -0.8333°. pressureHpa = 0 gives 0.
double refractionDeg(double geometricElevationDeg, double pressureHpa, double temperatureC);

// --- Lower-level pieces (Julian ephemeris day = Julian date in TT) ---

struct Nutation {
  double longitudeDeg;      // Δψ
  double obliquityDeg;      // Δε
  double meanObliquityDeg;  // ε0, Laskar's polynomial, Meeus (22.3)
  double trueObliquityDeg;  // ε = ε0 + Δε
};
// IAU 1980 nutation (Meeus Table 22.A, SPA 3.4) and the obliquity of the ecliptic.
Nutation nutation(double julianEphemerisDay);

// Apparent geocentric Sun (SPA 3.2-3.9): longitude with nutation and aberration, latitude,
// distance, right ascension and declination on the true equator and equinox of date.
struct GeocentricSun {
  double longitudeDeg;
  double latitudeDeg;
  double distanceAu;
  double rightAscensionDeg;
  double declinationDeg;
};
GeocentricSun sunGeocentric(double julianEphemerisDay);

// Geocentric Moon, Meeus chapter 47. longitudeDeg is Meeus's λ (mean equinox of date);
// apparentLongitudeDeg = λ + Δψ, and right ascension / declination are apparent (true equator
// and equinox of date, Meeus (13.3), (13.4)).
struct GeocentricMoon {
  double longitudeDeg;
  double latitudeDeg;
  double distanceKm;
  double apparentLongitudeDeg;
  double rightAscensionDeg;
  double declinationDeg;
};
GeocentricMoon moonGeocentric(double julianEphemerisDay);

// Rotation from the mean equator and equinox of J2000 to the mean equator and equinox of date,
// Meeus (21.2)-(21.4) (IAU 1976 angles ζ, z, θ).
glm::dmat3 precessionMatrix(double julianEphemerisDay);
// Rotation from the mean to the true equator and equinox of date.
glm::dmat3 nutationMatrix(const Nutation& n);

}  // namespace sky
