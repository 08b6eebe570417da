#include "presenter.h"

#include <cstring>

#include "engine/core/error.h"
#include "engine/gpu/barriers.h"
#include "engine/gpu/context.h"
#include "engine/gpu/vk_check.h"
#include "swapchain.h"

namespace sky::view {

namespace {

constexpr VkFormat kFormat = VK_FORMAT_R8G8B8A8_UNORM;

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  d.imageMemoryBarrierCount = 1;
  d.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &d);
}

}  // namespace

WindowImage::WindowImage(const Context& ctx, std::string name)
    : mCtx(ctx), mName(std::move(name)) {}

void WindowImage::ensure(uint32_t width, uint32_t height) {
  if (width == 0 || height == 0) internalError("skyview: an empty image to show");
  if (mImage.image && width == this->width() && height == this->height()) return;
  ImageDesc desc;
  desc.name = mName;
  desc.format = kFormat;
  desc.width = width;
  desc.height = height;
  // Storage: the display pass writes it; transfer: uploads, blits, dump-frame's read.
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
               VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  mImage = PersistentImage{Image(mCtx, desc), {}};
  mFilled = false;
  // Into the layout it is kept in, cleared: the frame graph and the blits find it there.
  const VkImage image = mImage.image.image();
  mCtx.submitAndWait([&](VkCommandBuffer cmd) {
    imageBarrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                 VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &all);
    imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kLayout,
                 VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
  });
}

PersistentImage& WindowImage::target(uint32_t width, uint32_t height) {
  ensure(width, height);
  mPending = false;  // the frame replaces an upload not yet made
  return mImage;
}

void WindowImage::set(const uint8_t* rgba, uint32_t width, uint32_t height) {
  ensure(width, height);
  const VkDeviceSize bytes = VkDeviceSize(width) * height * 4;
  if (!mStaging || mStaging.size() < bytes)
    mStaging = Buffer(mCtx, {mName + " staging", bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                             BufferMemory::HostVisible});
  std::memcpy(mStaging.mapped(), rgba, bytes);
  mPending = true;
}

void WindowImage::record(VkCommandBuffer cmd) {
  if (!mPending) return;
  // The old contents are not needed: UNDEFINED discards them. The previous frame's blits
  // read the image, so the transfer write waits for them (same stage, execution order).
  imageBarrier(cmd, image(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {width(), height(), 1};
  vkCmdCopyBufferToImage(cmd, mStaging.buffer(), image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                         &region);
  imageBarrier(cmd, image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kLayout,
               VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
               VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  mPending = false;
  mFilled = true;
}

std::vector<uint8_t> WindowImage::read() const {
  if (!valid()) return {};
  const VkDeviceSize bytes = VkDeviceSize(width()) * height() * 4;
  Buffer readback(
      mCtx, {mName + " read", bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, BufferMemory::HostVisible});
  mCtx.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width(), height(), 1};
    vkCmdCopyImageToBuffer(cmd, image(), kLayout, readback.buffer(), 1, &region);
    copiesVisibleToHost(cmd);
  });
  const auto* codes = static_cast<const uint8_t*>(readback.mapped());
  return {codes, codes + bytes};
}

Presenter::Presenter(const Context& ctx, Swapchain& swapchain)
    : mCtx(ctx), mSwapchain(swapchain), mFrame(ctx, "skyview frame"), mTile(ctx, "skyview debug") {
  VkDevice device = ctx.device();
  VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool.queueFamilyIndex = ctx.queueFamily();
  SKY_VK(vkCreateCommandPool(device, &pool, nullptr, &mPool));
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = mPool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  SKY_VK(vkAllocateCommandBuffers(device, &alloc, &mCmd));
  VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // no frame yet: nothing to wait for
  SKY_VK(vkCreateFence(device, &fence, nullptr, &mFence));
  VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  SKY_VK(vkCreateSemaphore(device, &semaphore, nullptr, &mAcquired));

  VkFormatProperties p;
  vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), kFormat, &p);
  if (!(p.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT))
    internalError("cannot open a window: " + ctx.deviceName() + " cannot blit RGBA8 images");
  if (p.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT)
    mFilter = VK_FILTER_LINEAR;
}

Presenter::~Presenter() {
  VkDevice device = mCtx.device();
  vkDeviceWaitIdle(device);
  vkDestroySemaphore(device, mAcquired, nullptr);
  vkDestroyFence(device, mFence, nullptr);
  vkDestroyCommandPool(device, mPool, nullptr);
}

