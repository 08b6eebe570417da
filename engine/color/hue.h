#pragma once
// Hue, measured two ways: the HSV hue of an RGB triple (what a colour picker says of a
// display pixel, the number users quote: "the lit clouds have a display hue of 38°"), and the
// OKLab hue (Ottosson 2020), which follows perceived hue closely enough that the hue a display
// transform shifts can be compared across lightness. And the sweep that says how far a view
// of an OCIO config moves the hue of saturated scene colours (docs/outputs.md, "Views").
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace sky {

class OcioOutput;

// HSV hue in degrees, [0, 360), of any RGB triple (linear or encoded); 0 for a grey.
double hsvHueDeg(const glm::dvec3& rgb);
// HSV saturation, (max - min) / max; 0 for black.
double hsvSaturation(const glm::dvec3& rgb);

// OKLab (L, a, b) of a linear Rec.709 (sRGB primaries, D65) colour.
glm::dvec3 oklabFromLinearRec709(const glm::dvec3& rgb);
// OKLab hue in degrees, [0, 360), and chroma sqrt(a^2 + b^2).
double oklabHueDeg(const glm::dvec3& lab);
double oklabChroma(const glm::dvec3& lab);
// b - a wrapped into (-180, 180].
double hueDifferenceDeg(double a, double b);

// IEC 61966-2-1: the sRGB encoding's inverse, for reading a display's code values as light.
double srgbDecode(double code);

struct HueSweepResult {
  std::string view;
  // Over every swept colour whose display chroma is still a hue (OKLab chroma >= 0.02): the
  // mean and the largest |display hue - scene hue|, OKLab degrees.
  double meanShiftDeg = 0.0;
  double maxShiftDeg = 0.0;
  // The same over the oranges and reds of a low sun's light (scene HSV hue 10..45°), signed:
  // > 0 turns them toward yellow.
  double orangeMeanShiftDeg = 0.0;
  int samples = 0;  // colours that kept a hue
};

// Sweeps scene colours of HSV saturation 0.6 and 0.9 around the hue circle (every 10°) at 9
// exposures (luminance 0.18 x 2^-4 .. 2^4), through `view` of `display` with OCIO's CPU
// processor, and compares each colour's OKLab hue in the scene with the display's (its codes
// decoded as sRGB).
HueSweepResult measureHueSweep(const OcioOutput& ocio, const std::string& display,
                               const std::string& view);

}  // namespace sky
