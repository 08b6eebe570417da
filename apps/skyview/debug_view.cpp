#include "debug_view.h"

#include <algorithm>
#include <cmath>

namespace sky::view {

void DebugView::setImages(std::vector<DebugTile> tiles) {
  mTiles = std::move(tiles);
  if (mIndex >= mTiles.size()) mIndex = 0;
  ++mRevision;
}

std::string DebugView::next() {
  if (mTiles.empty()) return status();
  if (mLayout == DebugLayout::Hidden)
    mLayout = DebugLayout::SideBySide;
  else
    mIndex = (mIndex + 1) % mTiles.size();
  ++mRevision;
  return status();
}

std::string DebugView::toggleLayout() {
  if (mTiles.empty()) return status();
  mLayout = mLayout == DebugLayout::SideBySide ? DebugLayout::FullScreen : DebugLayout::SideBySide;
  ++mRevision;
  return status();
}

const DebugTile* DebugView::current() const {
  if (mLayout == DebugLayout::Hidden || mTiles.empty()) return nullptr;
  return &mTiles[mIndex];
}

std::string DebugView::status() const {
  if (mTiles.empty()) return "no debug resources";
  const DebugTile& t = mTiles[mIndex];
  std::string where = mLayout == DebugLayout::Hidden       ? "hidden"
                      : mLayout == DebugLayout::SideBySide ? "side by side"
                                                           : "full screen";
  return t.caption + " (" + std::to_string(mIndex + 1) + "/" + std::to_string(mTiles.size()) +
         ", " + std::to_string(t.width) + "x" + std::to_string(t.height) + ", " + where + ")";
}

Rect fitInside(const Rect& area, uint32_t w, uint32_t h) {
  if (area.width == 0 || area.height == 0 || w == 0 || h == 0) return {area.x, area.y, 0, 0};
  // The larger scale that still fits both sides; rounding keeps at least one pixel.
  const double scale =
      std::min(static_cast<double>(area.width) / w, static_cast<double>(area.height) / h);
  const uint32_t fw =
      std::clamp<uint32_t>(static_cast<uint32_t>(std::lround(w * scale)), 1, area.width);
  const uint32_t fh =
      std::clamp<uint32_t>(static_cast<uint32_t>(std::lround(h * scale)), 1, area.height);
  return {area.x + static_cast<int32_t>((area.width - fw) / 2),
          area.y + static_cast<int32_t>((area.height - fh) / 2), fw, fh};
}

DebugPlacement DebugView::place(uint32_t windowW, uint32_t windowH, uint32_t frameW,
                                uint32_t frameH) const {
  const Rect window{0, 0, windowW, windowH};
  const DebugTile* tile = current();
  if (!tile) return {fitInside(window, frameW, frameH), {}};
  if (mLayout == DebugLayout::FullScreen) return {{}, fitInside(window, tile->width, tile->height)};
  const uint32_t left = windowW / 2;
  return {fitInside({0, 0, left, windowH}, frameW, frameH),
          fitInside({static_cast<int32_t>(left), 0, windowW - left, windowH}, tile->width,
                    tile->height)};
}

}  // namespace sky::view