void Presenter::waitForLastFrame() {
  mCtx.wait(mFence);
}

PersistentImage& Presenter::frameTarget(uint32_t width, uint32_t height) {
  waitForLastFrame();
  return mFrame.target(width, height);
}

Presenter::Codes Presenter::readFrame() {
  waitForLastFrame();
  return {mFrame.read(), mFrame.width(), mFrame.height()};
}

void Presenter::setFrame(const uint8_t* rgba, uint32_t width, uint32_t height) {
  waitForLastFrame();
  mFrame.set(rgba, width, height);
}

void Presenter::setTile(const uint8_t* rgba, uint32_t width, uint32_t height) {
  waitForLastFrame();
  mTile.set(rgba, width, height);
}

void Presenter::blit(VkCommandBuffer cmd, const WindowImage& from, const Rect& to, VkImage target) {
  if (!from.valid() || to.width == 0 || to.height == 0) return;
  VkImageBlit region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.srcOffsets[1] = {static_cast<int32_t>(from.width()), static_cast<int32_t>(from.height()),
                          1};
  region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.dstOffsets[0] = {to.x, to.y, 0};
  region.dstOffsets[1] = {to.x + static_cast<int32_t>(to.width),
                          to.y + static_cast<int32_t>(to.height), 1};
  // Same size: nearest copies the codes exactly; scaled: linear when the format allows it.
  const bool sameSize = to.width == from.width() && to.height == from.height();
  vkCmdBlitImage(cmd, from.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region,
                 sameSize ? VK_FILTER_NEAREST : mFilter);
}

PresentStatus Presenter::present(const DebugPlacement& placement,
                                 const std::function<void(VkCommandBuffer)>& drawUi) {
  VkDevice device = mCtx.device();
  waitForLastFrame();
  uint32_t index = 0;
  VkResult acquired = vkAcquireNextImageKHR(device, mSwapchain.handle(), UINT64_MAX, mAcquired,
                                            VK_NULL_HANDLE, &index);
  // Out of date: nothing was acquired and the semaphore stays unsignalled. Suboptimal: the
  // image was acquired and must be presented; the swapchain is recreated after.
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return PresentStatus::Recreate;
  if (acquired != VK_SUBOPTIMAL_KHR && acquired != VK_SUCCESS)
    mCtx.failed(acquired, "acquiring a window image");

  SKY_VK(vkResetCommandBuffer(mCmd, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  SKY_VK(vkBeginCommandBuffer(mCmd, &begin));
  mFrame.record(mCmd);
  mTile.record(mCmd);

  const VkImage target = mSwapchain.image(index);
  // The semaphore wait covers ALL_TRANSFER, so the layout change waits for the acquire.
  imageBarrier(mCmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const VkClearColorValue grey{{0.08f, 0.08f, 0.09f, 1.0f}};
  const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(mCmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &grey, 1, &all);
  // The blits write where the clear wrote.
  memoryBarrier(mCmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  blit(mCmd, mFrame, placement.frame, target);
  blit(mCmd, mTile, placement.tile, target);
  imageBarrier(mCmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);

  VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  pass.renderPass = mSwapchain.renderPass();
  pass.framebuffer = mSwapchain.framebuffer(index);
  pass.renderArea = {{0, 0}, mSwapchain.extent()};
  vkCmdBeginRenderPass(mCmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
  if (drawUi) drawUi(mCmd);
  vkCmdEndRenderPass(mCmd);
  SKY_VK(vkEndCommandBuffer(mCmd));

  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = mAcquired;
  wait.stageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = mSwapchain.renderFinished(index);
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo cb{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cb.commandBuffer = mCmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.waitSemaphoreInfoCount = 1;
  submit.pWaitSemaphoreInfos = &wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cb;
  submit.signalSemaphoreInfoCount = 1;
  submit.pSignalSemaphoreInfos = &signal;
  SKY_VK(vkResetFences(device, 1, &mFence));
  mCtx.submit(submit, mFence);

  VkSemaphore finished = mSwapchain.renderFinished(index);
  VkSwapchainKHR swapchain = mSwapchain.handle();
  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &finished;
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain;
  present.pImageIndices = &index;
  const VkResult presented = vkQueuePresentKHR(mCtx.queue(), &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR ||
      acquired == VK_SUBOPTIMAL_KHR)
    return PresentStatus::Recreate;
  if (presented != VK_SUCCESS) mCtx.failed(presented, "at present");
  return PresentStatus::Presented;
}

}  // namespace sky::view
