#include "engine/gpu/buffer.h"

#include <utility>

#include "engine/gpu/context.h"
#include "engine/gpu/vk_check.h"

namespace sky {

Buffer::Buffer(const Context& ctx, const BufferDesc& desc, bool allocate)
    : mCtx(&ctx), mDesc(desc) {
  if (desc.size == 0) internalError("buffer '" + desc.name + "' has size 0");
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = desc.size;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  SKY_VK(vkCreateBuffer(ctx.device(), &info, nullptr, &mBuffer));
  ctx.setName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(mBuffer), desc.name);
  if (!allocate) {
    if (desc.memory != BufferMemory::Device)
      internalError("buffer '" + desc.name + "': host buffers own their memory");
    return;
  }

  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), mBuffer, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  if (desc.memory == BufferMemory::HostVisible) {
    // Prefer coherent + cached (fast readback); Vulkan guarantees visible + coherent exists.
    VkMemoryPropertyFlags cached = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                   VK_MEMORY_PROPERTY_HOST_COHERENT_BIT |
                                   VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    try {
      alloc.memoryTypeIndex = ctx.memoryType(req.memoryTypeBits, cached);
    } catch (const Error&) {
      alloc.memoryTypeIndex =
          ctx.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                 VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    }
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &mem);
    mCoherent =
        mem.memoryTypes[alloc.memoryTypeIndex].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  } else {
    alloc.memoryTypeIndex = ctx.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  }
  try {
    mMemory = ctx.allocate(alloc, "buffer '" + desc.name + "'");
  } catch (...) {
    reset();
    throw;
  }
  SKY_VK(vkBindBufferMemory(ctx.device(), mBuffer, mMemory, 0));
  if (desc.memory == BufferMemory::HostVisible)
    SKY_VK(vkMapMemory(ctx.device(), mMemory, 0, VK_WHOLE_SIZE, 0, &mMapped));
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    reset();
    mCtx = std::exchange(o.mCtx, nullptr);
    mDesc = o.mDesc;
    mBuffer = std::exchange(o.mBuffer, VK_NULL_HANDLE);
    mMemory = std::exchange(o.mMemory, VK_NULL_HANDLE);
    mMapped = std::exchange(o.mMapped, nullptr);
    mCoherent = o.mCoherent;
  }
  return *this;
}

Buffer::~Buffer() {
  reset();
}

void Buffer::reset() {
  if (!mCtx) return;
  if (mBuffer) vkDestroyBuffer(mCtx->device(), mBuffer, nullptr);
  if (mMemory) vkFreeMemory(mCtx->device(), mMemory, nullptr);  // unmaps implicitly
  mBuffer = VK_NULL_HANDLE;
  mMemory = VK_NULL_HANDLE;
  mMapped = nullptr;
}

void Buffer::bindMemory(VkDeviceMemory memory, VkDeviceSize offset) {
  SKY_VK(vkBindBufferMemory(mCtx->device(), mBuffer, memory, offset));
}

void Buffer::invalidate() const {
  if (mCoherent || !mMemory) return;
  VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
  range.memory = mMemory;
  range.size = VK_WHOLE_SIZE;
  SKY_VK(vkInvalidateMappedMemoryRanges(mCtx->device(), 1, &range));
}

}  // namespace sky
