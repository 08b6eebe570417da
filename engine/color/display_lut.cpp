#include "engine/color/display_lut.h"

#include <algorithm>
#include <cmath>

#include "engine/color/ocio_output.h"

namespace sky {

float displayLutShaper(float linear) {
  const float l = std::log2(std::max(linear, std::exp2(DisplayLut::kMinLog2)));
  return std::clamp((l - DisplayLut::kMinLog2) / (DisplayLut::kMaxLog2 - DisplayLut::kMinLog2),
                    0.0f, 1.0f);
}

float displayLutUnshaper(float coordinate) {
  return std::exp2(DisplayLut::kMinLog2 +
                   coordinate * (DisplayLut::kMaxLog2 - DisplayLut::kMinLog2));
}

DisplayLut bakeDisplayLut(const OcioOutput& ocio, const std::string& display,
                          const std::string& view) {
  constexpr int n = DisplayLut::kSize;
  DisplayLut lut;
  lut.rgba.resize(static_cast<size_t>(n) * n * n * 4);
  // Texel centres sit at the grid points: coordinate i / (n - 1) (the sampler reads it at
  // (i + 0.5) / n, display_transform.comp maps one onto the other).
  std::vector<float> axis(n);
  for (int i = 0; i < n; ++i) axis[i] = displayLutUnshaper(static_cast<float>(i) / (n - 1));
  size_t k = 0;
  for (int b = 0; b < n; ++b)
    for (int g = 0; g < n; ++g)
      for (int r = 0; r < n; ++r) {
        lut.rgba[k++] = axis[r];
        lut.rgba[k++] = axis[g];
        lut.rgba[k++] = axis[b];
        lut.rgba[k++] = 1.0f;
      }
  ocio.toDisplay(lut.rgba, display, view, 0.0);
  return lut;
}

}  // namespace sky
