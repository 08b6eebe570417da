#include "engine/color/hue.h"

#include <algorithm>
#include <cmath>

#include "engine/color/ocio_output.h"

namespace sky {

double hsvHueDeg(const glm::dvec3& c) {
  const double hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b});
  const double d = hi - lo;
  if (!(d > 0.0)) return 0.0;
  double h;
  if (hi == c.r)
    h = (c.g - c.b) / d;
  else if (hi == c.g)
    h = 2.0 + (c.b - c.r) / d;
  else
    h = 4.0 + (c.r - c.g) / d;
  h *= 60.0;
  return h < 0.0 ? h + 360.0 : h;
}

double hsvSaturation(const glm::dvec3& c) {
  const double hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b});
  return hi > 0.0 ? (hi - lo) / hi : 0.0;
}

glm::dvec3 oklabFromLinearRec709(const glm::dvec3& c) {
  // Ottosson, "A perceptual color space for image processing" (2020): linear sRGB to LMS,
  // cube root, then to Lab.
  const double l = 0.4122214708 * c.r + 0.5363325363 * c.g + 0.0514459929 * c.b;
  const double m = 0.2119034982 * c.r + 0.6806995451 * c.g + 0.1073969566 * c.b;
  const double s = 0.0883024619 * c.r + 0.2817188376 * c.g + 0.6299787005 * c.b;
  const double l3 = std::cbrt(l), m3 = std::cbrt(m), s3 = std::cbrt(s);
  return {0.2104542553 * l3 + 0.7936177850 * m3 - 0.0040720468 * s3,
          1.9779984951 * l3 - 2.4285922050 * m3 + 0.4505937099 * s3,
          0.0259040371 * l3 + 0.7827717662 * m3 - 0.8086757660 * s3};
}

double oklabHueDeg(const glm::dvec3& lab) {
  const double h = std::atan2(lab.z, lab.y) * 180.0 / M_PI;
  return h < 0.0 ? h + 360.0 : h;
}

double oklabChroma(const glm::dvec3& lab) { return std::hypot(lab.y, lab.z); }

double hueDifferenceDeg(double a, double b) {
  double d = std::fmod(b - a, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return d;
}

double srgbDecode(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

HueSweepResult measureHueSweep(const OcioOutput& ocio, const std::string& display,
                               const std::string& view) {
  // HSV in linear light: value 1 at hue h and saturation s, scaled to luminance 0.18 x 2^e.
  std::vector<glm::dvec3> scene;
  for (double sat : {0.6, 0.9})
    for (int h = 0; h < 360; h += 10)
      for (int e = -4; e <= 4; ++e) {
        const double hh = h / 60.0;
        const double x = 1.0 - std::abs(std::fmod(hh, 2.0) - 1.0);
        glm::dvec3 c;
        switch (int(hh)) {
          case 0: c = {1, x, 0}; break;
          case 1: c = {x, 1, 0}; break;
          case 2: c = {0, 1, x}; break;
          case 3: c = {0, x, 1}; break;
          case 4: c = {x, 0, 1}; break;
          default: c = {1, 0, x}; break;
        }
        c = glm::dvec3(1.0 - sat) + sat * c;
        const double y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
        scene.push_back(c * (0.18 * std::exp2(double(e)) / y));
      }
  std::vector<float> rgba;
  rgba.reserve(scene.size() * 4);
  for (const glm::dvec3& c : scene) rgba.insert(rgba.end(), {float(c.r), float(c.g), float(c.b), 1.0f});
  ocio.toDisplay(rgba, display, view, 0.0);

  HueSweepResult r;
  r.view = view;
  double sum = 0.0, orangeSum = 0.0;
  int orange = 0;
  for (size_t i = 0; i < scene.size(); ++i) {
    const glm::dvec3 shown(srgbDecode(rgba[i * 4]), srgbDecode(rgba[i * 4 + 1]),
                           srgbDecode(rgba[i * 4 + 2]));
    const glm::dvec3 labShown = oklabFromLinearRec709(shown);
    if (oklabChroma(labShown) < 0.02) continue;  // gone to white or black: no hue to shift
    const double d = hueDifferenceDeg(oklabHueDeg(oklabFromLinearRec709(scene[i])),
                                      oklabHueDeg(labShown));
    sum += std::abs(d);
    r.maxShiftDeg = std::max(r.maxShiftDeg, std::abs(d));
    ++r.samples;
    const double hsv = hsvHueDeg(scene[i]);
    if (hsv >= 10.0 && hsv <= 45.0) {
      orangeSum += d;
      ++orange;
    }
  }
  r.meanShiftDeg = r.samples ? sum / r.samples : 0.0;
  r.orangeMeanShiftDeg = orange ? orangeSum / orange : 0.0;
  return r;
}

}  // namespace sky
