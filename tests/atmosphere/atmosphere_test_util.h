#pragma once
// Shared by the atmosphere tests: one AtmosphereLuts and GraphRuntime per test suite, frames
// with the sun placed by hand, and small image helpers.
#include <cmath>
#include <memory>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"
#include "passes/atmosphere_luts/atmosphere_luts.h"

namespace sky::test {

constexpr double kPi = 3.14159265358979323846;

// Unit east-north-up direction for an azimuth (from north through east) and elevation.
inline glm::dvec3 enuDirection(double azimuthDeg, double elevationDeg) {
  const double az = azimuthDeg * kPi / 180.0, el = elevationDeg * kPi / 180.0;
  return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

// A pinhole camera looking at `azimuthDeg`/`pitchDeg` (right-handed: right x forward = up).
inline shared::ViewState testView(double azimuthDeg, double pitchDeg, double verticalFovDeg,
                                  uint32_t width, uint32_t height) {
  const glm::dvec3 forward = enuDirection(azimuthDeg, pitchDeg);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 0, 1)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tanV = std::tan(0.5 * verticalFovDeg * kPi / 180.0);
  const double tanH = tanV * width / height;
  shared::ViewState v{};
  v.right = glm::vec4(glm::vec3(right), tanH);
  v.up = glm::vec4(glm::vec3(up), tanV);
  v.forward = glm::vec4(glm::vec3(forward), 2.0 * tanV / height);
  v.size = glm::uvec4(width, height, 0, 0);
  return v;
}

// The view ray through screen position uv (0..1, row 0 at the top), as shaders/common/view.glsl.
inline glm::dvec3 viewRay(const shared::ViewState& v, double u, double w) {
  const double nx = u * 2 - 1, ny = w * 2 - 1;
  return glm::normalize(glm::dvec3(glm::vec3(v.forward)) +
                        nx * double(v.right.w) * glm::dvec3(glm::vec3(v.right)) -
                        ny * double(v.up.w) * glm::dvec3(glm::vec3(v.up)));
}

// The sun (and a dark moon) at the given place in the sky, unit illuminance in every channel.
inline AtmosphereLuts::Frame sunFrame(double sunAzimuthDeg, double sunElevationDeg,
                                      double cameraAltitudeM = 200.0) {
  AtmosphereLuts::Frame f;
  f.cameraAltitudeM = cameraAltitudeM;
  f.view = testView(sunAzimuthDeg, 10.0, 60.0, 64, 36);
  f.sunDirection = glm::vec3(enuDirection(sunAzimuthDeg, sunElevationDeg));
  f.sunIlluminance = glm::vec3(1.0f);
  f.moonDirection = glm::vec3(enuDirection(sunAzimuthDeg + 180.0, -30.0));
  f.moonIlluminance = glm::vec3(0.0f);
  return f;
}

class AtmosphereTest : public GpuTest {
protected:
  static void SetUpTestSuite() {
    static ShaderCompiler compiler;
    sRuntime = std::make_unique<GraphRuntime>(sharedContext());
    sLuts = std::make_unique<AtmosphereLuts>(sharedContext(), compiler);
  }
  // Before main() destroys the shared context.
  static void TearDownTestSuite() {
    sLuts.reset();
    sRuntime.reset();
  }
  AtmosphereLuts& luts() { return *sLuts; }
  GraphRuntime& runtime() { return *sRuntime; }

  // One frame: the LUTs, optionally the sky probe, every output read back under its name
  // ("transmittance", "multiscattering", "sky_view_sun", "sky_view_moon",
  // "aerial_perspective", "probe").
  FrameResult run(const AtmosphereLuts::Frame& frame, uint32_t probeWidth = 0,
                  uint32_t probeHeight = 0) {
    FrameGraph graph(runtime());
    AtmosphereLuts::Outputs out = luts().addTo(graph, frame);
    graph.requestOutput(out.transmittance, "transmittance");
    graph.requestOutput(out.multiScattering, "multiscattering");
    graph.requestOutput(out.skyViewSun, "sky_view_sun");
    graph.requestOutput(out.skyViewMoon, "sky_view_moon");
    graph.requestOutput(out.aerialPerspective, "aerial_perspective");
    if (probeWidth)
      graph.requestOutput(luts().addSkyProbe(graph, out, probeWidth, probeHeight), "probe");
    return graph.execute();
  }

  static inline std::unique_ptr<GraphRuntime> sRuntime;
  static inline std::unique_ptr<AtmosphereLuts> sLuts;
};

// Texel (x, y, z) channel c of a read-back image.
inline float texel(const ReadbackImage& img, uint32_t x, uint32_t y, uint32_t c, uint32_t z = 0) {
  return img.pixels[((static_cast<size_t>(z) * img.height + y) * img.width + x) * img.channels + c];
}

inline glm::dvec3 rgb(const ReadbackImage& img, uint32_t x, uint32_t y, uint32_t z = 0) {
  return {texel(img, x, y, 0, z), texel(img, x, y, 1, z), texel(img, x, y, 2, z)};
}

}  // namespace sky::test
