#include "atmosphere_reference.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "engine/lighting/light_model.h"
#include "reference_common.h"

namespace sky::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

glm::dvec2 cornetteShanksMoments(double g) {
  // Cornette-Shanks is 3 / (2 (2 + g^2)) (1 + c^2) times Henyey-Greenstein, whose Legendre
  // moments are g^l; c (1 + c^2) and P_2(c) (1 + c^2) expanded in Legendre polynomials.
  const double g2 = g * g, k = 3.0 / (2.0 * (2.0 + g2));
  return {k * (8.0 * g + 2.0 * g * g2) / 5.0,
          k * (2.0 / 15.0 + 32.0 / 21.0 * g2 + 12.0 / 35.0 * g2 * g2)};
}

// Newton's method on the Legendre polynomial P_n.
std::vector<std::pair<double, double>> gaussLegendre(int n) {
  std::vector<std::pair<double, double>> out;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-15) break;
    }
    out.emplace_back(x, 2.0 / ((1.0 - x * x) * dp * dp));
  }
  return out;
}

namespace {

// The channels' share of the Mie coefficients, which stand for 550 nm: Angstrom's law at
// the lighting model's wavelengths (1 for grey aerosols, mieAngstrom 0).
glm::dvec3 angstrom(const AtmosphereSettings& s) {
  glm::dvec3 f;
  for (int c = 0; c < 3; ++c)
    f[c] = std::pow(light::kChannelAerosolWavelengthsNm[c] / 550.0, -s.mieAngstrom);
  return f;
}

}  // namespace

ReferenceAtmosphere::ReferenceAtmosphere(const AtmosphereSettings& s)
    : groundRadius(s.groundRadiusKm),
      topRadius(s.groundRadiusKm + s.thicknessKm),
      rayleigh(glm::dvec3(s.rayleighScattering) * 1e-3),
      rayleighHeight(s.rayleighScaleHeightKm),
      mieScattering(angstrom(s) * s.mieScattering * 1e-3),
      mieExtinction(angstrom(s) * s.mieExtinction * 1e-3),
      mieHeight(s.mieScaleHeightKm),
      mieG(s.mieAnisotropy),
      ozone(glm::dvec3(s.ozoneAbsorption) * 1e-3),
      ozoneCenter(s.ozoneCenterKm),
      ozoneHalfWidth(s.ozoneHalfWidthKm),
      albedo(s.groundAlbedo) {}

namespace {

struct Medium {
  glm::dvec3 rayleigh;
  glm::dvec3 mie;
  glm::dvec3 extinction;
};

Medium medium(const ReferenceAtmosphere& a, double altitude) {
  const double h = std::max(altitude, 0.0);
  const double dr = std::exp(-h / a.rayleighHeight);
  const double dm = std::exp(-h / a.mieHeight);
  const double dO = std::max(0.0, 1.0 - std::abs(h - a.ozoneCenter) / a.ozoneHalfWidth);
  return {a.rayleigh * dr, a.mieScattering * dm,
          a.rayleigh * dr + a.mieExtinction * dm + a.ozone * dO};
}

Warp warpFor(const ReferenceAtmosphere& a, double r, double mu) {
  return mu >= 0.0 ? Warp::Start : (hitsGround(a.groundRadius, r, mu) ? Warp::End : Warp::Uniform);
}

}  // namespace

AtmosphereReference::AtmosphereReference(const AtmosphereSettings& s, ReferenceQuality q)
    : mA(s), mQ(q) {}

glm::dvec3 AtmosphereReference::extinction(double altitude) const {
  return medium(mA, altitude).extinction;
}

glm::dvec3 AtmosphereReference::opticalDepth(glm::dvec3 origin, glm::dvec3 dir, double length,
                                             int steps) const {
  const double r = glm::length(origin);
  const Warp w = warpFor(mA, r, glm::dot(origin, dir) / r);
  glm::dvec3 tau(0.0);
  for (int i = 0; i < steps; ++i) {
    const double t0 = warpT(double(i) / steps, length, w);
    const double t1 = warpT(double(i + 1) / steps, length, w);
    const glm::dvec3 p = origin + 0.5 * (t0 + t1) * dir;
    tau += medium(mA, glm::length(p) - mA.groundRadius).extinction * (t1 - t0);
  }
  return tau;
}

double AtmosphereReference::rayLength(double r, double mu) const {
  return hitsGround(mA.groundRadius, r, mu) ? distanceToGround(mA.groundRadius, r, mu)
                                            : distanceToTop(mA.topRadius, r, mu);
}

