#pragma once
// What both CPU references of the sky (atmosphere_reference.cpp, spectral_sky_reference.cpp)
// integrate with: the phase functions, per steradian, of the cosine c of the scattering angle;
// a ray's geometry on the sphere; and where its steps lie.
#include <algorithm>
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

// A ray from radius r with the cosine mu of its zenith angle, against the ground's sphere of
// radius Rg and the atmosphere's top of radius Rt.
inline bool hitsGround(double Rg, double r, double mu) {
  return mu < 0.0 && r * r * (mu * mu - 1.0) + Rg * Rg >= 0.0;
}

inline double distanceToGround(double Rg, double r, double mu) {
  const double disc = r * r * (mu * mu - 1.0) + Rg * Rg;
  const double far = -r * mu + std::sqrt(std::max(disc, 0.0));
  // The near root as (product of the roots) / (far root), without cancellation.
  return std::max((r - Rg) * (r + Rg), 0.0) / std::max(far, 1e-12);
}

inline double distanceToTop(double Rt, double r, double mu) {
  const double disc = r * r * (mu * mu - 1.0) + Rt * Rt;
  return std::max(-r * mu + std::sqrt(std::max(disc, 0.0)), 0.0);
}

// Step boundaries t(s), s in [0, 1]: dense at the start of rays going up, at the end of rays
// that meet the ground (where the air is densest, as in atmosphere.glsl), uniform otherwise.
enum class Warp { Uniform, Start, End };

inline double warpT(double s, double length, Warp w) {
  switch (w) {
    case Warp::Start:
      return length * s * s;
    case Warp::End:
      return length * (1.0 - (1.0 - s) * (1.0 - s));
    case Warp::Uniform:
      break;
  }
  return length * s;
}

}  // namespace sky::test
