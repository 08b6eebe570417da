#include "debug_panel.h"

#include <algorithm>
#include <cmath>

namespace sky::view {

bool DebugPanel::setImages(const std::vector<DebugImageInfo>& images) {
  const std::optional<std::string> before = wanted();
  const std::string selected = mIndex < mImages.size() ? mImages[mIndex].name : std::string();
  mImages = images;
  const auto it = std::find_if(mImages.begin(), mImages.end(),
                               [&](const DebugImageInfo& i) { return i.name == selected; });
  if (it != mImages.end()) {
    mIndex = static_cast<size_t>(it - mImages.begin());
  } else {
    mIndex = 0;
    if (mTile) {
      mTile.reset();
      ++mRevision;
    }
  }
  return wanted() != before;
}

std::optional<std::string> DebugPanel::wanted() const {
  if (mLayout == DebugLayout::Hidden || mIndex >= mImages.size()) return std::nullopt;
  return mImages[mIndex].name;
}

void DebugPanel::setTile(DebugTile tile) {
  mTile = std::move(tile);
  ++mRevision;
}

std::string DebugPanel::next() {
  if (mImages.empty()) return status();
  if (mLayout == DebugLayout::Hidden)
    mLayout = DebugLayout::SideBySide;
  else
    mIndex = (mIndex + 1) % mImages.size();
  mTile.reset();  // the next frame reads the new selection back
  ++mRevision;
  return status();
}

std::string DebugPanel::toggleLayout() {
  if (mImages.empty()) return status();
  mLayout = mLayout == DebugLayout::SideBySide ? DebugLayout::FullScreen : DebugLayout::SideBySide;
  ++mRevision;
  return status();
}

void DebugPanel::hide() {
  mLayout = DebugLayout::Hidden;
  mTile.reset();
  ++mRevision;
}

const DebugTile* DebugPanel::current() const {
  if (mLayout == DebugLayout::Hidden || !mTile) return nullptr;
  return &*mTile;
}

std::string DebugPanel::status() const {
  if (mImages.empty()) return "no debug resources";
  const DebugImageInfo& i = mImages[mIndex];
  std::string where = mLayout == DebugLayout::Hidden       ? "hidden"
                      : mLayout == DebugLayout::SideBySide ? "side by side"
                                                           : "full screen";
  std::string size = std::to_string(i.width) + "x" + std::to_string(i.height);
  if (i.depth > 1) size += "x" + std::to_string(i.depth);
  return i.name + " (" + std::to_string(mIndex + 1) + "/" + std::to_string(mImages.size()) +
         ", " + size + ", " + where + ")";
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

DebugPlacement DebugPanel::place(uint32_t windowW, uint32_t windowH, uint32_t frameW,
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
