#pragma once
// Camera and sky geometry shared by the renderer and the tests: the local east-north-up
// frame at the camera (x east, y north, z up), azimuth from north through east.
#include <cstdint>

#include <glm/vec3.hpp>

#include "engine/scene/scene.h"
#include "shaders/common/view_shared.h"

namespace sky {

// Unit direction for an azimuth/elevation in degrees.
glm::vec3 directionFromAzEl(double azimuthDeg, double elevationDeg);
// The view rays of an image of width x height pixels seen by `camera`.
shared::ViewState makeViewState(const CameraSettings& camera, uint32_t width, uint32_t height);
// The unit east-north-up direction through `pixel` (centres at integer + 0.5, row 0 the
// top): the twin of viewDirection in shaders/common/view.glsl, in double.
glm::dvec3 viewDirection(const shared::ViewState& view, double x, double y);

}  // namespace sky
