// Lighting for the host: the sun and moon after the atmosphere and the clouds above a place,
// and the sky's ambient as spherical harmonics (docs/library.md).
#include "sky_impl.h"

#include <algorithm>
#include <cmath>

#include "apps/common/default_scene.h"
#include "engine/lighting/lighting_state.h"
#include "engine/render/camera.h"
#include "engine/render/perception.h"
#include "engine/scene/scene_io.h"

namespace skylayers {

using namespace detail;

namespace {

// Illuminance in the renderer's units (1 = pi * 10^4 lux, shaders/common/lighting_shared.h)
// to lux.
constexpr double kLuxPerUnit = 3.14159265358979323846 * 1.0e4;

Light lightOf(const sky::BodyLight& body, const sky::shared::DirectionalLight& gpu) {
  Light light;
  light.direction = array3(body.direction.x, body.direction.y, body.direction.z);
  light.azimuthDeg = body.azimuthDeg;
  light.elevationDeg = body.elevationDeg;
  light.illuminanceLux = array3(gpu.illuminance.x * kLuxPerUnit, gpu.illuminance.y * kLuxPerUnit,
                                gpu.illuminance.z * kLuxPerUnit);
  return light;
}

}  // namespace

namespace {

// The lights of `scene` at its camera and time; with `field` (made for that scene), behind
// the clouds there.
Lighting lightingOf(const sky::Scene& scene, const sky::CloudField* field) {
  const sky::LightingState state = sky::computeLighting(scene, scene.time.start);
  Lighting lighting;
  lighting.sun = lightOf(state.sun, state.gpu.sun);
  lighting.moon = lightOf(state.moon, state.gpu.moon);
  lighting.dayFactor = state.dayFactor;
  lighting.key = state.key;
  if (field)
    for (Light* light : {&lighting.sun, &lighting.moon}) {
      light->cloudTransmittance = sky::cloudTransmittanceToward(
          *field, glm::dvec3(light->direction[0], light->direction[1], light->direction[2]));
      for (double& e : light->illuminanceLux) e *= light->cloudTransmittance;
    }
  return lighting;
}

std::vector<std::string> placeAndTime(const std::string& iso8601, double latitudeDeg,
                                      double longitudeDeg, double altitudeM) {
  return {"time=" + iso8601, "camera.latitude=" + exact(latitudeDeg),
          "camera.longitude=" + exact(longitudeDeg), "camera.altitude_m=" + exact(altitudeM)};
}

}  // namespace

Lighting lightingAt(double latitudeDeg, double longitudeDeg, double altitudeM,
                    const std::string& iso8601) {
  return translated([&] {
    return lightingOf(
        with(sky::loadSceneText(skyDefaultSceneText(), sky::ConfigFormat::Yaml, "<default scene>"),
             placeAndTime(iso8601, latitudeDeg, longitudeDeg, altitudeM)),
        nullptr);
  });
}

namespace {

// A top-down view has no observer under the clouds: its lights are the clear sky's.
bool observer(const sky::Scene& scene) {
  return scene.camera.mode != sky::CameraMode::GeographicTopdown;
}

}  // namespace

Lighting Sky::lighting() const {
  return translated([&] {
    return lightingOf(mImpl->scene, observer(mImpl->scene) ? &mImpl->cloudField() : nullptr);
  });
}

Lighting Sky::lighting(const std::string& iso8601) const {
  return lighting(iso8601, mImpl->scene.camera.latitude, mImpl->scene.camera.longitude,
                  mImpl->scene.camera.altitudeM);
}

Lighting Sky::lighting(const std::string& iso8601, double latitudeDeg, double longitudeDeg,
                       double altitudeM) const {
  return translated([&] {
    const sky::Scene scene =
        with(mImpl->scene, placeAndTime(iso8601, latitudeDeg, longitudeDeg, altitudeM));
    if (!observer(scene)) return lightingOf(scene, nullptr);
    const sky::CloudField field = mImpl->renderer.cloudField(scene, scene.time.start);
    return lightingOf(scene, &field);
  });
}

namespace {

// The real SH basis of skylayers.h at unit direction d.
std::array<double, 9> shBasis(const glm::dvec3& d) {
  return {0.282095,
          0.488603 * d.y,
          0.488603 * d.z,
          0.488603 * d.x,
          1.092548 * d.x * d.y,
          1.092548 * d.y * d.z,
          0.315392 * (3.0 * d.z * d.z - 1.0),
          1.092548 * d.x * d.z,
          0.546274 * (d.x * d.x - d.y * d.y)};
}

// Radiance in the renderer's units (1 = 10^4 cd/m^2, docs/outputs.md) to cd/m^2.
constexpr double kNitsPerUnit = 1.0e4;
// The probe of ambient(): the whole sphere at this size.
constexpr int kProbeWidth = 64, kProbeHeight = 32;

}  // namespace

std::array<double, 3> irradiance(const SphericalHarmonics& sh,
                                 const std::array<double, 3>& normal) {
  const glm::dvec3 n = glm::normalize(glm::dvec3(normal[0], normal[1], normal[2]));
  const std::array<double, 9> y = shBasis(n);
  constexpr double kPi = 3.14159265358979323846;
  const double band[9] = {kPi,       2.0 * kPi / 3.0, 2.0 * kPi / 3.0, 2.0 * kPi / 3.0, kPi / 4.0,
                          kPi / 4.0, kPi / 4.0,       kPi / 4.0,       kPi / 4.0};
  std::array<double, 3> e{0.0, 0.0, 0.0};
  for (int i = 0; i < 9; ++i)
    for (int c = 0; c < 3; ++c) e[c] += band[i] * sh[i][c] * y[i];
  return e;
}

SphericalHarmonics Sky::ambient() {
  return translated([&] {
    Impl& m = *mImpl;
    // The sphere as the camera's scene shows it, the discs left out; without temporal reuse,
    // which would take this for a cut of the Sky's own sequence.
    const sky::Scene probe =
        with(m.scene, {"camera.projection=equirectangular", "camera.heading=0", "camera.pitch=0",
                       "output.width=" + std::to_string(kProbeWidth),
                       "output.height=" + std::to_string(kProbeHeight), "sun.disc_scale=0",
                       "moon.disc_scale=0", "clouds.temporal.mode=off"});
    sky::RenderOptions options;
    options.readBack = sky::ReadBack::Beauty;
    const sky::RenderedFrame frame = m.renderer.render(probe, probe.time.start, options);
    const sky::ImageLayer* beauty = frame.image.find("");
    if (!beauty) sky::internalError("ambient: the probe frame has no beauty");
    const sky::shared::ViewState view = sky::makeViewState(probe.camera, kProbeWidth, kProbeHeight);
    constexpr double kPi = 3.14159265358979323846;
    SphericalHarmonics sh{};
    const size_t channels = beauty->channels.size();
    for (int y = 0; y < kProbeHeight; ++y)
      for (int x = 0; x < kProbeWidth; ++x) {
        const glm::dvec3 d = sky::viewDirection(view, x + 0.5, y + 0.5);
        // An equirectangular pixel's solid angle: (2 pi / W) (pi / H) cos(elevation).
        const double omega = (2.0 * kPi / kProbeWidth) * (kPi / kProbeHeight) *
                             std::sqrt(std::max(0.0, 1.0 - d.z * d.z));
        const std::array<double, 9> basis = shBasis(d);
        const float* px = &beauty->pixels[(size_t(y) * kProbeWidth + x) * channels];
        for (int i = 0; i < 9; ++i)
          for (int c = 0; c < 3; ++c) sh[i][c] += double(px[c]) * kNitsPerUnit * basis[i] * omega;
      }
    return sh;
  });
}

}  // namespace skylayers
