#pragma once
// The GFS fixture of tests/data/weather/ as a scene's weather map source, and the regions the
// tests use.
#include <cstdlib>
#include <filesystem>
#include <string>

#include "engine/scene/scene.h"

namespace sky::test {

// Lu et al.'s region (section 5): 0-55N, 39-105E.
inline const WeatherRegion kLuRegion{{0.0, 55.0}, {39.0, 105.0}};
// Europe and the North Atlantic, 35-70N, 30W-30E: across 0E, the seam of the 0-357.5 grid.
inline const WeatherRegion kAtlanticRegion{{35.0, 70.0}, {-30.0, 30.0}};

inline std::filesystem::path weatherDataDir() {
  return std::filesystem::path(std::getenv("SKY_TEST_DATA")) / "weather";
}

// A scene whose weather map comes from the GFS GRIB2 fixture over `region` (256 texels along
// the longer side), cover from relative humidity (Rh) or the model's tcc (Tcc).
inline Scene gfsScene(const WeatherRegion& region, WeatherCover cover) {
  Scene scene;
  scene.baseDir = weatherDataDir();
  scene.weather.source = WeatherMapSource::File;
  scene.weather.file = "gfs_2p5deg_r_gh_t_tcc_uv500.grib2";
  scene.weather.cover = cover;
  scene.weather.region = region;
  scene.weather.resolution = 256;
  return scene;
}

}  // namespace sky::test
