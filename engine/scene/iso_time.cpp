#include "engine/scene/iso_time.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace sky {
namespace {

// Days from 1970-01-01 to y-m-d in the proleptic Gregorian calendar (Howard Hinnant's
// days_from_civil), valid for every year we accept.
int64_t daysFromCivil(int64_t y, unsigned m, unsigned d) {
  y -= m <= 2;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<int64_t>(doe) - 719468;
}

void civilFromDays(int64_t z, int& y, unsigned& m, unsigned& d) {
  z += 719468;
  const int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const unsigned doe = static_cast<unsigned>(z - era * 146097);
  const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const int64_t yy = static_cast<int64_t>(yoe) + era * 400;
  const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const unsigned mp = (5 * doy + 2) / 153;
  d = doy - (153 * mp + 2) / 5 + 1;
  m = mp < 10 ? mp + 3 : mp - 9;
  y = static_cast<int>(yy + (m <= 2));
}

bool isLeap(int y) {
  return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

int daysInMonth(int y, int m) {
  static const int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return m == 2 && isLeap(y) ? 29 : kDays[m - 1];
}

// Reads exactly n digits at text[pos...]; advances pos.
bool digits(std::string_view t, size_t& pos, int n, int& out) {
  if (pos + static_cast<size_t>(n) > t.size()) return false;
  out = 0;
  for (int i = 0; i < n; ++i) {
    char c = t[pos + static_cast<size_t>(i)];
    if (c < '0' || c > '9') return false;
    out = out * 10 + (c - '0');
  }
  pos += static_cast<size_t>(n);
  return true;
}

bool expect(std::string_view t, size_t& pos, char c) {
  if (pos < t.size() && t[pos] == c) {
    ++pos;
    return true;
  }
  return false;
}

std::optional<IsoTime> fail(std::string* why, const char* reason) {
  if (why) *why = reason;
  return std::nullopt;
}

}  // namespace

std::optional<IsoTime> IsoTime::parse(std::string_view t, std::string* why) {
  constexpr const char* kForm = "expected YYYY-MM-DDTHH:MM[:SS[.fff]] followed by Z or +HH:MM";
  size_t p = 0;
  int year, month, day, hour, minute, second = 0;
  if (!digits(t, p, 4, year) || !expect(t, p, '-') || !digits(t, p, 2, month) ||
      !expect(t, p, '-') || !digits(t, p, 2, day))
    return fail(why, kForm);
  if (!(expect(t, p, 'T') || expect(t, p, 't') || expect(t, p, ' '))) return fail(why, kForm);
  if (!digits(t, p, 2, hour) || !expect(t, p, ':') || !digits(t, p, 2, minute))
    return fail(why, kForm);
  double frac = 0.0;
  if (expect(t, p, ':')) {
    if (!digits(t, p, 2, second)) return fail(why, kForm);
    if (expect(t, p, '.') || expect(t, p, ',')) {
      size_t start = p;
      while (p < t.size() && t[p] >= '0' && t[p] <= '9') ++p;
      if (p == start) return fail(why, kForm);
      // One correctly rounded conversion of "0.<digits>": summing digit * 0.1^k drifts
      // (".3" gave 0.30000000000000004), and format() must print back what was read.
      std::string digitsText = "0." + std::string(t.substr(start, p - start));
      std::from_chars(digitsText.data(), digitsText.data() + digitsText.size(), frac);
      // ".99999999999999999999" rounds to 1.0; keep the documented [0, 1).
      if (frac >= 1.0) frac = std::nextafter(1.0, 0.0);
    }
  }
  int offset = 0;
  if (expect(t, p, 'Z') || expect(t, p, 'z')) {
    offset = 0;
  } else if (p < t.size() && (t[p] == '+' || t[p] == '-')) {
    int sign = t[p] == '-' ? -1 : 1;
    ++p;
    int oh, om = 0;
    if (!digits(t, p, 2, oh)) return fail(why, kForm);
    if (expect(t, p, ':')) {
      if (!digits(t, p, 2, om)) return fail(why, kForm);
    } else if (p < t.size()) {
      if (!digits(t, p, 2, om)) return fail(why, kForm);
    }
    if (om > 59 || oh * 60 + om > 18 * 60)
      return fail(why, "time zone offset out of range (at most +-18:00)");
    offset = sign * (oh * 60 + om);
  } else {
    return fail(why, "missing time zone: add Z (UTC) or an offset such as +02:00");
  }
  if (p != t.size()) return fail(why, kForm);
  if (year < 1) return fail(why, "year out of range (0001 to 9999)");
  if (month < 1 || month > 12) return fail(why, "month out of range");
  if (day < 1 || day > daysInMonth(year, month)) return fail(why, "day out of range for the month");
  if (hour > 23 || minute > 59 || second > 59)
    return fail(why, "hour, minute or second out of range");

  IsoTime r;
  r.unixSeconds =
      daysFromCivil(year, static_cast<unsigned>(month), static_cast<unsigned>(day)) * 86400 +
      hour * 3600 + minute * 60 + second - offset * 60;
  // The zone can carry an instant written inside the years accepted outside them
  // (9999-12-31T23:59-18:00 is in the year 10000 UTC): UTC, which the ephemeris and every
  // report use, stays inside them too.
  const int64_t firstUtc = daysFromCivil(1, 1, 1) * 86400;
  const int64_t lastUtc = daysFromCivil(9999, 12, 31) * 86400 + 86399;
  if (r.unixSeconds < firstUtc || r.unixSeconds > lastUtc)
    return fail(why, "the instant in UTC is outside 0001-01-01T00:00:00Z to 9999-12-31T23:59:59Z");
  r.subsecond = frac;
  r.offsetMinutes = offset;
  return r;
}

std::string IsoTime::format() const {
  int64_t local = unixSeconds + offsetMinutes * 60;
  int64_t days = local >= 0 ? local / 86400 : (local - 86399) / 86400;
  int64_t secs = local - days * 86400;
  int y;
  unsigned m, d;
  civilFromDays(days, y, m, d);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%04d-%02u-%02uT%02d:%02d:%02d", y, m, d,
                static_cast<int>(secs / 3600), static_cast<int>(secs / 60 % 60),
                static_cast<int>(secs % 60));
  std::string s = buf;
  if (subsecond > 0.0) {
    // Shortest fixed-point text that reads back as the same double ("0.25" -> ".25").
    // A fixed 9 digits lost precision and printed 0.9999999999 as ".0".
    char f[400];
    auto [end, ec] = std::to_chars(f, f + sizeof f, subsecond, std::chars_format::fixed);
    if (ec == std::errc() && end - f > 2) s.append(f + 1, end);  // skip the leading '0'
  }
  if (offsetMinutes == 0) {
    s += "Z";
  } else {
    int o = offsetMinutes < 0 ? -offsetMinutes : offsetMinutes;
    std::snprintf(buf, sizeof buf, "%c%02d:%02d", offsetMinutes < 0 ? '-' : '+', o / 60, o % 60);
    s += buf;
  }
  return s;
}

