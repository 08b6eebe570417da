#pragma once
// Where the sun stands for a place and time. This is the low-precision solar position of
// the Astronomical Almanac (about 0.01 degrees for 1950-2050, no refraction); the sun/moon
// issue replaces it with a full ephemeris.
namespace sky {

struct HorizontalPosition {
  double azimuthDeg;    // from north through east, [0, 360)
  double elevationDeg;  // above the horizon, geometric (no refraction)
};

HorizontalPosition sunPosition(double julianDateUtc, double latitudeDeg, double longitudeDeg);

}  // namespace sky
