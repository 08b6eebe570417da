#pragma once
// The phase functions both CPU references of the sky integrate with (atmosphere_reference.cpp
// and spectral_sky_reference.cpp), per steradian, of the cosine c of the scattering angle.
#include <cmath>

namespace sky::test {

inline double rayleighPhase(double c) {
  constexpr double kPi = 3.14159265358979323846;
  return 3.0 / (16.0 * kPi) * (1.0 + c * c);
}

// Cornette & Shanks (1992), the aerosols' phase in Hillaire 2020 and the GPU LUTs.
inline double cornetteShanks(double g, double c) {
  constexpr double kPi = 3.14159265358979323846;
  const double g2 = g * g;
  return 3.0 / (8.0 * kPi) * (1.0 - g2) * (1.0 + c * c) /
         ((2.0 + g2) * std::pow(1.0 + g2 - 2.0 * g * c, 1.5));
}

// Rayleigh's phase 3 (1 + c^2) / (16 pi) = (1 + P_2(c) / 2) / (4 pi): p_2 = 1/10.
constexpr double kRayleighP2 = 0.1;

}  // namespace sky::test