double IsoTime::julianDateUtc() const {
  return 2440587.5 + (static_cast<double>(unixSeconds) + subsecond) / 86400.0;
}

IsoTime IsoTime::plusSeconds(double seconds) const {
  // Whole and fractional parts apart: a 64-bit second count plus a double fraction keeps
  // sub-microsecond steps exact over centuries, which one double of unix seconds does not.
  double whole = std::floor(seconds);
  double frac = subsecond + (seconds - whole);
  double carry = std::floor(frac);
  IsoTime r = *this;
  r.unixSeconds = unixSeconds + static_cast<int64_t>(whole) + static_cast<int64_t>(carry);
  r.subsecond = frac - carry;
  return r;
}

double IsoTime::secondsSince(const IsoTime& other) const {
  return static_cast<double>(unixSeconds - other.unixSeconds) + (subsecond - other.subsecond);
}

std::optional<double> parseDuration(std::string_view text, std::string* why) {
  auto failWith = [&](const char* reason) -> std::optional<double> {
    if (why) *why = reason;
    return std::nullopt;
  };
  constexpr const char* kForm = "expected a duration such as 15m, 1h30m, 90s, 2d or ISO 8601 PT15M";
  std::string_view t = text;
  double sign = 1.0;
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) {
    sign = t[0] == '-' ? -1.0 : 1.0;
    t.remove_prefix(1);
  }
  bool iso = !t.empty() && (t[0] == 'P' || t[0] == 'p');
  if (iso) t.remove_prefix(1);
  bool inTime = !iso;  // the short form has no date/time split; 'm' means minutes
  double total = 0.0;
  int parts = 0;
  // Each unit at most once and in order, so "1m1h" or "PT1M1M" are errors, not sums.
  int lastRank = -1;
  // ISO 8601 wants at least one time component after the 'T': "P1DT" is malformed.
  bool emptyTimePart = false;
  while (!t.empty()) {
    if (iso && (t[0] == 'T' || t[0] == 't')) {
      if (inTime) return failWith(kForm);
      inTime = true;
      emptyTimePart = true;
      t.remove_prefix(1);
      continue;
    }
    size_t n = 0;
    while (n < t.size() && ((t[n] >= '0' && t[n] <= '9') || t[n] == '.')) ++n;
    if (n == 0 || n == t.size()) return failWith(kForm);
    double value = 0.0;
    auto [end, ec] = std::from_chars(t.data(), t.data() + n, value);
    if (ec != std::errc() || end != t.data() + n) return failWith(kForm);
    char unit = static_cast<char>(t[n] | 0x20);  // lower case
    int rank;
    double seconds;
    if (unit == 'd' && !(iso && inTime)) {
      rank = 0, seconds = 86400.0;
    } else if (unit == 'h' && inTime) {
      rank = 1, seconds = 3600.0;
    } else if (unit == 'm' && inTime) {
      rank = 2, seconds = 60.0;
    } else if (unit == 's' && inTime) {
      rank = 3, seconds = 1.0;
    } else {
      return failWith(kForm);
    }
    if (rank <= lastRank) return failWith(kForm);
    lastRank = rank;
    total += value * seconds;
    ++parts;
    emptyTimePart = false;
    t.remove_prefix(n + 1);
  }
  if (parts == 0 || emptyTimePart) return failWith(kForm);
  return sign * total;
}

std::string formatDuration(double seconds) {
  std::string out = seconds < 0 ? "-" : "";
  double s = std::fabs(seconds);
  // Whole units only while they are exact; the remainder goes out as shortest-round-trip
  // seconds, so parseDuration(formatDuration(x)) == x.
  if (s == std::floor(s) && s < 9.0e15) {
    auto whole = static_cast<int64_t>(s);
    const std::pair<int64_t, char> units[] = {{86400, 'd'}, {3600, 'h'}, {60, 'm'}, {1, 's'}};
    for (auto [size, unit] : units) {
      if (whole >= size) {
        out += std::to_string(whole / size) + unit;
        whole %= size;
      }
    }
    return out == "" || out == "-" ? "0s" : out;
  }
  // Fixed notation needs room for every digit: 1e300 has 301 before the point and 1e-300
  // 300 after it (64 bytes used to fail and print garbage). Shortest fixed text of any
  // finite double is under 400 characters (at most 309 integer digits, or "0." + 323 zeros
  // + 17 significant digits), so to_chars cannot fail here.
  char buf[400];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, s, std::chars_format::fixed);
  (void)ec;
  return out + std::string(buf, end) + "s";
}

}  // namespace sky
