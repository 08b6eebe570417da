#include "engine/render/camera.h"

#include "engine/lighting/lighting_state.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace sky {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
}  // namespace

glm::vec3 directionFromAzEl(double az, double el) {
  return glm::vec3(enuDirection(az, el));
}

shared::ViewState makeViewState(const CameraSettings& cam, uint32_t width, uint32_t height) {
  if (cam.mode == CameraMode::GeographicTopdown) {
    // Straight down everywhere; the cloud pass maps pixels onto the weather region.
    shared::ViewState v{};
    v.forward = glm::vec4(0.0f, 0.0f, -1.0f, static_cast<float>(1e-3));
    v.right = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
    v.up = glm::vec4(0.0f, 1.0f, 0.0f, 0.0f);
    v.size = glm::uvec4(width, height, VIEW_PROJECTION_TOPDOWN, 0);
    return v;
  }
  if (cam.projection == CameraProjection::Equirectangular) {
    shared::ViewState v{};
    v.forward =
        glm::vec4(directionFromAzEl(cam.heading, 0.0), static_cast<float>(180.0 * kDeg / height));
    v.right = glm::vec4(directionFromAzEl(cam.heading + 90.0, 0.0), 0.0f);
    v.up = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
    v.size = glm::uvec4(width, height, VIEW_PROJECTION_EQUIRECTANGULAR, 0);
    return v;
  }
  const glm::vec3 forward = directionFromAzEl(cam.heading, cam.pitch);
  // Looking straight up or down the heading still defines "right"; the cross product with
  // the zenith does not.
  const glm::vec3 level = directionFromAzEl(cam.heading + 90.0, 0.0);
  const glm::vec3 levelUp = glm::normalize(glm::cross(level, forward));
  // Roll banks the camera right: its right side goes down, its top toward the old right.
  const float c = static_cast<float>(std::cos(cam.roll * kDeg));
  const float s = static_cast<float>(std::sin(cam.roll * kDeg));
  const glm::vec3 right = c * level - s * levelUp;
  const glm::vec3 up = s * level + c * levelUp;
  const double tanV = std::tan(0.5 * cam.verticalFov * kDeg);
  const double tanH = tanV * width / height;
  shared::ViewState v{};
  v.right = glm::vec4(right, static_cast<float>(tanH));
  v.up = glm::vec4(up, static_cast<float>(tanV));
  v.forward = glm::vec4(forward, static_cast<float>(2.0 * tanV / height));
  v.size = glm::uvec4(width, height, VIEW_PROJECTION_PERSPECTIVE, 0);
  return v;
}

glm::dvec3 viewDirection(const shared::ViewState& view, double x, double y) {
  const glm::dvec2 uv(x / double(view.size.x), y / double(view.size.y));
  const glm::dvec3 right(view.right), up(view.up), forward(view.forward);
  if (view.size.z == VIEW_PROJECTION_TOPDOWN) return glm::dvec3(0.0, 0.0, -1.0);
  if (view.size.z == VIEW_PROJECTION_EQUIRECTANGULAR) {
    const double azimuth = (uv.x - 0.5) * 2.0 * kPi;  // clockwise from the heading
    const double elevation = (0.5 - uv.y) * kPi;
    const glm::dvec3 horizontal = std::cos(azimuth) * forward + std::sin(azimuth) * right;
    return std::cos(elevation) * horizontal + std::sin(elevation) * up;
  }
  const glm::dvec2 ndc = uv * 2.0 - 1.0;
  return glm::normalize(forward + ndc.x * double(view.right.w) * right -
                        ndc.y * double(view.up.w) * up);
}

}  // namespace sky
