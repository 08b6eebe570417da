#pragma once
// Puts a frame on the screen: the rendered frame's 8-bit codes, which the renderer wrote into
// the window's frame image on the GPU (or which were uploaded, metered on the CPU), and a debug
// image blitted into the swapchain image, ImGui drawn over them in the swapchain's render pass, and
// the image presented. One frame in flight: a frame takes 100 ms or more to render on lavapipe
// and the renderer waits for its own work, so a second one would overlap nothing; one also
// lets the staging buffers be rewritten as soon as the last submit's fence has signalled.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "debug_panel.h"
#include "engine/gpu/buffer.h"
#include "engine/graph/frame_graph.h"

namespace sky {
class Context;
}

namespace sky::view {

class Swapchain;

// An RGBA8 image the window blits from, kept in TRANSFER_SRC_OPTIMAL between frames. The
// renderer's display pass writes the frame into it on the GPU (target(): the frame never comes
// back to the host); a frame metered on the CPU and the debug view's image are uploaded (set()).
class WindowImage {
public:
  WindowImage(const Context& ctx, std::string name);
  WindowImage(const WindowImage&) = delete;
  WindowImage& operator=(const WindowImage&) = delete;

  // The image at `width` x `height` for the renderer to write (RenderOptions::displayTarget,
  // in kLayout); made, cleared, when the size changes. The caller has waited for the last
  // frame, and calls filled() once a frame has written it.
  PersistentImage& target(uint32_t width, uint32_t height);
  void filled() { mFilled = true; }
  // Copies the pixels to the staging buffer (the caller has waited for the last frame); the
  // next record() uploads them.
  void set(const uint8_t* rgba, uint32_t width, uint32_t height);
  // Records the pending upload, if any, and the barrier that makes it readable by blits.
  void record(VkCommandBuffer cmd);
  // What the image holds, 8-bit RGBA codes, row 0 the top (dump-frame): a copy to the host,
  // waited for. The caller has waited for the last frame.
  std::vector<uint8_t> read() const;
  VkImage image() const { return mImage.image.image(); }
  uint32_t width() const { return mImage.image.desc().width; }
  uint32_t height() const { return mImage.image.desc().height; }
  bool valid() const { return mImage.image && mFilled; }

  static constexpr VkImageLayout kLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;

private:
  void ensure(uint32_t width, uint32_t height);

  const Context& mCtx;
  std::string mName;
  PersistentImage mImage;
  Buffer mStaging;
  bool mPending = false;
  bool mFilled = false;
};

enum class PresentStatus {
  Presented,
  Recreate,  // the swapchain is out of date or suboptimal: recreate it before the next frame
};

class Presenter {
public:
  Presenter(const Context& ctx, Swapchain& swapchain);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // The image the renderer draws the next frame into (width x height), once the last
  // present has finished with it; frameDrawn() once it has. Or the pixels to show from the
  // next present on (the frame metered on the CPU, the debug view's image).
  PersistentImage& frameTarget(uint32_t width, uint32_t height);
  void frameDrawn() { mFrame.filled(); }
  void setFrame(const uint8_t* rgba, uint32_t width, uint32_t height);
  void setTile(const uint8_t* rgba, uint32_t width, uint32_t height);
  // The frame's codes as the window shows them before scaling (dump-frame), and their size;
  // empty before the first frame.
  struct Codes {
    std::vector<uint8_t> rgba;
    uint32_t width = 0, height = 0;
  };
  Codes readFrame();

  // Acquires an image, clears it, blits the frame into `placement.frame` and the tile into
  // `placement.tile` (zero-sized: not drawn), records `drawUi` inside the render pass, submits
  // and presents.
  PresentStatus present(const DebugPlacement& placement,
                        const std::function<void(VkCommandBuffer)>& drawUi);
  // Waits for the last submitted frame (before touching what it reads).
  void waitForLastFrame();

private:
  void blit(VkCommandBuffer cmd, const WindowImage& from, const Rect& to, VkImage target);

  const Context& mCtx;
  Swapchain& mSwapchain;
  VkCommandPool mPool = VK_NULL_HANDLE;
  VkCommandBuffer mCmd = VK_NULL_HANDLE;
  VkFence mFence = VK_NULL_HANDLE;         // the last submit
  VkSemaphore mAcquired = VK_NULL_HANDLE;  // the acquired image may be written
  WindowImage mFrame;
  WindowImage mTile;
  VkFilter mFilter = VK_FILTER_NEAREST;
};

}  // namespace sky::view
