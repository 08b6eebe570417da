#include "spectral_sky_reference.h"

#include <algorithm>
#include <cmath>
#include <thread>
#include <utility>

#include <glm/geometric.hpp>

#include "atmosphere_reference.h"
#include "passes/atmosphere_luts/atmosphere_luts.h"
#include "engine/lighting/spectral_tables.h"
#include "reference_common.h"

namespace sky::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
// One Dobson unit: 2.687e16 molecules per cm^2.
constexpr double kDobsonPerCm2 = 2.687e16;

using spectral::rgbMatching;
using spectral::tableWeight;

// The sun's luminance in table units: the integral of y times the solar spectrum.
double solarLuminance() {
  double y = 0.0;
  for (int i = 0; i < spectral::kCount; ++i)
    y += tableWeight(i) * spectral::kCieY[i] * spectral::kSolarIrradiance[i];
  return y;
}

struct Density {
  double rayleigh, mie, ozone;
};

Density density(const SkyMedium& m, double r) {
  const double h = std::max(r - m.groundRadiusKm, 0.0);
  return {std::exp(-h / m.rayleighHeightKm), std::exp(-h / m.mieHeightKm),
          std::max(0.0, 1.0 - std::abs(h - m.ozoneCenterKm) / m.ozoneHalfWidthKm)};
}

// An orthonormal basis around unit `up`.
void basis(glm::dvec3 up, glm::dvec3& e1, glm::dvec3& e2) {
  const glm::dvec3 helper = std::abs(up.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  e1 = glm::normalize(glm::cross(helper, up));
  e2 = glm::cross(up, e1);
}

}  // namespace

SpectralAtmosphere spectralAtmosphere(const AtmosphereSettings& s) {
  SpectralAtmosphere a;
  a.groundRadiusKm = s.groundRadiusKm;
  a.thicknessKm = s.thicknessKm;
  a.rayleighScaleHeightKm = s.rayleighScaleHeightKm;
  a.mieExtinctionAt550PerKm = s.mieExtinction * 1e-3;
  a.mieSingleScatteringAlbedo = s.mieExtinction > 0.0 ? s.mieScattering / s.mieExtinction : 1.0;
  a.mieAngstrom = s.mieAngstrom;
  a.mieScaleHeightKm = s.mieScaleHeightKm;
  a.mieG = s.mieAnisotropy;
  a.ozoneCenterKm = s.ozoneCenterKm;
  a.ozoneHalfWidthKm = s.ozoneHalfWidthKm;
  a.groundAlbedo = luminance709(glm::dvec3(s.groundAlbedo));
  return a;
}

namespace {

double rayleighAt(const SpectralAtmosphere& a, double nm) {
  const double x = 550.0 / nm;
  return a.rayleighAt550PerKm * x * x * x * x;
}

double angstromAt(double angstrom, double nm) {
  return std::pow(nm / 550.0, -angstrom);
}

// Ozone absorption at the tent's peak, 1/km: the column spread over the tent (whose integral
// is its half width) times the cross-section. DU 2.687e16 /cm^2 over w km = 1e5 w cm gives
// molecules/cm^3; times sigma (cm^2) per cm, times 1e5 per km.
double ozoneAt(const SpectralAtmosphere& a, int tableIndex) {
  const double sigma = spectral::kOzoneCrossSection[tableIndex] * 1e-21;
  return a.ozoneColumnDu * kDobsonPerCm2 / a.ozoneHalfWidthKm * sigma;
}

SkyMedium mediumShape(double groundRadius, double thickness, double rayleighHeight,
                      double mieHeight, double g, double ozoneCenter, double ozoneHalfWidth) {
  SkyMedium m;
  m.groundRadiusKm = groundRadius;
  m.topRadiusKm = groundRadius + thickness;
  m.rayleighHeightKm = rayleighHeight;
  m.mieHeightKm = mieHeight;
  m.mieG = g;
  m.ozoneCenterKm = ozoneCenter;
  m.ozoneHalfWidthKm = ozoneHalfWidth;
  return m;
}

}  // namespace

