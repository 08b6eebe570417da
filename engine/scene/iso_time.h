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
  // The instant `seconds` later (earlier when negative), written in the same zone.
  IsoTime plusSeconds(double seconds) const;
  // Seconds from `other` to this instant.
  double secondsSince(const IsoTime& other) const;

  bool operator==(const IsoTime&) const = default;
};

// A length of time for time-lapse steps: ISO 8601 ("PT15M", "P1DT2H", "PT0.5S") or short
// unit form ("15m", "1h30m", "90s", "2d", "0.5s"). Returns seconds, which may be zero or
// negative ("-15m") so the caller can say what is wrong; nullopt for text that is neither form.
std::optional<double> parseDuration(std::string_view text, std::string* why = nullptr);
// Short unit form, reading back as the same number of seconds: 900 -> "15m", 5400 -> "1h30m".
std::string formatDuration(double seconds);

}  // namespace sky
