#include "engine/weather/weather_region.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/core/error.h"
#include "engine/weather/geo.h"

namespace sky {
namespace {

constexpr double kDegPerRad = 57.29577951308232;
const double kKmPerDegree = kEarthRadiusM * 1e-3 / kDegPerRad;

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}

// Longitude `lon` moved by whole turns to lie within 180 degrees of `centre`.
double near(double lon, double centre) {
  return centre + std::remainder(lon - centre, 360.0);
}

}  // namespace

WeatherRegion cameraRegion(double latDeg, double lonDeg, const WeatherSettings& weather) {
  const double halfLat = 0.5 * weather.cameraRegionKm / kKmPerDegree;
  const double texels = std::max(weather.resolution, 2);
  const double pitchLat = 2.0 * halfLat / texels;
  const double lat = std::clamp(std::round(latDeg / pitchLat) * pitchLat, -90.0, 90.0);
  WeatherRegion r;
  r.lat = {std::max(-90.0, lat - halfLat), std::min(90.0, lat + halfLat)};
  // Near the poles the square is wider than the parallel through its middle: all longitudes.
  const double cosLat = std::cos(lat / kDegPerRad);
  const double halfLon = cosLat > 1e-9 ? halfLat / cosLat : 180.0;
  if (halfLon >= 180.0) {
    r.lon = {lonDeg - 180.0, lonDeg + 180.0};
    return r;
  }
  const double pitchLon = 2.0 * halfLon / texels;
  const double lon = std::round(lonDeg / pitchLon) * pitchLon;
  r.lon = {lon - halfLon, lon + halfLon};
  return r;
}

WeatherRegion dataRegion(const GridGeometry& grid) {
  const size_t n = grid.size();
  if (n == 0) inputError("weather.file: the grid has no points");
  // Longitudes unwrapped around the grid's middle point, so a grid across 180E is one piece.
  const double centre = grid.lonDeg[n / 2];
  double latMin = 90.0, latMax = -90.0, lonMin = 1e9, lonMax = -1e9;
  for (size_t k = 0; k < n; ++k) {
    if (!std::isfinite(grid.latDeg[k]) || !std::isfinite(grid.lonDeg[k])) continue;
    const double lon = near(grid.lonDeg[k], centre);
    latMin = std::min(latMin, grid.latDeg[k]);
    latMax = std::max(latMax, grid.latDeg[k]);
    lonMin = std::min(lonMin, lon);
    lonMax = std::max(lonMax, lon);
  }
  WeatherRegion box{{latMin, latMax}, {lonMin, lonMax}};
  const uint32_t nx = grid.nx, ny = grid.ny;
  const bool table = nx >= 2 && ny >= 2 && size_t(nx) * ny == n;
  if (grid.regularLatLon && table) {
    // A global grid: uniform columns whose spacing closes the circle.
    const double dLon = (grid.lonDeg[nx - 1] - grid.lonDeg[0]) / (nx - 1);
    if (nx > 2 && std::fabs(std::fabs(dLon) * nx - 360.0) < 1e-3 * std::fabs(dLon)) {
      box.lon = {lonMin, lonMin + 360.0};
      const double dLat = (latMax - latMin) / (ny - 1);
      if (latMax >= 90.0 - 1.5 * dLat) box.lat[1] = 90.0;
      if (latMin <= -90.0 + 1.5 * dLat) box.lat[0] = -90.0;
    }
    return box;
  }
  if (!table) {
    // A list of points (a reduced Gaussian grid): their range; all longitudes when they
    // go round the globe.
    if (lonMax - lonMin > 350.0) box.lon = {lonMin, lonMin + 360.0};
    return box;
  }
  // A projected grid: the rectangle inside its four edges.
  std::vector<double> first(nx), last(nx), left(ny), right(ny);
  for (uint32_t i = 0; i < nx; ++i) {
    first[i] = grid.latDeg[i];
    last[i] = grid.latDeg[size_t(ny - 1) * nx + i];
  }
  for (uint32_t j = 0; j < ny; ++j) {
    left[j] = near(grid.lonDeg[size_t(j) * nx], centre);
    right[j] = near(grid.lonDeg[size_t(j) * nx + nx - 1], centre);
  }
  const bool southFirst = mean(first) < mean(last);
  const std::vector<double>& south = southFirst ? first : last;
  const std::vector<double>& north = southFirst ? last : first;
  const bool westLeft = mean(left) < mean(right);
  const std::vector<double>& west = westLeft ? left : right;
  const std::vector<double>& east = westLeft ? right : left;
  WeatherRegion inner{
      {*std::max_element(south.begin(), south.end()),
       *std::min_element(north.begin(), north.end())},
      {*std::max_element(west.begin(), west.end()), *std::min_element(east.begin(), east.end())}};
  if (inner.lat[0] < inner.lat[1] && inner.lon[0] < inner.lon[1]) return inner;
  return box;
}

WeatherRegion mapRegion(const WeatherInputs& in, const WeatherRegion* dataExtent) {
  const WeatherSettings& w = in.settings;
  if (w.region) return *w.region;
  const glm::dvec2 camera = in.cameraLatLonDeg;
  const WeatherRegion square = cameraRegion(camera.x, camera.y, w);
  if (!dataExtent) return square;
  const WeatherRegion& data = *dataExtent;
  WeatherRegion out;
  out.lat = {std::max(square.lat[0], data.lat[0]), std::min(square.lat[1], data.lat[1])};
  // Longitudes: the square moved by whole turns to overlap the data most.
  double best = 0.0;
  for (double k : {0.0, -360.0, 360.0, -720.0, 720.0}) {
    const double west = std::max(square.lon[0] + k, data.lon[0]);
    const double east = std::min(square.lon[1] + k, data.lon[1]);
    if (east - west > best) {
      best = east - west;
      out.lon = {west, east};
    }
  }
  if (!(out.lat[0] < out.lat[1]) || best <= 0.0)
    inputError("weather.region: not given, and the data (grid covers lat " + number(data.lat[0]) +
               ".." + number(data.lat[1]) + ", lon " + number(data.lon[0]) + ".." +
               number(data.lon[1]) + ") do not reach the " + number(w.cameraRegionKm) +
               " km around the camera at " + number(camera.x) + ", " + number(camera.y) +
               "; set weather.region or move the camera");
  return out;
}

const WeatherRegion& resolvedRegion(const WeatherSettings& weather) {
  if (!weather.region) internalError("weather.region read before the weather map resolved it");
  return *weather.region;
}

}  // namespace sky