SkyMedium spectralSky(const SpectralAtmosphere& a, int stepNm) {
  SkyMedium m = mediumShape(a.groundRadiusKm, a.thicknessKm, a.rayleighScaleHeightKm,
                            a.mieScaleHeightKm, a.mieG, a.ozoneCenterKm, a.ozoneHalfWidthKm);
  const int stride = std::max(1, stepNm / static_cast<int>(spectral::kStepNm));
  const double step = stride * spectral::kStepNm;
  const double norm = kPi / solarLuminance();
  for (int i = 0; i < spectral::kCount; i += stride) {
    const double nm = spectral::wavelengthNm(i);
    SkyBand b;
    b.rayleigh = rayleighAt(a, nm);
    b.mieExtinction = a.mieExtinctionAt550PerKm * angstromAt(a.mieAngstrom, nm);
    b.mieScattering = b.mieExtinction * a.mieSingleScatteringAlbedo;
    b.ozone = ozoneAt(a, i);
    b.groundAlbedo = a.groundAlbedo;
    // The hat around this wavelength, integrated over the 5 nm table.
    for (int k = 0; k < spectral::kCount; ++k) {
      const double hat = 1.0 - std::abs(spectral::wavelengthNm(k) - nm) / step;
      if (hat <= 0.0) continue;
      b.toRgb += norm * tableWeight(k) * hat * spectral::kSolarIrradiance[k] * rgbMatching(k);
    }
    m.bands.push_back(b);
  }
  // A grid that does not end at 780 nm: the last sample takes the rest of the table.
  const int last = (spectral::kCount - 1) / stride * stride;
  for (int k = last + 1; k < spectral::kCount; ++k) {
    const double hat = (spectral::wavelengthNm(k) - spectral::wavelengthNm(last)) / step;
    m.bands.back().toRgb +=
        norm * tableWeight(k) * std::min(hat, 1.0) * spectral::kSolarIrradiance[k] * rgbMatching(k);
  }
  return m;
}

SkyMedium channelSky(const AtmosphereSettings& s, glm::dvec3 sunIlluminance) {
  // Exactly the GPU's coefficients (1/km, floats as uploaded).
  const shared::AtmosphereParams p = atmosphereParams(s);
  SkyMedium m =
      mediumShape(p.radii.x, double(p.radii.y) - double(p.radii.x), p.rayleighScattering.w,
                  p.mieScattering.w, p.mieExtinction.w, p.ozoneProfile.x, p.ozoneProfile.y);
  m.groundRadiusKm = p.radii.x;
  m.topRadiusKm = p.radii.y;
  for (int c = 0; c < 3; ++c) {
    SkyBand b;
    b.rayleigh = p.rayleighScattering[c];
    b.mieScattering = p.mieScattering[c];
    b.mieExtinction = p.mieExtinction[c];
    b.ozone = p.ozoneAbsorption[c];
    b.groundAlbedo = p.groundAlbedo[c];
    b.toRgb[c] = kPi * sunIlluminance[c];
    m.bands.push_back(b);
  }
  return m;
}

glm::dvec3 solarColor() {
  glm::dvec3 rgb(0.0);
  for (int i = 0; i < spectral::kCount; ++i)
    rgb += tableWeight(i) * spectral::kSolarIrradiance[i] * rgbMatching(i);
  return rgb / solarLuminance();
}

glm::dvec3 channelAverage(const std::function<double(double)>& spectrum) {
  glm::dvec3 sum(0.0), weight(0.0);
  for (int i = 0; i < spectral::kCount; ++i) {
    const glm::dvec3 w = tableWeight(i) * spectral::kSolarIrradiance[i] * rgbMatching(i);
    sum += w * spectrum(spectral::wavelengthNm(i));
    weight += w;
  }
  return glm::max(sum / weight, glm::dvec3(0.0));
}

glm::dvec3 channelRayleighPerMm(const SpectralAtmosphere& a) {
  return 1e3 * channelAverage([&](double nm) { return rayleighAt(a, nm); });
}

glm::dvec3 channelOzonePerMm(const SpectralAtmosphere& a) {
  return 1e3 * channelAverage([&](double nm) {
           const int i =
               static_cast<int>(std::lround((nm - spectral::kFirstNm) / spectral::kStepNm));
           return ozoneAt(a, i);
         });
}

