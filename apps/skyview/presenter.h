#pragma once
// Puts a frame on the screen: the rendered frame's 8-bit codes (and a debug image) uploaded and
// blitted into the swapchain image, ImGui drawn over them in the swapchain's render pass, and
// the image presented. One frame in flight: a frame takes 100 ms or more to render on lavapipe
// and the renderer waits for its own work, so a second one would overlap nothing; one also
// lets the staging buffers be rewritten as soon as the last submit's fence has signalled.
#include <cstdint>
#include <functional>
#include <string>

#include <vulkan/vulkan.h>

#include "debug_panel.h"
#include "engine/gpu/buffer.h"

namespace sky {
class Context;
}

namespace sky::view {

class Swapchain;

// An RGBA8 image uploaded from the host, left in TRANSFER_SRC_OPTIMAL for blits.
class UploadImage {
public:
  UploadImage(const Context& ctx, std::string name);
  ~UploadImage();
  UploadImage(const UploadImage&) = delete;
  UploadImage& operator=(const UploadImage&) = delete;

  // Copies the pixels to the staging buffer (the caller has waited for the last frame); the
  // next record() uploads them.
  void set(const uint8_t* rgba, uint32_t width, uint32_t height);
  // Records the pending upload, if any, and the barrier that makes it readable by blits.
  void record(VkCommandBuffer cmd);
  VkImage image() const { return mImage; }
  uint32_t width() const { return mWidth; }
  uint32_t height() const { return mHeight; }
  bool valid() const { return mImage != VK_NULL_HANDLE && mUploaded; }

private:
  void destroy();

  const Context& mCtx;
  std::string mName;
  Buffer mStaging;
  VkImage mImage = VK_NULL_HANDLE;
  VkDeviceMemory mMemory = VK_NULL_HANDLE;
  uint32_t mWidth = 0, mHeight = 0;
  bool mPending = false;
  bool mUploaded = false;
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

  // The pixels to show from the next present on (the frame, the debug view's image).
  void setFrame(const uint8_t* rgba, uint32_t width, uint32_t height);
  void setTile(const uint8_t* rgba, uint32_t width, uint32_t height);

  // Acquires an image, clears it, blits the frame into `placement.frame` and the tile into
  // `placement.tile` (zero-sized: not drawn), records `drawUi` inside the render pass, submits
  // and presents.
  PresentStatus present(const DebugPlacement& placement,
                        const std::function<void(VkCommandBuffer)>& drawUi);
  // Waits for the last submitted frame (before touching what it reads).
  void waitForLastFrame();

private:
  void blit(VkCommandBuffer cmd, const UploadImage& from, const Rect& to, VkImage target);

  const Context& mCtx;
  Swapchain& mSwapchain;
  VkCommandPool mPool = VK_NULL_HANDLE;
  VkCommandBuffer mCmd = VK_NULL_HANDLE;
  VkFence mFence = VK_NULL_HANDLE;         // the last submit
  VkSemaphore mAcquired = VK_NULL_HANDLE;  // the acquired image may be written
  UploadImage mFrame;
  UploadImage mTile;
  VkFilter mFilter = VK_FILTER_NEAREST;
};

}  // namespace sky::view
