// The CPU queries: transmittance, cloud density, cover and the first cloud along lines, from
// the density field the GPU marches (engine/render/cloud_field.h), batched over the cores.
#include "sky_impl.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "engine/render/camera.h"
#include "engine/weather/geo.h"

namespace skylayers {

using namespace detail;

namespace {

glm::dvec3 enuOf(const sky::CloudField& field, const GeoPoint& p) {
  return field.enuOf(p.latitudeDeg, p.longitudeDeg, p.altitudeM);
}

// The lines' queries over the machine's cores: the field is read-only.
template <typename F>
void parallelFor(size_t count, F&& f) {
  const size_t threads =
      std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), (count + 7) / 8);
  if (threads <= 1) {
    for (size_t i = 0; i < count; ++i) f(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::vector<std::thread> pool;
  for (size_t t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (size_t i = next++; i < count; i = next++) f(i);
    });
  for (std::thread& t : pool) t.join();
}

Transmittance lineTransmittance(const sky::CloudField& field, const GeoPoint& from,
                                const GeoPoint& to) {
  const glm::dvec3 a = enuOf(field, from), b = enuOf(field, to);
  Transmittance t;
  t.cloudOpticalDepth = field.cloudOpticalDepth(a, b, Sky::kQueryStepM);
  t.cloud = std::exp(-t.cloudOpticalDepth);
  const glm::dvec3 air = field.airOpticalDepth(a, b);
  t.air = array3(std::exp(-air.x), std::exp(-air.y), std::exp(-air.z));
  return t;
}

}  // namespace

Transmittance Sky::transmittance(const GeoPoint& from, const GeoPoint& to) {
  return translated([&] { return lineTransmittance(mImpl->cloudField(), from, to); });
}

std::vector<Transmittance> Sky::transmittance(const std::vector<std::array<GeoPoint, 2>>& lines) {
  return translated([&] {
    const sky::CloudField& field = mImpl->cloudField();
    std::vector<Transmittance> out(lines.size());
    parallelFor(lines.size(),
                [&](size_t i) { out[i] = lineTransmittance(field, lines[i][0], lines[i][1]); });
    return out;
  });
}

double Sky::cloudExtinction(const GeoPoint& point) {
  return translated([&] {
    const sky::CloudField& field = mImpl->cloudField();
    return field.extinction(enuOf(field, point));
  });
}

CloudCover Sky::cover(double latitudeDeg, double longitudeDeg) {
  return translated([&] {
    const glm::vec4 w = mImpl->cloudField().weatherAt(latitudeDeg, longitudeDeg);
    return CloudCover{w.r, w.g, w.b};
  });
}

double Sky::firstCloud(const GeoPoint& from, const GeoPoint& to, double opticalDepth) {
  return translated([&] {
    const sky::CloudField& field = mImpl->cloudField();
    const glm::dvec3 a = enuOf(field, from), b = enuOf(field, to);
    const double length = glm::length(b - a);
    if (length <= 0.0) return -1.0;
    const std::optional<double> d =
        field.distanceToOpticalDepth(a, (b - a) / length, length, opticalDepth, kQueryStepM);
    return d.value_or(-1.0);
  });
}

GeoPoint Sky::pixelPoint(double x, double y, double distanceM) const {
  return translated([&] {
    const sky::Scene& scene = mImpl->scene;
    const sky::shared::ViewState view =
        sky::makeViewState(scene.camera, static_cast<uint32_t>(scene.output.width),
                           static_cast<uint32_t>(scene.output.height));
    const glm::dvec3 enu = sky::viewDirection(view, x, y) * distanceM;
    const glm::dvec3 lla = sky::latLonAltitude(
        {scene.camera.latitude, scene.camera.longitude, scene.camera.altitudeM}, enu);
    return GeoPoint{lla.x, lla.y, lla.z};
  });
}

}  // namespace skylayers
