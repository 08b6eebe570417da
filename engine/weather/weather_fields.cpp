#include "engine/weather/weather_fields.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace sky {

const LevelField* WeatherStep::find(const std::string& name, double pressureHpa) const {
  for (const LevelField& f : fields)
    if (f.name == name && std::fabs(f.pressureHpa - pressureHpa) < 0.01) return &f;
  return nullptr;
}

std::vector<double> WeatherStep::levels(const std::string& name) const {
  std::vector<double> out;
  for (const LevelField& f : fields)
    if (f.name == name && f.pressureHpa > 0.0) out.push_back(f.pressureHpa);
  std::sort(out.begin(), out.end(), std::greater<double>());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace sky
