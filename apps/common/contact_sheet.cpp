#include "apps/common/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace sky {
namespace {

constexpr int kCellWidth = 384;    // a tile's width, its label's too
constexpr int kImageHeight = 216;  // the room an image has in its tile (16:9 of the width)
constexpr int kPad = 8;
constexpr uint8_t kBackground[3] = {28, 28, 30};
constexpr uint8_t kText[3] = {232, 232, 232};
constexpr uint8_t kDim[3] = {160, 160, 166};

// "1.23e+04" for big or small numbers, "0.125" otherwise.
std::string number(float v) {
  char s[32];
  const float a = std::abs(v);
  std::snprintf(s, sizeof s, (a != 0.0f && (a < 1e-2f || a >= 1e5f)) ? "%.3g" : "%.4g", double(v));
  return s;
}

void fill(DisplayTile& image, int x0, int y0, int x1, int y1, const uint8_t rgb[3]) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, static_cast<int>(image.width));
  y1 = std::min(y1, static_cast<int>(image.height));
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      uint8_t* px = &image.rgba[(size_t(y) * image.width + size_t(x)) * 4];
      px[0] = rgb[0];
      px[1] = rgb[1];
      px[2] = rgb[2];
      px[3] = 255;
    }
}

// `tile` scaled to fit w x h (box-filtered when it shrinks), its top-left at (x, y).
void blitFit(DisplayTile& sheet, const DisplayTile& tile, int x, int y, int w, int h) {
  if (tile.width == 0 || tile.height == 0) return;
  const double scale = std::min(double(w) / tile.width, double(h) / tile.height);
  const int dw = std::max(1, static_cast<int>(tile.width * scale));
  const int dh = std::max(1, static_cast<int>(tile.height * scale));
  for (int dy = 0; dy < dh; ++dy)
    for (int dx = 0; dx < dw; ++dx) {
      // The source texels under this pixel, averaged.
      const uint32_t sx0 = static_cast<uint32_t>(dx / scale),
                     sy0 = static_cast<uint32_t>(dy / scale);
      const uint32_t sx1 =
          std::max(sx0 + 1, std::min(tile.width, static_cast<uint32_t>((dx + 1) / scale)));
      const uint32_t sy1 =
          std::max(sy0 + 1, std::min(tile.height, static_cast<uint32_t>((dy + 1) / scale)));
      uint32_t sum[3] = {0, 0, 0}, n = 0;
      for (uint32_t sy = sy0; sy < sy1 && sy < tile.height; ++sy)
        for (uint32_t sx = sx0; sx < sx1 && sx < tile.width; ++sx, ++n)
          for (int c = 0; c < 3; ++c)
            sum[c] += tile.rgba[(size_t(sy) * tile.width + sx) * 4 + size_t(c)];
      const uint8_t rgb[3] = {static_cast<uint8_t>(sum[0] / std::max(n, 1u)),
                              static_cast<uint8_t>(sum[1] / std::max(n, 1u)),
                              static_cast<uint8_t>(sum[2] / std::max(n, 1u))};
      fill(sheet, x + dx, y + dy, x + dx + 1, y + dy + 1, rgb);
    }
}

}  // namespace

int textWidth(const std::string& text, int scale) {
  std::string t = text;
  return stb_easy_font_width(t.data()) * scale;
}

int textHeight(int scale) {
  return 10 * scale;
}

void drawText(DisplayTile& image, int x, int y, const std::string& text, const uint8_t rgb[3],
              int scale) {
  std::string t = text;
  // stb_easy_font: 4 vertices of 16 bytes (x, y, z, colour) per quad, about 30 quads a glyph.
  std::vector<char> buffer(t.size() * 30 * 64 + 64);
  unsigned char colour[4] = {rgb[0], rgb[1], rgb[2], 255};
  const int quads = stb_easy_font_print(0.0f, 0.0f, t.data(), colour, buffer.data(),
                                        static_cast<int>(buffer.size()));
  for (int q = 0; q < quads; ++q) {
    const float* v0 = reinterpret_cast<const float*>(buffer.data() + q * 64);
    const float* v2 = reinterpret_cast<const float*>(buffer.data() + q * 64 + 32);
    fill(image, x + static_cast<int>(v0[0]) * scale, y + static_cast<int>(v0[1]) * scale,
         x + static_cast<int>(v2[0]) * scale, y + static_cast<int>(v2[1]) * scale, rgb);
  }
}

DisplayTile contactSheet(const std::vector<DebugImage>& images, const std::string& heading,
                         uint32_t columns) {
  columns = std::max(1u, std::min<uint32_t>(columns, static_cast<uint32_t>(images.size())));
  const int labelHeight = textHeight(2) + 2 * textHeight(1) + kPad;
  const int legendHeight = 10 + textHeight(1);
  const int cellHeight = labelHeight + kImageHeight + legendHeight + kPad;
  const int headingHeight = textHeight(2) + 2 * kPad;
  const uint32_t rows = (static_cast<uint32_t>(images.size()) + columns - 1) / columns;
  DisplayTile sheet;
  sheet.width = columns * (kCellWidth + kPad) + kPad;
  sheet.height =
      static_cast<uint32_t>(headingHeight) + rows * static_cast<uint32_t>(cellHeight + kPad);
  sheet.rgba.resize(size_t(sheet.width) * sheet.height * 4);
  fill(sheet, 0, 0, static_cast<int>(sheet.width), static_cast<int>(sheet.height), kBackground);
  drawText(sheet, kPad, kPad, heading, kText, 2);

  for (size_t i = 0; i < images.size(); ++i) {
    const DebugImage& image = images[i];
    const DebugImageInfo& info = image.info;
    const int x = kPad + static_cast<int>(i % columns) * (kCellWidth + kPad);
    int y = headingHeight + static_cast<int>(i / columns) * (cellHeight + kPad);
    drawText(sheet, x, y, info.name, kText, 2);
    y += textHeight(2);
    std::string size = std::to_string(info.width) + "x" + std::to_string(info.height);
    if (info.depth > 1) size += "x" + std::to_string(info.depth);
    char ms[32];
    std::snprintf(ms, sizeof ms, ", %.2f ms", image.gpuMs);
    drawText(sheet, x, y,
             size + "  " +
                 (info.pass.empty() ? std::string("imported (not written this frame)")
                                    : "by " + info.pass + ms),
             kDim);
    y += textHeight(1);
    drawText(
        sheet, x, y,
        std::string(debugViewName(info.view)) + (info.depth > 1 ? ", slices side by side" : ""),
        kDim);
    y += textHeight(1) + kPad / 2;
    const DisplayTile tile = debugDisplay(image);
    blitFit(sheet, tile, x, y, kCellWidth, kImageHeight);
    y += kImageHeight + 4;
    if (tile.legend) {
      // The ramp, with the values at its two ends.
      const bool nearBright = info.view == DebugView::Depth;
      for (int k = 0; k < kCellWidth; ++k) {
        uint8_t rgb[3];
        const float t = float(k) / float(kCellWidth - 1);
        falseColour(nearBright ? 1.0f - t : t, rgb);
        fill(sheet, x + k, y, x + k + 1, y + 6, rgb);
      }
      const std::string lo = number(tile.low) + std::string(tile.unit);
      const std::string hi = number(tile.high) + std::string(tile.unit);
      drawText(sheet, x, y + 8, lo, kText);
      drawText(sheet, x + kCellWidth - textWidth(hi), y + 8, hi, kText);
    }
  }
  return sheet;
}

}  // namespace sky
