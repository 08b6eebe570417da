#pragma once
// How the apps show a frame-graph image (skyrender --debug-passes' contact sheet, skyview's
// debug view): each image as its pass asked (DebugView): colour exposed to its own
// brightness, scalars and step counts in false colour with their range, normals remapped,
// depth near-bright. A 3D image shows a few of its slices side by side.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/render/renderer.h"

namespace sky {

struct DisplayTile {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;  // 8-bit sRGB codes, row 0 the top
  // For false colour (Scalar, Heat, Depth): the values at the two ends of the colour ramp,
  // and the unit ("m" for depth); `legend` false otherwise.
  bool legend = false;
  float low = 0.0f, high = 0.0f;
  const char* unit = "";
};

// `maxSlices` of a 3D image, evenly spaced, side by side (all of them when it has fewer).
DisplayTile debugDisplay(const DebugImage& image, uint32_t maxSlices = 4);

// The false-colour ramp the Scalar, Heat and Depth views use (t in 0..1): dark blue through
// green to yellow-white, monotonic in lightness so it reads in greyscale too.
void falseColour(float t, uint8_t rgb[3]);

// A name as the view kinds are written in lists and docs: colour, scalar, normals, depth,
// heat.
const char* debugViewName(DebugView view);

}  // namespace sky
