#include "swapchain.h"

#include <algorithm>

#include "engine/core/error.h"
#include "engine/gpu/context.h"
#include "engine/gpu/vk_check.h"

namespace sky::view {

Swapchain::Swapchain(const Context& ctx, VkSurfaceKHR surface) : mCtx(ctx), mSurface(surface) {
  VkBool32 canPresent = VK_FALSE;
  SKY_VK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice(), ctx.queueFamily(), surface,
                                              &canPresent));
  if (!canPresent)
    internalError("cannot open a window: " + ctx.deviceName() +
                  " cannot present from its compute queue");

  uint32_t count = 0;
  SKY_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  SKY_VK(
      vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), surface, &count, formats.data()));
  auto blittable = [&](VkFormat f) {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), f, &p);
    return (p.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) != 0;
  };
  bool found = false;
  for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
    for (const VkSurfaceFormatKHR& f : formats)
      if (!found && f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR &&
          blittable(f.format)) {
        mFormat = f;
        found = true;
      }
  if (!found) internalError("cannot open a window: the surface offers no 8-bit UNORM format");

  SKY_VK(vkGetPhysicalDeviceSurfacePresentModesKHR(ctx.physicalDevice(), surface, &count, nullptr));
  std::vector<VkPresentModeKHR> modes(count);
  SKY_VK(vkGetPhysicalDeviceSurfacePresentModesKHR(ctx.physicalDevice(), surface, &count,
                                                   modes.data()));
  // Mailbox when offered: a frame takes 100 ms on lavapipe already, there is no need to also
  // wait for a vertical blank. FIFO is always there.
  if (std::find(modes.begin(), modes.end(), VK_PRESENT_MODE_MAILBOX_KHR) != modes.end())
    mPresentMode = VK_PRESENT_MODE_MAILBOX_KHR;

  // ImGui draws over the blitted frame: load what is there, leave it ready to present.
  VkAttachmentDescription color{};
  color.format = mFormat.format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  // The blit's layout change before the pass already waits for the transfer; this orders the
  // pass's attachment access after it.
  VkSubpassDependency dependency{};
  dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
  dependency.dstSubpass = 0;
  dependency.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependency.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependency.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  dependency.dstAccessMask =
      VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 1;
  info.pAttachments = &color;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 1;
  info.pDependencies = &dependency;
  SKY_VK(vkCreateRenderPass(ctx.device(), &info, nullptr, &mRenderPass));
}

Swapchain::~Swapchain() {
  vkDeviceWaitIdle(mCtx.device());
  destroyImages();
  if (mSwapchain) vkDestroySwapchainKHR(mCtx.device(), mSwapchain, nullptr);
  vkDestroyRenderPass(mCtx.device(), mRenderPass, nullptr);
}

void Swapchain::destroyImages() {
  VkDevice device = mCtx.device();
  for (VkFramebuffer f : mFramebuffers) vkDestroyFramebuffer(device, f, nullptr);
  for (VkImageView v : mViews) vkDestroyImageView(device, v, nullptr);
  for (VkSemaphore s : mRenderFinished) vkDestroySemaphore(device, s, nullptr);
  mFramebuffers.clear();
  mViews.clear();
  mRenderFinished.clear();
  mImages.clear();
}

bool Swapchain::recreate(VkExtent2D size) {
  VkDevice device = mCtx.device();
  VkSurfaceCapabilitiesKHR caps;
  SKY_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(mCtx.physicalDevice(), mSurface, &caps));
  // Minimised between the caller's look and this one: keep what there is.
  if (caps.currentExtent.width == 0 || caps.currentExtent.height == 0) return false;
  // Every use of the old images (and their semaphores, including the last presents' waits)
  // must be over before they go.
  SKY_VK(vkDeviceWaitIdle(device));
  destroyImages();
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    internalError("cannot open a window: the surface's images cannot be blitted to");
  // The surface's own extent when it has one (X11: the window's); the framebuffer's otherwise.
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == UINT32_MAX) {
    extent.width = std::clamp(size.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(size.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  mMinImageCount = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) mMinImageCount = std::min(mMinImageCount, caps.maxImageCount);
  mMinImageCount = std::max(mMinImageCount, 2u);  // ImGui's backend wants at least 2

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = mSurface;
  info.minImageCount = mMinImageCount;
  info.imageFormat = mFormat.format;
  info.imageColorSpace = mFormat.colorSpace;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR)
                          ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                          : caps.currentTransform;
  info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  info.presentMode = mPresentMode;
  info.clipped = VK_TRUE;
  info.oldSwapchain = mSwapchain;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  SKY_VK(vkCreateSwapchainKHR(device, &info, nullptr, &created));
  if (mSwapchain) vkDestroySwapchainKHR(device, mSwapchain, nullptr);
  mSwapchain = created;
  mExtent = extent;

  uint32_t count = 0;
  SKY_VK(vkGetSwapchainImagesKHR(device, mSwapchain, &count, nullptr));
  mImages.resize(count);
  SKY_VK(vkGetSwapchainImagesKHR(device, mSwapchain, &count, mImages.data()));
  for (VkImage image : mImages) {
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = mFormat.format;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView v = VK_NULL_HANDLE;
    SKY_VK(vkCreateImageView(device, &view, nullptr, &v));
    mViews.push_back(v);
    VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fb.renderPass = mRenderPass;
    fb.attachmentCount = 1;
    fb.pAttachments = &v;
    fb.width = extent.width;
    fb.height = extent.height;
    fb.layers = 1;
    VkFramebuffer f = VK_NULL_HANDLE;
    SKY_VK(vkCreateFramebuffer(device, &fb, nullptr, &f));
    mFramebuffers.push_back(f);
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore s = VK_NULL_HANDLE;
    SKY_VK(vkCreateSemaphore(device, &si, nullptr, &s));
    mRenderFinished.push_back(s);
  }
  return true;
}

}  // namespace sky::view
