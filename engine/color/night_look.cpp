#include "engine/color/night_look.h"

#include <algorithm>
#include <cmath>

namespace sky {
namespace {

constexpr double kCdPerUnit = 1.0e4;     // renderer radiance unit (docs/lighting.md)
constexpr double kScotopicLimit = 0.01;  // cd/m^2: below, rods alone
constexpr double kPhotopicLimit = 3.0;   // cd/m^2: above, cones alone
// Larson's scotopic luminance of D65 white per unit of its photopic luminance:
// 1.33 (1 + (1 + 1.0889) / 0.9505) - 1.68.
constexpr double kWhiteScotopic = 1.33 * (1.0 + (1.0 + 1.0889) / 0.9505) - 1.68;

// The rods' blue grey: chromaticity (0.28, 0.29) at unit luminance, in linear Rec.709.
struct Tint {
  double r, g, b;
};
Tint rodTint() {
  const double x = 0.28, y = 0.29;
  const double X = x / y, Y = 1.0, Z = (1.0 - x - y) / y;
  return {3.2406 * X - 1.5372 * Y - 0.4986 * Z, -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
          0.0557 * X - 0.2040 * Y + 1.0570 * Z};
}

}  // namespace

double photopicShare(double cdPerM2) {
  if (!(cdPerM2 > kScotopicLimit)) return 0.0;
  if (cdPerM2 >= kPhotopicLimit) return 1.0;
  const double t = std::log(cdPerM2 / kScotopicLimit) / std::log(kPhotopicLimit / kScotopicLimit);
  return t * t * (3.0 - 2.0 * t);
}

void applyNightLook(std::vector<float>& rgba) {
  static const Tint tint = rodTint();
  for (size_t i = 0; i + 3 < rgba.size(); i += 4) {
    const double r = std::max(0.0f, rgba[i]), g = std::max(0.0f, rgba[i + 1]),
                 b = std::max(0.0f, rgba[i + 2]);
    // Linear Rec.709 to CIE XYZ (D65).
    const double X = 0.4124 * r + 0.3576 * g + 0.1805 * b;
    const double Y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    const double Z = 0.0193 * r + 0.1192 * g + 0.9505 * b;
    const double w = photopicShare(Y * kCdPerUnit);
    if (w >= 1.0) continue;
    // Scaled so that white keeps its luminance: blues come out brighter, reds darker.
    const double V =
        X > 0.0 ? std::max(Y * (1.33 * (1.0 + (Y + Z) / X) - 1.68), 0.0) / kWhiteScotopic : 0.0;
    rgba[i] = static_cast<float>(w * r + (1.0 - w) * V * tint.r);
    rgba[i + 1] = static_cast<float>(w * g + (1.0 - w) * V * tint.g);
    rgba[i + 2] = static_cast<float>(w * b + (1.0 - w) * V * tint.b);
  }
}

}  // namespace sky
