#pragma once
// The procedural weather map's noise (Kozlov et al. section 5: cover painted by fbm): seeded
// 3D gradient-noise fbm evaluated on the Earth's surface, so features have a fixed size in
// km whatever the latitude, and the cover calibration that keeps a map's mean cover at the
// asked value. CPU only, deterministic across platforms (integer hashing, double maths).
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace sky::weather_detail {

// Octaves of the fbm: the finest features are scale / 2^(kFbmOctaves - 1).
constexpr int kFbmOctaves = 6;

// Improved Perlin noise (gradient noise, quintic fade) at p, about in [-1, 1]; `seed` picks an
// independent field.
double gradientNoise3(const glm::dvec3& p, uint32_t seed);

// fbm of gradientNoise3 at the point of the sphere in direction `unit` (|unit| = 1), with
// lattice spacing `scaleKm` on the ground at the first octave, divided by the fbm's standard
// deviation: mean 0, standard deviation about 1, independent fields for different seeds.
double standardFbmOnEarth(const glm::dvec3& unit, double scaleKm, uint32_t seed);

// Replaces each value z by clamp(s + amplitude * z, 0, 1), with the offset s chosen so the
// mean of the results is `mean` (to 1e-9): the clamping at 0 and 1 otherwise pulls the mean
// of a sparse or dense map toward 0.5. mean 0 gives exactly 0 everywhere, mean 1 exactly 1,
// amplitude 0 the mean everywhere.
void calibrateCover(std::vector<float>& values, double mean, double amplitude);

// A 32-bit integer hash (Chris Wellons' lowbias32) of the values in order.
uint32_t hashIntegers(std::initializer_list<uint32_t> values);

}  // namespace sky::weather_detail
