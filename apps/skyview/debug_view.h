#pragma once
// The debug view's presentation: a list of 8-bit images (frame-graph resources, once the
// registry feeds them) shown beside the frame or over the whole window, with a caption.
// Tab steps through the images, V switches side by side / full screen, Shift+Tab hides.
// Plain data and arithmetic only: the presenter uploads and blits what this says.
#include <cstdint>
#include <string>
#include <vector>

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

class DebugView {
public:
  // Replaces the images (any time between frames); keeps the selection when it is still in range.
  void setImages(std::vector<DebugTile> tiles);
  // Tab: the next image, showing the view side by side if it was hidden. Returns the status line.
  std::string next();
  // V: side by side <-> full screen (shows the view if hidden). Returns the status line.
  std::string toggleLayout();
  // Shift+Tab: hides the view.
  void hide() { mLayout = DebugLayout::Hidden; }

  DebugLayout layout() const { return current() ? mLayout : DebugLayout::Hidden; }
  // The image on screen, nullptr when hidden or there is none.
  const DebugTile* current() const;
  // Bumped whenever the image on screen changes, so the presenter uploads it once.
  uint64_t revision() const { return mRevision; }
  // "no debug resources", or "<caption> (i/n, side by side)".
  std::string status() const;

  // Places a frame of frameW x frameH and the current tile (if shown) in a window of
  // windowW x windowH: each fitted inside its area with its aspect kept, centred.
  DebugPlacement place(uint32_t windowW, uint32_t windowH, uint32_t frameW, uint32_t frameH) const;

private:
  std::vector<DebugTile> mTiles;
  size_t mIndex = 0;
  DebugLayout mLayout = DebugLayout::Hidden;
  uint64_t mRevision = 0;
};

// `w` x `h` fitted (aspect kept, centred) inside `area`; zero-sized when either is empty.
Rect fitInside(const Rect& area, uint32_t w, uint32_t h);

}  // namespace sky::view
