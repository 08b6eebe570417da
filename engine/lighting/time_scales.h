#pragma once
// Calendar dates, time scales and sidereal time for the ephemeris (engine/lighting/ephemeris.h).
// Julian dates are plain doubles; which scale one is in (UTC, TT) is in the variable's name.
namespace sky {

inline constexpr double kJulianDateJ2000 = 2451545.0;  // 2000-01-01 12:00 TT
inline constexpr double kDaysPerJulianCentury = 36525.0;

// Julian date of a Gregorian calendar date and time of day (Meeus (7.1)); any time scale.
// Day, hour, minute and second may run past their range (hour 24, second 75) and carry over.
double julianDate(int year, int month, int day, int hour = 0, int minute = 0, double second = 0.0);

// Decimal year of a Julian date, continuous in time: 2000.0 + (jd - J2000) / 365.25. The ΔT
// polynomials take this (not NASA's month-stepped "year + (month - 0.5) / 12"), so ΔT and
// with it every position changes smoothly from one frame to the next.
double decimalYear(double julianDate);

// ΔT = TT - UT in seconds, Espenak & Meeus's polynomials ("Polynomial expressions for Delta T",
// NASA Five Millennium Canon of Solar Eclipses, 2006). Pieces: before -500 and after 2150 the
// long-term parabola -20 + 32 u², u = (y - 1820)/100; fits to observed ΔT for -500..1986;
// 1986-2005 a fit to IERS values; 2005-2050 and 2050-2150 NASA's extrapolations. Past 2005 the
// values are predictions that run high (2024.5: 74.2 s against about 69 s measured); each second of
// error moves the Moon by about 0.5" and the Sun by 0.04". Every year gets a value: outside
// -1999..3000 the parabola still applies.
double deltaTSeconds(double decimalYear);

// Julian centuries since J2000 for a Julian date in any scale.
inline double julianCenturies(double julianDate) {
  return (julianDate - kJulianDateJ2000) / kDaysPerJulianCentury;
}

// Greenwich mean sidereal time in degrees [0, 360) at a UT Julian date, Meeus (12.4)
// (IAU 1982). UTC is used as UT1: |UT1 - UTC| < 0.9 s is at most 0.004 degrees.
double greenwichMeanSiderealTimeDeg(double julianDateUt);

}  // namespace sky
