#include "synthetic_noise.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace sky::test {
namespace {

// One channel in [0, 1] per texel, x fastest.
using Channel = std::vector<float>;

int wrap(int i, int n) {
  return (i % n + n) % n;
}

// Inverted Worley F1 with one random feature point per cell, `cells` cells along each axis
// (the volume tiles because cell indices wrap).
Channel worley(uint32_t size, int cells, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> points(size_t(cells) * size_t(cells) * size_t(cells) * 3);
  for (float& p : points) p = u(rng);
  Channel out(size_t(size) * size * size);
  const float cellSize = float(size) / float(cells);
  for (uint32_t z = 0; z < size; ++z)
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        const float px = (float(x) + 0.5f) / cellSize, py = (float(y) + 0.5f) / cellSize,
                    pz = (float(z) + 0.5f) / cellSize;
        const int cx = int(px), cy = int(py), cz = int(pz);
        float best = 1e9f;
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int i = (wrap(cz + dz, cells) * cells + wrap(cy + dy, cells)) * cells +
                            wrap(cx + dx, cells);
              const float* f = &points[size_t(i) * 3];
              const float ex = float(cx + dx) + f[0] - px, ey = float(cy + dy) + f[1] - py,
                          ez = float(cz + dz) + f[2] - pz;
              best = std::min(best, ex * ex + ey * ey + ez * ez);
            }
        // F1 rarely exceeds 1 cell; invert so that cell centres are dense (Schneider).
        out[(size_t(z) * size + y) * size + x] = 1.0f - std::min(std::sqrt(best), 1.0f);
      }
  return out;
}

// Value noise: random lattice values, `cells` along each axis, smoothstep-interpolated.
Channel valueNoise(uint32_t size, int cells, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> lattice(size_t(cells) * size_t(cells) * size_t(cells));
  for (float& v : lattice) v = u(rng);
  auto at = [&](int x, int y, int z) {
    return lattice[size_t((wrap(z, cells) * cells + wrap(y, cells)) * cells + wrap(x, cells))];
  };
  auto smooth = [](float t) { return t * t * (3.0f - 2.0f * t); };
  Channel out(size_t(size) * size * size);
  const float cellSize = float(size) / float(cells);
  for (uint32_t z = 0; z < size; ++z)
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        const float px = float(x) / cellSize, py = float(y) / cellSize, pz = float(z) / cellSize;
        const int ix = int(px), iy = int(py), iz = int(pz);
        const float fx = smooth(px - float(ix)), fy = smooth(py - float(iy)),
                    fz = smooth(pz - float(iz));
        float v = 0;
        for (int c = 0; c < 8; ++c) {
          const int dx = c & 1, dy = (c >> 1) & 1, dz = c >> 2;
          v += at(ix + dx, iy + dy, iz + dz) * (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) *
               (dz ? fz : 1 - fz);
        }
        out[(size_t(z) * size + y) * size + x] = v;
      }
  return out;
}

// Stretches a channel to fill [0, 1], as a bake normalises its noise.
void normalise(Channel& c) {
  const auto [lo, hi] = std::minmax_element(c.begin(), c.end());
  const float a = *lo, b = *hi;
  for (float& v : c) v = (v - a) / (b - a);
}

NoiseVolume pack(uint32_t size, const Channel* channels[4]) {
  NoiseVolume v;
  v.size = size;
  v.rgba.resize(size_t(size) * size * size * 4);
  for (size_t i = 0; i < size_t(size) * size * size; ++i)
    for (size_t c = 0; c < 4; ++c)
      v.rgba[i * 4 + c] = uint8_t(std::lround(std::clamp((*channels[c])[i], 0.0f, 1.0f) * 255.0f));
  return v;
}

}  // namespace

NoiseVolume syntheticShapeVolume(uint32_t size, uint32_t seed) {
  std::mt19937 rng(seed);
  Channel value = valueNoise(size, 4, rng);
  const Channel cells = worley(size, 4, rng);
  // The low-frequency channel: value noise sharpened by the Worley cells (Perlin-Worley-like).
  for (size_t i = 0; i < value.size(); ++i) value[i] = 0.5f * value[i] + 0.5f * cells[i];
  normalise(value);
  Channel g = worley(size, 4, rng), b = worley(size, 8, rng), a = worley(size, 16, rng);
  const Channel* channels[4] = {&value, &g, &b, &a};
  return pack(size, channels);
}

NoiseVolume syntheticDetailVolume(uint32_t size, uint32_t seed) {
  std::mt19937 rng(seed);
  Channel r = worley(size, 2, rng), g = worley(size, 4, rng), b = worley(size, 8, rng);
  Channel fbm(r.size());
  for (size_t i = 0; i < r.size(); ++i) fbm[i] = 0.625f * r[i] + 0.25f * g[i] + 0.125f * b[i];
  const Channel* channels[4] = {&r, &g, &b, &fbm};
  return pack(size, channels);
}

}  // namespace sky::test
