#pragma once
// An OCIO display/view baked into a 3D table for the GPU display path
// (passes/display_transform): the exposed scene-linear value of each channel through a log2
// shaper onto [0, 1], DisplayLut::kSize points a side. The CPU path (OcioOutput::toDisplay)
// stays exact; the table serves a viewer or a benchmark frame, whose display transform would
// otherwise cost a quarter of a second a frame on two cores at 1280 x 720.
#include <string>
#include <vector>

namespace sky {

class OcioOutput;

struct DisplayLut {
  static constexpr int kSize = 64;
  // The shaper's range, stops of the renderer's units (1 = 10^4 cd/m^2) after the exposure:
  // 2^-20 is black on any view, 2^8 past the brightest highlight a view keeps.
  static constexpr float kMinLog2 = -20.0f;
  static constexpr float kMaxLog2 = 8.0f;
  std::vector<float> rgba;  // kSize^3 texels, red fastest, then green, then blue; alpha 1
};

// The shaper coordinate (0..1) of an exposed scene-linear value, and back.
float displayLutShaper(float linear);
float displayLutUnshaper(float coordinate);

// Bakes `view` of `display` (validated by OcioOutput) without exposure: the GPU applies the
// exposure before the table.
DisplayLut bakeDisplayLut(const OcioOutput& ocio, const std::string& display,
                          const std::string& view);

}  // namespace sky
