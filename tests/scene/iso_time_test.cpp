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

}  // namespace
}  // namespace sky
