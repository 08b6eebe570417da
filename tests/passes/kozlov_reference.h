#pragma once
// C++ references for the pass tests, written independently of the shaders: view rays of a
// pinhole camera and the Kozlov 3.1 clear sky lit by the sun and the moon.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "engine/lighting/lighting_state.h"
#include "engine/render/camera.h"
#include "engine/scene/scene.h"

namespace sky::test {

inline glm::vec3 referenceDirection(const CameraSettings& cam, int w, int h, int x, int y) {
  shared::ViewState v = makeViewState(cam, w, h);
  const float nx = (x + 0.5f) / w * 2 - 1, ny = (y + 0.5f) / h * 2 - 1;
  return glm::normalize(glm::vec3(v.forward) + nx * v.right.w * glm::vec3(v.right) -
                        ny * v.up.w * glm::vec3(v.up));
}

// Kozlov 3.1's haze with the eased ramp of shaders/common/kozlov_sky.glsl (kozlovHaze).
inline float referenceHaze(float z, const SkySettings& sky) {
  const float t = std::min(std::max(z, 0.0f) / static_cast<float>(sky.hazeHeight), 1.0f);
  return 1.0f - (1.0f - t) * (1.0f - t);
}

// Kozlov 3.1, written independently of shaders/common/kozlov_sky.glsl.
inline glm::vec3 referenceKozlov(glm::vec3 v, glm::vec3 s, const PaletteKey& p,
                                 const SkySettings& sky) {
  const float l = static_cast<float>(sky.glowSize) *
                  std::pow(std::max(glm::dot(v, s), 0.0f), static_cast<float>(sky.glowExponent));
  const float h = referenceHaze(v.z, sky);
  return (p.skyColor * h + p.fogColor * (1.0f - h)) * (1.0f - l) + p.glowColor * l;
}

// The clear sky of a frame: the daylit sky around the sun plus the moonlit one around the moon.
inline glm::vec3 referenceClearSky(glm::vec3 v, const LightingState& st, const SkySettings& sky) {
  return referenceKozlov(v, glm::vec3(st.sun.direction), st.palette, sky) +
         referenceKozlov(v, glm::vec3(st.moon.direction), st.moonPalette, sky);
}

}  // namespace sky::test
