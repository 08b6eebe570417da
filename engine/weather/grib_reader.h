#pragma once
// GRIB2 (and GRIB1) forecast files through ecCodes: relative humidity, geopotential height,
// temperature and wind on isobaric levels, and the model's low/middle/high cloud-layer cover,
// on the file's own grid with every point's latitude and longitude. See docs/weather.md.
#include <filesystem>

#include "engine/weather/weather_fields.h"

namespace sky {

// Reads every usable message of `file` (r, gh, t, u, v on isobaric levels; tcc on the low,
// middle and high cloud layers) into fields in WeatherFields' units, one WeatherStep per valid
// time. Throws a one-line BadInput naming the file and the message number for a missing,
// non-GRIB, truncated or corrupt file, a grid that changes between messages, or a file with
// no relative humidity or cloud cover. Safe to call from several threads (calls are
// serialised: ecCodes' multi-field state is per process).
WeatherFields readGrib2(const std::filesystem::path& file);

}  // namespace sky
