#pragma once
// Weather fields as read from a forecast file (GRIB2 through ecCodes, NetCDF through
// libnetcdf), on the file's own horizontal grid, in SI-like units that every reader
// normalises to. The cloud-layer builder (Lu (1)(2)) reads only this, so a new format is a
// new reader and nothing else. See docs/weather.md.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sky {

// The horizontal grid: every point's latitude and longitude, as the file's geolocation gives
// them (any projection: regular lat/lon, Lambert conformal, Gaussian, reduced).
struct GridGeometry {
  uint32_t nx = 0;             // points along the fastest axis
  uint32_t ny = 0;             // rows (1 for a reduced grid stored as one list)
  std::vector<double> latDeg;  // nx * ny, row-major (x fastest), north or south first as stored
  std::vector<double> lonDeg;  // nx * ny, in [-180, 360)
  // A regular lat/lon grid: latDeg depends on the row only and lonDeg on the column only,
  // both monotonic (resamplers may then interpolate in index space directly).
  bool regularLatLon = false;
  size_t size() const { return latDeg.size(); }
};

// One 2D field on the grid.
//  name "r": relative humidity as a fraction 0..1 (readers convert percent and clamp, with a
//            warning when outside); "gh": geopotential height, metres; "t": temperature, K;
//  name "tcc_low" / "tcc_mid" / "tcc_high": the model's own cloud cover of its low, middle
//            and high cloud layers, fraction 0..1 (pressureHpa 0);
//  name "u" / "v": wind components, m/s.
struct LevelField {
  std::string name;
  double pressureHpa = 0.0;   // isobaric level; 0 for a field on a layer or the surface
  std::vector<float> values;  // grid.size() values; NaN where missing
};

// The fields valid at one time.
struct WeatherStep {
  double validTimeUnix = 0.0;  // seconds since 1970-01-01T00:00Z
  std::vector<LevelField> fields;
  // The field `name` at `pressureHpa` (within 0.01 hPa), or nullptr.
  const LevelField* find(const std::string& name, double pressureHpa = 0.0) const;
  // The isobaric levels (hPa, descending: surface first) at which `name` exists.
  std::vector<double> levels(const std::string& name) const;
};

struct WeatherFields {
  std::filesystem::path file;  // for error messages
  GridGeometry grid;
  std::vector<WeatherStep> steps;  // ascending valid time
};

}  // namespace sky
