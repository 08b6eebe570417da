#pragma once
// An instant written as ISO 8601 with an explicit zone: "2024-06-21T12:00:00+02:00",
// "2024-06-21T10:00Z", fractional seconds allowed. The zone is kept so printing the scene
// back gives the same text the user wrote.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace sky {

struct IsoTime {
  int64_t unixSeconds = 0;  // UTC seconds since 1970-01-01T00:00:00Z (whole seconds)
  double subsecond = 0.0;   // [0, 1)
  int offsetMinutes = 0;    // the zone the text was written in (UTC offset)

  // Parses the text; on failure returns nullopt and, if `why` is given, a short reason.
  static std::optional<IsoTime> parse(std::string_view text, std::string* why = nullptr);
  // ISO 8601 in the original zone, seconds always written, fraction only when non-zero.
  std::string format() const;
  // Julian date (UTC) — the ephemeris works from this.
  double julianDateUtc() const;

  bool operator==(const IsoTime&) const = default;
};

}  // namespace sky
