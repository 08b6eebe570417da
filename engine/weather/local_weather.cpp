#include "engine/weather/local_weather.h"

#include <algorithm>
#include <cmath>

#include "engine/weather/geo.h"

namespace sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr int kRings = 5;            // plus the centre
constexpr int kSamplesPerRing = 12;  // 1 + 5 * 12 = 61 samples

// Bilinear over the texel centres with 0 outside the map (half a texel of fade at the
// border): low, mid and high cover at map coordinate (u, v) (u east, v south, 0..1).
glm::vec3 coverAt(const WeatherMap& map, double u, double v) {
  const double x = u * map.width - 0.5, y = v * map.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = x - fx, ty = y - fy;
  glm::dvec3 sum(0.0);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const long xi = long(fx) + i, yi = long(fy) + j;
      if (xi < 0 || yi < 0 || xi >= long(map.width) || yi >= long(map.height)) continue;
      const double w = (i ? tx : 1.0 - tx) * (j ? ty : 1.0 - ty);
      const size_t k = size_t(yi) * map.width + size_t(xi);
      const glm::vec4& t = map.texels[k];
      sum += w * glm::dvec3(t.r, t.g, map.coverHigh.empty() ? 0.0f : map.coverHigh[k]);
    }
  return glm::vec3(sum);
}

}  // namespace

LocalWeather localWeather(const WeatherMap& map, double latDeg, double lonDeg, double radiusKm) {
  LocalWeather out;
  if (map.width == 0 || map.height == 0 || map.texels.size() != size_t(map.width) * map.height)
    return out;
  const WeatherRegion& r = map.region;
  const double radiusM = radiusKm * 1000.0;
  const double metresPerDegLat = kEarthRadiusM * kDeg;
  const double metresPerDegLon = std::max(std::cos(latDeg * kDeg), 1e-3) * metresPerDegLat;
  glm::dvec3 sum(0.0);
  double weights = 0.0;
  for (int ring = 0; ring <= kRings; ++ring) {
    // Ring k at radius k / (kRings + 1) of the disc (the kernel is 0 at its edge) stands for
    // the annulus around it: weight = annulus area x kernel.
    const double step = 1.0 / (kRings + 1);
    const double s = ring * step;
    const double kernel = (1.0 - s * s) * (1.0 - s * s);
    const int n = ring == 0 ? 1 : kSamplesPerRing;
    const double area = ring == 0 ? 0.25 * step * step : 2.0 * s * step;
    for (int k = 0; k < n; ++k) {
      // Rings are turned by half a step against each other so samples do not line up.
      const double a = 2.0 * kPi * (k + 0.5 * (ring % 2)) / n;
      const double lat = latDeg + s * radiusM * std::cos(a) / metresPerDegLat;
      double lon = lonDeg + s * radiusM * std::sin(a) / metresPerDegLon;
      // The region's longitudes may run past 180 (e.g. [170, 200]).
      while (lon < r.lon[0] - 180.0) lon += 360.0;
      while (lon > r.lon[0] + 180.0) lon -= 360.0;
      const double u = (lon - r.lon[0]) / (r.lon[1] - r.lon[0]);
      const double v = (r.lat[1] - lat) / (r.lat[1] - r.lat[0]);
      const double w = kernel * area / n;
      sum += w * glm::dvec3(coverAt(map, u, v));
      weights += w;
    }
  }
  const glm::dvec3 c = glm::clamp(sum / weights, 0.0, 1.0);
  out.low = float(c.x);
  out.mid = float(c.y);
  out.high = float(c.z);
  out.overcast = float(1.0 - (1.0 - c.x) * (1.0 - c.y) * (1.0 - c.z));
  return out;
}

}  // namespace sky
