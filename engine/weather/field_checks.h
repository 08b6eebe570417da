#pragma once
// The one validation path of forecast fields, shared by the GRIB and NetCDF readers (issue
// 31): longitudes into one range, the regular-grid test, fractions converted and clamped
// with one warning, and the checks for values that are not finite. Each reader used to carry
// its own copy, and the copies had drifted (a 1 x 1 grid was regular in one and not the
// other; a NaN reference value or scale_factor passed without a word). Warnings go to the
// process's warning sink (engine/core/warnings.h).
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "engine/weather/weather_fields.h"

namespace sky {

// A longitude into [-180, 360) (east of Greenwich either way): values already there are
// kept as the file wrote them.
double normaliseLon(double lon);

// Latitude a function of the row only, longitude of the column only, both strictly
// monotonic, and at least two points along one axis (a single point has no spacing to
// interpolate by).
bool isRegularGrid(const GridGeometry& g);

// Gathers what a reader found in the values of one file and says it once at the end.
class FieldChecks {
public:
  explicit FieldChecks(std::string fileName) : mFile(std::move(fileName)) {}

  // A fraction field (r, tcc_*) read in units of `scale` (0.01 for percent): converts to
  // 0..1 and clamps. Values outside by more than 1 % are counted for one warning; within,
  // they are rounding and clamped silently. NaN (missing) stays NaN.
  void toFraction(std::vector<float>& values, double scale, const std::string& name);
  // Values of `name` that decoded to NaN or infinity though the file did not mark them
  // missing (a NaN reference value, a garbage scale): `count` of `total`, now NaN.
  void noteNonFinite(const std::string& name, size_t count, size_t total);
  // The end of the file: an input error when every value of a field the renderer uses is
  // missing or not finite (a whole field unusable), else one warning per kind of finding.
  void finish(const WeatherFields& fields) const;

private:
  struct Range {
    size_t count = 0;
    double lo = 0.0, hi = 1.0;
  };
  struct NonFinite {
    size_t count = 0, total = 0;
  };
  std::string mFile;
  std::map<std::string, Range> mRanges;          // by field name
  std::map<std::string, NonFinite> mNonFinite;   // by field name
};

}  // namespace sky
