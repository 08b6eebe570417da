#pragma once
// Spectral data, every 5 nm from 380 to 780 nm: the CIE colour-matching functions, the sun
// above the atmosphere and ozone's absorption. The sources are cited at each table
// (spectral_tables.cpp). The sunlight's colour through the air (light_model.cpp,
// atmosphereTransmittance) integrates over them, and so does the tests' brute-force spectral
// sky (tests/atmosphere/spectral_sky_reference.h).
#include <glm/vec3.hpp>

namespace sky::spectral {

constexpr double kFirstNm = 380.0;
constexpr double kStepNm = 5.0;
constexpr int kCount = 81;

inline double wavelengthNm(int i) {
  return kFirstNm + kStepNm * i;
}

extern const double kCieX[kCount];
extern const double kCieY[kCount];
extern const double kCieZ[kCount];
extern const double kSolarIrradiance[kCount];    // W m^-2 nm^-1 at 1 AU
extern const double kOzoneCrossSection[kCount];  // 1e-21 cm^2 per molecule, 293 K

// Linear sRGB (Rec. 709 primaries, D65 white) from CIE XYZ, IEC 61966-2-1: the inverse of the
// matrix the renderer's tests use for Rec. 709 to XYZ.
constexpr double kXyzToSrgb[3][3] = {
    {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};

// Linear Rec. 709 colour-matching function of table entry i (CIE 1931 through kXyzToSrgb).
glm::dvec3 rgbMatching(int i);

// Trapezoid weights of the 5 nm table (its ends count half).
inline double tableWeight(int i) {
  return (i == 0 || i == kCount - 1) ? 0.5 : 1.0;
}

}  // namespace sky::spectral
