#pragma once
// GLSL type names for C++, so headers in shaders/common/ compile on both sides.
// Only 4-component vectors and 32-bit scalars belong in shared structs (std140 and std430
// agree on them); a bare vec3 or a bool would silently differ between the two languages.
#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

namespace sky::glsl {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = uint32_t;
}  // namespace sky::glsl

// Shared headers wrap their structs in these so C++ sees them as sky::shared::Name.
#define SKY_SHARED_BEGIN  \
  namespace sky::shared { \
  using namespace ::sky::glsl;
#define SKY_SHARED_END }
