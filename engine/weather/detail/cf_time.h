#pragma once
// CF time coordinates ("hours since 1900-01-01 00:00:00.0") and the date-time strings of
// their reference dates and of WRF's Times variable, as Unix seconds (Gregorian calendar).
#include <optional>
#include <string_view>

namespace sky::detail {

// "YYYY-MM-DD[( |T|_)hh[:mm[:ss[.f]]]][ Z|UTC|GMT|(+|-)hh[:mm]]" (case-insensitive) as
// seconds since 1970-01-01T00:00Z; nullopt when it does not read as one.
std::optional<double> parseDateTime(std::string_view text);

// A CF time value in `units` ("<unit> since <date>" with milliseconds, seconds, minutes,
// hours or days) as seconds since 1970-01-01T00:00Z. Throws sky::inputError naming the units
// when they cannot be read.
double cfTimeToUnix(double value, std::string_view units);

}  // namespace sky::detail
