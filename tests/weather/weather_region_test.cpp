// engine/weather/weather_region.h: the square around the camera when a scene gives no region
// (its size, the snapping that keeps the map still for small camera moves, the poles), the
// extent of forecast grids (regular, global, projected, a list of points) and the clipping of
// the square to the data.
#include <cmath>
#include <string>

#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/weather/geo.h"
#include "engine/weather/weather_map.h"
#include "engine/weather/weather_region.h"
#include "error_capture.h"

namespace sky {
namespace {

const double kKmPerDegree = kEarthRadiusM * 1e-3 * glm::radians(1.0);

// A regular lat/lon grid of nx x ny points from (lat0, lon0) by (dLat, dLon).
GridGeometry regularGrid(uint32_t nx, uint32_t ny, double lat0, double lon0, double dLat,
                         double dLon) {
  GridGeometry g;
  g.nx = nx;
  g.ny = ny;
  g.regularLatLon = true;
  for (uint32_t j = 0; j < ny; ++j)
    for (uint32_t i = 0; i < nx; ++i) {
      g.latDeg.push_back(lat0 + j * dLat);
      g.lonDeg.push_back(lon0 + i * dLon);
    }
  return g;
}

TEST(CameraRegion, IsASquareOfTheGivenSizeAroundTheCamera) {
  WeatherSettings w;
  w.cameraRegionKm = 800.0;
  const WeatherRegion r = cameraRegion(47.37, 8.54, w);
  EXPECT_NEAR((r.lat[1] - r.lat[0]) * kKmPerDegree, 800.0, 1e-6);
  const glm::dvec2 km = regionSizeKm(r);
  EXPECT_NEAR(km.x, 800.0, 1.0);
  EXPECT_NEAR(km.y, 800.0, 1e-6);
  // Centred on the camera to within half a texel (the snapping).
  const double texelLat = 800.0 / kKmPerDegree / w.resolution;
  EXPECT_LE(std::fabs(0.5 * (r.lat[0] + r.lat[1]) - 47.37), 0.5 * texelLat + 1e-12);
  EXPECT_LE(std::fabs(0.5 * (r.lon[0] + r.lon[1]) - 8.54),
            0.5 * texelLat / std::cos(glm::radians(47.37)) + 1e-3);
  // The map over it is square in texels.
  EXPECT_EQ(proceduralMapSize(w, r), glm::uvec2(256, 256));
}

TEST(CameraRegion, ASmallMoveKeepsTheSameMapAndALargeOneMovesIt) {
  WeatherSettings w;
  const WeatherRegion a = cameraRegion(47.37, 8.54, w);
  // 100 m east and north: well inside one texel (3.1 km).
  EXPECT_EQ(cameraRegion(47.3709, 8.5413, w), a);
  // 50 km north: moved by a whole number of texels.
  const WeatherRegion b = cameraRegion(47.37 + 50.0 / kKmPerDegree, 8.54, w);
  const double texelLat = (a.lat[1] - a.lat[0]) / w.resolution;
  const double moved = (b.lat[0] - a.lat[0]) / texelLat;
  EXPECT_NEAR(moved, std::round(moved), 1e-6);
  EXPECT_NEAR(moved, 50.0 / (800.0 / 256.0), 1.0);
}

TEST(CameraRegion, NearAPoleItSpansEveryLongitude) {
  WeatherSettings w;
  const WeatherRegion r = cameraRegion(89.0, 30.0, w);
  EXPECT_EQ(r.lat[1], 90.0);
  EXPECT_NEAR(r.lon[1] - r.lon[0], 360.0, 1e-9);
  // Across 180E the west edge may lie below -180; regionUv takes longitudes modulo 360.
  const WeatherRegion dateLine = cameraRegion(0.0, -179.0, w);
  EXPECT_LT(dateLine.lon[0], -180.0);
  glm::dvec2 uv;
  EXPECT_TRUE(regionUv(dateLine, 0.0, 179.0, uv));
}

TEST(DataRegion, ARegularGridIsItsRowsAndColumns) {
  const WeatherRegion r = dataRegion(regularGrid(21, 11, 30.0, -20.0, 3.0, 2.0));
  EXPECT_EQ(r.lat, glm::dvec2(30.0, 60.0));
  EXPECT_EQ(r.lon, glm::dvec2(-20.0, 20.0));
  // Stored north first: the same extent.
  const WeatherRegion n = dataRegion(regularGrid(21, 11, 60.0, -20.0, -3.0, 2.0));
  EXPECT_EQ(n.lat, glm::dvec2(30.0, 60.0));
}

TEST(DataRegion, AGlobalGridIsTheWholeSphere) {
  // 2.5 degree GFS: 90N to 90S, 0 to 357.5E.
  const WeatherRegion r = dataRegion(regularGrid(144, 73, 90.0, 0.0, -2.5, 2.5));
  EXPECT_EQ(r.lat, glm::dvec2(-90.0, 90.0));
  EXPECT_EQ(r.lon, glm::dvec2(0.0, 360.0));
  // Cell-centred rows short of the poles still reach them.
  const WeatherRegion c = dataRegion(regularGrid(144, 72, 88.75, 1.25, -2.5, 2.5));
  EXPECT_EQ(c.lat, glm::dvec2(-90.0, 90.0));
}

TEST(DataRegion, AProjectedGridIsTheRectangleInsideItsEdges) {
  // A fan of curved rows and slanted columns, like a Lambert grid: the rectangle lies inside
  // every edge point.
  GridGeometry g;
  g.nx = 5;
  g.ny = 4;
  for (uint32_t j = 0; j < g.ny; ++j)
    for (uint32_t i = 0; i < g.nx; ++i) {
      const double x = double(i) - 2.0;
      g.latDeg.push_back(20.0 + 3.0 * j + 0.2 * x * x);    // rows bow north toward the ends
      g.lonDeg.push_back(-120.0 + 4.0 * i + 0.5 * x * j);  // columns fan out northward
    }
  const WeatherRegion r = dataRegion(g);
  EXPECT_DOUBLE_EQ(r.lat[0], 20.8);  // the southern row's highest point
  EXPECT_DOUBLE_EQ(r.lat[1], 29.0);  // the northern row's lowest
  EXPECT_DOUBLE_EQ(r.lon[0], -120.0);
  EXPECT_DOUBLE_EQ(r.lon[1], -104.0);
}

TEST(DataRegion, AListOfPointsIsTheirRange) {
  GridGeometry g;
  g.nx = 4;
  g.ny = 1;
  g.latDeg = {-10.0, 0.0, 5.0, 12.0};
  g.lonDeg = {100.0, 110.0, 95.0, 105.0};
  const WeatherRegion r = dataRegion(g);
  EXPECT_EQ(r.lat, glm::dvec2(-10.0, 12.0));
  EXPECT_EQ(r.lon, glm::dvec2(95.0, 110.0));
}

TEST(MapRegion, TheScenesRegionWinsThenTheCameraClippedToTheData) {
  Scene scene;
  scene.camera.latitude = 58.0;
  scene.camera.longitude = 0.0;
  const WeatherRegion europe =
      dataRegion(regularGrid(21, 11, 30.0, -20.0, 3.0, 2.0));  // 30-60N, 20W-20E
  scene.weather.region = WeatherRegion{{40.0, 45.0}, {0.0, 5.0}};
  EXPECT_EQ(mapRegion(weatherInputs(scene), &europe), *scene.weather.region);
  scene.weather.region.reset();
  const WeatherRegion square = cameraRegion(58.0, 0.0, scene.weather);
  EXPECT_EQ(mapRegion(weatherInputs(scene)), square);
  const WeatherRegion clipped = mapRegion(weatherInputs(scene), &europe);
  EXPECT_EQ(clipped.lat, glm::dvec2(square.lat[0], 60.0));
  EXPECT_EQ(clipped.lon, square.lon);
  // A grid in 0-360 longitudes seen from west of 0E: the square is moved by a turn to meet it.
  const WeatherRegion east = dataRegion(regularGrid(21, 11, 30.0, 340.0, 3.0, 2.0));  // 340-380E
  scene.camera.latitude = 45.0;
  scene.camera.longitude = -10.0;
  const WeatherRegion turned = mapRegion(weatherInputs(scene), &east);
  EXPECT_GE(turned.lon[0], 340.0);
  EXPECT_NEAR(0.5 * (turned.lon[0] + turned.lon[1]), 350.0, 0.5);
}

TEST(MapRegion, DataThatDoNotReachTheCameraAreOneLineSayingWhatToDo) {
  Scene scene;
  scene.camera.latitude = -30.0;
  scene.camera.longitude = 20.0;
  const WeatherRegion europe = dataRegion(regularGrid(21, 11, 30.0, -20.0, 3.0, 2.0));
  const Error e = test::catchError([&] { mapRegion(weatherInputs(scene), &europe); });
  EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  EXPECT_EQ(std::string(e.what()),
            "weather.region: not given, and the data (grid covers lat 30..60, lon -20..20) do "
            "not reach the 800 km around the camera at -30, 20; set weather.region or move the "
            "camera");
}

TEST(MapRegion, AResolvedRegionIsReadOnlyOnceSet) {
  WeatherSettings w;
  EXPECT_EQ(test::catchError([&] { resolvedRegion(w); }).kind(), ErrorKind::Internal);
  w.region = WeatherRegion{{1.0, 2.0}, {3.0, 4.0}};
  EXPECT_EQ(resolvedRegion(w), *w.region);
}

}  // namespace
}  // namespace sky
