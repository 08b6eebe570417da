#include "engine/weather/detail/cover_noise.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/weather/geo.h"

namespace sky::weather_detail {
namespace {

uint32_t lowbias32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// Perlin's (2002) twelve gradients, the edges of a cube: no axis is favoured.
constexpr double kGradients[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                      {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                      {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};

double corner(uint32_t h, double fx, double fy, double fz) {
  const double* g = kGradients[h % 12u];
  return g[0] * fx + g[1] * fy + g[2] * fz;
}

double fade(double t) {
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

double lerp(double a, double b, double t) {
  return a + t * (b - a);
}

// The standard deviation of the unnormalised fbm below over the sphere, measured once on
// 200000 random points (seeds 1..8); dividing by it makes the cover's spread mean the same
// at every scale. tests/weather checks the result stays within 10% of 1.
constexpr double kFbmStdDev = 0.3117;

}  // namespace

uint32_t hashIntegers(std::initializer_list<uint32_t> values) {
  uint32_t h = 0x9e3779b9u;
  for (uint32_t v : values) h = lowbias32(h ^ v);
  return h;
}

double gradientNoise3(const glm::dvec3& p, uint32_t seed) {
  const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int x = int(fx), y = int(fy), z = int(fz);
  const double dx = p.x - fx, dy = p.y - fy, dz = p.z - fz;
  // The corner hashes are hashIntegers({seed, x, y, z}) with the shared prefixes of the
  // chain computed once: 14 mixes for the eight corners instead of 32.
  const uint32_t hs = lowbias32(0x9e3779b9u ^ seed);
  double c[2][2][2];
  for (int i = 0; i < 2; ++i) {
    const uint32_t hx = lowbias32(hs ^ uint32_t(x + i));
    for (int j = 0; j < 2; ++j) {
      const uint32_t hxy = lowbias32(hx ^ uint32_t(y + j));
      for (int k = 0; k < 2; ++k)
        c[k][j][i] = corner(lowbias32(hxy ^ uint32_t(z + k)), dx - i, dy - j, dz - k);
    }
  }
  const double u = fade(dx), v = fade(dy), w = fade(dz);
  return lerp(lerp(lerp(c[0][0][0], c[0][0][1], u), lerp(c[0][1][0], c[0][1][1], u), v),
              lerp(lerp(c[1][0][0], c[1][0][1], u), lerp(c[1][1][0], c[1][1][1], u), v), w);
}

double standardFbmOnEarth(const glm::dvec3& unit, double scaleKm, uint32_t seed) {
  glm::dvec3 p = unit * (kEarthRadiusM * 1e-3 / scaleKm);
  double sum = 0.0, amplitude = 1.0;
  for (int octave = 0; octave < kFbmOctaves; ++octave) {
    const uint32_t octaveSeed = hashIntegers({seed, uint32_t(octave)});
    // A per-octave shift keeps the octaves' lattices from lining up (no grid pattern where
    // every octave has a zero at the same integer points).
    const glm::dvec3 shift(double(octaveSeed & 0x3ffu) / 1024.0,
                           double((octaveSeed >> 10) & 0x3ffu) / 1024.0,
                           double((octaveSeed >> 20) & 0x3ffu) / 1024.0);
    sum += amplitude * gradientNoise3(p + shift, octaveSeed);
    amplitude *= 0.5;
    p *= 2.0;
  }
  return sum / kFbmStdDev;
}

void calibrateCover(std::vector<float>& values, double mean, double amplitude) {
  if (values.empty()) return;
  if (mean <= 0.0 || mean >= 1.0 || amplitude <= 0.0) {
    // Exact constants: cover 0 must switch the layer off, not leave a faint residue.
    std::fill(values.begin(), values.end(), float(std::clamp(mean, 0.0, 1.0)));
    return;
  }
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  std::vector<double> prefix(sorted.size() + 1, 0.0);
  std::partial_sum(sorted.begin(), sorted.end(), prefix.begin() + 1);
  const double n = double(sorted.size());
  // The mean of clamp(s + a z, 0, 1) over the sorted values: zeros below -s/a, ones from
  // (1 - s)/a on, s + a z between. Non-decreasing in s, so bisection finds the offset.
  auto meanFor = [&](double s) {
    const size_t lo =
        size_t(std::upper_bound(sorted.begin(), sorted.end(), -s / amplitude) - sorted.begin());
    const size_t hi = size_t(std::lower_bound(sorted.begin(), sorted.end(), (1.0 - s) / amplitude) -
                             sorted.begin());
    return (double(hi - lo) * s + amplitude * (prefix[hi] - prefix[lo]) + (n - double(hi))) / n;
  };
  double lo = -amplitude * sorted.back(), hi = 1.0 - amplitude * sorted.front();
  for (int i = 0; i < 200 && hi - lo > 1e-12; ++i) {
    const double mid = 0.5 * (lo + hi);
    (meanFor(mid) < mean ? lo : hi) = mid;
  }
  const double s = 0.5 * (lo + hi);
  for (float& v : values) v = float(std::clamp(s + amplitude * double(v), 0.0, 1.0));
}

}  // namespace sky::weather_detail
