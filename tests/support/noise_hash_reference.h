#pragma once
// The C++ reference of the integer hash in shaders/common/noise.glsl (which noise3d.glsl
// reuses), for the noise kernel tests: the same operations on 32-bit unsigned integers.
#include <cstdint>

#include <glm/vec3.hpp>

namespace sky::test {

inline glm::uvec3 hash3(glm::uvec3 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

// The per-octave seed derived from a noise seed.
inline uint32_t seedOf(uint32_t seed, uint32_t index) {
  return hash3({seed, index, 0x5bd1e995u}).x;
}

}  // namespace sky::test
