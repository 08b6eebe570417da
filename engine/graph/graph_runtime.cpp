#include "engine/graph/graph_runtime.h"

#include <algorithm>
#include <cstring>

#include "engine/gpu/context.h"
#include "engine/gpu/vk_check.h"

namespace sky {
namespace {
constexpr VkDeviceSize kUniformChunk = 64 * 1024;
}

GraphRuntime::GraphRuntime(const Context& ctx) : mCtx(ctx), mDescriptors(ctx) {
  VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool.queueFamilyIndex = ctx.queueFamily();
  SKY_VK(vkCreateCommandPool(ctx.device(), &pool, nullptr, &mPool));
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = mPool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  SKY_VK(vkAllocateCommandBuffers(ctx.device(), &alloc, &mCmd));
  VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  SKY_VK(vkCreateFence(ctx.device(), &fence, nullptr, &mFence));
}

GraphRuntime::~GraphRuntime() {
  vkDeviceWaitIdle(mCtx.device());
  releaseTransients(GraphUse::Frame);
  releaseTransients(GraphUse::Bake);
  vkDestroyFence(mCtx.device(), mFence, nullptr);
  vkDestroyCommandPool(mCtx.device(), mPool, nullptr);
}

uint64_t GraphRuntime::transientBytes() const {
  return mTransients[static_cast<int>(GraphUse::Frame)].bytes;
}

void GraphRuntime::releaseTransients(GraphUse use) {
  Transients& t = transients(use);
  t.images.clear();
  t.buffers.clear();
  for (VkDeviceMemory m : t.memory) vkFreeMemory(mCtx.device(), m, nullptr);
  t.memory.clear();
  t.key.clear();
  t.bytes = 0;
}

void GraphRuntime::beginHostFrame() {
  mDescriptors.reset();
  mUniformChunk = 0;
  mUniformOffset = 0;
  mHostStaging.clear();
}

VkCommandBuffer GraphRuntime::beginFrame() {
  beginHostFrame();
  SKY_VK(vkResetCommandBuffer(mCmd, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  SKY_VK(vkBeginCommandBuffer(mCmd, &begin));
  return mCmd;
}

void GraphRuntime::submitAndWait() {
  SKY_VK(vkEndCommandBuffer(mCmd));
  VkCommandBufferSubmitInfo cb{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cb.commandBuffer = mCmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cb;
  SKY_VK(vkResetFences(mCtx.device(), 1, &mFence));
  mCtx.submit(submit, mFence);
  mCtx.wait(mFence);
}

// The arena's ranges bind as uniform or as storage buffers, so its chunks carry both usages
// and the larger of the two offset alignments. The passes' parameter blocks are uniform
// blocks read through shaders/common/params_block.glsl, which keeps lavapipe from recompiling
// a shader at every dispatch.
UniformRange GraphRuntime::uploadUniform(const void* data, VkDeviceSize size) {
  const VkDeviceSize align = std::max(mCtx.properties().limits.minUniformBufferOffsetAlignment,
                                      mCtx.properties().limits.minStorageBufferOffsetAlignment);
  if (size > kUniformChunk)
    internalError("uniform block of " + std::to_string(size) + " bytes is too large");
  mUniformOffset = (mUniformOffset + align - 1) / align * align;
  if (mUniformChunk < mUniformChunks.size() && mUniformOffset + size > kUniformChunk) {
    ++mUniformChunk;
    mUniformOffset = 0;
  }
  if (mUniformChunk >= mUniformChunks.size())
    mUniformChunks.emplace_back(
        mCtx, BufferDesc{"uniforms", kUniformChunk,
                         VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         BufferMemory::HostVisible});
  Buffer& chunk = mUniformChunks[mUniformChunk];
  std::memcpy(static_cast<uint8_t*>(chunk.mapped()) + mUniformOffset, data, size);
  UniformRange range{chunk.buffer(), mUniformOffset, size};
  mUniformOffset += size;
  return range;
}

}  // namespace sky
