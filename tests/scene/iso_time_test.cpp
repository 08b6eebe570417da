#include "engine/scene/iso_time.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sky {
namespace {

IsoTime parsed(const char* text) {
  std::string why;
  std::optional<IsoTime> t = IsoTime::parse(text, &why);
  EXPECT_TRUE(t.has_value()) << text << ": " << why;
  return t.value_or(IsoTime{});
}

std::string whyNot(const char* text) {
  std::string why;
  EXPECT_FALSE(IsoTime::parse(text, &why).has_value()) << text;
  return why;
}

TEST(IsoTime, J2000IsJulianDate2451545) {
  EXPECT_EQ(parsed("2000-01-01T12:00:00Z").julianDateUtc(), 2451545.0);
  EXPECT_EQ(parsed("2000-01-01T13:30:00+01:30").julianDateUtc(), 2451545.0);
  EXPECT_EQ(parsed("1970-01-01T00:00:00Z").julianDateUtc(), 2440587.5);
}

TEST(IsoTime, UnixSecondsAndOffsets) {
  EXPECT_EQ(parsed("1970-01-01T00:00:00Z").unixSeconds, 0);
  EXPECT_EQ(parsed("2024-06-21T10:00:00Z").unixSeconds, 1718964000);
  IsoTime zurich = parsed("2024-06-21T12:00:00+02:00");
  EXPECT_EQ(zurich.unixSeconds, 1718964000);
  EXPECT_EQ(zurich.offsetMinutes, 120);
  IsoTime newYork = parsed("2024-06-21T06:00:00-04:00");
  EXPECT_EQ(newYork.unixSeconds, 1718964000);
  EXPECT_EQ(newYork.offsetMinutes, -240);
  EXPECT_EQ(parsed("2024-06-21T15:30:00+0530").unixSeconds, 1718964000);
  EXPECT_EQ(parsed("2024-06-21T12:00:00+02").offsetMinutes, 120);
  EXPECT_EQ(parsed("2024-06-21T10:00Z").unixSeconds, 1718964000);  // seconds optional
  EXPECT_EQ(parsed("1969-12-31T23:59:59Z").unixSeconds, -1);
  // The local date may differ from the UTC date.
  EXPECT_EQ(parsed("2024-01-01T01:00:00+03:00").unixSeconds,
            parsed("2023-12-31T22:00:00Z").unixSeconds);
}

TEST(IsoTime, FormatKeepsZoneAndRoundTrips) {
  for (const char* text :
       {"2024-06-21T12:00:00+02:00", "2024-06-21T06:00:00-04:00", "2000-01-01T12:00:00Z",
        "2024-02-29T23:59:59-09:30", "1969-12-31T23:59:59Z", "2024-06-21T12:00:00.25Z",
        "2024-06-21T12:00:00.3+01:00", "2024-06-21T12:00:00.123456789012-00:30"}) {
    IsoTime t = parsed(text);
    EXPECT_EQ(t.format(), text);
    EXPECT_EQ(parsed(t.format().c_str()), t) << text;
  }
  // Normalised spellings: seconds always written, 'Z' for +00:00.
  EXPECT_EQ(parsed("2024-06-21T10:00Z").format(), "2024-06-21T10:00:00Z");
  EXPECT_EQ(parsed("2024-06-21t10:00:00+00:00").format(), "2024-06-21T10:00:00Z");
  EXPECT_EQ(parsed("2024-06-21 12:00:00+0200").format(), "2024-06-21T12:00:00+02:00");
}

TEST(IsoTime, FractionalSecondsAreExact) {
  EXPECT_EQ(parsed("2024-06-21T12:00:00.3Z").subsecond, 0.3);
  EXPECT_EQ(parsed("2024-06-21T12:00:00,5Z").subsecond, 0.5);
  EXPECT_EQ(parsed("2024-06-21T12:00:00.000Z").subsecond, 0.0);
  EXPECT_EQ(parsed("2024-06-21T12:00:00.000Z").format(), "2024-06-21T12:00:00Z");
  // Used to print as ".0" (a 9-digit printf rounded it up to 1.000000000).
  IsoTime nearlyNext = parsed("2024-06-21T12:00:00.9999999999Z");
  EXPECT_LT(nearlyNext.subsecond, 1.0);
  EXPECT_EQ(nearlyNext.format(), "2024-06-21T12:00:00.9999999999Z");
  IsoTime roundsToOne = parsed("2024-06-21T12:00:00.99999999999999999999Z");
  EXPECT_LT(roundsToOne.subsecond, 1.0);
  EXPECT_EQ(parsed(roundsToOne.format().c_str()), roundsToOne);
  EXPECT_NEAR(parsed("2000-01-01T12:00:00.5Z").julianDateUtc(), 2451545.0 + 0.5 / 86400.0, 1e-9);
}

TEST(IsoTime, LeapDays) {
  EXPECT_EQ(parsed("2024-02-29T00:00:00Z").format(), "2024-02-29T00:00:00Z");
  EXPECT_EQ(parsed("2000-02-29T00:00:00Z").unixSeconds + 86400,
            parsed("2000-03-01T00:00:00Z").unixSeconds);
  EXPECT_EQ(whyNot("2023-02-29T00:00:00Z"), "day out of range for the month");
  EXPECT_EQ(whyNot("1900-02-29T00:00:00Z"), "day out of range for the month");
  EXPECT_EQ(whyNot("2024-02-30T00:00:00Z"), "day out of range for the month");
  EXPECT_EQ(whyNot("2024-04-31T00:00:00Z"), "day out of range for the month");
}

TEST(IsoTime, RejectsBadText) {
  EXPECT_EQ(whyNot("2024-06-21T12:00:00"),
            "missing time zone: add Z (UTC) or an offset such as +02:00");
  EXPECT_EQ(whyNot("2024-13-01T00:00:00Z"), "month out of range");
  EXPECT_EQ(whyNot("0000-01-01T00:00:00Z"), "year out of range (0001 to 9999)");
  EXPECT_EQ(whyNot("2024-00-01T00:00:00Z"), "month out of range");
  EXPECT_EQ(whyNot("2024-06-00T00:00:00Z"), "day out of range for the month");
  EXPECT_EQ(whyNot("2024-06-21T24:00:00Z"), "hour, minute or second out of range");
  EXPECT_EQ(whyNot("2024-06-21T12:60:00Z"), "hour, minute or second out of range");
  EXPECT_EQ(whyNot("2024-06-21T12:00:60Z"), "hour, minute or second out of range");
  EXPECT_EQ(whyNot("2024-06-21T12:00:00+19:00"), "time zone offset out of range (at most +-18:00)");
  // Used to pass: hours were checked against 18 but the minutes were not counted.
  EXPECT_EQ(whyNot("2024-06-21T12:00:00+18:30"), "time zone offset out of range (at most +-18:00)");
  EXPECT_EQ(parsed("2024-06-21T12:00:00-18:00").offsetMinutes, -18 * 60);
  for (const char* bad :
       {"", "2024", "2024-6-21T12:00Z", "2024-06-21", "2024-06-21T12Z", "2024-06-21T12:00:00.Z",
        "2024-06-21T12:00:00Zx", "2024-06-21T12:00:00+2:00", "2024-06-21T12:00:00+02:0",
        "2024-06-21X12:00:00Z", " 2024-06-21T12:00:00Z"}) {
    EXPECT_FALSE(IsoTime::parse(bad).has_value()) << "'" << bad << "'";
  }
}

TEST(IsoTime, PlusSecondsKeepsTheZone) {
  IsoTime t = parsed("2024-06-21T23:30:00+05:30");
  IsoTime later = t.plusSeconds(3600);
  EXPECT_EQ(later.format(), "2024-06-22T00:30:00+05:30");  // the local date moves on
  EXPECT_EQ(later.offsetMinutes, 330);
  EXPECT_EQ(later.secondsSince(t), 3600.0);
  EXPECT_EQ(t.secondsSince(later), -3600.0);
  EXPECT_EQ(t.plusSeconds(-86400).format(), "2024-06-20T23:30:00+05:30");
  EXPECT_EQ(t.plusSeconds(0), t);
  // Across a leap day and a year end.
  EXPECT_EQ(parsed("2024-02-28T12:00:00Z").plusSeconds(86400).format(), "2024-02-29T12:00:00Z");
  EXPECT_EQ(parsed("2023-02-28T12:00:00Z").plusSeconds(86400).format(), "2023-03-01T12:00:00Z");
  EXPECT_EQ(parsed("2024-12-31T23:59:59-01:00").plusSeconds(1).format(),
            "2025-01-01T00:00:00-01:00");
  // Seconds since compares instants, not wall-clock text.
  EXPECT_EQ(parsed("2024-06-21T12:00:00+02:00").secondsSince(parsed("2024-06-21T10:00:00Z")), 0.0);
}

TEST(IsoTime, PlusSecondsCarriesFractions) {
  IsoTime t = parsed("2024-06-21T12:00:00.75Z");
  EXPECT_EQ(t.plusSeconds(0.5).format(), "2024-06-21T12:00:01.25Z");
  EXPECT_EQ(t.plusSeconds(0.25).format(), "2024-06-21T12:00:01Z");
  EXPECT_EQ(t.plusSeconds(0.25).subsecond, 0.0);
  EXPECT_EQ(t.plusSeconds(-0.75).format(), "2024-06-21T12:00:00Z");
  EXPECT_EQ(t.plusSeconds(-1.0).format(), "2024-06-21T11:59:59.75Z");
  EXPECT_EQ(t.plusSeconds(-1.5).format(), "2024-06-21T11:59:59.25Z");
  EXPECT_EQ(t.plusSeconds(0.5).secondsSince(t), 0.5);
  // A tiny step far from 1970 is not lost: unix seconds and the fraction are kept apart.
  IsoTime far = parsed("9999-12-31T23:59:58Z");
  EXPECT_EQ(far.plusSeconds(1e-6).subsecond, 1e-6);
  EXPECT_EQ(far.plusSeconds(1e-6).unixSeconds, far.unixSeconds);
  for (int i = 0; i < 100; ++i) {
    IsoTime u = t.plusSeconds(i * 0.01);
    EXPECT_GE(u.subsecond, 0.0);
    EXPECT_LT(u.subsecond, 1.0);
  }
}

std::optional<double> duration(const char* text) {
  std::string why;
  std::optional<double> d = parseDuration(text, &why);
  EXPECT_TRUE(d.has_value()) << text << ": " << why;
  return d;
}

TEST(Duration, ShortForm) {
  EXPECT_EQ(duration("15m"), 900.0);
  EXPECT_EQ(duration("1h30m"), 5400.0);
  EXPECT_EQ(duration("90s"), 90.0);
  EXPECT_EQ(duration("2d"), 172800.0);
  EXPECT_EQ(duration("0.5s"), 0.5);
  EXPECT_EQ(duration("1d1s"), 86401.0);
  EXPECT_EQ(duration("1d2h3m4.25s"), 93784.25);
  EXPECT_EQ(duration("1.5h"), 5400.0);
  EXPECT_EQ(duration("90M"), 5400.0);  // unit letters in either case
  EXPECT_EQ(duration("+10s"), 10.0);
  // Zero and negative durations parse; the scene reader says why they are wrong.
  EXPECT_EQ(duration("0s"), 0.0);
  EXPECT_EQ(duration("-15m"), -900.0);
}

TEST(Duration, IsoForm) {
  EXPECT_EQ(duration("PT15M"), 900.0);
  EXPECT_EQ(duration("P1DT2H"), 93600.0);
  EXPECT_EQ(duration("PT0.5S"), 0.5);
  EXPECT_EQ(duration("P2D"), 172800.0);
  EXPECT_EQ(duration("PT1H30M"), 5400.0);
  EXPECT_EQ(duration("pt1m"), 60.0);
  EXPECT_EQ(duration("P1DT1S"), 86401.0);
  EXPECT_EQ(duration("-PT15M"), -900.0);
  // In the ISO form M before T would be months: not a fixed length, so not accepted.
  EXPECT_FALSE(parseDuration("P1M").has_value());
}

TEST(Duration, RejectsBadText) {
  for (const char* bad :
       {"",   "-",    "15",   "m",     "15 m",   " 15m",   "15m ",  "15min", "1m1h",   "1h1h",
        "PT", "P",    "P1H",  "PT1D",  "PT1H1H", "P1DT",   "PTT1H", "1y",    "1w",     "1.2.3s",
        ".s", "--1s", "1e3s", "nan s", "infs",   "1h-30m", "P-1D",  "15m/",  "PT15M30"}) {
    std::string why;
    EXPECT_FALSE(parseDuration(bad, &why).has_value()) << "'" << bad << "'";
    EXPECT_EQ(why, "expected a duration such as 15m, 1h30m, 90s, 2d or ISO 8601 PT15M")
        << "'" << bad << "'";
  }
}

TEST(Duration, FormatIsShortAndReadsBack) {
  EXPECT_EQ(formatDuration(900), "15m");
  EXPECT_EQ(formatDuration(5400), "1h30m");
  EXPECT_EQ(formatDuration(86401), "1d1s");
  EXPECT_EQ(formatDuration(0.5), "0.5s");
  EXPECT_EQ(formatDuration(90), "1m30s");
  EXPECT_EQ(formatDuration(172800), "2d");
  EXPECT_EQ(formatDuration(0), "0s");
  EXPECT_EQ(formatDuration(-900), "-15m");
  EXPECT_EQ(formatDuration(61.3), "61.3s");
  // Every value reads back exactly, including fractions and sums of every unit.
  for (double s : {900.0, 5400.0, 86401.0, 0.5, 1e-8, 61.3, 0.1 + 0.2, 93784.0, 1.0 / 3.0,
                   123456789.0, 86400.0 * 365.25, 3e15, 1e20, 1e300, 1e-300, -0.25, -90061.0}) {
    std::string text = formatDuration(s);
    std::string why;
    std::optional<double> back = parseDuration(text, &why);
    ASSERT_TRUE(back.has_value()) << s << " -> '" << text << "': " << why;
    EXPECT_EQ(*back, s) << s << " -> '" << text << "'";
  }
}

}  // namespace
}  // namespace sky