glm::dvec3 AtmosphereReference::transmittanceToLight(glm::dvec3 pos, glm::dvec3 L) const {
  const double r = glm::length(pos);
  const double mu = glm::dot(pos, L) / r;
  if (hitsGround(mA.groundRadius, r, mu)) return glm::dvec3(0.0);
  return glm::exp(-opticalDepth(pos, L, distanceToTop(mA.topRadius, r, mu), mQ.lightSteps));
}

ReferenceMultipleScattering AtmosphereReference::multipleScattering(double r, double muS) const {
  static thread_local std::vector<std::pair<double, double>> nodes;
  if (nodes.size() != static_cast<size_t>(mQ.sphereBands)) nodes = gaussLegendre(mQ.sphereBands);
  const glm::dvec3 origin(0.0, 0.0, r);
  const glm::dvec3 L(std::sqrt(std::max(1.0 - muS * muS, 0.0)), 0.0, muS);
  // Split cos(zenith) at the horizon, where the ground cuts the integrand off.
  const double muH = -std::sqrt(std::max(1.0 - std::pow(mA.groundRadius / r, 2.0), 0.0));
  const double spans[2][2] = {{-1.0, muH}, {muH, 1.0}};
  // Means over the sphere of L_1, of the transfer path (9) and of L_1 times the moments of
  // the direction in the light's frame (x toward its azimuth, z up): z, x, z^2 - 1/3,
  // x^2 - 1/3, x z.
  glm::dvec3 l2(0.0), fms(0.0), moment[5] = {};
  for (const auto& span : spans) {
    const double half = 0.5 * (span[1] - span[0]), mid = 0.5 * (span[1] + span[0]);
    for (const auto& [x, w] : nodes) {
      const double mu = mid + half * x;
      const double weight = w * half;
      const double sinT = std::sqrt(std::max(1.0 - mu * mu, 0.0));
      const bool ground = hitsGround(mA.groundRadius, r, mu);
      const double length =
          ground ? distanceToGround(mA.groundRadius, r, mu) : distanceToTop(mA.topRadius, r, mu);
      const Warp warp = warpFor(mA, r, mu);
      for (int k = 0; k < mQ.sphereAzimuths; ++k) {
        const double phi = kPi * (k + 0.5) / mQ.sphereAzimuths;
        const glm::dvec3 dir(sinT * std::cos(phi), sinT * std::sin(phi), mu);
        // The light reaching the point from dir was scattered by the angle between dir and L.
        const double cosLight = glm::dot(dir, L);
        const double phaseR = rayleighPhase(cosLight), phaseM = cornetteShanks(mA.mieG, cosLight);
        glm::dvec3 tau(0.0), lp(0.0), fp(0.0);
        const int n = mQ.sphereSteps;
        for (int i = 0; i < n; ++i) {
          const double t0 = warpT(double(i) / n, length, warp);
          const double t1 = warpT(double(i + 1) / n, length, warp);
          const double dt = t1 - t0;
          const glm::dvec3 p = origin + 0.5 * (t0 + t1) * dir;
          const Medium m = medium(mA, glm::length(p) - mA.groundRadius);
          const glm::dvec3 T = glm::exp(-(tau + 0.5 * dt * m.extinction));
          // Hillaire (7) with the phase functions, and (9).
          lp += T * (m.rayleigh * phaseR + m.mie * phaseM) * transmittanceToLight(p, L) * dt;
          fp += T * (m.rayleigh + m.mie) * dt;
          tau += m.extinction * dt;
        }
        if (ground) {
          const glm::dvec3 p = origin + length * dir;
          const double muG = std::max(glm::dot(glm::normalize(p), L), 0.0);
          lp += glm::exp(-tau) * mA.albedo / kPi * muG * transmittanceToLight(p, L);
        }
        // (1/4pi) over the sphere: weight in cos(zenith) times pi / n over the half circle,
        // doubled for the mirror half (whose moments in y cancel, the rest are the same).
        const double sphere = weight * 2.0 * (kPi / mQ.sphereAzimuths) / (4.0 * kPi);
        l2 += lp * sphere;
        fms += fp * sphere;
        const double moments[5] = {dir.z, dir.x, dir.z * dir.z - 1.0 / 3.0,
                                   dir.x * dir.x - 1.0 / 3.0, dir.x * dir.z};
        for (int m = 0; m < 5; ++m) moment[m] += lp * moments[m] * sphere;
      }
    }
  }
  ReferenceMultipleScattering out;
  // Hillaire (10), (11).
  out.psi = l2 / (glm::dvec3(1.0) - fms);
  // The phase functions' P_1 and P_2 terms against L_1 (shaders/common/atmosphere_shared.h).
  out.dipoleUp = 3.0 * moment[0];
  out.dipoleLight = 3.0 * moment[1];
  out.quadrupoleUp = 7.5 * moment[2];
  out.quadrupoleLight = 7.5 * moment[3];
  out.quadrupoleCross = 7.5 * moment[4];
  return out;
}

