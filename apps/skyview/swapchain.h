#pragma once
// The window's swapchain: images the viewer blits its frame into (TRANSFER_DST) and ImGui then
// draws on (COLOR_ATTACHMENT), their views and framebuffers for ImGui's render pass, and one
// "rendering finished" semaphore per image (a present holds its semaphore until the image
// comes back, so it cannot be one per frame in flight).
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace sky {
class Context;
}

namespace sky::view {

class Swapchain {
public:
  // Picks the surface format (8-bit UNORM: the frame's codes are already display-encoded and
  // must be copied, not encoded twice) and creates the render pass; no images until recreate().
  // Internal error when the device cannot present to `surface` from the context's queue.
  Swapchain(const Context& ctx, VkSurfaceKHR surface);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // (Re)creates the images for a framebuffer of `size` (not 0 x 0: a minimised window keeps
  // its old swapchain). Waits for the device to be idle first. False, changing nothing, when
  // the surface has become 0 x 0 meanwhile.
  bool recreate(VkExtent2D size);

  VkSwapchainKHR handle() const { return mSwapchain; }
  VkExtent2D extent() const { return mExtent; }
  VkFormat format() const { return mFormat.format; }
  VkRenderPass renderPass() const { return mRenderPass; }
  uint32_t minImageCount() const { return mMinImageCount; }
  uint32_t imageCount() const { return static_cast<uint32_t>(mImages.size()); }
  VkImage image(uint32_t i) const { return mImages[i]; }
  VkFramebuffer framebuffer(uint32_t i) const { return mFramebuffers[i]; }
  VkSemaphore renderFinished(uint32_t i) const { return mRenderFinished[i]; }

private:
  void destroyImages();

  const Context& mCtx;
  VkSurfaceKHR mSurface;
  VkSurfaceFormatKHR mFormat{};
  VkPresentModeKHR mPresentMode = VK_PRESENT_MODE_FIFO_KHR;
  VkRenderPass mRenderPass = VK_NULL_HANDLE;
  VkSwapchainKHR mSwapchain = VK_NULL_HANDLE;
  VkExtent2D mExtent{0, 0};
  uint32_t mMinImageCount = 2;
  std::vector<VkImage> mImages;
  std::vector<VkImageView> mViews;
  std::vector<VkFramebuffer> mFramebuffers;
  std::vector<VkSemaphore> mRenderFinished;
};

}  // namespace sky::view
