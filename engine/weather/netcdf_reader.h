#pragma once
// NetCDF weather files through libnetcdf: ERA5/CDS pressure-level downloads (CF conventions,
// 1D latitude/longitude), WRF-style pressure-level output (2D XLAT/XLONG) and any CF file
// with 1D or 2D latitude/longitude coordinates. See docs/weather.md, "NetCDF".
#include <filesystem>

#include "engine/weather/weather_fields.h"

namespace sky {

// Reads every recognised variable (r, t, gh or z, u, v, lcc/mcc/hcc) at every pressure level
// and time; values unpacked and normalised to weather_fields.h's units. Throws a one-line
// sky::inputError naming the file (and the variable) when the file is missing, not NetCDF,
// truncated, holds no usable variable, or a variable has the wrong units or dimensions.
// Prints one warning line on stderr per variable whose fractions were clamped by more than 1 %.
WeatherFields readNetcdf(const std::filesystem::path& file);

}  // namespace sky
