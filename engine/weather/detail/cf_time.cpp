#include "engine/weather/detail/cf_time.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>

#include "engine/core/error.h"
#include "engine/weather/detail/text.h"

namespace sky::detail {
namespace {

bool oneOf(const std::string& s, std::initializer_list<const char*> list) {
  return std::any_of(list.begin(), list.end(), [&](const char* x) { return s == x; });
}

// Days from 1970-01-01 to y-m-d in the proleptic Gregorian calendar (H. Hinnant's
// days_from_civil), exact for any year.
int64_t daysFromCivil(int64_t y, int64_t m, int64_t d) {
  y -= m <= 2;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const int64_t yoe = y - era * 400;
  const int64_t doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

// A small cursor over "1900-01-01 00:00:00.0", "2011-01-15_12:00:00", "2000-1-1T06Z",
// "1970-01-01 00:00:00 +02:00".
class DateCursor {
public:
  explicit DateCursor(std::string_view s) : mS(s) {}
  bool atEnd() const { return mPos >= mS.size(); }
  void skipBlanks() {
    while (!atEnd() && std::isspace(static_cast<unsigned char>(mS[mPos]))) ++mPos;
  }
  bool accept(char c) {
    if (atEnd() || mS[mPos] != c) return false;
    ++mPos;
    return true;
  }
  std::optional<int64_t> integer(size_t maxDigits) {
    size_t start = mPos;
    int64_t v = 0;
    while (!atEnd() && std::isdigit(static_cast<unsigned char>(mS[mPos])) &&
           mPos - start < maxDigits)
      v = v * 10 + (mS[mPos++] - '0');
    if (mPos == start) return std::nullopt;
    return v;
  }
  double fraction() {  // after a '.', the digits as a fraction of one
    double f = 0.0, scale = 0.1;
    while (!atEnd() && std::isdigit(static_cast<unsigned char>(mS[mPos]))) {
      f += (mS[mPos++] - '0') * scale;
      scale *= 0.1;
    }
    return f;
  }
  std::string rest() const { return std::string(mS.substr(std::min(mPos, mS.size()))); }

private:
  std::string_view mS;
  size_t mPos = 0;
};

}  // namespace

std::optional<double> parseDateTime(std::string_view text) {
  DateCursor c(text);
  c.skipBlanks();
  auto y = c.integer(4);
  if (!y || !c.accept('-')) return std::nullopt;
  auto mo = c.integer(2);
  if (!mo || !c.accept('-')) return std::nullopt;
  auto d = c.integer(2);
  if (!d || *mo < 1 || *mo > 12 || *d < 1 || *d > 31) return std::nullopt;
  double secondsOfDay = 0.0;
  if (c.accept('T') || c.accept('t') || c.accept('_') || c.accept(' ')) {
    c.skipBlanks();
    if (auto h = c.integer(2)) {
      int64_t mi = 0, s = 0;
      double frac = 0.0;
      if (c.accept(':')) {
        auto m = c.integer(2);
        if (!m) return std::nullopt;
        mi = *m;
        if (c.accept(':')) {
          auto sec = c.integer(2);
          if (!sec) return std::nullopt;
          s = *sec;
          if (c.accept('.')) frac = c.fraction();
        }
      }
      if (*h > 24 || mi > 59 || s > 60) return std::nullopt;
      secondsOfDay = double(*h * 3600 + mi * 60 + s) + frac;
    }
  }
  c.skipBlanks();
  double zoneSeconds = 0.0;
  const std::string zone = lower(trim(c.rest()));
  if (!zone.empty() && zone != "z" && zone != "utc" && zone != "gmt") {
    DateCursor z(zone);
    const bool minus = z.accept('-');
    if (!minus && !z.accept('+')) return std::nullopt;
    auto hh = z.integer(2);
    if (!hh) return std::nullopt;
    int64_t mm = 0;
    if (z.accept(':') || !z.atEnd())
      if (auto m = z.integer(2)) mm = *m;
    if (!z.atEnd()) return std::nullopt;
    zoneSeconds = (minus ? -1.0 : 1.0) * double(*hh * 3600 + mm * 60);
  }
  return double(daysFromCivil(*y, *mo, *d)) * 86400.0 + secondsOfDay - zoneSeconds;
}

double cfTimeToUnix(double value, std::string_view units) {
  const std::string l = lower(trim(units));
  const size_t since = l.find(" since ");
  if (since == std::string::npos)
    inputError("time units \"" + printable(units) + "\" are not \"<unit> since <date>\"");
  const std::string unit = trim(l.substr(0, since));
  double seconds = 0.0;
  if (oneOf(unit, {"seconds", "second", "secs", "sec", "s"}))
    seconds = 1.0;
  else if (oneOf(unit, {"minutes", "minute", "mins", "min"}))
    seconds = 60.0;
  else if (oneOf(unit, {"hours", "hour", "hrs", "hr", "h"}))
    seconds = 3600.0;
  else if (oneOf(unit, {"days", "day", "d"}))
    seconds = 86400.0;
  else if (oneOf(unit, {"milliseconds", "millisecond", "msec", "ms"}))
    seconds = 1e-3;
  else
    inputError("time units \"" + printable(units) + "\": unknown unit \"" + printable(unit) + "\"");
  const auto reference = parseDateTime(l.substr(since + 7));
  if (!reference)
    inputError("time units \"" + printable(units) + "\": cannot read the reference date");
  return *reference + value * seconds;
}

}  // namespace sky::detail