glm::dvec3 AtmosphereReference::psiMs(double r, double muS) const {
  return multipleScattering(r, muS).psi;
}

glm::dvec3 AtmosphereReference::march(double r0, glm::dvec3 V, glm::dvec3 L, double length,
                                      glm::dvec3* transmittance) const {
  const glm::dvec3 origin(0.0, 0.0, r0);
  const Warp warp = warpFor(mA, r0, V.z);
  const double nu = glm::dot(V, L);
  const double phaseR = rayleighPhase(nu), phaseM = cornetteShanks(mA.mieG, nu);

  // Multiple scattering varies slowly along a ray: its terms toward the camera (per unit
  // Rayleigh and Mie scattering coefficient) are evaluated directly at viewMsSteps + 1 evenly
  // spaced points of the step parameter and interpolated linearly between them, while the
  // density, transmittance and sunlight change at every step.
  const glm::dvec2 mieMoments = cornetteShanksMoments(mA.mieG);
  std::vector<glm::dvec3> towardR(static_cast<size_t>(mQ.viewMsSteps) + 1);
  std::vector<glm::dvec3> towardM(towardR.size());
  for (int j = 0; j <= mQ.viewMsSteps; ++j) {
    const glm::dvec3 p = origin + warpT(double(j) / mQ.viewMsSteps, length, warp) * V;
    const double r = std::max(glm::length(p), mA.groundRadius);
    const glm::dvec3 up = glm::normalize(p);
    const double muS = glm::dot(up, L);
    const ReferenceMultipleScattering ms = multipleScattering(r, muS);
    const glm::dvec3 h = L - muS * up;
    const glm::dvec3 toward = glm::length(h) > 1e-9 ? glm::normalize(h) : glm::dvec3(0.0);
    const double vu = glm::dot(V, up), vl = glm::dot(V, toward);
    const double across = std::max(1.0 - vu * vu - vl * vl, 0.0);
    const glm::dvec3 dipole = ms.dipoleUp * vu + ms.dipoleLight * vl;
    const glm::dvec3 quadrupole = ms.quadrupoleUp * (vu * vu - across) +
                                  ms.quadrupoleLight * (vl * vl - across) +
                                  2.0 * ms.quadrupoleCross * (vu * vl);
    towardR[static_cast<size_t>(j)] = ms.psi + kRayleighP2 * quadrupole;
    towardM[static_cast<size_t>(j)] = ms.psi + mieMoments.x * dipole + mieMoments.y * quadrupole;
  }

  glm::dvec3 radiance(0.0), tau(0.0);
  for (int i = 0; i < mQ.viewSteps; ++i) {
    const double s0 = double(i) / mQ.viewSteps, s1 = double(i + 1) / mQ.viewSteps;
    const double t0 = warpT(s0, length, warp), t1 = warpT(s1, length, warp);
    const double dt = t1 - t0;
    const glm::dvec3 p = origin + 0.5 * (t0 + t1) * V;
    const Medium m = medium(mA, glm::length(p) - mA.groundRadius);
    const glm::dvec3 T = glm::exp(-(tau + 0.5 * dt * m.extinction));
    const double x = 0.5 * (s0 + s1) * mQ.viewMsSteps;
    const int j = std::min(static_cast<int>(x), mQ.viewMsSteps - 1);
    const size_t k = static_cast<size_t>(j);
    const glm::dvec3 multiple = glm::max(m.rayleigh * glm::mix(towardR[k], towardR[k + 1], x - j) +
                                             m.mie * glm::mix(towardM[k], towardM[k + 1], x - j),
                                         glm::dvec3(0.0));
    const glm::dvec3 single = (m.rayleigh * phaseR + m.mie * phaseM) * transmittanceToLight(p, L);
    radiance += T * (single + multiple) * dt;
    tau += m.extinction * dt;
  }
  if (transmittance) *transmittance = glm::exp(-tau);
  return radiance;
}

glm::dvec3 AtmosphereReference::skyRadiance(double r0, glm::dvec3 V, glm::dvec3 L) const {
  return march(r0, V, L, rayLength(r0, V.z), nullptr);
}

glm::dvec3 AtmosphereReference::inScattered(double r0, glm::dvec3 V, glm::dvec3 L, double distance,
                                            glm::dvec3* transmittance) const {
  return march(r0, V, L, std::min(distance, rayLength(r0, V.z)), transmittance);
}

}  // namespace sky::test
