#include "engine/weather/weather_fields.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "engine/core/error.h"

namespace sky {

const char* fieldName(FieldKind kind) {
  switch (kind) {
    case FieldKind::RelativeHumidity: return "r";
    case FieldKind::GeopotentialHeight: return "gh";
    case FieldKind::Temperature: return "t";
    case FieldKind::CloudCoverLow: return "tcc_low";
    case FieldKind::CloudCoverMid: return "tcc_mid";
    case FieldKind::CloudCoverHigh: return "tcc_high";
    case FieldKind::WindU: return "u";
    case FieldKind::WindV: return "v";
  }
  internalError("no field kind " + std::to_string(int(kind)));
}

const LevelField* WeatherStep::find(FieldKind kind, double pressureHpa) const {
  for (const LevelField& f : fields)
    if (f.kind == kind && std::fabs(f.pressureHpa - pressureHpa) < 0.01) return &f;
  return nullptr;
}

std::vector<double> WeatherStep::levels(FieldKind kind) const {
  std::vector<double> out;
  for (const LevelField& f : fields)
    if (f.kind == kind && f.pressureHpa > 0.0) out.push_back(f.pressureHpa);
  std::sort(out.begin(), out.end(), std::greater<double>());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace sky
