#pragma once
// skyview's debug view: the frame graph's images by name (RenderedFrame::images, the one
// registry; docs/debug-view.md), one of them read back with each frame and shown beside the
// frame or over the whole window, with a caption. Tab steps through the images, V switches
// side by side / full screen, Shift+Tab hides. Plain data and arithmetic: the viewer asks for
// wanted() with its next frame and hands the result to setTile(); the presenter blits.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/render/renderer.h"

namespace sky::view {

struct DebugTile {
  std::string caption;
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4 codes, row 0 the top
};

enum class DebugLayout { Hidden, SideBySide, FullScreen };

// A rectangle in window pixels.
struct Rect {
  int32_t x = 0, y = 0;
  uint32_t width = 0, height = 0;
  bool operator==(const Rect&) const = default;
};

// Where the frame and the tile go; a zero-sized rect is not drawn.
struct DebugPlacement {
  Rect frame;
  Rect tile;
};

class DebugPanel {
public:
  // The images of the frame just rendered. Keeps the selection by name; when that image is
  // gone (the scene changed), selects the first and drops the tile. Returns whether wanted()
  // changed, so the viewer renders again to fetch it.
  bool setImages(const std::vector<DebugImageInfo>& images);
  // The image the next frame should read back: the selection, while the view is shown.
  std::optional<std::string> wanted() const;
  // The selection as read back with the last frame (apps/common/debug_view's picture).
  void setTile(DebugTile tile);
  // Tab: the next image, showing the view side by side if it was hidden. Returns the status.
  std::string next();
  // V: side by side <-> full screen (shows the view if hidden). Returns the status line.
  std::string toggleLayout();
  // Shift+Tab: hides the view.
  void hide();

  DebugLayout layout() const { return current() ? mLayout : DebugLayout::Hidden; }
  // The image on screen, nullptr when hidden or not read back yet.
  const DebugTile* current() const;
  // Bumped whenever the image on screen changes, so the presenter uploads it once.
  uint64_t revision() const { return mRevision; }
  // "no debug resources", or "<name> (i/n, side by side)".
  std::string status() const;

  // Places a frame of frameW x frameH and the current tile (if shown) in a window of
  // windowW x windowH: each fitted inside its area with its aspect kept, centred.
  DebugPlacement place(uint32_t windowW, uint32_t windowH, uint32_t frameW, uint32_t frameH) const;

private:
  std::vector<DebugImageInfo> mImages;
  size_t mIndex = 0;
  DebugLayout mLayout = DebugLayout::Hidden;
  std::optional<DebugTile> mTile;  // of mImages[mIndex], once read back
  uint64_t mRevision = 0;
};

// `w` x `h` fitted (aspect kept, centred) inside `area`; zero-sized when either is empty.
Rect fitInside(const Rect& area, uint32_t w, uint32_t h);

}  // namespace sky::view
