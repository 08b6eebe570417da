#include "engine/weather/field_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "engine/core/error.h"
#include "engine/core/warnings.h"

namespace sky {
namespace {

// Fractions within this of [0, 1] are rounding (100.5 % in GFS), clamped without a word.
constexpr double kRangeSlack = 0.01;

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

double normaliseLon(double lon) {
  if (lon >= -180.0 && lon < 360.0) return lon;
  return lon - 360.0 * std::floor((lon + 180.0) / 360.0);  // into [-180, 180)
}

bool isRegularGrid(const GridGeometry& g) {
  if (g.nx < 2 && g.ny < 2) return false;
  auto monotonic = [](auto at, size_t n) {
    int sign = 0;
    for (size_t i = 1; i < n; ++i) {
      const double d = at(i) - at(i - 1);
      const int s = d > 0 ? 1 : d < 0 ? -1 : 0;
      if (s == 0 || (sign != 0 && s != sign)) return false;
      sign = s;
    }
    return true;
  };
  for (size_t j = 0; j < g.ny; ++j)
    for (size_t i = 0; i < g.nx; ++i) {
      const size_t k = j * g.nx + i;
      if (g.latDeg[k] != g.latDeg[j * g.nx] || g.lonDeg[k] != g.lonDeg[i]) return false;
    }
  return monotonic([&](size_t j) { return g.latDeg[j * g.nx]; }, g.ny) &&
         monotonic([&](size_t i) { return g.lonDeg[i]; }, g.nx);
}

void FieldChecks::toFraction(std::vector<float>& values, double scale, const std::string& name) {
  for (float& v : values) {
    if (std::isnan(v)) continue;
    const double f = double(v) * scale;
    if (f < -kRangeSlack || f > 1.0 + kRangeSlack) {
      Range& r = mRanges[name];
      if (r.count == 0) r.lo = r.hi = f;
      ++r.count;
      r.lo = std::min(r.lo, f);
      r.hi = std::max(r.hi, f);
    }
    v = float(std::clamp(f, 0.0, 1.0));
  }
}

void FieldChecks::noteNonFinite(const std::string& name, size_t count, size_t total) {
  NonFinite& n = mNonFinite[name];
  n.count += count;
  n.total += total;
}

void FieldChecks::finish(const WeatherFields& fields) const {
  // A field with no usable value anywhere: the layers it feeds would be garbage (tops below
  // bases from a NaN gh, no cover from a NaN scale_factor).
  std::map<FieldKind, std::pair<size_t, bool>> seen;  // kind -> (fields, any finite)
  for (const WeatherStep& step : fields.steps)
    for (const LevelField& f : step.fields) {
      auto& [count, finite] = seen[f.kind];
      ++count;
      finite = finite || std::any_of(f.values.begin(), f.values.end(),
                                     [](float v) { return std::isfinite(v); });
    }
  for (const auto& [kind, info] : seen)
    if (!info.second)
      inputError(mFile + ": " + fieldName(kind) + ": no finite value in any of its " +
                 std::to_string(info.first) + (info.first == 1 ? " field" : " fields") +
                 " (every value missing, NaN or infinite): the field is unusable");
  for (const auto& [name, n] : mNonFinite)
    if (n.count > 0)
      warn(mFile + ": " + std::to_string(n.count) + " of " + std::to_string(n.total) +
           " values of " + name + " decoded to NaN or infinity; taken as missing");
  for (const auto& [name, r] : mRanges)
    warn(mFile + ": " + std::to_string(r.count) + " values of " + name +
         " outside [0, 1] by more than 1 % (" + number(r.lo) + " to " + number(r.hi) +
         "), clamped");
}

}  // namespace sky
