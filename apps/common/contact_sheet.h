#pragma once
// skyrender --debug-passes: every image of a frame on one labelled sheet. One tile per image,
// shown as its pass asked (debug_view.h), with its name, size, the pass that wrote it and that
// pass's GPU time, and for false colour the range its ramp spans.
#include <string>
#include <vector>

#include "apps/common/debug_view.h"

namespace sky {

// The sheet, `columns` tiles across, under a heading line (the scene, the time, the device).
DisplayTile contactSheet(const std::vector<DebugImage>& images, const std::string& heading,
                         uint32_t columns = 4);

// Draws `text` (ASCII) into `image` with its top-left corner at (x, y), each font pixel
// `scale` pixels square, clipped to the image.
void drawText(DisplayTile& image, int x, int y, const std::string& text, const uint8_t rgb[3],
              int scale = 1);
// The width and height `text` takes at `scale`.
int textWidth(const std::string& text, int scale = 1);
int textHeight(int scale = 1);

}  // namespace sky