glm::dvec3 channelAngstromFactor(double angstrom) {
  return channelAverage([&](double nm) { return angstromAt(angstrom, nm); });
}

double luminance709(glm::dvec3 c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

glm::dvec2 chromaticity709(glm::dvec3 c) {
  const double X = 0.4124 * c.r + 0.3576 * c.g + 0.1805 * c.b;
  const double Y = luminance709(c);
  const double Z = 0.0193 * c.r + 0.1192 * c.g + 0.9505 * c.b;
  const double sum = X + Y + Z;
  return sum > 0.0 ? glm::dvec2(X / sum, Y / sum) : glm::dvec2(0.0);
}

// ---- The integrator ----

BruteForceSky::Columns BruteForceSky::columnsDirect(double r, double mu, int steps) const {
  const double Rt = mM.topRadiusKm;
  const double length = distanceToTop(Rt, r, mu);
  const glm::dvec3 origin(0.0, 0.0, r);
  const glm::dvec3 dir(std::sqrt(std::max(1.0 - mu * mu, 0.0)), 0.0, mu);
  Columns c;
  auto segment = [&](double from, double to, Warp w, int n) {
    for (int i = 0; i < n; ++i) {
      const double t0 = from + warpT(double(i) / n, to - from, w);
      const double t1 = from + warpT(double(i + 1) / n, to - from, w);
      const Density d = density(mM, glm::length(origin + 0.5 * (t0 + t1) * dir));
      c.rayleigh += d.rayleigh * (t1 - t0);
      c.mie += d.mie * (t1 - t0);
      c.ozone += d.ozone * (t1 - t0);
    }
  };
  if (mu >= 0.0) {
    segment(0.0, length, Warp::Start, steps);
  } else {
    // Down to the lowest point, then up: steps dense at the lowest point on both sides.
    const double lowest = std::min(-r * mu, length);
    segment(0.0, lowest, Warp::End, steps / 2);
    segment(lowest, length, Warp::Start, steps - steps / 2);
  }
  return c;
}

namespace {

// The transmittance table's parametrisation (Bruneton & Neyret 2008): x from the distance to
// the top between its least and largest value, y = rho / H.
struct ColumnCoords {
  double x, y;
};

ColumnCoords columnCoords(double Rg, double Rt, double r, double mu) {
  const double H = std::sqrt(Rt * Rt - Rg * Rg);
  const double rho = std::sqrt(std::max(r * r - Rg * Rg, 0.0));
  const double d = distanceToTop(Rt, r, mu);
  const double dMin = Rt - r, dMax = rho + H;
  return {std::clamp((d - dMin) / std::max(dMax - dMin, 1e-12), 0.0, 1.0),
          std::clamp(rho / H, 0.0, 1.0)};
}

}  // namespace

BruteForceSky::BruteForceSky(SkyMedium medium, BruteForceQuality q) : mM(std::move(medium)), mQ(q) {
  const double Rg = mM.groundRadiusKm, Rt = mM.topRadiusKm;
  const double H = std::sqrt(Rt * Rt - Rg * Rg);
  mColumns.resize(static_cast<size_t>(mQ.columnRadii) * mQ.columnAngles);
  for (int i = 0; i < mQ.columnRadii; ++i) {
    const double rho = H * i / (mQ.columnRadii - 1);
    const double r = std::sqrt(rho * rho + Rg * Rg);
    for (int j = 0; j < mQ.columnAngles; ++j) {
      const double dMin = Rt - r, dMax = rho + H;
      const double d = dMin + (dMax - dMin) * j / (mQ.columnAngles - 1);
      // Law of cosines in the triangle centre - r - exit point: Rt^2 = r^2 + d^2 + 2 r d mu.
      const double mu =
          d <= 0.0 ? 1.0 : std::clamp((H * H - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
      mColumns[static_cast<size_t>(i) * mQ.columnAngles + j] = columnsDirect(r, mu, mQ.columnSteps);
    }
  }

  // Hillaire's transfer factor f (8), (9) per band at altitudes spaced quadratically (dense at
  // the ground), for orders 3 and up.
  const size_t nb = mM.bands.size();
  const std::vector<std::pair<double, double>> nodes = gaussLegendre(mQ.sphereBands);
  mTransfer.assign(static_cast<size_t>(mQ.transferAltitudes) * nb, 0.0);
  std::vector<double> T(nb);
  for (int k = 0; k < mQ.transferAltitudes; ++k) {
    const double u = double(k) / (mQ.transferAltitudes - 1);
    const double r = std::clamp(Rg + (Rt - Rg) * u * u, Rg + 1e-3, Rt - 1e-3);
    const glm::dvec3 origin(0.0, 0.0, r);
    const double muH = -std::sqrt(std::max(1.0 - (Rg / r) * (Rg / r), 0.0));
    const double spans[2][2] = {{-1.0, muH}, {muH, 1.0}};
    for (const auto& span : spans) {
      const double half = 0.5 * (span[1] - span[0]), mid = 0.5 * (span[1] + span[0]);
      for (const auto& [x, w] : nodes) {
        const double mu = mid + half * x;
        const bool ground = hitsGround(Rg, r, mu);
        const double length = ground ? distanceToGround(Rg, r, mu) : distanceToTop(Rt, r, mu);
        const Warp warp = mu >= 0.0 ? Warp::Start : (ground ? Warp::End : Warp::Uniform);
        // The integrand depends on the direction's zenith angle only: the whole circle of
        // azimuths has weight 2 pi, over 4 pi for the isotropic phase.
        const double weight = w * half * 2.0 * kPi / (4.0 * kPi);
        const glm::dvec3 dir(std::sqrt(std::max(1.0 - mu * mu, 0.0)), 0.0, mu);
        std::fill(T.begin(), T.end(), 1.0);
        const int n = mQ.sphereSteps;
        for (int i = 0; i < n; ++i) {
          const double t0 = warpT(double(i) / n, length, warp);
          const double t1 = warpT(double(i + 1) / n, length, warp);
          const double dt = t1 - t0;
          const Density d = density(mM, glm::length(origin + 0.5 * (t0 + t1) * dir));
          for (size_t b = 0; b < nb; ++b) {
            const SkyBand& band = mM.bands[b];
            const double scattering = d.rayleigh * band.rayleigh + d.mie * band.mieScattering;
            const double extinction =
                d.rayleigh * band.rayleigh + d.mie * band.mieExtinction + d.ozone * band.ozone;
            const double e = std::exp(-extinction * dt);
            const double integral = extinction > 1e-12 ? (1.0 - e) / extinction : dt;
            mTransfer[static_cast<size_t>(k) * nb + b] += weight * T[b] * scattering * integral;
            T[b] *= e;
          }
        }
      }
    }
  }
}

BruteForceSky::Columns BruteForceSky::sunColumns(double r, double mu) const {
  const ColumnCoords c = columnCoords(mM.groundRadiusKm, mM.topRadiusKm, r, mu);
  const double fx = c.x * (mQ.columnAngles - 1), fy = c.y * (mQ.columnRadii - 1);
  const int x0 = std::min(static_cast<int>(fx), mQ.columnAngles - 2);
  const int y0 = std::min(static_cast<int>(fy), mQ.columnRadii - 2);
  const double ax = fx - x0, ay = fy - y0;
  auto at = [&](int y, int x) { return mColumns[static_cast<size_t>(y) * mQ.columnAngles + x]; };
  const Columns a = at(y0, x0), b = at(y0, x0 + 1), cc = at(y0 + 1, x0), d = at(y0 + 1, x0 + 1);
  auto mix = [&](double va, double vb, double vc, double vd) {
    return (1 - ay) * ((1 - ax) * va + ax * vb) + ay * ((1 - ax) * vc + ax * vd);
  };
  return {mix(a.rayleigh, b.rayleigh, cc.rayleigh, d.rayleigh), mix(a.mie, b.mie, cc.mie, d.mie),
          mix(a.ozone, b.ozone, cc.ozone, d.ozone)};
}

std::vector<double> BruteForceSky::sunTransmittance(double r, double mu) const {
  std::vector<double> out(mM.bands.size(), 0.0);
  if (hitsGround(mM.groundRadiusKm, r, mu)) return out;
  const Columns c = sunColumns(r, mu);
  for (size_t b = 0; b < out.size(); ++b) {
    const SkyBand& band = mM.bands[b];
    out[b] =
        std::exp(-(band.rayleigh * c.rayleigh + band.mieExtinction * c.mie + band.ozone * c.ozone));
  }
  return out;
}

std::vector<double> BruteForceSky::sunTransmittanceDirect(double r, double mu, int steps) const {
  std::vector<double> out(mM.bands.size(), 0.0);
  if (hitsGround(mM.groundRadiusKm, r, mu)) return out;
  const Columns c = columnsDirect(r, mu, steps);
  for (size_t b = 0; b < out.size(); ++b) {
    const SkyBand& band = mM.bands[b];
    out[b] =
        std::exp(-(band.rayleigh * c.rayleigh + band.mieExtinction * c.mie + band.ozone * c.ozone));
  }
  return out;
}

double BruteForceSky::transferFactor(size_t band, double r) const {
  const double u = std::sqrt(
      std::clamp((r - mM.groundRadiusKm) / (mM.topRadiusKm - mM.groundRadiusKm), 0.0, 1.0));
  const double f = u * (mQ.transferAltitudes - 1);
  const int k = std::min(static_cast<int>(f), mQ.transferAltitudes - 2);
  const size_t nb = mM.bands.size();
  const double a = mTransfer[static_cast<size_t>(k) * nb + band];
  const double b = mTransfer[static_cast<size_t>(k + 1) * nb + band];
  return a + (b - a) * (f - k);
}

SkyRadiance BruteForceSky::radiance(double altitudeKm, glm::dvec3 V, glm::dvec3 L) const {
  const double Rg = mM.groundRadiusKm, Rt = mM.topRadiusKm;
  const size_t nb = mM.bands.size();
  const double r0 = Rg + altitudeKm;
  const glm::dvec3 origin(0.0, 0.0, r0);
  const bool viewGround = hitsGround(Rg, r0, V.z);
  const double viewLength = viewGround ? distanceToGround(Rg, r0, V.z) : distanceToTop(Rt, r0, V.z);
  const Warp viewWarp = V.z >= 0.0 ? Warp::Start : (viewGround ? Warp::End : Warp::Uniform);
  const double cosViewLight = glm::dot(V, L);
  const double viewPhaseR = rayleighPhase(cosViewLight);
  const double viewPhaseM = cornetteShanks(mM.mieG, cosViewLight);

  // Orders 2 and up at scatterPoints + 1 points along the view ray, per band: the once-
  // scattered light arriving from every direction weighted by each phase function toward the
  // camera (gR, gM, 1/sr per unit illuminance), and the isotropic series for orders 3+ (h).
  const int points = mQ.scatterPoints;
  std::vector<double> gR((points + 1) * nb), gM((points + 1) * nb), h((points + 1) * nb),
      iso((points + 1) * nb), dip((points + 1) * nb);
  const glm::dvec2 mieMoments = cornetteShanksMoments(mM.mieG);
  std::vector<double> quadV(nb), quad((points + 1) * nb);
  const std::vector<std::pair<double, double>> nodes = gaussLegendre(mQ.sphereBands);
  std::vector<double> T(nb), L1(nb), mean(nb), dipoleV(nb);
  for (int j = 0; j <= points; ++j) {
    const glm::dvec3 pos = origin + warpT(double(j) / points, viewLength, viewWarp) * V;
    const double r = std::clamp(glm::length(pos), Rg + 1e-6, Rt);
    const glm::dvec3 up = pos / glm::length(pos);
    glm::dvec3 e1, e2;
    basis(up, e1, e2);
    const glm::dvec3 p = up * r;
    std::fill(mean.begin(), mean.end(), 0.0);
    std::fill(dipoleV.begin(), dipoleV.end(), 0.0);
    std::fill(quadV.begin(), quadV.end(), 0.0);
    const double muH = -std::sqrt(std::max(1.0 - (Rg / r) * (Rg / r), 0.0));
    const double spans[2][2] = {{-1.0, muH}, {muH, 1.0}};
    for (const auto& span : spans) {
      const double half = 0.5 * (span[1] - span[0]), mid = 0.5 * (span[1] + span[0]);
      for (const auto& [x, w] : nodes) {
        const double mu = mid + half * x;
        const double sinT = std::sqrt(std::max(1.0 - mu * mu, 0.0));
        const bool ground = hitsGround(Rg, r, mu);
        const double length = ground ? distanceToGround(Rg, r, mu) : distanceToTop(Rt, r, mu);
        const Warp warp = mu >= 0.0 ? Warp::Start : (ground ? Warp::End : Warp::Uniform);
        const double weight = w * half * 2.0 * kPi / mQ.sphereAzimuths;
        for (int k = 0; k < mQ.sphereAzimuths; ++k) {
          const double phi = 2.0 * kPi * (k + 0.5) / mQ.sphereAzimuths;
          const glm::dvec3 dir = sinT * (std::cos(phi) * e1 + std::sin(phi) * e2) + mu * up;
          // Sunlight travelling -L scattered into -dir (toward p): cos = dot(dir, L).
          const double cosLight = glm::dot(dir, L);
          const double phaseR = rayleighPhase(cosLight), phaseM = cornetteShanks(mM.mieG, cosLight);
          std::fill(T.begin(), T.end(), 1.0);
          std::fill(L1.begin(), L1.end(), 0.0);
          const int n = mQ.sphereSteps;
          for (int i = 0; i < n; ++i) {
            const double t0 = warpT(double(i) / n, length, warp);
            const double t1 = warpT(double(i + 1) / n, length, warp);
            const double dt = t1 - t0;
            const glm::dvec3 q = p + 0.5 * (t0 + t1) * dir;
            const double rq = glm::length(q);
            const Density d = density(mM, rq);
            const double muS = glm::dot(q, L) / rq;
            const bool lit = !hitsGround(Rg, rq, muS);
            const Columns c = lit ? sunColumns(rq, muS) : Columns{};
            for (size_t b = 0; b < nb; ++b) {
              const SkyBand& band = mM.bands[b];
              const double extinction =
                  d.rayleigh * band.rayleigh + d.mie * band.mieExtinction + d.ozone * band.ozone;
              const double e = std::exp(-extinction * dt);
              if (lit) {
                const double sun = std::exp(-(band.rayleigh * c.rayleigh +
                                              band.mieExtinction * c.mie + band.ozone * c.ozone));
                const double source =
                    (d.rayleigh * band.rayleigh * phaseR + d.mie * band.mieScattering * phaseM) *
                    sun;
                // The step's own transmittance integrated exactly (source constant over it).
                L1[b] += T[b] * source * (extinction > 1e-12 ? (1.0 - e) / extinction : dt);
              }
              T[b] *= e;
            }
          }
          if (ground) {
            // The Lambertian ground lit by the sun through the air (radiance albedo/pi E mu).
            const glm::dvec3 g = p + length * dir;
            const double rg = glm::length(g);
            const double muG = glm::dot(g, L) / rg;
            if (muG > 0.0) {
              const Columns c = sunColumns(rg, muG);
              for (size_t b = 0; b < nb; ++b) {
                const SkyBand& band = mM.bands[b];
                const double sun = std::exp(-(band.rayleigh * c.rayleigh +
                                              band.mieExtinction * c.mie + band.ozone * c.ozone));
                L1[b] += T[b] * band.groundAlbedo / kPi * muG * sun;
              }
            }
          }
          // That light arriving at p travels -dir; scattered toward the camera (-V): cos =
          // dot(dir, V).
          const double cosView = glm::dot(dir, V);
          const double toViewR = rayleighPhase(cosView), toViewM = cornetteShanks(mM.mieG, cosView);
          for (size_t b = 0; b < nb; ++b) {
            gR[j * nb + b] += weight * toViewR * L1[b];
            gM[j * nb + b] += weight * toViewM * L1[b];
            mean[b] += weight * L1[b] / (4.0 * kPi);
            dipoleV[b] += weight * cosView * L1[b];
            quadV[b] += weight * 0.5 * (3.0 * cosView * cosView - 1.0) * L1[b];
          }
        }
      }
    }
    for (size_t b = 0; b < nb; ++b) {
      const double f = transferFactor(b, r);
      // Orders 3+: the mean once-scattered light times f + f^2 + ... (Hillaire (10) one order up).
      h[j * nb + b] = mean[b] * f / (1.0 - f);
      iso[j * nb + b] = mean[b] / (1.0 - f);
      // The phase functions' Legendre series, P = sum (2l + 1) p_l P_l / (4 pi), against the
      // once-scattered light's first two moments about V.
      dip[j * nb + b] = 3.0 / (4.0 * kPi) * dipoleV[b];
      quad[j * nb + b] = 5.0 / (4.0 * kPi) * quadV[b];
    }
  }

  // Along the view ray: the single scattering at every step, orders 2+ from the points above
  // interpolated linearly in the step parameter, each times the density here.
  std::vector<double> single(nb, 0.0), second(nb, 0.0), higher(nb, 0.0), isotropic(nb, 0.0),
      moments(nb, 0.0);
  std::fill(T.begin(), T.end(), 1.0);
  const int n = mQ.viewSteps;
  for (int i = 0; i < n; ++i) {
    const double s0 = double(i) / n, s1 = double(i + 1) / n;
    const double t0 = warpT(s0, viewLength, viewWarp), t1 = warpT(s1, viewLength, viewWarp);
    const double dt = t1 - t0;
    const glm::dvec3 pos = origin + 0.5 * (t0 + t1) * V;
    const double r = glm::length(pos);
    const Density d = density(mM, r);
    const double muS = glm::dot(pos, L) / r;
    const bool lit = !hitsGround(Rg, r, muS);
    const Columns c = lit ? sunColumns(r, muS) : Columns{};
    const double x = 0.5 * (s0 + s1) * points;
    const int j = std::min(static_cast<int>(x), points - 1);
    const double a = x - j;
    for (size_t b = 0; b < nb; ++b) {
      const SkyBand& band = mM.bands[b];
      const double extinction =
          d.rayleigh * band.rayleigh + d.mie * band.mieExtinction + d.ozone * band.ozone;
      const double e = std::exp(-extinction * dt);
      const double integral = T[b] * (extinction > 1e-12 ? (1.0 - e) / extinction : dt);
      const double rayleigh = d.rayleigh * band.rayleigh, mie = d.mie * band.mieScattering;
      if (lit) {
        const double sun = std::exp(
            -(band.rayleigh * c.rayleigh + band.mieExtinction * c.mie + band.ozone * c.ozone));
        single[b] += integral * (rayleigh * viewPhaseR + mie * viewPhaseM) * sun;
      }
      auto lerp = [&](const std::vector<double>& v) {
        return (1.0 - a) * v[j * nb + b] + a * v[(j + 1) * nb + b];
      };
      second[b] += integral * (rayleigh * lerp(gR) + mie * lerp(gM));
      higher[b] += integral * (rayleigh + mie) * lerp(h);
      isotropic[b] += integral * (rayleigh + mie) * lerp(iso);
      moments[b] += integral * ((rayleigh + mie) * lerp(iso) + mie * mieMoments.x * lerp(dip) +
                                (rayleigh * kRayleighP2 + mie * mieMoments.y) * lerp(quad));
      T[b] *= e;
    }
  }

  SkyRadiance out;
  for (size_t b = 0; b < nb; ++b) {
    out.single += mM.bands[b].toRgb * single[b];
    out.second += mM.bands[b].toRgb * second[b];
    out.higher += mM.bands[b].toRgb * higher[b];
    out.isotropic += mM.bands[b].toRgb * isotropic[b];
    out.moments += mM.bands[b].toRgb * moments[b];
  }
  return out;
}

std::vector<SkyRadiance> BruteForceSky::radiance(double altitudeKm,
                                                 const std::vector<glm::dvec3>& V, glm::dvec3 L,
                                                 int threads) const {
  std::vector<SkyRadiance> out(V.size());
  auto work = [&](size_t first, size_t step) {
    for (size_t i = first; i < V.size(); i += step) out[i] = radiance(altitudeKm, V[i], L);
  };
  const size_t n = static_cast<size_t>(std::max(threads, 1));
  std::vector<std::thread> pool;
  for (size_t t = 1; t < n; ++t) pool.emplace_back(work, t, n);
  work(0, n);
  for (std::thread& t : pool) t.join();
  return out;
}

}  // namespace sky::test
