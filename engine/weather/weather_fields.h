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

// What a field holds, in the units every reader converts to.
enum class FieldKind : uint8_t {
  RelativeHumidity,    // a fraction 0..1 (readers convert percent and clamp, with a warning)
  GeopotentialHeight,  // metres
  Temperature,         // K
  CloudCoverLow,       // the model's own cloud cover of its low layer, fraction 0..1
  CloudCoverMid,       //   ... middle layer (these three on no pressure level: pressureHpa 0)
  CloudCoverHigh,      //   ... high layer
  WindU,               // eastward wind, m/s
  WindV,               // northward wind, m/s
};
// The kind's short name in messages: GRIB's shortName ("r", "gh", "t", "u", "v"), and
// "tcc_low", "tcc_mid", "tcc_high" for the layer cloud covers.
const char* fieldName(FieldKind kind);

// One 2D field on the grid.
struct LevelField {
  FieldKind kind = FieldKind::RelativeHumidity;
  double pressureHpa = 0.0;   // isobaric level; 0 for a field on a layer or the surface
  std::vector<float> values;  // grid.size() values; NaN where missing
};

// The fields valid at one time.
struct WeatherStep {
  double validTimeUnix = 0.0;  // seconds since 1970-01-01T00:00Z
  std::vector<LevelField> fields;
  // The field of `kind` at `pressureHpa` (within 0.01 hPa), or nullptr.
  const LevelField* find(FieldKind kind, double pressureHpa = 0.0) const;
  // The isobaric levels (hPa, descending: surface first) at which `kind` exists.
  std::vector<double> levels(FieldKind kind) const;
};

struct WeatherFields {
  std::filesystem::path file;  // for error messages
  GridGeometry grid;
  std::vector<WeatherStep> steps;  // ascending valid time
};

}  // namespace sky
